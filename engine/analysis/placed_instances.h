// Instances as world frames, for the measurements of engine/analysis (how things rest, how they pack,
// whether the tile's period shows). The instance store keeps only (tile, candidate) pairs; this expands
// them once with the instantiator's own expression, world = tileOrigin(tile) + p_j, R_j, scale_j, which
// is also what the exporter writes, so a measurement on these frames and one on an export agree.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "ghosttile/ghost_tile.h"
#include "instancer/instance_store.h"
#include "instancer/settling.h"
#include "mesh/detail_model.h"

namespace ug {

struct PlacedInstance {
    uint32_t type = 0;
    glm::vec3 position{0.0f};  // world, metres: the model's origin
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    float scale = 1.0f;
};

// Every instance of the store, in store order, lowered by its settled drop (when `drops` is given).
std::vector<PlacedInstance> placeInstances(const InstanceStore& store, const GhostTile& tile,
                                           const SettledDrops* drops = nullptr);

// The world spheres of one placed instance: centre = position + R (scale c), radius = scale r.
void placedSpheres(const PlacedInstance& instance, const DetailModel& model, std::vector<Sphere>* out);

}  // namespace ug
