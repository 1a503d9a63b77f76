#include <atomic>

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

namespace ug {

// A scan-sized model: the fit meets the coverage guarantee on its samples, its independent check set
// and a third, denser set of our own; the spheres do not depend on the thread count.
TEST(SphereFit, ScannedRockIsCoveredAndThreadCountIndependent) {
    const TriangleMesh scan = makeScannedRock(200000, 9);
    ASSERT_GE(scan.triangleCount(), 198000u);
    std::vector<Sphere> one, two;
    SphereFitReport report_one, report_two;
    std::string error;
    SphereFitSettings settings;
    settings.threads = 1;
    ASSERT_TRUE(fitSphereSet(scan, settings, &one, &report_one, &error)) << error;
    settings.threads = 2;
    ASSERT_TRUE(fitSphereSet(scan, settings, &two, &report_two, &error)) << error;
    ASSERT_EQ(one.size(), two.size());
    for (size_t i = 0; i < one.size(); ++i) {
        EXPECT_EQ(one[i].center, two[i].center) << i;
        EXPECT_EQ(one[i].radius, two[i].radius) << i;
    }
    EXPECT_EQ(report_one.max_check_distance_m, report_two.max_check_distance_m);
    EXPECT_EQ(report_one.radii_grown, report_two.radii_grown);
    expectTightCover(scan, one, report_one, "scanned rock");
    EXPECT_LE(report_one.max_check_distance_m, report_one.tolerance_m);
    EXPECT_EQ(report_one.check_sample_count, settings.surface_samples);
    EXPECT_LE(one.size(), settings.max_spheres);
}

TEST(SphereFit, SurfaceSampleLimitIsRefusedBeforeAnyWork) {
    SphereFitSettings s;
    s.surface_samples = 1000000;
    std::string error;
    EXPECT_FALSE(validateSphereFitSettings(s, &error));
    EXPECT_EQ(error, "fit.surface_samples = 1000000 exceeds the limit of 20000");
    // The settings are refused before the mesh is looked at: an empty mesh would say "no triangles".
    std::vector<Sphere> spheres;
    EXPECT_FALSE(fitSphereSet(TriangleMesh{}, s, &spheres, nullptr, &error));
    EXPECT_EQ(error, "fit.surface_samples = 1000000 exceeds the limit of 20000");
    EXPECT_TRUE(spheres.empty());
    // ... and before a model's file is read: a missing file would name the path.
    DetailModelSource source;
    source.name = "scan";
    source.mesh_path = test::tempPath("not_there.glb");
    source.fit = s;
    DetailModel model;
    EXPECT_FALSE(loadDetailModel(source, &model, &error));
    EXPECT_EQ(error, "detail model 'scan' (" + source.mesh_path +
                         "): fit.surface_samples = 1000000 exceeds the limit of 20000");
    // The limit itself is allowed, and so is the minimum; below the minimum is refused.
    s.surface_samples = kMaxSurfaceSamples;
    EXPECT_TRUE(validateSphereFitSettings(s, &error)) << error;
    s.surface_samples = kMinSurfaceSamples;
    EXPECT_TRUE(validateSphereFitSettings(s, &error)) << error;
    s.surface_samples = kMinSurfaceSamples - 1;
    EXPECT_FALSE(validateSphereFitSettings(s, &error));
    EXPECT_EQ(error, "fit.surface_samples = 15 is below the minimum of 16");
}

TEST(SphereFit, ProgressRisesToOneAndDoesNotChangeTheResult) {
    for (const TriangleMesh& mesh : {makeRock(5), makeOakLeaf(5), makeScannedRock(20000, 5)}) {
        SphereFitSettings plain;
        plain.threads = 2;
        std::vector<Sphere> want, got;
        SphereFitReport want_report, got_report;
        ASSERT_TRUE(fitSphereSet(mesh, plain, &want, &want_report, nullptr));
        std::vector<float> fractions;
        SphereFitSettings with = plain;
        with.progress = [&](float f) { fractions.push_back(f); };
        ASSERT_TRUE(fitSphereSet(mesh, with, &got, &got_report, nullptr));
        ASSERT_EQ(want.size(), got.size());
        for (size_t i = 0; i < want.size(); ++i) {
            EXPECT_EQ(want[i].center, got[i].center);
            EXPECT_EQ(want[i].radius, got[i].radius);
        }
        EXPECT_EQ(want_report.max_check_distance_m, got_report.max_check_distance_m);
        EXPECT_EQ(want_report.max_sample_distance_m, got_report.max_sample_distance_m);
        ASSERT_GE(fractions.size(), 5u);
        EXPECT_GE(fractions.front(), 0.0f);
        for (size_t i = 1; i < fractions.size(); ++i) EXPECT_GT(fractions[i], fractions[i - 1]) << i;
        EXPECT_EQ(fractions.back(), 1.0f);
    }
}

TEST(SphereFit, CancelStopsTheFit) {
    const TriangleMesh rock = makeScannedRock(20000, 6);
    std::atomic<bool> cancel{false};
    SphereFitSettings s;
    s.cancel = &cancel;
    int calls = 0;
    s.progress = [&](float f) {
        ++calls;
        if (f > 0.3f) cancel = true;
    };
    std::vector<Sphere> spheres;
    std::string error;
    EXPECT_FALSE(fitSphereSet(rock, s, &spheres, nullptr, &error));
    EXPECT_EQ(error, "cancelled");
    EXPECT_TRUE(spheres.empty());
    EXPECT_GT(calls, 0);
}

}  // namespace ug
