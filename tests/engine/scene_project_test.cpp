// The project file: round trip, and errors that name the file, the place and the reason.
#include <gtest/gtest.h>

#include "scene/ghost_tile_job.h"
#include "scene/project.h"

namespace ug {
namespace {

const char* kGood = R"({
  "format": "undergrowth-project", "format_version": 1, "name": "t",
  "ghost_tile": {"tile_size_m": 0.5, "delta_m": -0.002, "seed": 9},
  "detail_types": [
    {"name": "rock", "model": {"mesh": "../models/rock.glb", "spheres": {"max_spheres": 40}},
     "candidates": {"count": 300, "scale": [0.8, 1.2], "position": "jittered"}},
    {"name": "leaf", "model": {"mesh": "../models/leaf_oak.glb", "anchors": {"mode": "surface", "count": 5}},
     "candidates": {"count": 200, "orientation": {"mode": "tilt", "tilt_ranges": [[0, 30, 0.75], [45, 60, 0.25]]}}},
    {"name": "pebble", "model": {"mesh": "p.obj", "y_up": false, "spheres": [[0, 0, 0, 0.02]],
     "anchors": {"mode": "authored", "points": [[0, 0, 0]]}}}
  ]
})";

TEST(Project, ParsesEveryFieldAndRoundTrips) {
    Project p;
    std::string error;
    ASSERT_TRUE(parseProject(kGood, "t.json", &p, &error)) << error;
    ASSERT_EQ(p.detail_types.size(), 3u);
    EXPECT_EQ(p.ghost_tile.seed, 9u);
    EXPECT_FLOAT_EQ(p.ghost_tile.delta_m, -0.002f);
    EXPECT_EQ(p.detail_types[0].model.fit.max_spheres, 40u);
    EXPECT_EQ(p.detail_types[0].ghost.position, PositionMode::Jittered);
    EXPECT_FLOAT_EQ(p.detail_types[0].ghost.scale_max, 1.2f);
    EXPECT_EQ(p.detail_types[1].ghost.orientation.mode, OrientationMode::Tilt);
    ASSERT_EQ(p.detail_types[1].ghost.orientation.tilt_ranges.size(), 2u);
    EXPECT_FLOAT_EQ(p.detail_types[1].ghost.orientation.tilt_ranges[1].min_deg, 45.0f);
    EXPECT_EQ(p.detail_types[1].model.anchor_mode, AnchorMode::Surface);
    EXPECT_EQ(p.detail_types[1].model.anchor_count, 5u);
    EXPECT_EQ(p.detail_types[2].model.authored_spheres.size(), 1u);
    EXPECT_FALSE(p.detail_types[2].model.y_up);

    Project back;
    ASSERT_TRUE(parseProject(projectToJson(p), "back.json", &back, &error)) << error;
    EXPECT_EQ(projectToJson(back), projectToJson(p));
}

TEST(Project, GhostTileVariantsRoundTripAndDefaultToOne) {
    Project p;
    std::string error;
    ASSERT_TRUE(parseProject(kGood, "t.json", &p, &error)) << error;
    EXPECT_EQ(p.ghost_tile.variants, 1u);
    // A single-variant project saves without the key, exactly as before variants existed.
    EXPECT_EQ(projectToJson(p).find("variants"), std::string::npos);
    std::string text = kGood;
    const std::string seed = "\"seed\": 9}";
    ASSERT_NE(text.find(seed), std::string::npos);
    text.replace(text.find(seed), seed.size(), "\"seed\": 9, \"variants\": 4}");
    ASSERT_TRUE(parseProject(text, "v.json", &p, &error)) << error;
    EXPECT_EQ(p.ghost_tile.variants, 4u);
    EXPECT_EQ(ghostTileSpec(p).settings.variants, 4u);
    const std::string saved = projectToJson(p);
    EXPECT_NE(saved.find("\"variants\": 4"), std::string::npos) << saved;
    Project back;
    ASSERT_TRUE(parseProject(saved, "back.json", &back, &error)) << error;
    EXPECT_EQ(back.ghost_tile.variants, 4u);
    EXPECT_EQ(projectToJson(back), saved);
}

