// Candidate frames (Ghost Tile §4.2) and input validation.
#include <gtest/gtest.h>

#include <cmath>

#include "ghosttile/ghost_tile.h"
#include "ghosttile_test_util.h"

namespace ug {
namespace {

GhostTileInput oneType(const DetailModel* model, DetailTypeSettings type) {
    GhostTileInput input;
    input.settings = {.tile_size_m = 0.5f, .delta_m = 0.0f, .seed = 11};
    input.types = {type};
    input.models = {model};
    return input;
}

TEST(GhostTileCandidates, FramesAreInsideTheTileUnitAndInScaleRange) {
    DetailModel m = test::blobModel(4, 0.1f, 1);
    GhostTileInput input = oneType(&m, {.name = "rock", .candidate_count = 2000, .scale_min = 0.5f, .scale_max = 1.5f});
    CandidateSet c;
    std::string error;
    ASSERT_TRUE(generateCandidates(input, &c, &error)) << error;
    ASSERT_EQ(c.size(), 2000u);
    float smin = 10, smax = 0;
    for (uint32_t i = 0; i < c.size(); ++i) {
        for (int a = 0; a < 3; ++a) {
            EXPECT_GE(c.position[i][a], 0.0f);
            EXPECT_LT(c.position[i][a], 0.5f);
        }
        EXPECT_NEAR(glm::length(c.rotation[i]), 1.0f, 1e-5f);
        smin = std::min(smin, c.scale[i]);
        smax = std::max(smax, c.scale[i]);
    }
    EXPECT_GE(smin, 0.5f);
    EXPECT_LE(smax, 1.5f);
    EXPECT_LT(smin, 0.55f);  // the whole range is used
    EXPECT_GT(smax, 1.45f);
}

TEST(GhostTileCandidates, UniformRotationsCoverTheSphere) {
    DetailModel m = test::blobModel(4, 0.1f, 1);
    GhostTileInput input = oneType(&m, {.name = "rock", .candidate_count = 20000});
    CandidateSet c;
    std::string error;
    ASSERT_TRUE(generateCandidates(input, &c, &error)) << error;
    // For uniform rotations, the rotated +Z is uniform on the sphere: its z is uniform in [-1, 1].
    int upper = 0;
    double mean_z = 0;
    for (uint32_t i = 0; i < c.size(); ++i) {
        float z = (c.rotation[i] * glm::vec3(0, 0, 1)).z;
        upper += z > 0.5f;
        mean_z += z;
    }
    EXPECT_NEAR(upper / 20000.0, 0.25, 0.015);
    EXPECT_NEAR(mean_z / 20000.0, 0.0, 0.02);
}

TEST(GhostTileCandidates, TiltRangesAreRespectedInTheirProportions) {
    // The paper's Fig. 7: 75 % almost horizontal (0-30 deg), 25 % inclined (45-60 deg).
    DetailModel m = test::rodModel(3, 0.05f, 0.01f);
    DetailTypeSettings leaves{.name = "leaf", .candidate_count = 8000};
    leaves.orientation.mode = OrientationMode::Tilt;
    leaves.orientation.tilt_ranges = {{0.0f, 30.0f, 3.0f}, {45.0f, 60.0f, 1.0f}};
    CandidateSet c;
    std::string error;
    ASSERT_TRUE(generateCandidates(oneType(&m, leaves), &c, &error)) << error;
    int flat = 0, inclined = 0;
    for (uint32_t i = 0; i < c.size(); ++i) {
        float tilt = glm::degrees(std::acos(std::clamp((c.rotation[i] * glm::vec3(0, 0, 1)).z, -1.0f, 1.0f)));
        if (tilt <= 30.01f) ++flat;
        else if (tilt >= 44.99f && tilt <= 60.01f) ++inclined;
        else ADD_FAILURE() << "tilt " << tilt << " outside both ranges";
    }
    EXPECT_NEAR(flat / 8000.0, 0.75, 0.02);
    EXPECT_NEAR(inclined / 8000.0, 0.25, 0.02);
}

TEST(GhostTileCandidates, JitteredPositionsPutOneCandidatePerCell) {
    DetailModel m = test::blobModel(2, 0.05f, 1);
    GhostTileInput input = oneType(&m, {.name = "p", .candidate_count = 512, .position = PositionMode::Jittered});
    CandidateSet c;
    std::string error;
    ASSERT_TRUE(generateCandidates(input, &c, &error)) << error;
    std::vector<int> cell_count(512, 0);
    for (uint32_t i = 0; i < c.size(); ++i) {
        glm::ivec3 cell = glm::ivec3(c.position[i] / (0.5f / 8.0f));
        cell_count[size_t(cell.x + 8 * cell.y + 64 * cell.z)]++;
    }
    for (int n : cell_count) EXPECT_EQ(n, 1);
}

TEST(GhostTileCandidates, TypesAreGroupedAndIndependentOfOtherTypesCounts) {
    DetailModel a = test::blobModel(2, 0.05f, 1), b = test::rodModel(3, 0.05f, 0.01f);
    GhostTileInput input;
    input.settings = {.tile_size_m = 0.5f, .seed = 3};
    input.types = {{.name = "a", .candidate_count = 10}, {.name = "b", .candidate_count = 20}};
    input.models = {&a, &b};
    CandidateSet c1, c2;
    std::string error;
    ASSERT_TRUE(generateCandidates(input, &c1, &error));
    EXPECT_EQ(c1.type_begin, (std::vector<uint32_t>{0, 10, 30}));
    input.types[0].candidate_count = 15;
    ASSERT_TRUE(generateCandidates(input, &c2, &error));
    // Type b's candidate j keeps its frame when type a grows: frames hash (seed, type, j).
    for (uint32_t j = 0; j < 20; ++j) EXPECT_EQ(c1.position[10 + j], c2.position[15 + j]);
}

TEST(GhostTileValidation, RefusesBadInputWithTheTypeAndFieldNamed) {
    DetailModel m = test::blobModel(3, 0.1f, 1);
    DetailModel empty;
    struct Case {
        const char* what;
        std::function<void(GhostTileInput&)> spoil;
        const char* expect;
    };
    std::vector<Case> cases = {
        {"zero candidates", [](GhostTileInput& in) { in.types[0].candidate_count = 0; }, "candidate_count is 0"},
        {"absurd count", [](GhostTileInput& in) { in.types[0].candidate_count = 4000000000u; }, "exceeds the limit"},
        {"NaN scale", [](GhostTileInput& in) { in.types[0].scale_min = NAN; }, "scale range"},
        {"negative scale", [](GhostTileInput& in) { in.types[0].scale_min = -1.0f; }, "scale range"},
        {"inverted scale", [](GhostTileInput& in) { in.types[0].scale_max = 0.5f; }, "scale range"},
        {"NaN tile", [](GhostTileInput& in) { in.settings.tile_size_m = NAN; }, "tile_size_m"},
        {"negative tile", [](GhostTileInput& in) { in.settings.tile_size_m = -0.5f; }, "tile_size_m"},
        {"NaN delta", [](GhostTileInput& in) { in.settings.delta_m = NAN; }, "delta_m"},
        {"tile too small", [](GhostTileInput& in) { in.settings.tile_size_m = 0.05f; }, "does not fit"},
        {"no tilt ranges",
         [](GhostTileInput& in) { in.types[0].orientation.mode = OrientationMode::Tilt; }, "tilt range"},
        {"bad tilt range",
         [](GhostTileInput& in) {
             in.types[0].orientation = {OrientationMode::Tilt, {{50.0f, 10.0f, 1.0f}}};
         },
         "tilt range 0"},
        {"no spheres", [&](GhostTileInput& in) { in.models[0] = &empty; }, "no collision spheres"},
        {"model count", [](GhostTileInput& in) { in.models.clear(); }, "models"},
        {"no types", [](GhostTileInput& in) { in.types.clear(); in.models.clear(); }, "no detail types"},
    };
    for (const Case& k : cases) {
        GhostTileInput input = oneType(&m, {.name = "rock", .candidate_count = 10});
        k.spoil(input);
        std::string error;
        GhostTile tile;
        EXPECT_FALSE(buildGhostTile(input, {}, &tile, &error)) << k.what;
        EXPECT_NE(error.find(k.expect), std::string::npos) << k.what << ": " << error;
        if (std::string(k.what) != "no types" && std::string(k.what).find("tile") == std::string::npos &&
            std::string(k.what) != "NaN delta" && std::string(k.what) != "model count") {
            EXPECT_NE(error.find("'rock'"), std::string::npos) << k.what << ": " << error;
        }
    }
}

TEST(GhostTileBuild, CancelStopsTheBuild) {
    DetailModel m = test::blobModel(6, 0.1f, 1);
    GhostTileInput input = oneType(&m, {.name = "rock", .candidate_count = 3000});
    std::atomic<bool> cancel{true};
    GhostTile tile;
    std::string error;
    EXPECT_FALSE(buildGhostTile(input, {.cancel = &cancel}, &tile, &error));
    EXPECT_NE(error.find("cancelled"), std::string::npos);
}

TEST(GhostTileBuild, ReportsProgressUpToOne) {
    DetailModel m = test::blobModel(6, 0.1f, 1);
    GhostTileInput input = oneType(&m, {.name = "rock", .candidate_count = 300});
    float last = -1.0f;
    bool monotone = true;
    GhostTile tile;
    std::string error;
    ASSERT_TRUE(buildGhostTile(input, {.threads = 1, .progress = [&](float f) {
                                           monotone = monotone && f >= last;
                                           last = f;
                                       }},
                               &tile, &error));
    EXPECT_TRUE(monotone);
    EXPECT_EQ(last, 1.0f);
}

}  // namespace
}  // namespace ug
