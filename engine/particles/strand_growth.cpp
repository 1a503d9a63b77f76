#include "particles/strand_growth.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <optional>

#include "core/hash.h"
#include "core/large_pages.h"
#include "core/parallel.h"
#include "mesh/triangle_bvh.h"
#include "particles/growth_record.h"
#include "particles/particle_seeding.h"
#include "particles/segment_grid.h"

namespace ug {

namespace {

constexpr uint32_t kNone = 0xffffffffu;
constexpr uint64_t kTrialTag = 0x7419'a1c0'0000'0000ull;
constexpr uint64_t kSplitTag = 0x5b11'7c0f'0000'0000ull;
constexpr uint64_t kChildTag = 0x3c41'd0e9'0000'0000ull;
constexpr uint64_t kTurnTag = 0x7e4d'35a1'0000'0000ull;
constexpr uint64_t kActionTag = 0xac71'0b1e'0000'0000ull;
constexpr int kCutBisections = 40;
// The distance-keeping state's number in a random table's draw (0 collision, 1 age, 2 + c cutter c).
constexpr uint32_t kDistanceState = 0x10000;

enum class StrandState : uint8_t { Active, Stopped, Killed };

// Every point of every strand, in the order they were placed (steps, then strand ids). A strand is the
// chain of prev links from its last point back to its first; a split's children start at their parent's
// last point, which they share (that shared id is what exempts them from colliding with it).
struct PointStore {
    LargeVector<glm::vec3> pos;
    LargeVector<uint32_t> prev;    // the previous point of the strand, kNone at a root
    LargeVector<uint32_t> strand;  // the strand that placed it

    void clear() {
        pos.clear();
        prev.clear();
        strand.clear();
    }
};

// Per-strand state, one array per field.
struct StrandStore {
    // The strand's key to its random numbers: a root's id, a child's hash of its parent's key and its
    // rank. Ids shift when an edit changes where earlier strands split; keys do not, so a strand that an
    // edit does not reach draws the same numbers after it (incremental re-growth).
    std::vector<uint64_t> key;
    std::vector<uint32_t> first_child;  // the first of its split's children, kNone if it did not split
    // Re-growing from a record: the strand of the record this one has been identical to so far, kNone
    // once they differ (or for a strand the record does not have).
    std::vector<uint32_t> recorded;
    std::vector<uint32_t> first, last, npoints;
    std::vector<glm::quat> frame;
    std::vector<int32_t> parent;
    std::vector<uint32_t> root;  // the family: the seed this strand split from (itself for a seed)
    std::vector<uint8_t> depth;
    std::vector<StrandState> state;
    std::vector<uint32_t> age;
    std::vector<int32_t> countdown;  // -1: none running
    std::vector<uint8_t> countdown_stops;  // the running countdown ends in a stop (else a kill)
    std::vector<uint32_t> cut_mask;  // cutters this strand's lineage has triggered
    // A strand seeded on a solid mesh: the surface's outward normal there (its first move must not go
    // in); zero for the others.
    std::vector<glm::vec3> solid_normal;

    size_t size() const { return first.size(); }
    void clear() {
        const auto clearAll = [](auto&... arrays) { (arrays.clear(), ...); };
        clearAll(key, first_child, recorded, first, last, npoints, frame, parent, root, depth, state, age, countdown,
                 countdown_stops, cut_mask, solid_normal);
    }
    void add(uint64_t k, uint32_t point, glm::quat q, int32_t parent_id, uint8_t d, uint32_t mask, uint32_t rec) {
        key.push_back(k);
        first_child.push_back(kNone);
        recorded.push_back(rec);
        first.push_back(point);
        last.push_back(point);
        npoints.push_back(1);
        frame.push_back(q);
        root.push_back(parent_id < 0 ? uint32_t(root.size()) : root[size_t(parent_id)]);
        parent.push_back(parent_id);
        depth.push_back(d);
        state.push_back(StrandState::Active);
        age.push_back(0);
        countdown.push_back(-1);
        countdown_stops.push_back(0);
        cut_mask.push_back(mask);
        solid_normal.push_back(glm::vec3(0.0f));
    }
};

// One active strand's proposal for this step.
struct Moves {
    std::vector<glm::vec3> pos, dir;
    std::vector<int32_t> cutter;     // the cutter that clipped it, or -1
    // 1: refused by an earlier segment, 2: by a move of a lower id, 3: a solid, 4: crowded (no trial kept
    // walk.keep_distance_m)
    std::vector<uint8_t> blocked;
    std::vector<uint8_t> still;      // the clipped move did not leave its point
    void resize(size_t n) {
        pos.resize(n);
        dir.resize(n);
        cutter.resize(n);
        blocked.resize(n);
        still.resize(n);
    }
};

// Where along p0 → p1 a cutter triggers first: the last bisection point that does not trigger, so the
// placed point never crosses the threshold. p0 does not trigger, p1 does.
float cutParameter(const Cutter& c, glm::vec3 p0, glm::vec3 p1) {
    float lo = 0.0f, hi = 1.0f;
    for (int i = 0; i < kCutBisections; ++i) {
        const float mid = 0.5f * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        if (cutterTriggered(c, cutterValue(c, p0 + (p1 - p0) * mid)))
            hi = mid;
        else
            lo = mid;
    }
    return lo;
}

// A replay's arrays, kept in the growths' workspace between re-growths.
struct ReplayMemory {
    std::vector<uint8_t> parted;
    SegmentGrid changed_segments, changed_moves;
    std::vector<uint32_t> entry;
    std::vector<uint8_t> same, proposed, entry_same;
};

// Re-growing from a record (StrandRegrower): which strands may reuse their recorded move at this step,
// and the changed geometry that makes a recorded move stale. A strand reuses its recorded proposal when
// it is identical to its recorded strand so far and no changed attractor reaches its trials; it reuses its
// recorded collision verdicts when no changed segment (earlier steps) or changed move (this step) lies
// within the grids' reach of its move. "Changed" is every segment and move of a strand that differs
// from its record, in the new growth and in the record alike, from the step they part on.
struct Replay {
    const GrowthRecord& record;
    AttractorEdit edit;
    CutterEdit cutter_edit;
    std::vector<uint8_t>& parted;    // per recorded strand: the new growth no longer has an identical one
    SegmentGrid& changed_segments;   // changed segments of earlier steps, new and recorded
    SegmentGrid& changed_moves;      // changed moves of this step, new and recorded
    std::vector<uint32_t>& entry;    // per active strand: its recorded move at this step, or kNone
    std::vector<uint8_t>& same;      // per active strand: its proposal and first verdict equal the record's
    std::vector<uint8_t>& proposed;  // per active strand: its proposal was computed again
    std::vector<uint8_t>& entry_same;  // per recorded move of this step: its strand's `same`
    uint64_t reused = 0, recomputed = 0;

