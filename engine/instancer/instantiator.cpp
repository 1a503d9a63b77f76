// The instantiator's machinery. Reading order: Prepared (per-candidate anchors in tile space), TileState
// (the alive candidates of one tile with their keys and memoized statuses), computeTile (culling,
// acceptance, constraints, keys: the hot path), Resolver (the lazy lexicographically-first independent
// set), then the drivers: full, incremental and region.
#include "instancer/instantiator.h"

#include <algorithm>
#include <cassert>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <mutex>
#include <queue>
#include <unordered_map>

#include "core/hash.h"
#include "core/parallel.h"
#include "instancer/tile_coord.h"

namespace ug {

namespace {

// InstanceOptions::fraction: computing the tiles is the first 60 % of a full run, resolving them the rest.
constexpr float kComputeShare = 0.6f;

// Raises *a to v (never lowers it: workers finish out of order).
void storeMax(std::atomic<float>* a, float v) {
    float cur = a->load(std::memory_order_relaxed);
    while (cur < v && !a->compare_exchange_weak(cur, v, std::memory_order_relaxed)) {
    }
}

}  // namespace

namespace {

constexpr int32_t kEmptyTile = -1;    // a neighbour tile known to hold no alive candidate
constexpr int32_t kUnknownTile = -2;  // a neighbour tile not computed yet (region mode only)

constexpr uint8_t kUnknown = 0;
constexpr uint8_t kSelected = 1;
constexpr uint8_t kRejected = 2;
constexpr uint8_t kQueued = 0x80;  // update(): the candidate waits in the priority queue
constexpr uint8_t kStatusMask = 0x7f;

// Tiles are grouped into blocks of kBlock^3 for the first, coarse culling pass.
constexpr int kBlock = 8;
// Hard limits, refused before any per-tile memory is taken.
constexpr uint64_t kMaxBlocks = 4ull << 20;  // 2G tiles; larger worlds are cut into --region jobs

// Random-number streams of hashWords(seed, tile, j, stream).
constexpr uint64_t kStreamAccept = 1;
constexpr uint64_t kStreamWeight = 2;

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Per-candidate data derived once from the Ghost Tile and the models.
struct Prepared {
    float s = 0.5f;
    uint32_t n = 0;
    std::vector<uint32_t> anchor_begin;   // n + 1
    std::vector<glm::vec3> anchors;       // tile space: p_j + R_j (scale_j a_k)
    std::vector<glm::vec3> z_axis;        // R_j * +Z
    std::vector<float> reach;             // per type: the farthest anchor from its candidate's origin
    float max_reach = 0.0f;
    // The sink test's spheres: per candidate its kSinkSpheres lowest (by bottom), relative to its origin.
    std::vector<glm::vec4> low_spheres;   // xyz centre offset, w radius; kSinkSpheres per candidate
    // Every (type, variant) range [b, e) of candidate ids, permuted by the lowest anchor's z (tile space):
    // z_order[b..e) and z_low[k] = that z of z_order[k]. A thin layer's positive box holds a few percent of
    // a tile's height; two binary searches find the candidates whose anchors can lie in it, so the others
    // are never looked at (they would all be culled).
    std::vector<uint32_t> z_order;
    std::vector<float> z_low;
};

constexpr uint32_t kSinkSpheres = 4;

Prepared prepare(const InstancerInput& in) {
    Prepared p;
    const CandidateSet& c = in.tile->candidates;
    p.s = in.tile->settings.tile_size_m;
    p.n = c.size();
    p.anchor_begin.reserve(p.n + 1);
    p.anchor_begin.push_back(0);
    p.z_axis.resize(p.n);
    p.reach.assign(c.typeCount(), 0.0f);
    for (uint32_t j = 0; j < p.n; ++j) {
        const DetailModel& m = *in.models[c.type[j]];
        for (const glm::vec3& a : m.anchors) {
            const glm::vec3 offset = c.rotation[j] * (c.scale[j] * a);
            p.anchors.push_back(c.position[j] + offset);
            p.reach[c.type[j]] = std::max(p.reach[c.type[j]], glm::length(offset));
        }
        p.anchor_begin.push_back(uint32_t(p.anchors.size()));
        p.z_axis[j] = c.rotation[j] * glm::vec3(0.0f, 0.0f, 1.0f);
        std::vector<glm::vec4> spheres;
        for (const Sphere& sp : m.spheres)
            spheres.push_back(glm::vec4(c.rotation[j] * (c.scale[j] * sp.center), c.scale[j] * sp.radius));
        std::stable_sort(spheres.begin(), spheres.end(),
                         [](const glm::vec4& a, const glm::vec4& b) { return a.z - a.w < b.z - b.w; });
        for (uint32_t k = 0; k < kSinkSpheres; ++k)
            p.low_spheres.push_back(k < spheres.size() ? spheres[k] : (spheres.empty() ? glm::vec4(0.0f) : spheres[0]));
    }
    p.z_order.resize(p.n);
    p.z_low.resize(p.n);
    std::vector<float> lowest(p.n, std::numeric_limits<float>::infinity());
    for (uint32_t j = 0; j < p.n; ++j)
        for (uint32_t k = p.anchor_begin[j]; k < p.anchor_begin[j + 1]; ++k) lowest[j] = std::min(lowest[j], p.anchors[k].z);
    for (uint32_t t = 0; t < c.typeCount(); ++t)
        for (uint32_t v = 0; v < c.variants; ++v) {
            const uint32_t b = c.variantBegin(t, v), e = c.variantEnd(t, v);
            for (uint32_t j = b; j < e; ++j) p.z_order[j] = j;
            std::stable_sort(p.z_order.begin() + b, p.z_order.begin() + e,
                             [&](uint32_t x, uint32_t y) { return lowest[x] < lowest[y]; });
            for (uint32_t k = b; k < e; ++k) p.z_low[k] = lowest[p.z_order[k]];
        }
    // Pad against rounding in the world-space sums: reach only decides which boxes to look at.
    for (float& r : p.reach) r = r * 1.001f + 1e-4f;
    for (float r : p.reach) p.max_reach = std::max(p.max_reach, r);
    return p;
}

bool originInside(const Bounds& b, glm::vec3 p) {  // half-open [lo, hi): regions partition space
    return b.lo.x <= p.x && p.x < b.hi.x && b.lo.y <= p.y && p.y < b.hi.y && b.lo.z <= p.z && p.z < b.hi.z;
}

Bounds expand(const Bounds& b, float r) { return Bounds{b.lo - r, b.hi + r}; }

bool finiteBounds(const Bounds& b) {
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(b.lo[a]) || !std::isfinite(b.hi[a])) return false;
    return true;
}

// Bits set in w. std::popcount is a libgcc call on the x86-64 baseline (no POPCNT guaranteed), and the
// resolver ranks a candidate at every alive neighbour it meets: inlined, it is a dozen instructions.
inline uint32_t bitCount(uint64_t w) {
    w = w - ((w >> 1) & 0x5555555555555555ull);
    w = (w & 0x3333333333333333ull) + ((w >> 2) & 0x3333333333333333ull);
    w = (w + (w >> 4)) & 0x0f0f0f0f0f0f0f0full;
    return uint32_t((w * 0x0101010101010101ull) >> 56);
}

struct TileState {
    uint64_t key = 0;
    glm::ivec3 coord{0};
    // Views of one block (`memory`), allocated once at its final size: a tile used to make a dozen
    // allocations (six arrays, two of them grown one candidate at a time), and a scattered layer has
    // hundreds of thousands of tiles. The resolver reads one neighbour's bits, ranks, priorities and
    // statuses together, so they also share cache lines and pages now.
    std::span<uint32_t> alive;     // candidate ids, ascending
    std::span<uint64_t> priority;  // per alive candidate
    std::span<uint8_t> status;     // per alive candidate; accessed through atomic_ref while resolving
    std::span<uint64_t> bits;      // alive bitset over the Ghost Tile's candidates
    std::span<uint32_t> rank;      // alive count before each 64-bit word
    std::unique_ptr<std::byte[]> memory;  // bytes: storage for objects of several types
    int32_t neighbour[kOffsetCount];
    // Counters of the computation that produced this state.
    uint32_t tested = 0, culled = 0, density_rejected = 0, constraint_rejected = 0;

