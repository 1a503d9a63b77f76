#include "instancer/instance_query.h"

#include "core/hash.h"
#include "instancer/tile_coord.h"

namespace ug {

BoxCounts countInstancesInBox(const InstanceStore& store, const CandidateSet& candidates, float tile_size_m,
                              const Bounds& box) {
    BoxCounts out;
    out.inside.assign(candidates.typeCount(), 0);
    out.outside.assign(candidates.typeCount(), 0);
    glm::vec3 origin(0.0f);
    uint64_t last_key = ~uint64_t(0);
    store.forEach([&](uint64_t key, uint32_t id) {
        if (key != last_key) {
            origin = tileOrigin(unpackTile(key), tile_size_m);
            last_key = key;
        }
        const uint16_t type = candidates.type[id];
        (contains(box, origin + candidates.position[id]) ? out.inside : out.outside)[type]++;
    });
    return out;
}

uint64_t instanceStoreHash(const InstanceStore& store) {
    Hasher h;
    h.add(store.instanceCount());
    store.forEach([&](uint64_t key, uint32_t id) {
        h.add(key);
        h.add(id);
    });
    return h.value();
}

}  // namespace ug
