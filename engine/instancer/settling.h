// Settling (docs/architecture.md "Plausible rest and no visible tile"): after selection, each instance falls
// straight down until one of its collision spheres touches the support (terrain or ground plane) or a
// sphere of another instance below it, by at most max_drop_m. The paper leaves instances where their
// candidates were ("our method does not guarantee consistent contact points"); measured on our exports, a
// third of them could drop more than 2 cm.
//
// Definition (a pure function of the selected set, like the selection itself):
//  - "below": sphere e of instance B is below sphere a of instance A when e's centre is lower than a's in
//    the unsettled frames, ties broken by (tile, candidate, sphere): a fixed order of the sphere pairs.
//  - Passes (Jacobi): drop_0 = 0; in pass k every instance A falls from its unsettled frame as far as
//        drop_k(A) = min(max_drop, clearance to the support, min over pairs (a below-over e) of
//                        max(0, a.z - (e.z - drop_{k-1}(B)) - sqrt((ra + re + gap)^2 - h^2)))
//    with h the horizontal distance of the pair (pairs with h >= ra + re + gap never meet), rounded down
//    to kSettleQuantumM. An instance with nothing within max_drop below it in the unsettled frames (no
//    such pair, support farther) is HELD (a corbelled roof's stones are held by their neighbours; a
//    vertical fall would drop them into the room): it moves down with the wall that holds it,
//        drop_k(A) = min(max_drop, min over B beside A of drop_{k-1}(B)),
//    B beside A when their bounding spheres (around the box of each one's spheres) come within the gap,
//    B's bounding centre is not higher than A's, and their origins lie within one pass reach (below); with
//    nothing beside it its drop stays 0. Each pass reads only the previous one, so the result is the same
//    for any thread count and any order; passes stop after `passes` or when nothing moves.
//  - No two instances end up closer than they were allowed to be: in every pair the upper sphere stops
//    above where the lower one was in the previous pass, and the lower one only goes down (a held
//    instance falls at most max_drop, and all its pairs lie farther below it than that). Drops only
//    grow from pass to pass, so a pile compacts from the bottom up by one layer per pass.
//  - Locality: drop_k(A) depends on instances within `reach` horizontally and within max_drop + reach
//    vertically of A (reach = twice the largest distance from a candidate's origin to the far side of one
//    of its spheres, + gap; a held instance's neighbours beside it are limited to it), so after K passes
//    on the instances within K reach of A. A window that far around a changed region gives the exact
//    answer inside it: that is how edits (settleUpdate) and region jobs (settleHaloMetres) stay equal to
//    the whole.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "field/bounds.h"
#include "ghosttile/ghost_tile.h"
#include "instancer/instance_store.h"
#include "instancer/rest_support.h"
#include "mesh/detail_model.h"

namespace ug {

constexpr float kSettleQuantumM = 1e-4f;  // drops are stored in 0.1 mm units (uint16: up to 6.5 m)
constexpr float kMaxSettleDropM = 6.5f;
constexpr int kMaxSettlePasses = 64;

struct SettleSettings {
    bool enabled = false;
    int passes = 8;           // in [1, kMaxSettlePasses]
    float max_drop_m = 0.5f;  // in [0, kMaxSettleDropM]: beyond it an instance stays where it was
};

struct SettleInput {
    const GhostTile* tile = nullptr;           // not owned
    std::vector<const DetailModel*> models;    // one per Ghost Tile type; not owned
    RestSupport support;
    SettleSettings settings;
};

// The drop of every instance of a store, per tile in the store's id order, in kSettleQuantumM units.
// Flat like the store (sorted tile keys, offsets, drops), so a snapshot copies in three memcpys.
class SettledDrops {
public:
    // The drops of a tile's instances (ascending candidate ids); empty when the tile holds none.
    std::span<const uint16_t> tile(uint64_t tile_key) const;
    // Building: tiles in ascending key order.
    void append(uint64_t tile_key, std::span<const uint16_t> drops);
    void clear();
    size_t tileCount() const { return keys_.size(); }
    uint64_t instanceCount() const { return drops_.size(); }
    uint64_t byteSize() const { return drops_.size() * sizeof(uint16_t); }  // the drops (2 bytes each)
    bool operator==(const SettledDrops& o) const {
        return keys_ == o.keys_ && offsets_ == o.offsets_ && drops_ == o.drops_;
    }

private:
    std::vector<uint64_t> keys_;
    std::vector<uint32_t> offsets_{0};
    std::vector<uint16_t> drops_;
};

// The drops after each pass but the last (pass 1 .. passes - 1; the last pass's are the SettledDrops).
// An edit changes drop_k only within k pass halos of it, so with these an update computes just the tiles
// it can reach and reads the ring around them from here; without them it must compute a ring as wide again
// from scratch (2 x passes halos), most of an update's time. Kept by whoever keeps the drops (the live
// instancer): about (passes - 1) x 2 bytes an instance.
struct SettleHistory {
    int passes = 0;  // the pass count it was computed with; 0: none
    std::vector<SettledDrops> after_pass;  // passes - 1 entries
    void clear() {
        passes = 0;
        after_pass.clear();
    }
};

// Checks the settings (message names the setting) and that models match the tile.
bool validateSettleInput(const SettleInput& input, std::string* error);

// Drops for every instance of the store; `history` (optional) receives the drops after each pass.
void settleAll(const SettleInput& input, const InstanceStore& store, int threads, SettledDrops* out,
               SettleHistory* history = nullptr);

// After the store changed only in `changed_tiles` (what Instantiator::update reports): recomputes the drops
// that can have changed, exactly: *drops equals settleAll(store) afterwards. `touched` (optional) receives
// changed_tiles and the tiles whose drops changed, ascending. `history` (optional): the one settleAll or
// an earlier update left with these drops; when it was computed with the input's pass count the update
// computes only the tiles the edit can reach, and keeps it equal to settleAll's. Otherwise it is cleared.
void settleUpdate(const SettleInput& input, const InstanceStore& store, std::span<const uint64_t> changed_tiles,
                  int threads, SettledDrops* drops, std::vector<uint64_t>* touched, SettleHistory* history = nullptr);

// How far around a region the selection must be known for the region's drops to be exact (metres): a
// region job instantiates its region grown by this, settles, and keeps its own instances.
float settleHaloMetres(const SettleInput& input);

// A region job's own part of a wider instantiation: the instances whose (unsettled) origin lies in
// `region` ([lo, hi) like instantiateRegion), with their drops.
void cropToRegion(const InstanceStore& store, const SettledDrops& drops, const GhostTile& tile, const Bounds& region,
                  InstanceStore* out_store, SettledDrops* out_drops);

// The settled translation offset of an instance: (0, 0, -drop).
inline float dropMetres(uint16_t units) { return float(units) * kSettleQuantumM; }

// f(tile_key, candidate, drop_m) for every instance of the store, in store order; drop 0 where `drops` is
// null or has no entry for the tile (settling off).
template <typename F>
void forEachSettled(const InstanceStore& store, const SettledDrops* drops, F&& f) {
    std::vector<uint32_t> ids;
    for (size_t t = 0; t < store.tileCount(); ++t) {
        store.tileIds(t, &ids);
        const std::span<const uint16_t> d = drops ? drops->tile(store.tileKey(t)) : std::span<const uint16_t>();
        for (size_t k = 0; k < ids.size(); ++k) f(store.tileKey(t), ids[k], k < d.size() ? dropMetres(d[k]) : 0.0f);
    }
}

}  // namespace ug
