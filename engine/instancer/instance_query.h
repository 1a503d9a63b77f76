// Questions about an instantiation result that tests, scripted editor runs and statistics ask: how many
// instances of each type have their origin inside a box (and outside it), and a hash of the whole set so
// two results can be compared without keeping both.
#pragma once

#include <cstdint>
#include <vector>

#include "field/bounds.h"
#include "ghosttile/ghost_tile.h"
#include "instancer/instance_store.h"

namespace ug {

struct BoxCounts {
    std::vector<uint64_t> inside;   // per detail type: instances whose origin lies in the box (closed)
    std::vector<uint64_t> outside;  // per detail type: the others
};

// An instance's origin is tileOrigin(tile, tile_size_m) + candidates.position[id] (the instantiator's own
// expression). An empty box has every instance outside.
BoxCounts countInstancesInBox(const InstanceStore& store, const CandidateSet& candidates, float tile_size_m,
                              const Bounds& box);

// A 64-bit hash (core/hash.h's Hasher) of the (tile key, candidate id) pairs in store order: equal sets
// give equal hashes whatever their encoding or history; different sets differ but for a 2^-64 chance.
uint64_t instanceStoreHash(const InstanceStore& store);

}  // namespace ug