    uint8_t load(uint32_t a) const {
        return std::atomic_ref<uint8_t>(const_cast<uint8_t&>(status[a])).load(std::memory_order_relaxed);
    }
    void store(uint32_t a, uint8_t v) {
        std::atomic_ref<uint8_t>(status[a]).store(v, std::memory_order_relaxed);
    }
    // Sizes the views for `count` alive candidates over `words` bitset words: bits zero, statuses unknown.
    void allocate(uint32_t count, uint32_t words) {
        const size_t wide = size_t(count) + words;           // priorities, bits
        const size_t narrow = size_t(words) + count;         // ranks, ids
        const size_t bytes = wide * 8 + narrow * 4 + count;  // and statuses
        // new[] of bytes is aligned for every fundamental type; the 8-byte views come first.
        memory.reset(new std::byte[bytes]);
        priority = {reinterpret_cast<uint64_t*>(memory.get()), count};
        bits = {priority.data() + count, words};
        rank = {reinterpret_cast<uint32_t*>(bits.data() + words), words};
        alive = {rank.data() + words, count};
        status = {reinterpret_cast<uint8_t*>(alive.data() + count), count};
        std::fill(bits.begin(), bits.end(), 0);
        std::fill(status.begin(), status.end(), kUnknown);
    }
    // The alive index of candidate j, or -1.
    int64_t find(uint32_t j) const {
        const uint64_t w = bits[j >> 6];
        const uint64_t bit = uint64_t(1) << (j & 63);
        if (!(w & bit)) return -1;
        return int64_t(rank[j >> 6]) + bitCount(w & (bit - 1));
    }
};

struct TypeRuntime {
    const DensityField* field = nullptr;
    bool direction_uses_list = false;  // the direction field is the type's own field: reuse the tile list
    bool size_uses_list = false;
};

// Scratch of one worker, reused across tiles.
struct TileScratch {
    TileFieldList list;
    std::vector<uint32_t> survivors;
    std::vector<glm::vec3> points;
    std::vector<float> first_values;
    std::vector<uint32_t> second;  // survivors (indices) whose first anchor is positive
    std::vector<float> values;
    std::vector<uint32_t> scan_alive;                    // alive candidates in scan (z) order ...
    std::vector<uint64_t> scan_priority;                 // ... and their priorities, before ranking by id
};

}  // namespace

class Instantiator::Engine {
public:
    InstancerInput input;
    Prepared prep;
    std::vector<TypeRuntime> runtime;
    std::vector<TileFieldList> global_lists;  // per type, over the extent padded by the reach
    bool complete = true;  // every tile that can hold an alive candidate is in the map (full mode)
    Bounds region = Bounds::everything();  // region mode: candidates whose origin is here are wanted

    std::vector<TileState> tiles;
    std::unordered_map<uint64_t, int32_t> index;  // packed tile -> tiles[]
    InstanceStore store;
    bool instantiated = false;

    bool setInput(InstancerInput in, std::string* error);
    void refreshRuntime();

    // ---- tile computation ----
    void computeTile(TileState* ts, const std::vector<const TileFieldList*>& parents, TileScratch* scratch) const;
    // With `plan_only`: stops after planning (pass 1) and stores what the computation would hold there.
    bool enumerateAndCompute(const Bounds& box, const InstanceOptions& options, std::vector<TileState>* out,
                             std::string* error, RegionFootprint* plan_only = nullptr) const;
    // Computes the given tiles one by one (no block pass), in parallel: dirty tiles, lazily needed tiles.
    std::vector<TileState> computeTiles(const std::vector<uint64_t>& keys, const InstanceOptions& options) const;
    // `threads` links the tiles in parallel when the engine holds none yet (a full or region run).
    void install(std::vector<TileState>&& computed, std::vector<int32_t>* installed, int threads = 1);
    void link(int32_t t);
    void linkAround(int32_t t);

    // ---- resolution ----
    bool resolveTiles(const std::vector<int32_t>& which, const InstanceOptions& options,
                      std::vector<glm::ivec3>* missing, uint64_t* resolved);

    void rebuildStore();
    void fillStats(InstanceStats* stats) const;
};

// ---- input ---------------------------------------------------------------------------------------------

namespace {

bool validateInput(const InstancerInput& in, std::string* error) {
    auto fail = [&](const std::string& what) {
        if (error) *error = what;
        return false;
    };
    if (!in.tile) return fail("instancer: no Ghost Tile");
    const GhostTile& gt = *in.tile;
    const uint32_t type_count = gt.candidates.typeCount();
    if (in.models.size() != type_count || in.types.size() != type_count)
        return fail("instancer: the Ghost Tile has " + std::to_string(type_count) + " detail types, got " +
                    std::to_string(in.models.size()) + " models and " + std::to_string(in.types.size()) +
                    " instancing settings");
    if (!finiteBounds(in.extent) || in.extent.empty())
        return fail("instancer: the scene extent must be finite and non-empty");
    const float s = gt.settings.tile_size_m;
    for (int a = 0; a < 3; ++a)
        if (std::fabs(in.extent.lo[a]) / s >= float(kTileCoordLimit - 2) ||
            std::fabs(in.extent.hi[a]) / s >= float(kTileCoordLimit - 2))
            return fail("instancer: the scene extent reaches beyond ±" +
                        std::to_string(int64_t(double(kTileCoordLimit) * s)) + " m (" +
                        std::to_string(kTileCoordLimit) + " tiles of " + std::to_string(s) + " m)");
    if (gt.graph.nodeCount() != gt.candidates.size()) return fail("instancer: the Ghost Tile's graph is inconsistent");
    const uint32_t variants = gt.candidates.variants;
    if (variants < 1 || variants > kMaxTileVariants) return fail("instancer: the Ghost Tile's variant count is out of range");
    for (uint32_t i = 0; i < type_count; ++i)
        if ((gt.candidates.type_begin[i + 1] - gt.candidates.type_begin[i]) % variants != 0)
            return fail("instancer: the Ghost Tile's candidates do not split into its variants");
    for (uint32_t i = 0; i < type_count; ++i) {
        const std::string where = "detail type " + std::to_string(i) + " ('" +
                                  (in.models[i] ? in.models[i]->name : std::string("?")) + "'): ";
        if (!in.models[i]) return fail(where + "no model");
        if (in.models[i]->anchors.empty()) return fail(where + "the model has no anchor points");
        const InstanceTypeSettings& t = in.types[i];
        std::string e;
        if (t.field && !validate(*t.field, &e)) return fail(where + "density field: " + e);
        if (!std::isfinite(t.layer_m) || !(t.layer_m > 0.0f))
            return fail(where + "layer_m must be finite and > 0");
        if (int(t.strategy) > int(PriorityStrategy::DistanceToBoundary)) return fail(where + "unknown strategy");
        if (t.orientation.enabled) {
            if (!std::isfinite(t.orientation.min_cos) || t.orientation.min_cos < -1.0f || t.orientation.min_cos > 1.0f)
                return fail(where + "orientation min_cos must be in [-1, 1]");
            if (!validate(t.orientation.direction, &e)) return fail(where + "orientation: " + e);
        }
        if (t.sink.enabled() && !(std::isfinite(t.sink.max_sink_m) && t.sink.max_sink_m >= 0.0f))
            return fail(where + "max_sink_m must be finite and >= 0");
        if (t.size.enabled) {
            if (!std::isfinite(t.size.tolerance) || t.size.tolerance < 0.0f)
                return fail(where + "size tolerance must be finite and >= 0");
            if (!validate(t.size.target, &e)) return fail(where + "size: " + e);
        }
    }
    return true;
}

}  // namespace

