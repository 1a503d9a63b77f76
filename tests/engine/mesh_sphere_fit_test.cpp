#include <gtest/gtest.h>

#include "mesh_test_util.h"
#include "mesh/detail_model.h"
#include "mesh/procedural_models.h"

namespace ug {
namespace {

// Worst distance from a dense, independent sample set (seed unrelated to the fit's) to the union.
float independentCoverage(const TriangleMesh& mesh, const std::vector<Sphere>& spheres) {
    std::vector<glm::vec3> points;
    sampleSurface(mesh, 20000, 0xfeedbeefull, &points, nullptr);
    float worst = 0.0f;
    for (const glm::vec3& p : points) worst = std::max(worst, distanceToSphereUnion(spheres, p));
    return worst;
}

void expectTightCover(const TriangleMesh& mesh, const std::vector<Sphere>& spheres, const SphereFitReport& report,
                      const std::string& what) {
    SCOPED_TRACE(what);
    ASSERT_FALSE(spheres.empty());
    EXPECT_EQ(report.sphere_count, spheres.size());
    EXPECT_LE(report.max_sample_distance_m, report.tolerance_m);
    EXPECT_LE(independentCoverage(mesh, spheres), report.tolerance_m);
    // Tight: no sphere wanders off the model or outgrows it.
    const Bounds3 box = meshBounds(mesh);
    const glm::vec3 extent = box.max - box.min;
    const float half_extent = 0.5f * std::max(extent.x, std::max(extent.y, extent.z));
    for (const Sphere& s : spheres) {
        EXPECT_GT(s.radius, 0.0f);
        if (!report.radii_grown) {
            EXPECT_LE(s.radius, half_extent);
        }
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(s.center, box.min - report.tolerance_m)) &&
                    glm::all(glm::lessThanEqual(s.center, box.max + report.tolerance_m)));
    }
}

}  // namespace

TEST(SphereFit, DistanceToUnionIsZeroInsideAndGapOutside) {
    const std::vector<Sphere> spheres = {{{0, 0, 0}, 1.0f}, {{3, 0, 0}, 0.5f}};
    EXPECT_EQ(distanceToSphereUnion(spheres, {0.5f, 0, 0}), 0.0f);
    EXPECT_FLOAT_EQ(distanceToSphereUnion(spheres, {0, 2, 0}), 1.0f);
    EXPECT_FLOAT_EQ(distanceToSphereUnion(spheres, {4, 0, 0}), 0.5f);
}

TEST(SphereFit, SamplesLieOnTheSurfaceAndAreDeterministic) {
    const TriangleMesh cube = test::unitCube();
    std::vector<glm::vec3> a, b, normals;
    sampleSurface(cube, 500, 3, &a, &normals);
    sampleSurface(cube, 500, 3, &b, nullptr);
    ASSERT_EQ(a.size(), 500u);
    EXPECT_EQ(a, b);
    for (size_t i = 0; i < a.size(); ++i) {
        const glm::vec3 q = glm::abs(a[i]);
        EXPECT_NEAR(std::max(q.x, std::max(q.y, q.z)), 0.5f, 1e-5f);
        EXPECT_NEAR(glm::dot(normals[i], a[i]), 0.5f, 1e-5f);  // outward face normal
    }
}

TEST(SphereFit, CoversUnitCubeWithinTolerance) {
    const TriangleMesh cube = test::unitCube();
    std::vector<Sphere> spheres;
    SphereFitReport report;
    std::string error;
    ASSERT_TRUE(fitSphereSet(cube, SphereFitSettings{}, &spheres, &report, &error)) << error;
    expectTightCover(cube, spheres, report, "cube");
}

