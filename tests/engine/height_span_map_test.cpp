// HeightSpanMap::coveredAlong skips the steps of a slanted ray where it passes a block of cells wholly above
// or below the block's crossings. The skip must never change an answer: checked against the same map built
// without the blocks, whose walk tests every step, over rays of every drift and direction from points
// around and inside real environmental objects and an open mesh.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/hash.h"
#include "env/env_models.h"
#include "env/height_span_map.h"
#include "mesh/triangle_mesh.h"

namespace ug {
namespace {

struct Agreement {
    int rays = 0, covered = 0, mismatches = 0;
};

// Rays from points in the mesh's bounds (padded by a metre sideways, from below it to above it), drifts
// from nearly vertical (0.01) to 3 m a metre, in every direction.
Agreement compareWalks(const TriangleMesh& mesh, uint64_t seed, int rays) {
    const HeightSpanMap skipping(mesh), stepping(mesh, false);
    const Bounds3 b = meshBounds(mesh);
    Agreement out;
    for (int i = 0; i < rays; ++i) {
        const auto u = [&](uint64_t k) { return unitFloat(hashWords(seed, uint64_t(i), k)); };
        const glm::vec3 p(b.min.x - 1.0f + u(0) * (b.max.x - b.min.x + 2.0f),
                          b.min.y - 1.0f + u(1) * (b.max.y - b.min.y + 2.0f),
                          b.min.z - 0.2f + u(2) * (b.max.z - b.min.z + 0.4f));
        const float drift = 0.01f * std::pow(300.0f, u(3)), turn = 6.2831853f * u(4);
        const glm::vec2 slope = drift * glm::vec2(std::cos(turn), std::sin(turn));
        const bool a = skipping.coveredAlong(p, slope, 0.005f, b.min.z, b.max.z);
        const bool e = stepping.coveredAlong(p, slope, 0.005f, b.min.z, b.max.z);
        ++out.rays;
        out.covered += a;
        out.mismatches += a != e;
    }
    return out;
}

TEST(HeightSpanMap, SkippingBlocksNeverChangesWhatASlantedRayMeets) {
    for (const std::string name : {"bus_shelter", "bench", "tree", "fountain", "facade", "lamppost"}) {
        TriangleMesh mesh;
        ASSERT_TRUE(makeEnvStarterModel(name, 7, &mesh)) << name;
        const Agreement a = compareWalks(mesh, 11, 20000);
        EXPECT_EQ(a.mismatches, 0) << name;
        // Both answers occur hundreds of times, so the comparison is not of two constant walks.
        EXPECT_GT(a.covered, 200) << name;
        EXPECT_LT(a.covered, a.rays - 200) << name;
    }
}

// An open mesh (a canopy of down-facing triangles, no top): a vertical line through it is "inside" above
// its only crossing, so a block's top is no bound there and a step above it must still be tested.
TEST(HeightSpanMap, SkippingBlocksKeepsAnOpenMeshsInside) {
    TriangleMesh canopy;
    canopy.positions = {{0, 0, 2}, {3, 0, 2}, {3, 3, 2.5f}, {0, 3, 2.5f}};
    canopy.indices = {0, 2, 1, 0, 3, 2};  // clockwise seen from above: the faces look down
    const Agreement a = compareWalks(canopy, 5, 20000);
    EXPECT_EQ(a.mismatches, 0);
    EXPECT_GT(a.covered, 200);
    // A point above the canopy's only crossing counts as inside it, whatever the ray's drift.
    const HeightSpanMap map(canopy);
    EXPECT_TRUE(map.coveredAlong({1.5f, 1.5f, 2.4f}, {0.7f, 0.2f}, 0.005f, 2.0f, 4.0f));
}

}  // namespace
}  // namespace ug