bool Instantiator::Engine::setInput(InstancerInput in, std::string* error) {
    if (!validateInput(in, error)) return false;
    input = std::move(in);
    prep = prepare(input);
    tiles.clear();
    index.clear();
    store.clear();
    instantiated = false;
    refreshRuntime();
    return true;
}

void Instantiator::Engine::refreshRuntime() {
    runtime.assign(input.types.size(), TypeRuntime{});
    global_lists.assign(input.types.size(), TileFieldList{});
    for (size_t i = 0; i < input.types.size(); ++i) {
        const InstanceTypeSettings& t = input.types[i];
        TypeRuntime& r = runtime[i];
        r.field = t.field.get();
        r.direction_uses_list = t.orientation.direction.kind == DirectionFieldKind::Gradient &&
                                t.orientation.direction.field.get() == r.field;
        r.size_uses_list = t.size.target.kind == SizeFieldKind::Ramp && t.size.target.field.get() == r.field;
        if (r.field) buildTileList(*r.field, expand(input.extent, prep.max_reach + prep.s), &global_lists[i]);
    }
}

// ---- one tile: culling, acceptance, constraints, keys ------------------------------------------------

void Instantiator::Engine::computeTile(TileState* ts, const std::vector<const TileFieldList*>& parents,
                                       TileScratch* scratch) const {
    const CandidateSet& c = input.tile->candidates;
    const glm::vec3 origin = tileOrigin(ts->coord, prep.s);
    const Bounds tile_box{origin, origin + prep.s};
    const uint64_t tile_key = ts->key;
    // Alive candidates are gathered in the scratch (in scan order) and copied once, by id, at the end:
    // the tile's own arrays are allocated once, at their final size.
    auto& scan_alive = scratch->scan_alive;
    auto& scan_priority = scratch->scan_priority;
    scan_alive.clear();
    scan_priority.clear();
    // The tile holds one variant: the other variants' candidates are never alive here, so the resolver,
    // which looks neighbours up by candidate id (TileState::find), never sees them.
    const uint32_t variant = tileVariant(input.seed, tile_key, c.variants);

    for (uint32_t i = 0; i < c.typeCount(); ++i) {
        const uint32_t begin = c.variantBegin(i, variant), end = c.variantEnd(i, variant);
        const TypeRuntime& rt = runtime[i];
        const InstanceTypeSettings& settings = input.types[i];
        if (!rt.field || !parents[i]) continue;  // nothing of this type can live here: not even tested
        ts->tested += end - begin;
        TileFieldList& list = scratch->list;
        buildTileList(*rt.field, expand(tile_box, prep.reach[i]), &list, parents[i]);
        const Bounds positive = list.empty() ? Bounds{} : positiveBoundsIn(*rt.field, list);
        if (positive.empty()) {
            ts->culled += end - begin;
            continue;
        }
        // Cheap culling first: every anchor must lie where the field can be positive. Only candidates whose
        // lowest anchor lies in the box's z range (widened by more than the rounding of origin + anchor)
        // can pass; the exact test below decides for those.
        const float slack = 1e-5f + 4e-7f * (std::abs(origin.z) + prep.s);
        const auto z_first = prep.z_low.begin() + begin, z_last = prep.z_low.begin() + end;
        const uint32_t scan_begin = uint32_t(std::lower_bound(z_first, z_last, positive.lo.z - origin.z - slack) -
                                             prep.z_low.begin());
        const uint32_t scan_end = std::max(scan_begin, uint32_t(std::upper_bound(z_first, z_last, positive.hi.z - origin.z + slack) -
                                                                prep.z_low.begin()));
        ts->culled += (end - begin) - (scan_end - scan_begin);
        scratch->survivors.clear();
        scratch->points.clear();
        for (uint32_t z = scan_begin; z < scan_end; ++z) {
            const uint32_t j = prep.z_order[z];
            const glm::vec3 o = origin + c.position[j];
            bool keep = originInside(input.extent, o);
            for (uint32_t k = prep.anchor_begin[j]; keep && k < prep.anchor_begin[j + 1]; ++k)
                keep = contains(positive, origin + prep.anchors[k]);
            if (!keep) {
                ++ts->culled;
                continue;
            }
            scratch->survivors.push_back(j);
            scratch->points.push_back(origin + prep.anchors[prep.anchor_begin[j]]);
        }
        // Two stages: the first anchor of every survivor, then the other anchors of those it did not
        // cull (most candidates of a thin layer fall out at the first).
        scratch->first_values.resize(scratch->points.size());
        evaluateBatch(*rt.field, &list, scratch->points.data(), scratch->points.size(), scratch->first_values.data());
        scratch->points.clear();
        scratch->second.clear();
        for (size_t k = 0; k < scratch->survivors.size(); ++k) {
            const uint32_t j = scratch->survivors[k];
            if (!(scratch->first_values[k] > 0.0f)) {
                ++ts->culled;
                continue;
            }
            scratch->second.push_back(uint32_t(k));
            for (uint32_t a = prep.anchor_begin[j] + 1; a < prep.anchor_begin[j + 1]; ++a)
                scratch->points.push_back(origin + prep.anchors[a]);
        }
        scratch->values.resize(scratch->points.size());
        evaluateBatch(*rt.field, &list, scratch->points.data(), scratch->points.size(), scratch->values.data());

        size_t v = 0;
        for (uint32_t k : scratch->second) {
            const uint32_t j = scratch->survivors[k];
            const uint32_t count = prep.anchor_begin[j + 1] - prep.anchor_begin[j];
            const float* rest = scratch->values.data() + v;
            v += count - 1;
            bool positive_everywhere = true;
            float sum = 0.0f;
            sum += scratch->first_values[k];  // the same order of additions as one pass over the anchors
            for (uint32_t a = 0; a + 1 < count; ++a) {
                positive_everywhere = positive_everywhere && rest[a] > 0.0f;
                sum += rest[a];
            }
            if (!positive_everywhere) {
                ++ts->culled;
                continue;
            }
            const float mean = sum / float(count);
            const float u = unitFloat(hashWords(input.seed, tile_key, j, kStreamAccept));
            if (!(u < std::min(1.0f, mean))) {
                ++ts->density_rejected;
                continue;
            }
            const glm::vec3 o = origin + c.position[j];
            if (settings.orientation.enabled) {
                const glm::vec3 u_dir = evaluateDirection(settings.orientation.direction,
                                                          rt.direction_uses_list ? &list : nullptr, o);
                if (glm::dot(prep.z_axis[j], u_dir) < settings.orientation.min_cos) {
                    ++ts->constraint_rejected;
                    continue;
                }
            }
            if (settings.size.enabled) {
                const float target = evaluateSize(settings.size.target, rt.size_uses_list ? &list : nullptr, o);
                if (!(std::fabs(c.scale[j] / target - 1.0f) <= settings.size.tolerance)) {
                    ++ts->constraint_rejected;
                    continue;
                }
            }
            if (settings.sink.enabled()) {
                const HeightField* terrain = settings.sink.terrain.get();
                bool sunk = false;
                for (uint32_t low = 0; low < kSinkSpheres && !sunk; ++low) {
                    const glm::vec4 sp = prep.low_spheres[size_t(j) * kSinkSpheres + low];
                    const float ground = terrain ? terrain->sample(o.x + sp.x, o.y + sp.y) : settings.sink.ground_z;
                    sunk = ground - (o.z + sp.z - sp.w) > settings.sink.max_sink_m;
                }
                if (sunk) {
                    ++ts->constraint_rejected;
                    continue;
                }
            }
            // Key, part 1: the strategy's layer (smaller first).
            double layer = 0.0;
            if (settings.strategy == PriorityStrategy::Elevation) {
                layer = std::floor(double(o.z) / double(settings.layer_m));
            } else if (settings.strategy == PriorityStrategy::DistanceToBoundary) {
                glm::vec4 g;
                evaluateBatchWithGradient(*rt.field, &list, &o, 1, &g);
                const float grad = glm::length(glm::vec3(g));
                // f / |∇f| estimates the distance to the boundary f = 0 (exact for linear fields).
                const float d = grad > 1e-6f ? std::max(0.0f, g.w) / grad : 1e6f;
                layer = std::floor(double(d) / double(settings.layer_m));
            }
            layer = std::clamp(layer, -2147483648.0, 2147483647.0);
            const uint32_t layer_bits = uint32_t(int32_t(layer)) ^ 0x80000000u;
            // Key, part 2: Efraimidis–Spirakis, ordered by -ln(u')/w (smaller first <=> larger u'^(1/w)).
            const float u2 = (float(hashWords(input.seed, tile_key, j, kStreamWeight) >> 40) + 0.5f) * (1.0f / 16777216.0f);
            float e = -std::log(u2) / mean;
            if (!(e <= std::numeric_limits<float>::max())) e = std::numeric_limits<float>::max();
            uint32_t e_bits;
            std::memcpy(&e_bits, &e, 4);  // e >= 0: the bit pattern orders like the value
            scan_alive.push_back(j);
            scan_priority.push_back((uint64_t(layer_bits) << 32) | e_bits);
        }
    }

    // The alive bitset and its ranks: TileState::find ranks candidates by id, so alive is kept by id.
    ts->allocate(uint32_t(scan_alive.size()), (prep.n + 63) / 64);
    for (uint32_t j : scan_alive) ts->bits[j >> 6] |= uint64_t(1) << (j & 63);
    uint32_t running = 0;
    for (uint32_t w = 0; w < ts->bits.size(); ++w) {
        ts->rank[w] = running;
        running += bitCount(ts->bits[w]);
    }
    // The scan went in z order: each candidate goes to its rank (no sort needed).
    for (size_t k = 0; k < scan_alive.size(); ++k) {
        const size_t a = size_t(ts->find(scan_alive[k]));
        ts->alive[a] = scan_alive[k];
        ts->priority[a] = scan_priority[k];
    }
    std::fill(std::begin(ts->neighbour), std::end(ts->neighbour), complete ? kEmptyTile : kUnknownTile);
}

