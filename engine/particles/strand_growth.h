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

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

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
};

// The output: polylines of at least one segment, in strand id order.
struct Strands {
    std::vector<glm::vec3> points;
    std::vector<float> radii;             // per point (the tube radius r)
    std::vector<uint32_t> offsets{0};     // strand s is points[offsets[s], offsets[s + 1])
    std::vector<int32_t> parent;          // per strand: the strand it split from, or -1
    std::vector<uint32_t> particle;       // per strand: its id in the simulation (hash key)
    StrandStats stats;

    size_t size() const { return parent.size(); }
};

struct GrowOptions {
    int threads = 0;  // 0 = all hardware threads; never changes the result
};

// Validates the scene (validateParticleScene) and grows its strands. Returns false with *error when the
// scene is invalid or when splits would need more than walk.max_points points (refused, not truncated).
bool growStrands(const ParticleScene& scene, const GrowOptions& options, Strands* out, std::string* error);

}  // namespace ug