    Replay(const GrowthRecord& r, const ParticleScene& before, const ParticleScene& after, float reach,
           ReplayMemory* memory)
        : record(r), edit(before.attractors, after.attractors, after.walk.step_length_m),
          cutter_edit(before.cutters, after.cutters, after.walk.step_length_m),
          parted(memory->parted), changed_segments(memory->changed_segments), changed_moves(memory->changed_moves),
          entry(memory->entry), same(memory->same), proposed(memory->proposed), entry_same(memory->entry_same) {
        parted.assign(r.strand_parent.size(), 0);
        changed_segments.reset(reach);
        changed_moves.reset(reach);
    }

    // Files changed geometry; only its presence is asked, so its id is just the next one.
    static void fileChanged(SegmentGrid* grid, glm::vec3 midpoint) { grid->insert(uint32_t(grid->size()), midpoint, 0); }
};

}  // namespace

// What a growth writes step by step, kept by a StrandRegrower from one growth to the next: a re-growth
// then writes into memory the process already holds. Fresh, its pages fault in one by one: the first
// re-growth after a full growth took as long as the full growth did (docs/particles.md).
struct GrowthWorkspace {
    PointStore points;
    StrandStore strands;
    SegmentGrid grid;
    StepSegmentGrid step_grid;
    std::vector<SegmentGrid::Filed> filing;
    std::vector<uint32_t> point_at, active;
    Moves moves;
    ReplayMemory replay;

    // Room for a growth like the one `record` holds, in the arrays that keepRecord swaps with a record's:
    // `point_room` points exactly (warmArrayExactly), as many strands as the record's (warmArray).
    void warmLike(const GrowthRecord& record, size_t point_room) {
        warmArrayExactly(points.pos, point_room);
        warmArrayExactly(points.prev, point_room);
        warmArrayExactly(points.strand, point_room);
        warmArray(strands.parent, record.strand_parent.size());
        warmArray(strands.first_child, record.strand_first_child.size());
    }
};

namespace {

class Growth {
public:
    // Grows into `memory`'s arrays (emptied first; their capacity is kept).
    Growth(const ParticleScene& scene, const GrowOptions& options, GrowthWorkspace* memory)
        : scene_(scene), walk_(scene.walk), threads_(options.threads), cancel_(options.cancel),
          steps_done_(options.steps_done),
          cone_(glm::radians(walk_.cone_deg)), cos_cone_(std::cos(cone_)),
          reach2_(4.0f * walk_.strand_radius_m * walk_.strand_radius_m),
          keep2_(walk_.keep_distance_m * walk_.keep_distance_m),
          files_segments_(walk_.collisions || walk_.keep_distance_m > 0.0f),
          proposal_reads_segments_(walk_.keep_distance_m > 0.0f || (walk_.retry_refused && walk_.collisions)),
          choosy_(walk_.keep_distance_m > 0.0f || walk_.retry_refused),
          // A segment is at most step_length long; two whose tubes touch have midpoints within
          // step_length + 2r (padded against rounding), the reach of the grids' queries. When a proposal
          // reads the segments (keeping distance, retrying), a trial's move (a step from the strand's
          // point) within keep or 2r of a segment is within that + step / 2 of its midpoint, and a
          // re-growth asks from the strand's point: 2 steps + max(keep, 2r).
          reach_(proposal_reads_segments_
                     ? 1.001f * (2.0f * walk_.step_length_m + std::max(walk_.keep_distance_m, 2.0f * walk_.strand_radius_m))
                     : walk_.step_length_m * 1.001f + 2.0f * walk_.strand_radius_m * 1.001f),
          points_(memory->points),
          strands_(memory->strands),
          grid_(memory->grid),
          step_grid_(memory->step_grid),
          filing_(memory->filing),
          point_at_(memory->point_at),
          active_(memory->active),
          moves_(memory->moves),
          replay_memory_(memory->replay) {
        points_.clear();
        strands_.clear();
        grid_.reset(reach_);
        step_grid_.reset(reach_);
        if (!walk_.solids) return;
        // The surfaces objects and details generators gather are among the obstacles already.
        for (const ParticleGenerator& g : scene_.generators)
            if (g.kind == GeneratorKind::Mesh && g.mesh)
                addSolid(ParticleObstacle{.mesh = g.mesh, .translation = g.center_m, .scale = g.scale}, false);
        for (const ParticleObstacle& o : scene_.obstacles) addSolid(o, true);
        for (const ParticleObstacle& o : scene_.detail_obstacles) addSolid(o, true);
    }

    // Grow again from `record`, a growth of `before` (regrowable(before, scene_)).
    void replayFrom(const GrowthRecord& record, const ParticleScene& before) {
        replay_.emplace(record, before, scene_, reach_, &replay_memory_);
    }
    // Keep what a later replayFrom needs in *record (swapped in when run returns).
    void recordInto(GrowthRecord* record) { record_ = record; }
    RegrowReport report() const {
        return {replay_.has_value(), replay_ ? replay_->recomputed : proposals_, replay_ ? replay_->reused : 0};
    }

    bool run(Strands* out, std::string* error);

private:
    void seed();
    void propose(size_t k, uint32_t step);
    void place(size_t k, glm::vec3 p0, glm::vec3 dir);
    uint8_t refusal(size_t k) const;
    uint8_t earlierVerdict(size_t k) const;
    void proposeAndTest(size_t k, uint32_t step);
    void replayMove(size_t k, uint32_t step, bool everywhere);
    void matchRecordedMoves(uint32_t step);
    void testLowerMoves(uint32_t step);
    bool hitsChangedMove(size_t k) const;
    void partFromRecord(uint32_t step);
    bool isAncestor(uint32_t strand, uint32_t s) const;
    bool hitsEarlierSegment(size_t k) const;
    bool crowded(uint32_t strand, glm::vec3 p) const;
    bool hitsLowerMove(size_t k) const;
    bool entersSolid(size_t k) const;
    // `state` tells the states apart in a random table's draw (0 collision, 1 age, 2 + c cutter c).
    void apply(const StrandAction& action, uint32_t strand, uint32_t step, uint32_t state);
    const StrandAction& chosen(const StrandAction& action, uint32_t strand, uint32_t step, uint32_t state) const;
    bool canAct(const StrandAction& action, uint32_t strand) const;
    void turn(const StrandAction& action, uint32_t strand, uint32_t step);
    void split(const StrandAction& action, uint32_t strand);
    void placePoints();
    void emit(Strands* out) const;
    void keepRecord();
    glm::vec3 moveMidpoint(size_t k) const { return 0.5f * (points_.pos[strands_.last[active_[k]]] + moves_.pos[k]); }
    bool filed(size_t k) const { return !moves_.still[k] && (moves_.blocked[k] == 0 || moves_.blocked[k] == 2); }
    // Move k is accepted and leaves its point: it places a new one.
    bool movedTo(size_t k) const { return moves_.blocked[k] == 0 && !moves_.still[k]; }
    glm::vec3 segmentMidpoint(uint32_t point) const {
        return 0.5f * (points_.pos[points_.prev[point]] + points_.pos[point]);
    }

