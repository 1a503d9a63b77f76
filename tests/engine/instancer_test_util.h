// A small two-type scene for instantiator tests: blobs ("rocks") and rods ("twigs") in a 0.5 m Ghost Tile,
// with density fields the tests edit, plus independent references (brute-force greedy selection and
// sphere-set distances) computed without the instantiator's machinery.
#pragma once

#include <algorithm>
#include <map>
#include <set>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "ghosttile/ghost_tile.h"
#include "ghosttile_test_util.h"
#include "instancer/instantiator.h"
#include "instancer/tile_coord.h"

namespace ug::test {

struct InstancerFixture {
    std::vector<DetailModel> models;
    GhostTile tile;
    InstancerInput input;

    explicit InstancerFixture(float delta_m = 0.0f, uint32_t blobs = 150, uint32_t rods = 100, uint32_t variants = 1) {
        models.push_back(blobModel(6, 0.12f, 3));
        models.back().name = "blob";
        models.push_back(rodModel(5, 0.1f, 0.025f));
        GhostTileInput gi;
        gi.settings = {.tile_size_m = 0.5f, .delta_m = delta_m, .seed = 11, .variants = variants};
        gi.types.push_back({.name = "blob", .candidate_count = blobs, .scale_min = 0.8f, .scale_max = 1.2f});
        DetailTypeSettings rod{.name = "rod", .candidate_count = rods, .scale_min = 0.9f, .scale_max = 1.1f};
        gi.types.push_back(rod);
        gi.models = {&models[0], &models[1]};
        std::string error;
        EXPECT_TRUE(buildGhostTile(gi, {.threads = 2}, &tile, &error)) << error;
        input.tile = &tile;
        input.models = {&models[0], &models[1]};
        input.types.resize(2);
        input.extent = Bounds{glm::vec3(-2.0f, -2.0f, -1.0f), glm::vec3(2.0f, 2.0f, 1.0f)};
        input.seed = 5;
    }

    static std::shared_ptr<const DensityField> field(std::vector<Primitive> prims) {
        return std::make_shared<DensityField>(makeBlendField(prims));
    }
};

using InstanceKey = std::pair<uint64_t, uint32_t>;

inline std::vector<InstanceKey> instancesOf(const InstanceStore& store) {
    std::vector<InstanceKey> out;
    store.forEach([&](uint64_t t, uint32_t j) { out.push_back({t, j}); });
    return out;
}

// World-space spheres of candidate j in tile t, computed directly from the candidate frame.
inline std::vector<Sphere> worldSpheres(const GhostTile& tile, const DetailModel& model, uint64_t tile_key, uint32_t j) {
    const CandidateSet& c = tile.candidates;
    const glm::vec3 origin = tileOrigin(unpackTile(tile_key), tile.settings.tile_size_m);
    std::vector<Sphere> out;
    for (const Sphere& s : model.spheres)
        out.push_back({origin + c.position[j] + c.rotation[j] * (c.scale[j] * s.center), c.scale[j] * s.radius});
    return out;
}

// The reference selection: sort every alive candidate by key, take each one whose already-taken
// neighbours (by the collision graph) do not include it. Sequential and obviously correct.
inline std::vector<InstanceKey> greedyReference(const Instantiator& inst) {
    auto alive = inst.aliveCandidates();
    std::sort(alive.begin(), alive.end(), [](const auto& a, const auto& b) {
        return keyBefore(a.priority, a.tile_key, a.candidate, b.priority, b.tile_key, b.candidate);
    });
    const GhostTile& tile = *inst.input().tile;
    std::set<InstanceKey> taken;
    for (const auto& a : alive) {
        const glm::ivec3 t = unpackTile(a.tile_key);
        bool blocked = false;
        tile.graph.forEachNeighbor(a.candidate, [&](uint32_t k, uint32_t v) {
            if (taken.count({packTile(t + offsetVector(v)), k})) blocked = true;
        });
        if (!blocked) taken.insert({a.tile_key, a.candidate});
    }
    return {taken.begin(), taken.end()};
}

}  // namespace ug::test