// Computes every tile of `box` (clipped to the extent) that may hold an alive candidate. Tiles a coarse
// block test proves empty are not produced (in complete mode, absence means empty).
bool Instantiator::Engine::enumerateAndCompute(const Bounds& box_in, const InstanceOptions& options,
                                               std::vector<TileState>* out, std::string* error,
                                               RegionFootprint* plan_only) const {
    const Bounds box = intersect(box_in, input.extent);
    out->clear();
    if (plan_only) *plan_only = RegionFootprint{};
    if (box.empty()) return true;
    const float s = prep.s;
    const glm::ivec3 tlo = tileOf(box.lo, s), thi = tileOf(box.hi, s);
    const glm::ivec3 nblocks = (thi - tlo) / kBlock + 1;
    const uint64_t block_count = uint64_t(nblocks.x) * uint64_t(nblocks.y) * uint64_t(nblocks.z);
    if (block_count > kMaxBlocks) {
        if (error)
            *error = "instancer: the scene extent spans " + std::to_string(block_count * kBlock * kBlock * kBlock) +
                     " tiles of " + std::to_string(s) + " m; refusing (more than " +
                     std::to_string(kMaxBlocks * kBlock * kBlock * kBlock) + ")";
        return false;
    }
    const int threads = resolveThreadCount(options.threads);
    const size_t type_count = input.types.size();

    // Worst case per planned tile: every candidate of its variant alive (13 bytes each), the alive bitset
    // and ranks (over all variants' ids), the tile's own state and its place in the plan. The budget is a
    // tile count, checked while planning: pass 1 holds no per-tile memory, so a world too dense for the
    // budget is refused before anything large is allocated.
    const uint32_t per_variant = input.tile->candidates.perVariantSize();
    const uint64_t per_tile =
        sizeof(TileState) + sizeof(glm::ivec3) + 2 * ((prep.n + 63) / 64) * 8 + uint64_t(per_variant) * 13;
    const uint64_t max_tiles = options.max_memory_bytes / per_tile;
    if (plan_only) plan_only->bytes_per_tile = per_tile;  // also when refused: the planner reports it

    // The tiles of one block that may hold an alive candidate, given each type's positive bounds in the
    // block. Pass 1 counts them, pass 2 visits the same ones (same block lists, same bounds, same order).
    auto forEachPlannedTile = [&](const glm::ivec3& first, const glm::ivec3& last, const std::vector<Bounds>& positive,
                                  auto&& visit) {
        for (int z = first.z; z <= last.z; ++z)
            for (int y = first.y; y <= last.y; ++y)
                for (int x = first.x; x <= last.x; ++x) {
                    const glm::vec3 o = tileOrigin(glm::ivec3(x, y, z), s);
                    const Bounds tile_box{o, o + s};
                    if (!overlaps(tile_box, input.extent)) continue;
                    for (size_t i = 0; i < type_count; ++i)
                        if (!positive[i].empty() && overlaps(expand(tile_box, prep.reach[i]), positive[i])) {
                            visit(glm::ivec3(x, y, z));
                            break;
                        }
                }
    };
    // Each type's positive bounds inside a block (empty where its field cannot be positive).
    auto blockPositive = [&](const Bounds& block_box, std::vector<TileFieldList>* lists, std::vector<Bounds>* positive) {
        bool any = false;
        for (size_t i = 0; i < type_count; ++i) {
            (*positive)[i] = Bounds{};
            if (!runtime[i].field) continue;
            buildTileList(*runtime[i].field, expand(block_box, prep.reach[i]), &(*lists)[i], &global_lists[i]);
            if ((*lists)[i].empty()) continue;
            (*positive)[i] = positiveBoundsIn(*runtime[i].field, (*lists)[i]);
            any = any || !(*positive)[i].empty();
        }
        return any;
    };

    // Pass 1: how many tiles of each block may hold an alive candidate (cheap, bounds only).
    std::vector<uint32_t> planned(block_count, 0);
    std::atomic<uint64_t> planned_total{0};
    std::atomic<bool> stop{false}, over_budget{false};
    parallelFor(block_count, threads, 16, [&](size_t b0, size_t b1, int) {
        std::vector<TileFieldList> block_lists(type_count);
        std::vector<Bounds> positive(type_count);
        for (size_t b = b0; b < b1; ++b) {
            if (options.cancel && options.cancel->load()) return stop.store(true);
            if (over_budget.load(std::memory_order_relaxed)) return;
            const glm::ivec3 bc(int(b % nblocks.x), int(b / nblocks.x % nblocks.y), int(b / nblocks.x / nblocks.y));
            const glm::ivec3 first = tlo + bc * kBlock;
            const glm::ivec3 last = glm::min(first + (kBlock - 1), thi);
            const Bounds block_box{tileOrigin(first, s), tileOrigin(last + 1, s)};
            if (!blockPositive(block_box, &block_lists, &positive)) continue;
            uint32_t count = 0;
            forEachPlannedTile(first, last, positive, [&](const glm::ivec3&) { ++count; });
            planned[b] = count;
            if (planned_total.fetch_add(count, std::memory_order_relaxed) + count > max_tiles) over_budget = true;
        }
    });
    if (stop.load()) {
        if (error) *error = "instancer: cancelled";
        return false;
    }
    const uint64_t tile_total = planned_total.load();
    if (over_budget.load() || tile_total > max_tiles) {
        if (error)
            *error = "instancer: the scene needs more than " + std::to_string(max_tiles * per_tile >> 20) +
                     " MiB (at least " + std::to_string(tile_total) + " tiles of " + std::to_string(per_variant) +
                     " candidates, up to " + std::to_string(per_tile) + " bytes each), more than the allowed " +
                     std::to_string(options.max_memory_bytes >> 20) +
                     " MiB; shrink the extent or the fields, or cut the world into --region jobs";
        return false;
    }
    if (plan_only) {
        *plan_only = RegionFootprint{.tiles = tile_total, .bytes_per_tile = per_tile};
        return true;
    }

    // Pass 2: compute the planned tiles, block by block (the block's lists prune the tiles' lists).
    std::vector<std::vector<TileState>> per_block(block_count);
    std::atomic<uint64_t> done{0};
    parallelFor(block_count, threads, 1, [&](size_t b0, size_t b1, int) {
        TileScratch scratch;
        std::vector<glm::ivec3> coords;
        std::vector<TileFieldList> block_lists(type_count);
        std::vector<Bounds> block_positive(type_count);
        std::vector<const TileFieldList*> parents(type_count);
        for (size_t b = b0; b < b1; ++b) {
            if (planned[b] == 0) continue;
            if (options.cancel && options.cancel->load()) return stop.store(true);
            const glm::ivec3 bc(int(b % nblocks.x), int(b / nblocks.x % nblocks.y), int(b / nblocks.x / nblocks.y));
            const glm::ivec3 first = tlo + bc * kBlock;
            const glm::ivec3 last = glm::min(first + (kBlock - 1), thi);
            const Bounds block_box{tileOrigin(first, s), tileOrigin(last + 1, s)};
            blockPositive(block_box, &block_lists, &block_positive);
            coords.clear();
            forEachPlannedTile(first, last, block_positive, [&](const glm::ivec3& c) { coords.push_back(c); });
            assert(coords.size() == planned[b]);
            per_block[b].resize(coords.size());
            for (size_t k = 0; k < coords.size(); ++k) {
                TileState& ts = per_block[b][k];
                ts.coord = coords[k];
                ts.key = packTile(ts.coord);
                // A type whose positive part misses this tile's reach is not even looked at here.
                const glm::vec3 o = tileOrigin(ts.coord, s);
                for (size_t i = 0; i < type_count; ++i)
                    parents[i] = overlaps(expand(Bounds{o, o + s}, prep.reach[i]), block_positive[i]) ? &block_lists[i]
                                                                                                    : nullptr;
                computeTile(&ts, parents, &scratch);
            }
            const uint64_t now_done = done.fetch_add(coords.size(), std::memory_order_relaxed) + coords.size();
            if (options.fraction && tile_total > 0) storeMax(options.fraction, kComputeShare * float(now_done) / float(tile_total));
        }
    });
    if (stop.load()) {
        if (error) *error = "instancer: cancelled";
        return false;
    }
    out->reserve(tile_total);
    for (auto& v : per_block)
        for (TileState& ts : v) out->push_back(std::move(ts));
    return true;
}