TEST(Project, ErrorsNameTheFileThePlaceAndTheReason) {
    struct Case {
        std::string text;
        std::string expect;
    };
    const std::string head = R"({"format": "undergrowth-project", "format_version": 1, )";
    const std::string rock = R"({"name": "rock", "model": {"mesh": "r.glb"}})";
    std::vector<Case> cases = {
        {"{\"format\": ", "s.json: invalid JSON at line 1, column 12 (in /format): syntax error"},
        // Numbers no double can hold are located errors too, not an uncaught exception.
        {"{\"format\": \"undergrowth-project\", \"format_version\": 2,\n \"detail_types\": [{\"name\": \"a\", "
         "\"candidates\": {\"count\": 1e400}}]}",
         "s.json: /detail_types/0/candidates/count: number 1e400 is out of range (larger than a double can hold) "
         "(line 2, column 57)"},
        {"{\"format\": \"undergrowth-project\", \"format_version\": 2, \"ghost_tile\": {\"seed\": "
         "1" + std::string(400, '0') + "}}",
         "s.json: /ghost_tile/seed: number 1" + std::string(400, '0') + " is out of range"},
        {"{\"a\": [1, 2, -1e999]}", "s.json: /a/2: number -1e999 is out of range"},
        {"[1, 2]", "s.json: /: expected an object"},
        {R"({"format": "other", "format_version": 1, "detail_types": []})", "/format: expected \"undergrowth-project\""},
        {R"({"format": "undergrowth-project", "format_version": 99, "detail_types": []})", "/format_version: version 99 is newer"},
        {head + R"("detail_types": []})", "/detail_types: at least one"},
        {head + R"("detail_types": [)" + rock + R"(], "tile_sise_m": 1})", "/tile_sise_m: unknown field"},
        {head + R"("ghost_tile": {"tile_size_m": "big"}, "detail_types": [)" + rock + "]}",
         "/ghost_tile/tile_size_m: expected a number, got a string"},
        {head + R"("ghost_tile": {"tile_size_m": -1}, "detail_types": [)" + rock + "]}",
         "/ghost_tile/tile_size_m: -1 is out of range"},
        {head + R"("ghost_tile": {"variants": 0}, "detail_types": [)" + rock + "]}",
         "s.json: /ghost_tile/variants: expected an integer in [1, 64], got 0"},
        {head + R"("ghost_tile": {"variants": 65}, "detail_types": [)" + rock + "]}",
         "/ghost_tile/variants: expected an integer in [1, 64], got 65"},
        {head + R"("ghost_tile": {"variants": 2.5}, "detail_types": [)" + rock + "]}",
         "/ghost_tile/variants: expected an integer in [1, 64], got 2.5"},
        {head + R"("ghost_tile": {"variants": "four"}, "detail_types": [)" + rock + "]}",
         "/ghost_tile/variants: expected an integer in [1, 64], got \"four\""},
        {head + R"("ghost_tile": {"variants": 64}, "detail_types": [{"name": "rock", "model": {"mesh": "r.glb"}, "candidates": {"count": 20000}}]})",
         "/detail_types/0/candidates/count: the detail types' candidates add up to 20000, times 64 variants"},
        {head + R"("detail_types": [{"name": "rock", "model": {}}]})", "/detail_types/0/model/mesh: missing"},
        {head + R"("detail_types": [{"name": "rock", "model": {"mesh": "r.glb"}, "candidates": {"count": -3}}]})",
         "/detail_types/0/candidates/count: expected a non-negative integer"},
        {head + R"("detail_types": [{"name": "rock", "model": {"mesh": "r.glb"}, "candidates": {"count": 0}}]})",
         "/detail_types/0/candidates/count: 0 is out of range"},
        {head + R"("detail_types": [{"name": "rock", "model": {"mesh": "r.glb"}, "candidates": {"count": 99999999999}}]})",
         "/detail_types/0/candidates/count: 1e+11 is out of range"},
        {head + R"("detail_types": [{"name": "rock", "model": {"mesh": "r.glb"}, "candidates": {"scale": [2, 1]}}]})",
         "/detail_types/0/candidates/scale: expected [min, max] with 0 < min <= max"},
        {head + R"("detail_types": [{"name": "rock", "model": {"mesh": "r.glb", "scale": 0}}]})",
         "/detail_types/0/model/scale: 0 is out of range"},
        {head + R"("detail_types": [{"name": "rock", "model": {"mesh": "r.glb", "spheres": [[0, 0, 0, -1]]}}]})",
         "/detail_types/0/model/spheres/0/3: radius must be"},
        {head + R"("detail_types": [)" + rock + "," + rock + "]}", "/detail_types/1/name: duplicate detail type 'rock'"},
        {head + R"("detail_types": [{"name": "leaf", "model": {"mesh": "l.glb"}, "candidates": {"orientation": {"mode": "tilt"}}}]})",
         "/detail_types/0/candidates/orientation/tilt_ranges: mode 'tilt' needs"},
        {head + R"("detail_types": [{"name": "leaf", "model": {"mesh": "l.glb"}, "candidates": {"orientation": {"mode": "tilt", "tilt_ranges": [[0, 200, 1]]}}}]})",
         "/detail_types/0/candidates/orientation/tilt_ranges/0: needs 0 <= min_deg <= max_deg <= 180"},
    };
    for (const Case& c : cases) {
        Project p;
        std::string error;
        EXPECT_FALSE(parseProject(c.text, "s.json", &p, &error)) << c.text;
        EXPECT_NE(error.find(c.expect), std::string::npos) << "expected: " << c.expect << "\n     got: " << error;
        EXPECT_EQ(error.rfind("s.json", 0), 0u) << error;
    }
}

TEST(Project, MissingFileIsAnErrorNamingIt) {
    Project p;
    std::string error;
    EXPECT_FALSE(loadProject("/nonexistent/scene.json", &p, &error));
    EXPECT_NE(error.find("/nonexistent/scene.json"), std::string::npos) << error;
}

TEST(Project, RelativePathsResolveAgainstTheProjectFolder) {
    Project p;
    p.base_dir = "/data/scenes";
    EXPECT_EQ(resolveProjectPath(p, "../models/rock.glb"), "/data/models/rock.glb");
    EXPECT_EQ(resolveProjectPath(p, "/abs/x.glb"), "/abs/x.glb");
}

}  // namespace
}  // namespace ug
