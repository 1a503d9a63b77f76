// The rest, packing and tiling measurements (engine/analysis) on hand-built cases with known answers.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/rest_metrics.h"
#include "analysis/tiling_metrics.h"
#include "core/hash.h"
#include "ghosttile_test_util.h"
#include "mesh_test_util.h"

namespace ug {
namespace {

using test::sphereModel;
using test::unitCube;

PlacedInstance at(glm::vec3 p, uint32_t type = 0) {
    PlacedInstance i;
    i.type = type;
    i.position = p;
    return i;
}

TEST(RestMetrics, DropIsTheGapToTheGroundOrToTheSphereBelow) {
    const DetailModel ball = sphereModel("ball", {{glm::vec3(0.0f), 0.05f}});
    const std::vector<const DetailModel*> models = {&ball};
    const std::vector<PlacedInstance> inst = {
        at({0.0f, 0.0f, 0.05f}),         // on the ground
        at({1.0f, 0.0f, 0.12f}),         // 7 cm above it
        at({0.0f, 0.0f, 0.18f}),         // 3 cm above the first ball
        at({0.06f, 0.0f, 0.30f}),        // beside the third: falls onto it, off-centre
    };
    const RestReport r = measureRest(inst, models, RestSupport{}, 0.02f, 1);
    ASSERT_EQ(r.drop_m.size(), 4u);
    EXPECT_NEAR(r.drop_m[0], 0.0f, 1e-6f);
    EXPECT_NEAR(r.drop_m[1], 0.07f, 1e-6f);
    EXPECT_NEAR(r.drop_m[2], 0.03f, 1e-6f);
    // Touches the third ball when the centres are 0.1 apart: vertical gap sqrt(0.1^2 - 0.06^2) = 0.08.
    EXPECT_NEAR(r.drop_m[3], 0.30f - 0.18f - 0.08f, 1e-6f);
    EXPECT_EQ(r.hovering, 3u);
    EXPECT_DOUBLE_EQ(r.hovering_fraction, 0.75);
    EXPECT_EQ(r.sunk, 0u);
}

TEST(RestMetrics, ABallAboveDoesNotHoldOneUpAndInterpenetrationIsContact) {
    const DetailModel ball = sphereModel("ball", {{glm::vec3(0.0f), 0.05f}});
    const std::vector<const DetailModel*> models = {&ball};
    const std::vector<PlacedInstance> inst = {at({0.0f, 0.0f, 0.20f}), at({0.0f, 0.0f, 0.26f}),
                                              at({2.0f, 0.0f, 0.02f})};
    const RestReport r = measureRest(inst, models, RestSupport{}, 0.02f, 1);
    EXPECT_NEAR(r.drop_m[0], 0.15f, 1e-6f);  // the ball overlapping it from above does not support it
    EXPECT_NEAR(r.drop_m[1], 0.0f, 1e-6f);   // overlapping the one below: in contact
    EXPECT_NEAR(r.drop_m[2], 0.0f, 1e-6f);
    EXPECT_NEAR(r.sunk_m[2], 0.03f, 1e-6f);  // its bottom is 3 cm into the ground
    EXPECT_EQ(r.sunk, 1u);
}

TEST(RestMetrics, SlopedTerrainIsTouchedOffCentre) {
    // h = 0.5 x: a ball of radius r touches the plane when its centre is r * sqrt(1.25) above h(x).
    std::vector<float> h;
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) h.push_back(0.5f * (-1.0f + 0.5f * float(i)));
    const HeightField terrain(glm::vec2(-1.0f), 0.5f, 5, 5, h);
    const DetailModel ball = sphereModel("ball", {{glm::vec3(0.0f), 0.1f}});
    const std::vector<const DetailModel*> models = {&ball};
    const float contact = 0.1f * std::sqrt(1.25f);
    RestSupport support;
    support.terrain = &terrain;
    const std::vector<PlacedInstance> inst = {at({0.0f, 0.0f, contact + 0.05f}), at({0.2f, 0.0f, 0.1f + contact})};
    const RestReport r = measureRest(inst, models, support, 0.02f, 1);
    // The underside is sampled on rings, so the measured drop may exceed the exact one by a little.
    EXPECT_GE(r.drop_m[0], 0.05f - 1e-5f);
    EXPECT_LE(r.drop_m[0], 0.05f + 0.004f);
    EXPECT_LE(r.drop_m[1], 0.004f);
}

TEST(RestMetrics, SameDropsForAnyThreadCountAndPerTypeSplitAddsUp) {
    const DetailModel a = sphereModel("a", {{glm::vec3(-0.02f, 0, 0), 0.03f}, {glm::vec3(0.02f, 0, 0), 0.03f}});
    const DetailModel b = sphereModel("b", {{glm::vec3(0.0f), 0.02f}});
    const std::vector<const DetailModel*> models = {&a, &b};
    std::vector<PlacedInstance> inst;
    for (uint64_t k = 0; k < 2000; ++k) {
        const glm::vec3 p(unitFloat(hashWords(9, k, 1)), unitFloat(hashWords(9, k, 2)),
                          0.3f * unitFloat(hashWords(9, k, 3)));
        inst.push_back(at(p, uint32_t(k % 2)));
    }
    const RestReport one = measureRest(inst, models, RestSupport{}, 0.02f, 1);
    const RestReport two = measureRest(inst, models, RestSupport{}, 0.02f, 2);
    EXPECT_EQ(one.drop_m, two.drop_m);
    const std::vector<RestReport> per = restPerType(one, inst, 2);
    EXPECT_EQ(per[0].instances + per[1].instances, one.instances);
    EXPECT_EQ(per[0].hovering + per[1].hovering, one.hovering);
    EXPECT_GT(one.hovering, 0u);
    EXPECT_LT(one.hovering, one.instances);
}

// An axis-aligned cube of the given side, its one collision sphere inscribed.
DetailModel cubeModel(float side) {
    DetailModel box = sphereModel("box", {{glm::vec3(0.0f), 0.5f * side}});
    box.mesh = unitCube();
    for (glm::vec3& p : box.mesh.positions) p *= side;
    box.bounds = {glm::vec3(0.0f), 0.5f * side * std::sqrt(3.0f)};
    return box;
}

// Instances on a 0.1 m lattice of nx x ny x nz, the lowest layer's centres 5.5 cm up.
std::vector<PlacedInstance> cubeLattice(int nx, int ny, int nz) {
    std::vector<PlacedInstance> inst;
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x)
                inst.push_back(at({0.05f + 0.1f * float(x), 0.05f + 0.1f * float(y), 0.055f + 0.1f * float(z)}));
    return inst;
}