    const ParticleScene& scene_;
    const WalkSettings& walk_;
    int threads_;
    const std::atomic<bool>* cancel_;      // GrowOptions::cancel
    std::atomic<uint32_t>* steps_done_;    // GrowOptions::steps_done
    float cone_, cos_cone_, reach2_, keep2_;
    bool files_segments_;  // earlier segments are filed in grid_ (collisions or distance keeping)
    // A proposal depends on the earlier segments near it (distance keeping, or retrying with collisions).
    bool proposal_reads_segments_;
    bool choosy_;  // a move is chosen among every trial that is not refused (keeping distance, retrying)
    float reach_;
    // The workspace's arrays.
    PointStore& points_;
    StrandStore& strands_;
    SegmentGrid& grid_;       // segments of earlier steps, by their end point's id
    StepSegmentGrid& step_grid_;  // this step's moves, by their index in active_
    std::vector<SegmentGrid::Filed>& filing_;  // what a step files in either grid, in id order
    std::vector<uint32_t>& point_at_;  // per active strand: the id of the point its move places (placePoints)
    std::vector<uint32_t>& active_;
    Moves& moves_;
    ReplayMemory& replay_memory_;
    std::vector<float> charge_;  // a_i(t) of this step
    StrandStats stats_;
    void addSolid(const ParticleObstacle& placement, bool obstacle);
    bool insideObstacle(glm::vec3 p) const;
    struct SolidMesh {
        ParticleObstacle placement;  // a mesh generator's (at its center_m, its scale) or an obstacle's
        const TriangleBvh* bvh;      // in the model's own space
        Bounds bounds;               // world, padded: moves that stay clear of it skip the ray
        bool obstacle;               // one of scene_.obstacles (closed meshes: the inside test holds)
    };
    std::vector<SolidMesh> solid_meshes_;
    // One BVH per distinct mesh: a street's benches share theirs.
    std::vector<std::pair<const TriangleMesh*, std::unique_ptr<TriangleBvh>>> bvhs_;
    std::optional<Replay> replay_;
    GrowthRecord* record_ = nullptr;
    uint64_t proposals_ = 0;  // moves proposed, over all steps
};

void Growth::seed() {
    ParticleSeeds seeds;
    std::vector<uint8_t> on_solid;  // per seed: it lies on a solid mesh
    for (size_t g = 0; g < scene_.generators.size(); ++g) {
        seedGenerator(scene_.generators[g], uint32_t(g), walk_.seed, &seeds, scene_.terrain.get());
        on_solid.resize(seeds.positions.size(),
                        walk_.solids && seedsOnMesh(scene_.generators[g]) ? 1 : 0);
    }
    const size_t expected = std::min<uint64_t>(walk_.max_points, seeds.positions.size() * (uint64_t(walk_.steps) + 1));
    points_.pos.reserve(expected);
    points_.prev.reserve(expected);
    points_.strand.reserve(expected);
    for (size_t i = 0; i < seeds.positions.size(); ++i) {
        points_.pos.push_back(seeds.positions[i]);
        points_.prev.push_back(kNone);
        points_.strand.push_back(uint32_t(i));
        // The generators are the record's, so are the seeds: every root starts identical to its record.
        strands_.add(i, uint32_t(i), seeds.frames[i], -1, 0, 0, replay_ ? uint32_t(i) : kNone);
        if (on_solid[i]) strands_.solid_normal.back() = seeds.normals[i];
        // A seed inside an environmental object (on a face one of its parts reaches into, or on the ground
        // under it) never grows: it is dropped like a strand that never moved.
        if (walk_.solids && insideObstacle(seeds.positions[i] + seeds.normals[i] * (1e-3f * walk_.step_length_m)))
            strands_.state.back() = StrandState::Stopped;
    }
    stats_.seeded = seeds.positions.size();
    if (files_segments_) grid_.reserve(expected);
}

void Growth::propose(size_t k, uint32_t step) {
    const uint32_t s = active_[k];
    const glm::vec3 p0 = points_.pos[strands_.last[s]];
    // The frame as a matrix once per move: a trial is then 9 multiply-adds, not a quaternion product.
    const glm::mat3 frame = glm::mat3_cast(strands_.frame[s]);
    const uint32_t n = walk_.trials;
    const float step_m = walk_.step_length_m;
    // The trials as arrays of floats, each loop below over all of them: the compiler runs four or more
    // at a time (the hashes, in 64-bit words, stay one at a time).
    alignas(32) std::array<float, 256> u, v, x, y, z, f;
    const uint64_t move_hash = hashFirstWords(walk_.seed, kTrialTag + strands_.key[s], step);
    for (uint32_t t = 0; t < n; ++t) {
        const uint64_t h = hashLastWord(move_hash, t);
        u[t] = unitFloat(h);
        v[t] = unitFloat(mix64(h));
    }
    coneDirectionsCos(cos_cone_, n, u.data(), v.data(), x.data(), y.data(), z.data());
    // The directions into the world (the frame's columns), in place; f starts at 0.
    for (uint32_t t = 0; t < n; ++t) {
        const float lx = x[t], ly = y[t], lz = z[t];
        x[t] = frame[0][0] * lx + frame[1][0] * ly + frame[2][0] * lz;
        y[t] = frame[0][1] * lx + frame[1][1] * ly + frame[2][1] * lz;
        z[t] = frame[0][2] * lx + frame[1][2] * ly + frame[2][2] * lz;
        f[t] = 0.0f;
    }
    // f = Σ a_i·d_i at each trial's end, the attractors in order (one attractor's terms over all trials).
    for (size_t a = 0; a < scene_.attractors.size(); ++a) {
        const Attractor& attractor = scene_.attractors[a];
        const float charge = charge_[a];
        if (attractor.kind == AttractorKind::Point) {  // attractorTerm's distance, written out per coordinate
            const glm::vec3 a_m = attractor.a_m;
            for (uint32_t t = 0; t < n; ++t) {
                const float ex = (p0.x + x[t] * step_m) - a_m.x, ey = (p0.y + y[t] * step_m) - a_m.y,
                            ez = (p0.z + z[t] * step_m) - a_m.z;
                f[t] += attractorTermAt(attractor, charge, std::sqrt(ex * ex + ey * ey + ez * ez));
            }
        } else {
            for (uint32_t t = 0; t < n; ++t) f[t] += attractorTerm(attractor, charge, p0 + glm::vec3(x[t], y[t], z[t]) * step_m);
        }
    }
    uint32_t best_t = 0;  // ties keep the lower trial
    for (uint32_t t = 1; t < n; ++t)
        if (f[t] < f[best_t]) best_t = t;
    const glm::vec3 best_dir(x[best_t], y[best_t], z[best_t]);
    // Keeping distance or retrying, every trial is kept, to take the fittest that is not refused.
    const bool choosy = choosy_;
    place(k, p0, best_dir);
    if (!choosy) return;
    const uint8_t fittest_verdict = refusal(k);
    if (fittest_verdict == 0) return;
    // The other trials, fittest first (ties: the lower trial), until one is not refused.
    std::array<uint8_t, 256> tried{};
    tried[best_t] = 1;
    for (uint32_t i = 1; i < n; ++i) {
        uint32_t next = n;
        for (uint32_t t = 0; t < n; ++t)
            if (!tried[t] && (next == n || f[t] < f[next])) next = t;
        tried[next] = 1;
        place(k, p0, glm::vec3(x[next], y[next], z[next]));
        if (refusal(k) == 0) return;
    }
    // Every trial refused: the fittest's verdict. A crowded strand stays where it is (on_distance).
    place(k, p0, best_dir);
    moves_.blocked[k] = fittest_verdict;
    if (fittest_verdict == 4) {
        moves_.pos[k] = p0;
        moves_.cutter[k] = -1;
        moves_.still[k] = 0;
    }
}

void Growth::place(size_t k, glm::vec3 p0, glm::vec3 dir) {
    const uint32_t s = active_[k];
    const glm::vec3 end = p0 + dir * walk_.step_length_m;
    // The first cutter along the move (lowest parameter, then lowest index) clips it.
    int32_t cutter = -1;
    float cut_at = 2.0f;
    for (size_t c = 0; c < scene_.cutters.size(); ++c) {
        const Cutter& cut = scene_.cutters[c];
        if ((strands_.cut_mask[s] >> c) & 1u) continue;
        if (!cutterTriggered(cut, cutterValue(cut, end)) || cutterTriggered(cut, cutterValue(cut, p0))) continue;
        const float u = cutParameter(cut, p0, end);
        if (u < cut_at) {
            cut_at = u;
            cutter = int32_t(c);
        }
    }
    glm::vec3 pos = end;
    if (cutter >= 0) pos = p0 + (end - p0) * cut_at;
    moves_.pos[k] = pos;
    moves_.dir[k] = dir;
    moves_.cutter[k] = cutter;
    moves_.still[k] = pos == p0;
    moves_.blocked[k] = 0;
}

// Why the placed move k is refused while choosing among the trials: 4 crowded (keeping distance), and
// with walk.retry_refused 3 a solid, 1 an earlier segment; 0 when it is not (a move that does not leave
// its point never is).
uint8_t Growth::refusal(size_t k) const {
    if (moves_.still[k]) return 0;
    if (keep2_ > 0.0f && crowded(active_[k], moves_.pos[k])) return 4;
    return walk_.retry_refused ? earlierVerdict(k) : 0;
}

// The placed move k against what earlier steps left: 3 it enters a solid, 1 it comes within 2r of an
// earlier segment, else 0 (a move that does not leave its point never does).
uint8_t Growth::earlierVerdict(size_t k) const {
    if (moves_.still[k]) return 0;
    if (walk_.solids && entersSolid(k)) return 3;
    if (walk_.collisions && hitsEarlierSegment(k)) return 1;
    return 0;
}

bool Growth::isAncestor(uint32_t strand, uint32_t s) const {
    for (int32_t p = strands_.parent[s]; p >= 0; p = strands_.parent[size_t(p)])
        if (uint32_t(p) == strand) return true;
    return false;
}

bool Growth::entersSolid(size_t k) const {
    const uint32_t s = active_[k];
    const glm::vec3 a = points_.pos[strands_.last[s]], b = moves_.pos[k];
    // Seeds lie on the terrain and on the meshes: a move that starts on a surface and leaves it must not
    // hit it at its start, so the tests allow a hair (a thousandth of a step) there.
    const float hair = 1e-3f * walk_.step_length_m;
    if (scene_.terrain && b.z < scene_.terrain->sample(b.x, b.y) - hair) return true;
    if (solid_meshes_.empty()) return false;  // seeds on a solid come from a mesh, which is one
    const float length = glm::length(b - a);
    if (!(length > 0.0f)) return false;
    const glm::vec3 d = (b - a) / length;
    // A first move from a seed on a mesh starts on its surface, where the ray below cannot tell in from
    // out: the surface's normal does.
    if (strands_.npoints[s] == 1 && glm::dot(strands_.solid_normal[s], d) < 0.0f) return true;
    // A move must end at least a hair in front of a surface, never on it or just past it, so the next move
    // starts outside even when it grazed the surface. Only a seed on a mesh starts on the surface: its ray
    // begins a hair along (its normal has already sent it outward).
    const float skip = strands_.npoints[s] == 1 && strands_.solid_normal[s] != glm::vec3(0.0f) ? hair : 0.0f;
    const Bounds move{glm::min(a, b), glm::max(a, b)};
    for (const SolidMesh& m : solid_meshes_) {
        if (!overlaps(move, m.bounds)) continue;
        const glm::vec3 o = m.placement.toLocal(a + d * skip);
        if (m.bvh->rayHit(o, m.placement.directionToLocal(d)) < (length - skip + hair) / m.placement.scale)
            return true;
    }
    return false;
}

// Parity of the crossings of a ray going up (tilted off the axes, so it misses the edges of axis-aligned
// boxes) through each obstacle's every triangle: odd is inside. Environmental objects are closed meshes
// (env_models.h); parts that reach into each other (a shelter's glass into its posts) count per part,
// faces that coincide included, which is right for a point inside one part only. Brute force: only seeds
// within an obstacle's bounds ask, once per growth.
bool Growth::insideObstacle(glm::vec3 p) const {
    const glm::dvec3 up = glm::normalize(glm::dvec3(0.0123, 0.0271, 1.0));
    for (const SolidMesh& m : solid_meshes_) {
        if (!m.obstacle || !contains(m.bounds, p)) continue;
        const glm::dvec3 o(m.placement.toLocal(p));
        const glm::dvec3 d(m.placement.directionToLocal(glm::vec3(up)));
        const TriangleMesh& mesh = *m.placement.mesh;
        int crossings = 0;
        for (size_t t = 0; t < mesh.triangleCount(); ++t) {
            const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]);
            const glm::dvec3 e1 = glm::dvec3(mesh.positions[mesh.indices[3 * t + 1]]) - a;
            const glm::dvec3 e2 = glm::dvec3(mesh.positions[mesh.indices[3 * t + 2]]) - a;
            const glm::dvec3 h = glm::cross(d, e2);
            const double det = glm::dot(e1, h);
            if (det == 0.0) continue;
            const glm::dvec3 s = o - a;
            const double u = glm::dot(s, h) / det;
            if (u < 0.0 || u > 1.0) continue;
            const glm::dvec3 q = glm::cross(s, e1);
            const double v = glm::dot(d, q) / det;
            if (v < 0.0 || u + v > 1.0) continue;
            crossings += glm::dot(e2, q) / det > 0.0;
        }
        if (crossings % 2 == 1) return true;
    }
    return false;
}

