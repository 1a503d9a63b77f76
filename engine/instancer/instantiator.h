// The instantiator (Ghost Tile §5, made a pure function in docs/architecture.md "Instantiation as a pure
// function"): which candidates of the infinite grid of Ghost Tiles become objects.
//
//  0. Each tile t holds one Ghost Tile variant, tileVariant(seed, t): only its candidates are looked at.
//  1. A tile-candidate c = (tile t, candidate j of type i) is ALIVE when its origin lies in the scene
//     extent, f_i > 0 at every anchor (§5.1 culling), u(seed, t, j) < min(1, mean of f_i at its anchors)
//     (§5.3 acceptance), and the orientation and size constraints accept it (§5.3 "Control").
//  2. Every alive candidate has a KEY, smaller = first: (priority layer of its strategy, then the weighted
//     random number -ln(u') / w with w the mean density at its anchors (Efraimidis–Spirakis: neighbours of
//     different types win in proportion to their densities), then the packed tile, then j).
//  3. The SELECTED set is the lexicographically-first independent set of the alive candidates under the
//     collision graph: c is selected iff no alive neighbour with a smaller key, in its tile or one of the
//     26 around it, is selected.
// The answer is unique for a scene and seed, so it is computed lazily (memoized, recursion climbs the keys),
// in parallel over tiles, incrementally after edits, or for one region alone, and always comes out the same.
//
// Usage:
//   Instantiator inst;
//   if (!inst.setInput(input, &error)) ...              // InstancerInput: Ghost Tile, models, types, extent
//   inst.instantiateAll({.threads = 0}, &stats, &error);
//   ... user edits type 2's field: its old and new supports are the dirty region ...
//   types[2].field = new_field;
//   inst.update(types, dirty_boxes, {}, &stats, &changed_tiles, &error);
//   inst.store().forEach([&](uint64_t tile, uint32_t j) { ... });
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/hash.h"
#include "field/bounds.h"
#include "ghosttile/ghost_tile.h"
#include "instancer/instance_store.h"
#include "instancer/instancing_settings.h"
#include "mesh/detail_model.h"

namespace ug {

struct InstancerInput {
    const GhostTile* tile = nullptr;              // not owned; must outlive the instantiator
    std::vector<const DetailModel*> models;      // one per Ghost Tile type (anchors); not owned
    std::vector<InstanceTypeSettings> types;     // one per Ghost Tile type
    Bounds extent;                                // finite; a candidate whose origin is outside is never alive
    uint64_t seed = 1;
};

struct InstanceOptions {
    int threads = 0;                                // 0 = all hardware threads
    const std::atomic<bool>* cancel = nullptr;      // true: stop early, the call returns false
    std::function<void(float fraction)> progress;   // from the calling thread, in [0, 1]
    // Optional: instantiateAll stores its progress here as the tiles are computed and resolved (from the
    // worker threads, never decreasing, 1 at the end), for a UI thread to read while the call runs.
    std::atomic<float>* fraction = nullptr;
    uint64_t max_memory_bytes = 8ull << 30;         // refuse up front a scene whose state may need more
    uint64_t tile_order_seed = 0;                   // tests: resolve tiles in a shuffled order (0 = sorted)
};

struct InstanceStats {
    uint64_t instances = 0;            // #I
    uint64_t candidates_tested = 0;    // tile-candidates examined (culled, accepted or not)
    uint64_t culled = 0;               // outside the extent or f_i <= 0 at an anchor (§5.1)
    uint64_t density_rejected = 0;     // u >= density (§5.3)
    uint64_t constraint_rejected = 0;  // orientation or size constraint
    uint64_t alive = 0;                // passed all of the above (current state, all tiles)
    uint64_t collision_rejected = 0;   // alive, not selected
    uint64_t rejected = 0;             // #R = candidates_tested - selected among them (the paper's count)
    uint64_t tiles_touched = 0;        // tiles whose candidates were (re)computed by this call
    uint64_t tiles_changed = 0;        // tiles whose selected set changed (update) or is non-empty (full)
    uint64_t resolved = 0;             // candidates whose status was (re)decided by this call
    double seconds = 0.0;
    std::vector<uint64_t> instances_per_type;
    uint64_t store_bytes = 0;
    double bytes_per_instance = 0.0;
};

class Instantiator {
public:
    Instantiator();
    ~Instantiator();
    Instantiator(const Instantiator&) = delete;
    Instantiator& operator=(const Instantiator&) = delete;