TEST(PackingMetrics, CubeLatticeFillsItsPitchCubed) {
    // Cubes of side 0.08 on a 0.1 lattice: each axis of the sample grid (2 cm) meets a cube at 4 of every
    // 5 samples, so the core is (0.8)^3 = 0.512 solid, up to the partial pitch the shell cuts at the top.
    const DetailModel box = cubeModel(0.08f);
    const std::vector<const DetailModel*> models = {&box};
    const std::vector<PlacedInstance> inst = cubeLattice(20, 20, 10);
    // Away from the block's sides, where the core meets open air.
    const Bounds interior{glm::vec3(0.5f, 0.5f, -1.0f), glm::vec3(1.5f, 1.5f, 2.0f)};
    const PackingReport r = measurePacking(inst, models, RestSupport{}, {}, 0.02f, 2, &interior);
    EXPECT_GT(r.core_samples, 100000u);
    EXPECT_NEAR(r.volume_fraction, 0.512, 0.03);
    EXPECT_EQ(r.overlap_samples, 0u);  // the cubes do not touch
    EXPECT_EQ(r.overlap_fraction, 0.0);
    // Every second cube removed (a checkerboard): half as much.
    std::vector<PlacedInstance> half;
    for (size_t i = 0; i < inst.size(); ++i)
        if ((i + i / 20 + i / 400) % 2 == 0) half.push_back(inst[i]);
    const PackingReport h = measurePacking(half, models, RestSupport{}, {}, 0.02f, 1, &interior);
    EXPECT_NEAR(h.volume_fraction, 0.256, 0.03);
    // Without the clip the open sides count too: less, but the block is still mostly solid.
    const PackingReport all = measurePacking(inst, models, RestSupport{}, {}, 0.02f, 1);
    EXPECT_LT(all.volume_fraction, r.volume_fraction);
    EXPECT_GT(all.volume_fraction, 0.35);
}

