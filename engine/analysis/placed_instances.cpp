#include "analysis/placed_instances.h"

#include "instancer/tile_coord.h"

namespace ug {

std::vector<PlacedInstance> placeInstances(const InstanceStore& store, const GhostTile& tile,
                                           const SettledDrops* drops) {
    std::vector<PlacedInstance> out;
    out.reserve(store.instanceCount());
    const CandidateSet& c = tile.candidates;
    const float s = tile.settings.tile_size_m;
    forEachSettled(store, drops, [&](uint64_t tile_key, uint32_t j, float drop_m) {
        PlacedInstance p;
        p.type = c.type[j];
        p.position = tileOrigin(unpackTile(tile_key), s) + c.position[j];
        p.position.z -= drop_m;
        p.rotation = c.rotation[j];
        p.scale = c.scale[j];
        out.push_back(p);
    });
    return out;
}

void placedSpheres(const PlacedInstance& instance, const DetailModel& model, std::vector<Sphere>* out) {
    out->clear();
    for (const Sphere& s : model.spheres)
        out->push_back({instance.position + instance.rotation * (instance.scale * s.center), instance.scale * s.radius});
}

}  // namespace ug