std::vector<TileState> Instantiator::Engine::computeTiles(const std::vector<uint64_t>& keys,
                                                          const InstanceOptions& options) const {
    std::vector<TileState> out(keys.size());
    parallelFor(out.size(), resolveThreadCount(options.threads), 8, [&](size_t b, size_t end, int) {
        TileScratch scratch;
        std::vector<const TileFieldList*> parents(input.types.size());
        for (size_t i = 0; i < parents.size(); ++i)
            parents[i] = runtime[i].field && !global_lists[i].empty() ? &global_lists[i] : nullptr;
        for (size_t k = b; k < end; ++k) {
            out[k].key = keys[k];
            out[k].coord = unpackTile(keys[k]);
            computeTile(&out[k], parents, &scratch);
        }
    });
    return out;
}

void Instantiator::Engine::link(int32_t t) {
    TileState& ts = tiles[t];
    for (uint32_t v = 0; v < kOffsetCount; ++v) {
        auto it = index.find(packTile(ts.coord + offsetVector(v)));
        ts.neighbour[v] = it != index.end() ? it->second : (complete ? kEmptyTile : kUnknownTile);
    }
}

void Instantiator::Engine::linkAround(int32_t t) {
    link(t);
    for (uint32_t v = 0; v < kOffsetCount; ++v) {
        const int32_t u = tiles[t].neighbour[v];
        if (u >= 0) tiles[u].neighbour[mirrorOffset(v)] = t;
    }
}

// Adds or replaces tiles, then links them and their neighbours.
void Instantiator::Engine::install(std::vector<TileState>&& computed, std::vector<int32_t>* installed, int threads) {
    installed->clear();
    if (tiles.empty() && index.empty()) {
        // A first install (a full or region run): the computed tiles, each key once, become the table as
        // they are, and each links itself from the finished index (its neighbours do the same for their
        // side), so the tiles link in parallel.
        tiles = std::move(computed);
        index.reserve(tiles.size());
        installed->resize(tiles.size());
        for (int32_t t = 0; t < int32_t(tiles.size()); ++t) {
            index.emplace(tiles[t].key, t);
            (*installed)[size_t(t)] = t;
        }
        assert(index.size() == tiles.size());
        parallelFor(tiles.size(), threads, 1024, [&](size_t b, size_t e, int) {
            for (size_t t = b; t < e; ++t) link(int32_t(t));
        });
        return;
    }
    for (TileState& ts : computed) {
        auto it = index.find(ts.key);
        int32_t t;
        if (it != index.end()) {
            t = it->second;
            tiles[t] = std::move(ts);
        } else {
            t = int32_t(tiles.size());
            index.emplace(ts.key, t);
            tiles.push_back(std::move(ts));
        }
        installed->push_back(t);
    }
    for (int32_t t : *installed) linkAround(t);
}