TEST(PackingMetrics, InterpenetratingCubesShowTheirSharedVolume) {
    // Cubes of side 0.14 on a 0.1 lattice: along each axis neighbours share 0.04 of every 0.1, so the block
    // is solid throughout and a point lies in one cube only where it is clear of the shared slabs along
    // all three axes: (0.6)^3 of the volume; the rest, 1 - 0.216 = 0.784, lies in two or more.
    const DetailModel box = cubeModel(0.14f);
    const std::vector<const DetailModel*> models = {&box};
    std::vector<PlacedInstance> inst = cubeLattice(12, 12, 8);
    const Bounds interior{glm::vec3(0.3f, 0.3f, -1.0f), glm::vec3(0.9f, 0.9f, 2.0f)};
    const PackingReport r = measurePacking(inst, models, RestSupport{}, {}, 0.02f, 2, &interior);
    EXPECT_GT(r.core_samples, 20000u);
    EXPECT_NEAR(r.volume_fraction, 1.0, 0.01);
    EXPECT_NEAR(r.overlap_fraction, 0.784, 0.03);
    EXPECT_LE(r.overlap_samples, r.solid_samples);
    // Spread to a 0.15 lattice the same cubes leave 1 cm gaps: nothing is shared.
    for (PlacedInstance& p : inst) p.position *= 1.5f;
    const Bounds wider{glm::vec3(0.45f, 0.45f, -1.0f), glm::vec3(1.35f, 1.35f, 3.0f)};
    const PackingReport apart = measurePacking(inst, models, RestSupport{}, {}, 0.02f, 2, &wider);
    EXPECT_GT(apart.solid_samples, 0u);
    EXPECT_EQ(apart.overlap_samples, 0u);
}

std::vector<PlacedInstance> tiledSet(int tiles_x, int tiles_y, int per_tile, float s, bool vary_tile) {
    std::vector<PlacedInstance> out;
    for (int ty = 0; ty < tiles_y; ++ty)
        for (int tx = 0; tx < tiles_x; ++tx)
            for (int j = 0; j < per_tile; ++j) {
                const uint64_t seed = vary_tile ? hashWords(uint64_t(tx), uint64_t(ty), 77) : 77;
                PlacedInstance p;
                p.position = glm::vec3(float(tx) * s, float(ty) * s, 0.0f) +
                             s * glm::vec3(unitFloat(hashWords(seed, uint64_t(j), 1)),
                                           unitFloat(hashWords(seed, uint64_t(j), 2)), 0.1f);
                p.rotation = glm::angleAxis(6.2831853f * unitFloat(hashWords(seed, uint64_t(j), 3)),
                                            glm::vec3(0.0f, 0.0f, 1.0f));
                out.push_back(p);
            }
    return out;
}

TEST(TilingMetrics, TwinFractionCountsExactCopiesOneTileAway) {
    const float s = 0.5f;
    EXPECT_DOUBLE_EQ(twinFraction(tiledSet(6, 6, 40, s, false), s), 1.0);
    EXPECT_DOUBLE_EQ(twinFraction(tiledSet(6, 6, 40, s, true), s), 0.0);
    // Three tiles in a row; the third holds the same positions turned: only the first two are twins.
    std::vector<PlacedInstance> row = tiledSet(3, 1, 30, s, false);
    for (size_t i = 60; i < 90; ++i) row[i].rotation = glm::angleAxis(0.3f, glm::vec3(0, 0, 1)) * row[i].rotation;
    EXPECT_NEAR(twinFraction(row, s), 2.0 / 3.0, 1e-12);
    // Two tiles apart is not one tile away.
    std::vector<PlacedInstance> apart = tiledSet(1, 1, 30, s, false);
    for (size_t i = 0; i < 30; ++i) {
        PlacedInstance p = apart[i];
        p.position.x += 2.0f * s;
        apart.push_back(p);
    }
    EXPECT_DOUBLE_EQ(twinFraction(apart, s), 0.0);
}

TEST(TilingMetrics, SpectralPeakSeesTheTilePeriodAndNotRandomPoints) {
    const float s = 0.5f;
    const SpectrumReport tiled = tilePeriodSpectrum(tiledSet(20, 20, 50, s, false), s, {}, 2);
    const SpectrumReport random = tilePeriodSpectrum(tiledSet(20, 20, 50, s, true), s, {}, 2);
    EXPECT_EQ(tiled.instances, 20000u);
    EXPECT_GT(tiled.ratio, 50.0);
    EXPECT_LT(random.ratio, 3.0);
    EXPECT_GT(random.background, 0.5);  // Poisson points: about 1 at every frequency
    EXPECT_LT(random.background, 2.0);
}

}  // namespace
}  // namespace ug