void Growth::addSolid(const ParticleObstacle& placement, bool obstacle) {
    const TriangleBvh* bvh = nullptr;
    for (const auto& [mesh, built] : bvhs_)
        if (mesh == placement.mesh.get()) bvh = built.get();
    if (!bvh) {
        bvhs_.emplace_back(placement.mesh.get(), std::make_unique<TriangleBvh>(*placement.mesh, threads_));
        bvh = bvhs_.back().second.get();
    }
    Bounds local;
    for (const glm::vec3& p : placement.mesh->positions) local = unite(local, Bounds{p, p});
    Bounds world;
    for (int c = 0; c < 8; ++c) {
        const glm::vec3 corner((c & 1) ? local.hi.x : local.lo.x, (c & 2) ? local.hi.y : local.lo.y,
                               (c & 4) ? local.hi.z : local.lo.z);
        const glm::vec3 w = placement.toWorld(corner);
        world = unite(world, Bounds{w, w});
    }
    if (world.empty()) return;  // no triangles: nothing to cross
    // Padded by a step: the ray starts a hair along the move and rounding must not cull a touching one.
    const glm::vec3 pad(walk_.step_length_m + 1e-4f * glm::length(world.hi - world.lo));
    solid_meshes_.push_back({placement, bvh, Bounds{world.lo - pad, world.hi + pad}, obstacle});
}