// ---- the lazy lexicographically-first independent set --------------------------------------------------

namespace {

struct Ref {
    int32_t tile;
    uint32_t alive;
};

enum class Lookup { None, Found, Missing };

class Resolver {
public:
    Resolver(std::vector<TileState>& tiles, const CollisionGraph& graph) : tiles_(tiles), graph_(graph) {}

    // Decides c (and, on the way, the higher-key candidates it depends on). Returns false when a needed
    // neighbour tile has not been computed (its coordinates are appended to *missing).
    bool resolve(Ref c, std::vector<glm::ivec3>* missing, uint64_t* resolved) {
        if (tiles_[c.tile].load(c.alive) != kUnknown) return true;
        frames_.clear();
        arena_.clear();
        if (!push(c, missing, resolved)) return false;
        while (!frames_.empty()) {
            Frame& f = frames_.back();
            if (f.pos == f.end) {
                finish(f, kSelected, resolved);
                continue;
            }
            const Ref r = arena_[f.pos];
            const uint8_t s = tiles_[r.tile].load(r.alive);
            if (s == kSelected) {
                finish(f, kRejected, resolved);
            } else if (s == kRejected) {
                ++f.pos;
            } else if (!push(r, missing, resolved)) {
                return false;
            }
        }
        return true;
    }

    // Its status from its higher-key neighbours' statuses, all known (update()'s key-order pass).
    uint8_t decide(Ref c) {
        const TileState& t = tiles_[c.tile];
        const uint32_t j = t.alive[c.alive];
        const uint64_t pc = t.priority[c.alive];
        const bool selected_above = graph_.anyNeighbor(j, [&](uint32_t k, uint32_t v) {
            const int32_t u = t.neighbour[v];
            if (u < 0) return false;
            const TileState& ut = tiles_[u];
            const int64_t a = ut.find(k);
            return a >= 0 && keyBefore(ut.priority[a], ut.key, k, pc, t.key, j) &&
                   (ut.load(uint32_t(a)) & kStatusMask) == kSelected;
        });
        return selected_above ? kRejected : kSelected;
    }

    // f(Ref, higher) for every alive neighbour of c.
    template <typename F>
    void forNeighbours(Ref c, F&& f) {
        const TileState& t = tiles_[c.tile];
        const uint32_t j = t.alive[c.alive];
        const uint64_t pc = t.priority[c.alive];
        graph_.forEachNeighbor(j, [&](uint32_t k, uint32_t v) {
            const int32_t u = t.neighbour[v];
            if (u < 0) return;
            const TileState& ut = tiles_[u];
            const int64_t a = ut.find(k);
            if (a < 0) return;
            f(Ref{u, uint32_t(a)}, keyBefore(ut.priority[a], ut.key, k, pc, t.key, j));
        });
    }

private:
    struct Frame {
        Ref c;
        uint32_t begin, end, pos;
    };

    void finish(Frame& f, uint8_t status, uint64_t* resolved) {
        tiles_[f.c.tile].store(f.c.alive, status);
        ++*resolved;
        arena_.resize(f.begin);
        frames_.pop_back();
    }

    // Opens a frame for c listing its undecided higher-key neighbours, or decides c at once.
    bool push(Ref c, std::vector<glm::ivec3>* missing, uint64_t* resolved) {
        const TileState& t = tiles_[c.tile];
        const uint32_t j = t.alive[c.alive];
        const uint64_t pc = t.priority[c.alive];
        const uint32_t begin = uint32_t(arena_.size());
        bool any_missing = false;
        const bool selected_above = graph_.anyNeighbor(j, [&](uint32_t k, uint32_t v) {
            const int32_t u = t.neighbour[v];
            if (u == kEmptyTile) return false;
            if (u == kUnknownTile) {
                any_missing = true;
                missing->push_back(t.coord + offsetVector(v));
                return false;
            }
            const TileState& ut = tiles_[u];
            const int64_t a = ut.find(k);
            if (a < 0 || !keyBefore(ut.priority[a], ut.key, k, pc, t.key, j)) return false;
            const uint8_t s = ut.load(uint32_t(a));
            if (s == kSelected) return true;
            if (s == kUnknown) arena_.push_back(Ref{u, uint32_t(a)});
            return false;
        });
        if (selected_above) {
            arena_.resize(begin);
            tiles_[c.tile].store(c.alive, kRejected);
            ++*resolved;
            return true;
        }
        if (any_missing) {
            arena_.resize(begin);
            return false;
        }
        frames_.push_back(Frame{c, begin, uint32_t(arena_.size()), begin});
        return true;
    }

    std::vector<TileState>& tiles_;
    const CollisionGraph& graph_;
    std::vector<Frame> frames_;
    std::vector<Ref> arena_;
};

}  // namespace

bool Instantiator::Engine::resolveTiles(const std::vector<int32_t>& which, const InstanceOptions& options,
                                        std::vector<glm::ivec3>* missing, uint64_t* resolved) {
    std::vector<int32_t> order = which;
    if (options.tile_order_seed != 0) {
        for (size_t k = order.size(); k > 1; --k)
            std::swap(order[k - 1], order[hashWords(options.tile_order_seed, k) % k]);
    }
    const int threads = resolveThreadCount(options.threads);
    std::vector<std::vector<glm::ivec3>> missing_per_worker;
    missing_per_worker.resize(size_t(threads));
    std::vector<uint64_t> resolved_per_worker(size_t(threads), 0);
    std::atomic<bool> stop{false};
    std::atomic<uint64_t> resolved_tiles{0};
    parallelFor(order.size(), threads, 4, [&](size_t b, size_t e, int worker) {
        Resolver resolver(tiles, input.tile->graph);
        // Counted here, on this worker's stack, and added once: the workers' slots share a cache line,
        // and counting every decision into them made both workers wait for that line.
        uint64_t resolved_here = 0;
        for (size_t k = b; k < e; ++k) {
            if (options.cancel && options.cancel->load()) {
                stop.store(true);
                break;
            }
            if (options.fraction) {
                const uint64_t n = resolved_tiles.fetch_add(1, std::memory_order_relaxed) + 1;
                storeMax(options.fraction, kComputeShare + (1.0f - kComputeShare) * float(n) / float(order.size() + 1));
            }
            const int32_t t = order[k];
            // Driven in id order: the selection does not depend on the order (any order gives the
            // lexicographically-first set), and sorting every tile by key cost more than the deeper
            // recursions it saved.
            for (uint32_t a = 0; a < tiles[t].alive.size(); ++a) {
                // In region mode, only the wanted candidates are driven; others resolve on demand.
                if (!complete && !originInside(region, tileOrigin(tiles[t].coord, prep.s) +
                                                          input.tile->candidates.position[tiles[t].alive[a]]))
                    continue;
                resolver.resolve(Ref{t, a}, &missing_per_worker[size_t(worker)], &resolved_here);
            }
        }
        resolved_per_worker[size_t(worker)] += resolved_here;
    });
    for (auto& m : missing_per_worker) missing->insert(missing->end(), m.begin(), m.end());
    for (uint64_t r : resolved_per_worker) *resolved += r;
    return !stop.load();
}