    // Validates (message names the type and setting) and prepares anchors; drops any previous state.
    bool setInput(InstancerInput input, std::string* error);
    const InstancerInput& input() const;

    // Instantiates the whole extent from scratch.
    bool instantiateAll(const InstanceOptions& options, InstanceStats* stats, std::string* error);

    // After an edit: `types` replaces the current settings (fields changed only inside `dirty`, the old
    // and new supports of what changed). Recomputes the tiles the dirty boxes reach, then re-decides, in
    // key order, exactly the candidates whose higher-key neighbourhood changed. The result equals
    // instantiateAll() on the new settings, bit for bit. `changed_tiles` (optional) receives the packed
    // keys of the tiles whose selected set changed, ascending (when the dirty region is so large that
    // update starts over with instantiateAll(), every tile of the old and the new store: a superset).
    // Requires a previous instantiateAll().
    bool update(std::vector<InstanceTypeSettings> types, std::span<const Bounds> dirty,
                const InstanceOptions& options, InstanceStats* stats, std::vector<uint64_t>* changed_tiles,
                std::string* error);

    // The selected set after the last successful call.
    const InstanceStore& store() const;

    // Every alive candidate with its key (tests' brute-force reference); order unspecified.
    struct AliveCandidate {
        uint64_t tile_key;
        uint32_t candidate;
        uint64_t priority;  // strategy layer and weighted random number, packed; ties broken by (tile, j)
    };
    std::vector<AliveCandidate> aliveCandidates() const;

    class Engine;

private:
    std::unique_ptr<Engine> engine_;
};

// Instantiates the candidates whose origin lies in `region` ([lo, hi) on every axis, clipped to the
// extent) without instantiating the rest: tiles outside are computed lazily, only as far as the decisions
// inside depend on them. Regions that partition the extent give disjoint results whose union is
// instantiateAll()'s. Errors: an empty, inverted or non-finite region.
bool instantiateRegion(const InstancerInput& input, const Bounds& region, const InstanceOptions& options,
                       InstanceStore* out, InstanceStats* stats, std::string* error);

// What instantiating a region holds at most, known before anything large is allocated: the tiles the
// memory check of instantiateRegion plans for the region and the worst-case bytes of each. A planner of
// region jobs sizes regions with it, so that no planned job is refused by that check.
struct RegionFootprint {
    uint64_t tiles = 0;
    uint64_t bytes_per_tile = 0;
    uint64_t bytes() const { return tiles * bytes_per_tile; }
};
// False (with the instancer's message) when the region alone is over options.max_memory_bytes; out still
// holds bytes_per_tile then.
bool measureRegionFootprint(const InstancerInput& input, const Bounds& region, const InstanceOptions& options,
                            RegionFootprint* out, std::string* error);

// The Ghost Tile variant of a world tile (docs/architecture.md "No period"): a hash of the instancing seed
// and the packed tile, so it is a pure function like everything else here. Only that variant's candidates
// can be alive in the tile; exporters, metrics and tests use this to know which ones a tile may hold.
constexpr uint64_t kTileVariantStream = 0x76617269616e74ull;  // "variant"
inline uint32_t tileVariant(uint64_t seed, uint64_t tile_key, uint32_t variants) {
    if (variants <= 1) return 0;
    return uint32_t(hashWords(seed, tile_key, kTileVariantStream) % variants);
}

// True when key a = (priority_a, tile_a, j_a) comes before b: a wins a collision against b.
inline bool keyBefore(uint64_t priority_a, uint64_t tile_a, uint32_t j_a, uint64_t priority_b, uint64_t tile_b,
                      uint32_t j_b) {
    if (priority_a != priority_b) return priority_a < priority_b;
    if (tile_a != tile_b) return tile_a < tile_b;
    return j_a < j_b;
}

}  // namespace ug
