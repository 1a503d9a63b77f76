// Growing strands by the directed random walk of particle sculpting (Beneš & Espinosa 2000 §4-5),
// exact and order-independent (docs/particles.md "Exactness"):
//
// - Synchronous steps: step t reads only the state after step t − 1. Every active strand first picks
//   its move from n hashed trials (seed, strand id, step, trial) in a cone around its heading, the one
//   of least fitness f = Σ a_i(t)·d_i; a cutter the move would cross clips it to the threshold.
// - Collisions: a move is refused when its segment comes closer than 2r to a segment of another strand
//   from an earlier step, or to another strand's move of this step whose strand has a lower id (and
//   was not itself refused by an earlier segment): a fixed priority, so two strands racing for the same
//   space resolve the same way on any number of threads. Segments that share a point (a split's parent
//   and children at the split point) are exempt.
// - Actions (stop, kill, split, countdown) are applied serially in strand id order; children get the
//   next ids in that order. parallelFor runs the per-strand work, which writes only its own slots.
//
// The strands are then a pure function of the scene: bit-identical for any thread count.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/large_pages.h"
#include "particles/particle_scene.h"

namespace ug {

struct StrandStats {
    uint64_t seeded = 0;        // particles the generators seeded
    uint64_t strands = 0;       // strands in the simulation, children included
    uint64_t moves = 0;         // accepted steps over all strands (the work done)
    uint64_t collisions = 0;    // moves refused by a collision
    uint64_t cutter_hits = 0;   // moves clipped by a cutter
    uint64_t splits = 0;        // strands that split
    uint64_t killed = 0;        // strands removed (kill, countdown)
    uint64_t dropped = 0;       // strands that never moved (no segment), left out of the output
    uint64_t solid_hits = 0;    // moves refused because they would enter a solid (walk.solids)
    uint64_t crowded = 0;       // moves refused because no trial kept walk.keep_distance_m
};

// The output: polylines of at least one segment, in strand id order.
struct Strands {
    // A fur ball's are tens of megabytes (large_pages.h).
    LargeVector<glm::vec3> points;
    LargeVector<float> radii;             // per point (the tube radius r)
    std::vector<uint32_t> offsets{0};     // strand s is points[offsets[s], offsets[s + 1])
    std::vector<int32_t> parent;          // per strand: the strand it split from, or -1
    std::vector<uint32_t> particle;       // per strand: its id in the simulation
    StrandStats stats;

    size_t size() const { return parent.size(); }
    // Empties it, keeping its memory.
    void clear() {
        points.clear();
        radii.clear();
        offsets.assign(1, 0);
        parent.clear();
        particle.clear();
        stats = {};
    }
};

struct GrowOptions {
    int threads = 0;  // 0 = all hardware threads; never changes the result
    // Set (by another thread): the growth stops before its next step and fails with "cancelled"; a
    // StrandRegrower then keeps the record of its last finished growth. Never changes a finished result.
    const std::atomic<bool>* cancel = nullptr;
    // Progress for another thread: the steps finished so far (of walk.steps; a growth whose strands all end
    // early stops short of it).
    std::atomic<uint32_t>* steps_done = nullptr;
};

constexpr const char* kGrowthCancelled = "cancelled";

// Validates the scene (validateParticleScene) and grows its strands. Returns false with *error when the
// scene is invalid or when splits would need more than walk.max_points points (refused, not truncated).
bool growStrands(const ParticleScene& scene, const GrowOptions& options, Strands* out, std::string* error);

struct GrowthRecord;  // growth_record.h

// What the last StrandRegrower::grow did.
struct RegrowReport {
    bool incremental = false;  // it re-grew from the record of the growth before
    uint64_t recomputed = 0;   // moves proposed again (every move, for a full growth)
    uint64_t reused = 0;       // moves taken from the record
};

struct GrowthWorkspace;

// Grows a scene again as it is edited (the editor's live strands, a sculpting session): each grow()
// keeps a record of its growth, and the next one, when the edit touched only the attractors (their place,
// shape and charges, at the same radius of influence), re-grows from it only the strands the edit
// reaches, directly or through strands it reached (docs/particles.md "Incremental re-growth"). The result
// is the full growth's, bit for bit; any other edit grows in full. Holds the record (about 40 bytes a
// move) and the growth's working arrays (about as much again) between calls.
class StrandRegrower {
public:
    StrandRegrower();
    ~StrandRegrower();
    StrandRegrower(const StrandRegrower&) = delete;
    StrandRegrower& operator=(const StrandRegrower&) = delete;

    // As growStrands; on failure the record is dropped and the next grow is a full one.
    bool grow(const ParticleScene& scene, const GrowOptions& options, Strands* out, std::string* error);
    const RegrowReport& lastReport() const { return report_; }
    // Forget the record: the next grow is a full one.
    void reset();

private:
    ParticleScene scene_;
    std::unique_ptr<GrowthRecord> record_, next_;
    std::unique_ptr<GrowthWorkspace> memory_;  // the growths' working arrays, kept for the next one
    RegrowReport report_;
};

}  // namespace ug