void Instantiator::Engine::rebuildStore() {
    std::vector<int32_t> sorted;
    sorted.reserve(tiles.size());
    for (int32_t t = 0; t < int32_t(tiles.size()); ++t)
        if (!tiles[t].alive.empty()) sorted.push_back(t);
    std::sort(sorted.begin(), sorted.end(), [&](int32_t a, int32_t b) { return tiles[a].key < tiles[b].key; });
    store.clear();
    std::vector<uint32_t> ids;
    const CandidateSet& c = input.tile->candidates;
    for (int32_t t : sorted) {
        const TileState& ts = tiles[t];
        ids.clear();
        const glm::vec3 origin = tileOrigin(ts.coord, prep.s);
        for (uint32_t a = 0; a < ts.alive.size(); ++a) {
            if ((ts.status[a] & kStatusMask) != kSelected) continue;
            if (!complete && !originInside(region, origin + c.position[ts.alive[a]])) continue;
            ids.push_back(ts.alive[a]);
        }
        store.appendTile(ts.key, ids);
    }
}

void Instantiator::Engine::fillStats(InstanceStats* st) const {
    st->instances = store.instanceCount();
    st->alive = 0;
    for (const TileState& ts : tiles) st->alive += ts.alive.size();
    st->instances_per_type.assign(input.types.size(), 0);
    const CandidateSet& c = input.tile->candidates;
    store.forEach([&](uint64_t, uint32_t j) { ++st->instances_per_type[c.type[j]]; });
    st->store_bytes = store.byteSize();
    st->bytes_per_instance = st->instances ? double(st->store_bytes) / double(st->instances) : 0.0;
}

// ---- public API ----------------------------------------------------------------------------------------

Instantiator::Instantiator() : engine_(std::make_unique<Engine>()) {}
Instantiator::~Instantiator() = default;

bool Instantiator::setInput(InstancerInput input, std::string* error) { return engine_->setInput(std::move(input), error); }
const InstancerInput& Instantiator::input() const { return engine_->input; }
const InstanceStore& Instantiator::store() const { return engine_->store; }

namespace {

void addTileCounters(const std::vector<TileState>& computed, InstanceStats* st) {
    for (const TileState& ts : computed) {
        st->candidates_tested += ts.tested;
        st->culled += ts.culled;
        st->density_rejected += ts.density_rejected;
        st->constraint_rejected += ts.constraint_rejected;
    }
    st->tiles_touched += computed.size();
}

}  // namespace

bool Instantiator::instantiateAll(const InstanceOptions& options, InstanceStats* stats, std::string* error) {
    Engine& e = *engine_;
    if (!e.input.tile) {
        if (error) *error = "instancer: no input";
        return false;
    }
    const auto t0 = Clock::now();
    InstanceStats st;
    e.complete = true;
    e.region = Bounds::everything();
    std::vector<TileState> computed;
    if (!e.enumerateAndCompute(e.input.extent, options, &computed, error)) return false;
    if (options.progress) options.progress(0.5f);
    addTileCounters(computed, &st);
    e.tiles.clear();
    e.index.clear();
    e.instantiated = false;
    std::vector<int32_t> installed;
    e.install(std::move(computed), &installed, resolveThreadCount(options.threads));
    std::vector<glm::ivec3> missing;
    if (!e.resolveTiles(installed, options, &missing, &st.resolved)) {
        if (error) *error = "instancer: cancelled";
        e.tiles.clear();
        e.index.clear();
        return false;
    }
    e.rebuildStore();
    e.instantiated = true;
    e.fillStats(&st);
    st.collision_rejected = st.alive - st.instances;
    st.rejected = st.candidates_tested - st.instances;
    st.tiles_changed = e.store.tileCount();
    st.seconds = secondsSince(t0);
    if (options.progress) options.progress(1.0f);
    if (options.fraction) options.fraction->store(1.0f);
    if (stats) *stats = st;
    return true;
}