bool Growth::hitsEarlierSegment(size_t k) const {
    const uint32_t s = active_[k];
    const uint32_t from = strands_.last[s];
    const glm::vec3 a = points_.pos[from], b = moves_.pos[k];
    // A child's first move leaves its split point, which may lie within reach of its ancestors' last
    // segments besides the one it ends (a cutter can clip the parent's last move to almost nothing):
    // those touch the child where it is rooted, as the parent's own segments touch each other.
    const bool leaving_split = strands_.parent[s] >= 0 && from == strands_.first[s];
    return grid_.anyNear(0.5f * (a + b), [&](uint32_t end, uint32_t strand) {
        if (strand == s || end == from) return false;
        const uint32_t start = points_.prev[end];
        if (start == from) return false;
        const glm::vec3 p = points_.pos[start], q = points_.pos[end];
        if (segmentSegmentDistance2(a, b, p, q) >= reach2_) return false;
        return !(leaving_split && segmentSegmentDistance2(a, a, p, q) < reach2_ && isAncestor(strand, s));
    });
}

// Whether p lies within keep_distance_m of an earlier segment of another family (the grid holds the
// segments of earlier steps only, so the verdict reads nothing this step changes).
bool Growth::crowded(uint32_t s, glm::vec3 p) const {
    const uint32_t family = strands_.root[s];
    return grid_.anyNear(p, [&](uint32_t end, uint32_t strand) {
        if (strands_.root[strand] == family) return false;
        const glm::vec3 q = points_.pos[end];
        return segmentSegmentDistance2(p, p, points_.pos[points_.prev[end]], q) < keep2_;
    });
}

bool Growth::hitsLowerMove(size_t k) const {
    const uint32_t from = strands_.last[active_[k]];
    const glm::vec3 a = points_.pos[from], b = moves_.pos[k];
    // Only lower ids have priority; siblings leaving their split point together share it.
    return step_grid_.anyNear(0.5f * (a + b), [&](uint32_t j, uint32_t) {
        const uint32_t other = strands_.last[active_[j]];
        if (other == from) return false;
        return segmentSegmentDistance2(a, b, points_.pos[other], moves_.pos[j]) < reach2_;
    }, uint32_t(k));
}

void Growth::split(const StrandAction& action, uint32_t s) {
    strands_.state[s] = StrandState::Stopped;
    ++stats_.splits;
    strands_.first_child[s] = uint32_t(strands_.size());
    // Children of a strand still identical to its record are identical to the record's children.
    const uint32_t recorded = strands_.recorded[s];
    const uint32_t recorded_child = recorded == kNone ? kNone : replay_->record.strand_first_child[recorded];
    const float cone = glm::radians(action.split_angle_deg);
    for (uint32_t c = 0; c < action.split_count; ++c) {
        glm::quat q = strands_.frame[s];
        if (cone > 0.0f) {
            const uint64_t h = hashWords(walk_.seed, kSplitTag + strands_.key[s], c);
            q = turnFrameTo(q, glm::normalize(q * coneDirection(cone, unitFloat(h), unitFloat(mix64(h)))));
        }
        strands_.add(hashWords(kChildTag, strands_.key[s], c), strands_.last[s], q, int32_t(s),
                     uint8_t(strands_.depth[s] + 1), strands_.cut_mask[s], recorded_child == kNone ? kNone : recorded_child + c);
    }
}

bool Growth::canAct(const StrandAction& action, uint32_t s) const {
    switch (action.kind) {
        case StrandActionKind::Split: return strands_.npoints[s] >= 2 && strands_.depth[s] < walk_.max_split_depth;
        case StrandActionKind::Countdown: return strands_.countdown[s] < 0;
        default: return true;
    }
}

const StrandAction& Growth::chosen(const StrandAction& action, uint32_t s, uint32_t step, uint32_t state) const {
    if (action.table.empty()) return action;
    if (action.choice == ActionChoice::Priority) {
        for (const StrandAction& a : action.table)
            if (canAct(a, s)) return a;
        return action.table.back();
    }
    double total = 0.0;
    for (const StrandAction& a : action.table) total += a.weight;
    const double u = unitDouble(hashWords(walk_.seed, kActionTag + strands_.key[s], step, state)) * total;
    double below = 0.0;
    for (const StrandAction& a : action.table) {
        below += a.weight;
        if (u < below) return a;
    }
    return action.table.back();
}

void Growth::turn(const StrandAction& action, uint32_t s, uint32_t step) {
    // About an axis across the heading (the frame's own z), at a hashed angle around it.
    const uint64_t h = hashWords(walk_.seed, kTurnTag + strands_.key[s], step);
    const float around = 2.0f * float(M_PI) * unitFloat(h);
    const glm::quat frame = strands_.frame[s];
    const glm::vec3 axis = frame * glm::vec3(std::cos(around), std::sin(around), 0.0f);
    strands_.frame[s] = glm::normalize(glm::angleAxis(glm::radians(action.turn_angle_deg), axis) * frame);
    strands_.age[s] = 0;
}