TEST(SphereFit, CoversFlatQuadWithinTolerance) {
    const TriangleMesh quad = test::flatQuad();
    SphereFitSettings settings;
    settings.max_spheres = 1024;
    std::vector<Sphere> spheres;
    SphereFitReport report;
    std::string error;
    ASSERT_TRUE(fitSphereSet(quad, settings, &spheres, &report, &error)) << error;
    expectTightCover(quad, spheres, report, "quad");
    EXPECT_FALSE(report.radii_grown);
    for (const Sphere& s : spheres) EXPECT_LE(s.radius, 2.0f * report.tolerance_m);  // thin: small spheres
}

TEST(SphereFit, CountBoundIsKeptAndCoverageStillHolds) {
    const TriangleMesh quad = test::flatQuad();
    SphereFitSettings settings;
    settings.max_spheres = 3;
    std::vector<Sphere> spheres;
    SphereFitReport report;
    ASSERT_TRUE(fitSphereSet(quad, settings, &spheres, &report, nullptr));
    EXPECT_LE(spheres.size(), 3u);
    EXPECT_TRUE(report.radii_grown);
    EXPECT_LE(report.max_sample_distance_m, report.tolerance_m);
}

TEST(SphereFit, EveryStarterAssetIsCoveredWithinTolerance) {
    for (const std::string& name : starterAssetNames()) {
        TriangleMesh mesh;
        ASSERT_TRUE(makeStarterAsset(name, kStarterAssetSeed, &mesh));
        std::vector<Sphere> spheres;
        SphereFitReport report;
        std::string error;
        ASSERT_TRUE(fitSphereSet(mesh, SphereFitSettings{}, &spheres, &report, &error)) << name << ": " << error;
        expectTightCover(mesh, spheres, report, name);
        EXPECT_LE(report.max_check_distance_m, report.tolerance_m) << name;
        EXPECT_LE(spheres.size(), 96u);
    }
}

TEST(SphereFit, FittingIsDeterministic) {
    const TriangleMesh rock = makeRock(5);
    std::vector<Sphere> a, b;
    ASSERT_TRUE(fitSphereSet(rock, SphereFitSettings{}, &a, nullptr, nullptr));
    ASSERT_TRUE(fitSphereSet(rock, SphereFitSettings{}, &b, nullptr, nullptr));
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].center, b[i].center);
        EXPECT_EQ(a[i].radius, b[i].radius);
    }
}

TEST(SphereFit, ThinLeavesAndTwigsNeedManySpheresPebbleFew) {
    auto count = [](const TriangleMesh& mesh) {
        std::vector<Sphere> spheres;
        EXPECT_TRUE(fitSphereSet(mesh, SphereFitSettings{}, &spheres, nullptr, nullptr));
        return spheres.size();
    };
    const size_t oak = count(makeOakLeaf(kStarterAssetSeed)), birch = count(makeBirchLeaf(kStarterAssetSeed));
    const size_t twig = count(makeTwig(kStarterAssetSeed)), pebble = count(makePebble(kStarterAssetSeed));
    EXPECT_GE(oak, 20u);
    EXPECT_GE(birch, 20u);
    EXPECT_GE(twig, 20u);
    EXPECT_LE(pebble, 32u);
    EXPECT_LT(pebble, std::min(oak, birch));
}

TEST(SphereFit, RejectsBadSettings) {
    const TriangleMesh cube = test::unitCube();
    std::vector<Sphere> spheres;
    std::string error;
    SphereFitSettings s;
    s.max_spheres = 0;
    EXPECT_FALSE(fitSphereSet(cube, s, &spheres, nullptr, &error));
    EXPECT_NE(error.find("max_spheres"), std::string::npos);
    s = SphereFitSettings{};
    s.tolerance_m = -1.0f;
    EXPECT_FALSE(fitSphereSet(cube, s, &spheres, nullptr, &error));
    EXPECT_NE(error.find("tolerance_m"), std::string::npos);
    s = SphereFitSettings{};
    s.surface_samples = 2000000;
    EXPECT_FALSE(fitSphereSet(cube, s, &spheres, nullptr, &error));
    EXPECT_NE(error.find("surface_samples"), std::string::npos);
}

}  // namespace ug