bool Instantiator::update(std::vector<InstanceTypeSettings> types, std::span<const Bounds> dirty,
                          const InstanceOptions& options, InstanceStats* stats, std::vector<uint64_t>* changed_tiles,
                          std::string* error) {
    Engine& e = *engine_;
    if (!e.instantiated) {
        if (error) *error = "instancer: update() before instantiateAll()";
        return false;
    }
    const auto t0 = Clock::now();
    {
        // Validate the new settings before touching the state.
        InstancerInput next = e.input;
        next.types = std::move(types);
        if (!validateInput(next, error)) return false;
        e.input.types = std::move(next.types);
        e.refreshRuntime();
    }
    InstanceStats st;
    const float s = e.prep.s;

    // 1. The dirty tiles: every tile whose candidates' anchors can reach a dirty box.
    std::vector<uint64_t> dirty_keys;
    for (const Bounds& d : dirty) {
        if (d.empty()) continue;
        // Infinite boxes (a terrain layer changed) clip to the extent and usually start over below.
        const Bounds b = intersect(expand(d, e.prep.max_reach), e.input.extent);
        if (b.empty()) continue;
        const glm::ivec3 lo = tileOf(b.lo, s), hi = tileOf(b.hi, s);
        const uint64_t count = uint64_t(hi.x - lo.x + 1) * uint64_t(hi.y - lo.y + 1) * uint64_t(hi.z - lo.z + 1);
        if (count > 4'000'000) {  // cheaper to start over; every tile of the old or new store changed
            std::vector<uint64_t> keys;
            for (size_t t = 0; t < e.store.tileCount(); ++t) keys.push_back(e.store.tileKey(t));
            if (!instantiateAll(options, stats, error)) return false;
            for (size_t t = 0; t < e.store.tileCount(); ++t) keys.push_back(e.store.tileKey(t));
            std::sort(keys.begin(), keys.end());
            keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
            if (changed_tiles) *changed_tiles = std::move(keys);
            return true;
        }
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x) dirty_keys.push_back(packTile(glm::ivec3(x, y, z)));
    }
    std::sort(dirty_keys.begin(), dirty_keys.end());
    dirty_keys.erase(std::unique(dirty_keys.begin(), dirty_keys.end()), dirty_keys.end());

    // 2. Recompute them (with the full-field lists as parents), keeping the old states for comparison.
    std::vector<TileState> fresh = e.computeTiles(dirty_keys, options);
    addTileCounters(fresh, &st);
    std::vector<TileState> old(fresh.size());
    std::vector<bool> existed(fresh.size(), false);
    for (size_t k = 0; k < fresh.size(); ++k) {
        auto it = e.index.find(fresh[k].key);
        if (it != e.index.end()) {
            old[k] = std::move(e.tiles[it->second]);
            existed[k] = true;
        }
    }
    // Keep empty fresh tiles only where a tile existed (so the slot stays valid and linked).
    std::vector<TileState> to_install;
    std::vector<size_t> fresh_of_installed;
    for (size_t k = 0; k < fresh.size(); ++k) {
        if (fresh[k].alive.empty() && !existed[k]) continue;
        to_install.push_back(std::move(fresh[k]));
        fresh_of_installed.push_back(k);
    }
    std::vector<int32_t> installed;
    e.install(std::move(to_install), &installed);

    // 3. Re-decide in key order. Seeds: every candidate of the dirty tiles, and the neighbours outside
    //    them of every old selected or new alive candidate there.
    struct Item {
        uint64_t priority, tile_key;
        uint32_t j;
        Ref ref;
        bool operator>(const Item& o) const { return keyBefore(o.priority, o.tile_key, o.j, priority, tile_key, j); }
    };
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    std::unordered_map<uint64_t, bool> is_dirty;
    is_dirty.reserve(dirty_keys.size() * 2);
    for (uint64_t k : dirty_keys) is_dirty.emplace(k, true);
    auto dirtyTile = [&](int32_t t) { return is_dirty.count(e.tiles[t].key) != 0; };
    auto enqueue = [&](Ref r) {
        TileState& ts = e.tiles[r.tile];
        if (ts.status[r.alive] & kQueued) return;
        ts.status[r.alive] |= kQueued;
        queue.push(Item{ts.priority[r.alive], ts.key, ts.alive[r.alive], r});
    };
    Resolver resolver(e.tiles, e.input.tile->graph);
    for (int32_t t : installed)
        for (uint32_t a = 0; a < e.tiles[t].alive.size(); ++a) {
            e.tiles[t].status[a] = kUnknown;
            enqueue(Ref{t, a});
            resolver.forNeighbours(Ref{t, a}, [&](Ref r, bool) {
                if (!dirtyTile(r.tile)) enqueue(r);
            });
        }
    // Old selected candidates influenced their neighbours; those outside the dirty tiles must look again.
    // They are found through the new tiles' links: a neighbour offset is a neighbour offset.
    for (size_t k = 0; k < old.size(); ++k) {
        if (!existed[k]) continue;
        const TileState& ot = old[k];
        auto it = e.index.find(ot.key);
        const int32_t t = it->second;
        for (uint32_t a = 0; a < ot.alive.size(); ++a) {
            if ((ot.status[a] & kStatusMask) != kSelected) continue;
            e.input.tile->graph.forEachNeighbor(ot.alive[a], [&](uint32_t j, uint32_t v) {
                const int32_t u = e.tiles[t].neighbour[v];
                if (u < 0 || dirtyTile(u)) return;
                const int64_t b = e.tiles[u].find(j);
                if (b >= 0) enqueue(Ref{u, uint32_t(b)});
            });
        }
    }
    std::unordered_map<int32_t, bool> changed_outside;
    while (!queue.empty()) {
        const Item item = queue.top();
        queue.pop();
        TileState& ts = e.tiles[item.ref.tile];
        const uint8_t before = ts.status[item.ref.alive] & kStatusMask;
        const uint8_t now = resolver.decide(item.ref);
        ts.status[item.ref.alive] = now;
        ++st.resolved;
        if (before == now || dirtyTile(item.ref.tile)) continue;
        changed_outside[item.ref.tile] = true;
        resolver.forNeighbours(item.ref, [&](Ref r, bool higher) {
            if (!higher) enqueue(r);
        });
    }

    // 4. What changed, for the renderer: dirty tiles whose selection differs, and tiles outside them.
    std::vector<uint64_t> changed;
    uint64_t selected_in_dirty = 0;
    auto selectedIds = [&](const TileState& ts) {
        std::vector<uint32_t> ids;
        for (uint32_t a = 0; a < ts.alive.size(); ++a)
            if ((ts.status[a] & kStatusMask) == kSelected) ids.push_back(ts.alive[a]);
        return ids;
    };
    for (size_t k = 0; k < fresh.size(); ++k) {
        auto it = e.index.find(dirty_keys[k]);
        const std::vector<uint32_t> now = it != e.index.end() ? selectedIds(e.tiles[it->second]) : std::vector<uint32_t>{};
        const std::vector<uint32_t> before = existed[k] ? selectedIds(old[k]) : std::vector<uint32_t>{};
        selected_in_dirty += now.size();
        if (now != before) changed.push_back(dirty_keys[k]);
    }
    for (const auto& [t, flag] : changed_outside) changed.push_back(e.tiles[t].key);
    std::sort(changed.begin(), changed.end());
    changed.erase(std::unique(changed.begin(), changed.end()), changed.end());

    e.rebuildStore();
    e.fillStats(&st);
    st.collision_rejected = st.alive - st.instances;
    st.rejected = st.candidates_tested - selected_in_dirty;  // of the recomputed tiles
    st.tiles_changed = changed.size();
    st.seconds = secondsSince(t0);
    if (changed_tiles) *changed_tiles = std::move(changed);
    if (stats) *stats = st;
    return true;
}

std::vector<Instantiator::AliveCandidate> Instantiator::aliveCandidates() const {
    std::vector<AliveCandidate> out;
    for (const TileState& ts : engine_->tiles)
        for (uint32_t a = 0; a < ts.alive.size(); ++a) out.push_back({ts.key, ts.alive[a], ts.priority[a]});
    return out;
}

bool instantiateRegion(const InstancerInput& input, const Bounds& region, const InstanceOptions& options,
                       InstanceStore* out, InstanceStats* stats, std::string* error) {
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(region.lo[a]) || !std::isfinite(region.hi[a]) || !(region.lo[a] < region.hi[a])) {
            if (error) *error = "region: min must be finite and < max on every axis";
            return false;
        }
    const auto t0 = Clock::now();
    Instantiator::Engine e;
    if (!e.setInput(input, error)) return false;
    e.complete = false;
    e.region = region;
    InstanceStats st;
    std::vector<TileState> computed;
    if (!e.enumerateAndCompute(region, options, &computed, error)) return false;
    addTileCounters(computed, &st);
    std::vector<int32_t> installed, pending;
    e.install(std::move(computed), &installed, resolveThreadCount(options.threads));
    pending = installed;
    // Decide the wanted candidates; whenever a decision needs a tile not computed yet, compute it and
    // try again. Each round only adds tiles, so this ends (at worst when the dependency chains do).
    for (;;) {
        std::vector<glm::ivec3> missing;
        if (!e.resolveTiles(pending, options, &missing, &st.resolved)) {
            if (error) *error = "instancer: cancelled";
            return false;
        }
        if (missing.empty()) break;
        std::vector<uint64_t> keys;
        for (const glm::ivec3& m : missing) keys.push_back(packTile(m));
        std::sort(keys.begin(), keys.end());
        keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
        std::vector<TileState> extra = e.computeTiles(keys, options);
        addTileCounters(extra, &st);
        std::vector<int32_t> added;
        e.install(std::move(extra), &added);
        // Retry every tile with an undecided wanted candidate.
        std::vector<int32_t> retry;
        for (int32_t t : pending) {
            const TileState& ts = e.tiles[t];
            for (uint32_t a = 0; a < ts.alive.size(); ++a)
                if (ts.status[a] == kUnknown &&
                    originInside(region, tileOrigin(ts.coord, e.prep.s) + e.input.tile->candidates.position[ts.alive[a]])) {
                    retry.push_back(t);
                    break;
                }
        }
        pending = std::move(retry);
    }
    e.rebuildStore();
    e.fillStats(&st);
    st.collision_rejected = 0;
    st.rejected = st.candidates_tested - st.instances;
    st.tiles_changed = e.store.tileCount();
    st.seconds = secondsSince(t0);
    if (out) *out = e.store;
    if (stats) *stats = st;
    return true;
}

bool measureRegionFootprint(const InstancerInput& input, const Bounds& region, const InstanceOptions& options,
                            RegionFootprint* out, std::string* error) {
    Instantiator::Engine e;
    if (!e.setInput(input, error)) return false;
    e.complete = false;
    e.region = region;
    std::vector<TileState> none;
    return e.enumerateAndCompute(region, options, &none, error, out);
}

}  // namespace ug