void Growth::apply(const StrandAction& table, uint32_t s, uint32_t step, uint32_t state) {
    const StrandAction& action = chosen(table, s, step, state);
    switch (action.kind) {
        case StrandActionKind::Stop: strands_.state[s] = StrandState::Stopped; break;
        case StrandActionKind::Kill:
            strands_.state[s] = StrandState::Killed;
            ++stats_.killed;
            break;
        case StrandActionKind::Split:
            // A strand that has not moved would split into copies of its parent's split; one beyond the
            // depth limit would split forever: both stop instead.
            if (!canAct(action, s))
                strands_.state[s] = StrandState::Stopped;
            else
                split(action, s);
            break;
        case StrandActionKind::Turn: turn(action, s, step); break;
        case StrandActionKind::Countdown:
            if (strands_.countdown[s] < 0) {
                strands_.countdown[s] = int32_t(action.countdown_steps);
                strands_.countdown_stops[s] = action.countdown_then == StrandActionKind::Stop;
            }
            break;
    }
}

void Growth::proposeAndTest(size_t k, uint32_t step) {
    propose(k, step);
    // Refused while choosing, or (retrying) already tested.
    if (moves_.blocked[k] || walk_.retry_refused) return;
    moves_.blocked[k] = earlierVerdict(k);
}

// The first verdict (before the test against this step's lower moves) of recorded move j.
static uint8_t firstVerdict(const GrowthRecord& r, uint32_t j) {
    return r.move_blocked[j] == 2 ? 0 : r.move_blocked[j];
}

void Growth::replayMove(size_t k, uint32_t step, bool everywhere) {
    Replay& rp = *replay_;
    const GrowthRecord& r = rp.record;
    const uint32_t j = rp.entry[k];
    const glm::vec3 p0 = points_.pos[strands_.last[active_[k]]];
    // Keeping distance or retrying, a proposal also reads the earlier segments near its trials.
    rp.proposed[k] = j == kNone || everywhere || rp.edit.reaches(p0) || rp.cutter_edit.reaches(p0) ||
                     (proposal_reads_segments_ && rp.changed_segments.anyNear(p0, [](uint32_t, uint32_t) { return true; }));
    if (rp.proposed[k]) {
        proposeAndTest(k, step);
        // A move a changed cutter clips is a changed move, whatever its place: the cutter's action may differ.
        rp.same[k] = j != kNone && moves_.pos[k] == r.move_pos[j] && moves_.dir[k] == r.move_dir[j] &&
                     moves_.cutter[k] == r.move_cutter[j] && !rp.cutter_edit.changed(moves_.cutter[k]) &&
                     moves_.still[k] == r.move_still[j] && moves_.blocked[k] == firstVerdict(r, j);
        return;
    }
    // The proposal is the record's, bit for bit, and so is the solid test (solids do not change).
    moves_.pos[k] = r.move_pos[j];
    moves_.dir[k] = r.move_dir[j];
    moves_.cutter[k] = r.move_cutter[j];
    moves_.still[k] = r.move_still[j];
    uint8_t blocked = firstVerdict(r, j);
    if ((blocked == 0 || blocked == 1) && walk_.collisions && !moves_.still[k] &&
        rp.changed_segments.anyNear(moveMidpoint(k), [](uint32_t, uint32_t) { return true; }))
        blocked = hitsEarlierSegment(k) ? 1 : 0;
    moves_.blocked[k] = blocked;
    rp.same[k] = blocked == firstVerdict(r, j);
}

// Finds each active strand's recorded move of this step. Strands identical to their record keep the
// record's relative order (ids follow birth step, then the parent's order, then the rank among siblings),
// so one merge pass finds them; one that is not found (it cannot happen) parts from its record instead.
void Growth::matchRecordedMoves(uint32_t step) {
    Replay& rp = *replay_;
    const GrowthRecord& r = rp.record;
    const uint32_t begin = r.stepBegin(r.step_moves, step), end = r.stepEnd(r.step_moves, step);
    rp.entry.assign(active_.size(), kNone);
    uint32_t j = begin;
    for (size_t k = 0; k < active_.size(); ++k) {
        const uint32_t s = active_[k], o = strands_.recorded[s];
        if (o == kNone) continue;
        uint32_t i = j;
        while (i < end && r.move_strand[i] != o) ++i;
        if (i == end) {
            assert(false && "a strand identical to its record is active in it");
            rp.parted[o] = 1;
            strands_.recorded[s] = kNone;
            continue;
        }
        rp.entry[k] = i;
        j = i + 1;
    }
    rp.same.assign(active_.size(), 0);
    rp.proposed.assign(active_.size(), 0);
}

bool Growth::hitsChangedMove(size_t k) const {
    return replay_->changed_moves.anyNear(moveMidpoint(k), [](uint32_t, uint32_t) { return true; });
}

// This step's moves against lower ids' moves. Re-growing, a move whose proposal and first verdict are
// the record's takes the record's verdict unless a changed move of this step lies within reach.
void Growth::testLowerMoves(uint32_t step) {
    if (replay_) {
        Replay& rp = *replay_;
        const GrowthRecord& r = rp.record;
        const uint32_t begin = r.stepBegin(r.step_moves, step), end = r.stepEnd(r.step_moves, step);
        rp.entry_same.assign(end - begin, 0);
        for (size_t k = 0; k < active_.size(); ++k)
            if (rp.entry[k] != kNone) rp.entry_same[rp.entry[k] - begin] = rp.same[k];
        rp.changed_moves.clear();
        for (size_t k = 0; k < active_.size(); ++k)
            if (!rp.same[k] && filed(k)) Replay::fileChanged(&rp.changed_moves, moveMidpoint(k));
        for (uint32_t j = begin; j < end; ++j)
            if (!rp.entry_same[j - begin] && !r.move_still[j] && (r.move_blocked[j] == 0 || r.move_blocked[j] == 2))
                Replay::fileChanged(&rp.changed_moves, 0.5f * (r.point_pos[r.move_from[j]] + r.move_pos[j]));
    }
    parallelFor(active_.size(), threads_, 512, [&](size_t begin, size_t end, int) {
        for (size_t k = begin; k < end; ++k) {
            if (moves_.blocked[k] || moves_.still[k]) continue;
            if (replay_ && replay_->same[k] && !hitsChangedMove(k))
                moves_.blocked[k] = replay_->record.move_blocked[replay_->entry[k]];
            else if (hitsLowerMove(k))
                moves_.blocked[k] = 2;
        }
    });
}

// After the actions of `step`: the recorded strands that parted from the new growth (and the children
// they had) now differ, so their recorded segments of this step are changed geometry from the next step on.
void Growth::partFromRecord(uint32_t step) {
    Replay& rp = *replay_;
    const GrowthRecord& r = rp.record;
    for (uint32_t o = r.stepBegin(r.step_strands, step); o < r.stepEnd(r.step_strands, step); ++o)
        if (r.strand_parent[o] >= 0 && rp.parted[size_t(r.strand_parent[o])]) rp.parted[o] = 1;
    if (!files_segments_) return;
    for (uint32_t p = r.stepBegin(r.step_points, step); p < r.stepEnd(r.step_points, step); ++p)
        if (rp.parted[r.point_strand[p]])
            Replay::fileChanged(&rp.changed_segments, 0.5f * (r.point_pos[r.point_prev[p]] + r.point_pos[p]));
}

// Appends the points of this step's accepted moves in id order and lists their segments for the grid
// (filing_). A move's point id is the number of points before it, so each move places its own on any
// thread. Ages advance here too. Nothing in it reads another strand, and the serial actions after it
// (a split appends strands) read only what it wrote for their own strand.
void Growth::placePoints() {
    point_at_.resize(active_.size() + 1);
    point_at_[0] = uint32_t(points_.pos.size());
    for (size_t k = 0; k < active_.size(); ++k) point_at_[k + 1] = point_at_[k] + uint32_t(movedTo(k));
    const size_t first = points_.pos.size(), placed = point_at_.back() - first;
    points_.pos.resize(first + placed);
    points_.prev.resize(first + placed);
    points_.strand.resize(first + placed);
    filing_.resize(files_segments_ ? placed : 0);
    stats_.moves += placed;
    parallelFor(active_.size(), threads_, 2048, [&](size_t begin, size_t end, int) {
        for (size_t k = begin; k < end; ++k) {
            if (moves_.blocked[k]) continue;
            const uint32_t s = active_[k];
            ++strands_.age[s];
            if (!movedTo(k)) continue;
            const uint32_t id = point_at_[k], from = strands_.last[s];
            points_.pos[id] = moves_.pos[k];
            points_.prev[id] = from;
            points_.strand[id] = s;
            if (files_segments_) filing_[id - first] = {id, s, segmentMidpoint(id)};
            strands_.last[s] = id;
            ++strands_.npoints[s];
        }
    });
}

bool Growth::run(Strands* out, std::string* error) {
    seed();
    if (record_) {
        record_->clear();
        record_->step_points = {0};
        record_->step_strands = {0};
        record_->step_moves = {0};
    }
    charge_.resize(scene_.attractors.size());
    for (uint32_t step = 1; step <= walk_.steps; ++step) {
        if (cancel_ && cancel_->load(std::memory_order_relaxed)) {
            if (error) *error = kGrowthCancelled;
            return false;
        }
        if (steps_done_) steps_done_->store(step - 1, std::memory_order_relaxed);
        active_.clear();
        for (uint32_t s = 0; s < strands_.size(); ++s)
            if (strands_.state[s] == StrandState::Active) active_.push_back(s);
        if (active_.empty()) break;
        // Children that never move add strands but no points: both are bounded by max_points.
        if (points_.pos.size() + active_.size() > walk_.max_points || strands_.size() > walk_.max_points) {
            if (error)
                *error = "walk.max_points: splits need more than " + std::to_string(walk_.max_points) +
                         " points or strands at step " + std::to_string(step);
            return false;
        }
        for (size_t a = 0; a < charge_.size(); ++a) charge_[a] = chargeAt(scene_.attractors[a].charge, step);
        moves_.resize(active_.size());
        proposals_ += active_.size();

        // Proposals and the test against earlier steps read only the state after step - 1.
        if (replay_) {
            matchRecordedMoves(step);
            const bool everywhere = replay_->edit.everywhereAt(step);
            parallelFor(active_.size(), threads_, 512, [&](size_t begin, size_t end, int) {
                for (size_t k = begin; k < end; ++k) replayMove(k, step, everywhere);
            });
        } else {
            parallelFor(active_.size(), threads_, 512, [&](size_t begin, size_t end, int) {
                for (size_t k = begin; k < end; ++k) proposeAndTest(k, step);
            });
        }
        if (walk_.collisions) {
            // Moves of this step, filed in id order; a move refused by an earlier segment never blocks.
            filing_.clear();
            for (size_t k = 0; k < active_.size(); ++k)
                if (filed(k)) filing_.push_back({uint32_t(k), active_[k], moveMidpoint(k)});
            step_grid_.build(filing_, threads_);
            testLowerMoves(step);
        }
        if (record_) {
            GrowthRecord& r = *record_;
            r.step_moves.push_back(uint32_t(r.move_strand.size()));
            r.step_points.push_back(uint32_t(points_.pos.size()));
            r.step_strands.push_back(uint32_t(strands_.size()));
            for (size_t k = 0; k < active_.size(); ++k) {
                r.move_strand.push_back(active_[k]);
                r.move_from.push_back(strands_.last[active_[k]]);
            }
            r.move_pos.insert(r.move_pos.end(), moves_.pos.begin(), moves_.pos.end());
            r.move_dir.insert(r.move_dir.end(), moves_.dir.begin(), moves_.dir.end());
            r.move_cutter.insert(r.move_cutter.end(), moves_.cutter.begin(), moves_.cutter.end());
            r.move_blocked.insert(r.move_blocked.end(), moves_.blocked.begin(), moves_.blocked.end());
            r.move_still.insert(r.move_still.end(), moves_.still.begin(), moves_.still.end());
        }

        // The strands that move (or are clipped where they stand) turn their frames to their moves, each
        // on its own, before the serial actions that may turn or split them.
        parallelFor(active_.size(), threads_, 512, [&](size_t begin, size_t end, int) {
            for (size_t k = begin; k < end; ++k)
                if (moves_.blocked[k] == 0) strands_.frame[active_[k]] = turnFrameTo(strands_.frame[active_[k]], moves_.dir[k]);
        });
        placePoints();
        // Actions, serially in id order: children get their ids in that order.
        for (size_t k = 0; k < active_.size(); ++k) {
            const uint32_t s = active_[k];
            if (replay_) {
                const uint32_t j = replay_->entry[k];
                replay_->reused += !replay_->proposed[k];
                replay_->recomputed += replay_->proposed[k];
                // A strand whose move or verdict differs from its record's parts from it for good.
                if (strands_.recorded[s] != kNone &&
                    !(replay_->same[k] && moves_.blocked[k] == replay_->record.move_blocked[j])) {
                    replay_->parted[strands_.recorded[s]] = 1;
                    strands_.recorded[s] = kNone;
                }
                // The segment it placed (placePoints) is changed geometry once the strand has parted.
                if (files_segments_ && movedTo(k) && strands_.recorded[s] == kNone) {
                    const glm::vec3 mid = segmentMidpoint(strands_.last[s]);
                    Replay::fileChanged(&replay_->changed_segments, mid);
                }
            }
            const bool counting = strands_.countdown[s] >= 0;
            if (moves_.blocked[k] == 4) {
                ++stats_.crowded;
                apply(walk_.on_distance, s, step, kDistanceState);
            } else if (moves_.blocked[k]) {
                ++(moves_.blocked[k] == 3 ? stats_.solid_hits : stats_.collisions);
                apply(walk_.on_collision, s, step, 0);
            } else if (moves_.cutter[k] >= 0) {
                ++stats_.cutter_hits;
                strands_.cut_mask[s] |= 1u << moves_.cutter[k];
                const uint32_t c = uint32_t(moves_.cutter[k]);
                apply(scene_.cutters[c].action, s, step, 2 + c);
            } else if (walk_.max_age_steps > 0 && strands_.age[s] >= walk_.max_age_steps) {
                apply(walk_.on_age, s, step, 1);
            }
            // A countdown started in an earlier step runs out here, whatever happened in this one.
            if (counting && strands_.state[s] == StrandState::Active && --strands_.countdown[s] <= 0) {
                if (strands_.countdown_stops[s]) {
                    strands_.state[s] = StrandState::Stopped;
                } else {
                    strands_.state[s] = StrandState::Killed;
                    ++stats_.killed;
                }
            }
        }
        // Filed after the actions, which read no segment: the next step's proposals are the first to.
        if (files_segments_) grid_.insert(filing_, threads_);
        if (replay_) partFromRecord(step);
    }
    emit(out);
    if (record_) keepRecord();
    if (steps_done_) steps_done_->store(walk_.steps, std::memory_order_relaxed);
    return true;
}

// Swaps the growth's points and strands into the record (after emit, the last reader); the workspace gets
// the record's old arrays, whose memory the next growth reuses.
void Growth::keepRecord() {
    GrowthRecord& r = *record_;
    r.step_moves.push_back(uint32_t(r.move_strand.size()));
    r.step_points.push_back(uint32_t(points_.pos.size()));
    r.step_strands.push_back(uint32_t(strands_.size()));
    std::swap(r.point_pos, points_.pos);
    std::swap(r.point_prev, points_.prev);
    std::swap(r.point_strand, points_.strand);
    std::swap(r.strand_parent, strands_.parent);
    std::swap(r.strand_first_child, strands_.first_child);
}

void Growth::emit(Strands* out) const {
    out->clear();  // its memory kept: a re-growth writes where the last growth's strands were
    out->stats = stats_;
    out->stats.strands = strands_.size();
    // Which strands come out and where their points go, serially (a parent always precedes its children
    // and, having split, has moved and was not killed); then each chain is walked back on its own.
    std::vector<int32_t> index(strands_.size(), -1);
    for (uint32_t s = 0; s < strands_.size(); ++s) {
        if (strands_.state[s] == StrandState::Killed) continue;
        if (strands_.npoints[s] < 2) {
            ++out->stats.dropped;
            continue;
        }
        index[s] = int32_t(out->size());
        out->offsets.push_back(out->offsets.back() + strands_.npoints[s]);
        out->parent.push_back(strands_.parent[s] >= 0 ? index[size_t(strands_.parent[s])] : -1);
        out->particle.push_back(s);
    }
    warmArray(out->points, out->offsets.back());  // a re-growth's strands may have a few more points
    out->points.resize(out->offsets.back());
    parallelFor(out->particle.size(), threads_, 1024, [&](size_t begin, size_t end, int) {
        for (size_t i = begin; i < end; ++i) {
            const uint32_t s = out->particle[i];
            size_t at = out->offsets[i + 1];
            for (uint32_t p = strands_.last[s];; p = points_.prev[p]) {
                out->points[--at] = points_.pos[p];
                if (p == strands_.first[s]) break;
            }
            assert(at == out->offsets[i]);
        }
    });
    warmArray(out->radii, out->points.size());
    out->radii.assign(out->points.size(), walk_.strand_radius_m);
}

}  // namespace

namespace {

// Checks what validateParticleScene cannot: a file is read (and checked) before a project gives it its
// terrain and its objects.
bool placedInAProject(const ParticleScene& scene, std::string* error) {
    for (size_t i = 0; i < scene.generators.size(); ++i) {
        const ParticleGenerator& g = scene.generators[i];
        if (g.on_terrain && (!scene.terrain || scene.terrain->empty())) {
            if (error)
                *error = "generators[" + std::to_string(i) +
                         "].on_terrain: needs a terrain: grow the system from a project that has one (its \"particles\")";
            return false;
        }
        if (g.kind == GeneratorKind::Objects && (!g.mesh || g.mesh->triangleCount() == 0)) {
            if (error)
                *error = "generators[" + std::to_string(i) + "].object_type: no '" + g.object_type +
                         "' object to seed on: grow the system from a project that has them (its \"particles\")";
            return false;
        }
        if (g.kind == GeneratorKind::Details && (!g.mesh || g.mesh->triangleCount() == 0)) {
            if (error)
                *error = "generators[" + std::to_string(i) + "].detail_type: no '" + g.detail_type +
                         "' instance to seed on in its box: grow the system from a project that instantiates them (its "
                         "\"particles\")";
            return false;
        }
    }
    return true;
}

}  // namespace

bool growStrands(const ParticleScene& scene, const GrowOptions& options, Strands* out, std::string* error) {
    if (!validateParticleScene(scene, error) || !placedInAProject(scene, error)) return false;
    GrowthWorkspace memory;
    Growth growth(scene, options, &memory);
    return growth.run(out, error);
}

StrandRegrower::StrandRegrower() = default;
StrandRegrower::~StrandRegrower() = default;

void StrandRegrower::reset() {
    record_.reset();
    report_ = {};
}

bool StrandRegrower::grow(const ParticleScene& scene, const GrowOptions& options, Strands* out, std::string* error) {
    if (!validateParticleScene(scene, error) || !placedInAProject(scene, error)) {
        reset();
        return false;
    }
    if (!next_) next_ = std::make_unique<GrowthRecord>();
    if (!memory_) memory_ = std::make_unique<GrowthWorkspace>();
    Growth growth(scene, options, memory_.get());
    if (record_ && regrowable(scene_, scene)) growth.replayFrom(*record_, scene_);
    growth.recordInto(next_.get());
    if (!growth.run(out, error)) {
        // Cancelled: the record of the last finished growth still describes scene_, so the next growth
        // (the edit undone, say) is incremental from it.
        if (!(options.cancel && options.cancel->load())) reset();
        return false;
    }
    report_ = growth.report();
    // The new record replaces the old, whose memory the next growth reuses.
    std::swap(record_, next_);
    scene_ = scene;
    // The next growth writes a record into next_ and points into the workspace. Where their memory is
    // new (after the first growth), its pages are brought in now: faulted in by the first edit, they
    // made it as slow as the full growth (docs/particles.md).
    // Its point arrays come to the workspace after that growth, for the one after it: they are warmed
    // too, so that the first edits' growths find all three sets of points in memory.
    // The record's points were the workspace's, reserved by the growth (seed): that room, no more.
    if (!next_) next_ = std::make_unique<GrowthRecord>();
    const size_t point_room = record_->point_pos.capacity();
    next_->warmLike(*record_, point_room);
    memory_->warmLike(*record_, point_room);
    return true;
}

}  // namespace ug
