// The environmental-object tree and the environment e(p) (engine/env/env_scene.h) on hand-made scenes with
// hand-computed values: fields blend by sum, occlusion by product, object-space fields follow their
// object, LOD nodes replace their subtree's fields, references instance groups, shelter and clearance
// follow the geometry, and bad trees are refused with the place and the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "env/env_json.h"
#include "env/env_scene.h"
#include "scene/project.h"
#include "scene_test_util.h"

namespace ug {
namespace {

// Axis-aligned boxes (lo, hi pairs) as one Z-up OBJ (outward faces).
std::string boxesObj(std::initializer_list<std::pair<glm::vec3, glm::vec3>> boxes) {
    std::string s;
    int base = 0;
    for (const auto& [lo, hi] : boxes) {
        for (int k = 0; k < 8; ++k)
            s += "v " + std::to_string((k & 1) ? hi.x : lo.x) + " " + std::to_string((k & 2) ? hi.y : lo.y) + " " +
                 std::to_string((k & 4) ? hi.z : lo.z) + "\n";
        const auto f = [&](int a, int b, int c, int d) {
            s += "f " + std::to_string(base + a) + " " + std::to_string(base + b) + " " + std::to_string(base + c) +
                 " " + std::to_string(base + d) + "\n";
        };
        f(1, 3, 4, 2), f(5, 6, 8, 7), f(1, 2, 6, 5), f(3, 7, 8, 4), f(1, 5, 7, 3), f(2, 4, 8, 6);
        base += 8;
    }
    return s;
}

std::string boxObj(glm::vec3 lo, glm::vec3 hi) { return boxesObj({{lo, hi}}); }

struct EnvFixture {
    test::TempDir dir{"ug_env_scene_"};
    EnvFixture() {
        std::ofstream(dir.path() / "cube.obj") << boxObj({-0.5f, -0.5f, 0.0f}, {0.5f, 0.5f, 1.0f});
        std::ofstream(dir.path() / "roof.obj") << boxObj({-1.0f, -1.0f, 2.0f}, {1.0f, 1.0f, 2.1f});
        std::ofstream(dir.path() / "wall.obj") << boxObj({-0.1f, -1.0f, 0.0f}, {0.1f, 1.0f, 3.0f});
        // A paving slab 12 cm thick with a 30 cm kerb along its +Y edge (taller than the shelter's 3 cm).
        std::ofstream(dir.path() / "kerbed_slab.obj")
            << boxesObj({{{-1.0f, -1.0f, 0.0f}, {1.0f, 0.85f, 0.12f}}, {{-1.0f, 0.85f, 0.0f}, {1.0f, 1.0f, 0.3f}}});
    }
    // A project with `env` as its environment; false with the error.
    bool load(const std::string& env, Project* p, std::string* error) {
        const std::string text = R"({"format": "undergrowth-project", "format_version": 3, "name": "env",
          "ghost_tile": {"tile_size_m": 0.5, "delta_m": 0.0, "seed": 1},
          "detail_types": [{"name": "d", "model": {"mesh": "cube.obj", "y_up": false}, "candidates": {"count": 4}}],
          "environment": )" + env + "}";
        const std::string path = (dir.path() / "scene.json").string();
        std::ofstream(path) << text;
        return loadProject(path, p, error);
    }
    bool compile(const std::string& env, EnvScene* out, std::string* error) {
        Project p;
        if (!load(env, &p, error)) return false;
        return compileEnvScene(p.environment, p.base_dir, "scene.json", nullptr, out, error);
    }
};

const std::string kTypes = R"("types": [
    {"name": "cube", "mesh": "cube.obj", "y_up": false,
     "fields": [{"channel": "temperature", "value": 2, "shape": {"point": {"center": [0, 0, 1], "radius": 1}}}]},
    {"name": "roof", "mesh": "roof.obj", "y_up": false},
    {"name": "wall", "mesh": "wall.obj", "y_up": false},
    {"name": "kerbed_slab", "mesh": "kerbed_slab.obj", "y_up": false}])";

TEST(EnvScene, ChannelsSumAndOcclusionMultiplies) {
    EnvFixture f;
    EnvScene env;
    std::string error;
    ASSERT_TRUE(f.compile(R"({)" + kTypes + R"(, "global_fields": [
        {"channel": "snow", "value": 0.1},
        {"channel": "snow", "value": 0.2, "shape": {"point": {"center": [5, 5, 0], "radius": 1}}},
        {"channel": "occlusion", "value": 0.5, "shape": {"point": {"center": [5, 5, 0], "radius": 1}}},
        {"channel": "occlusion", "value": 0.5, "shape": {"point": {"center": [5, 5, 0], "radius": 1}}},
        {"channel": "temperature", "value": -2},
        {"channel": "temperature", "value": 3, "shape": {"point": {"center": [5, 5, 0], "radius": 1}}}]})",
                          &env, &error))
        << error;
    // At the centre: K = 1.
    EnvSample c = env.channels({5.0f, 5.0f, 0.0f});
    EXPECT_FLOAT_EQ(c.snow, 0.3f);
    EXPECT_FLOAT_EQ(c.occlusion, 0.25f);  // (1 - 0.5)(1 - 0.5)
    EXPECT_FLOAT_EQ(c.temperature, 1.0f); // -2 + 3
    // Half a radius out: K = (1 - 1/4)^3 = 0.421875.
    EnvSample h = env.channels({5.5f, 5.0f, 0.0f});
    EXPECT_FLOAT_EQ(h.snow, 0.1f + 0.2f * 0.421875f);
    EXPECT_FLOAT_EQ(h.occlusion, (1.0f - 0.5f * 0.421875f) * (1.0f - 0.5f * 0.421875f));
    EXPECT_FLOAT_EQ(h.temperature, -2.0f + 3.0f * 0.421875f);
    // Outside every support: the global values, nothing occluded.
    EnvSample o = env.channels({50.0f, 5.0f, 0.0f});
    EXPECT_FLOAT_EQ(o.snow, 0.1f);
    EXPECT_EQ(o.occlusion, 1.0f);
    EXPECT_FLOAT_EQ(o.temperature, -2.0f);
    EXPECT_EQ(o.leaves, 0.0f);
    EXPECT_EQ(o.humidity, 0.0f);
}

TEST(EnvScene, ObjectFieldsFollowTheirObject) {
    EnvFixture f;
    EnvScene env;
    std::string error;
    // The cube's temperature point sits at (0, 0, 1) in its space with R = 1; placed at (10, 0, 0),
    // turned 90 degrees and doubled, it is at (10, 0, 2) with R = 2.
    ASSERT_TRUE(f.compile(R"({)" + kTypes + R"(, "tree": [{"object": "cube", "at": [10, 0, 0], "yaw_deg": 90, "scale": 2}]})",
                          &env, &error))
        << error;
    ASSERT_EQ(env.objects().size(), 1u);
    EXPECT_NEAR(env.channels({10.0f, 0.0f, 2.0f}).temperature, 2.0f, 1e-5f);
    EXPECT_NEAR(env.channels({10.0f, 1.0f, 2.0f}).temperature, 2.0f * 0.421875f, 1e-5f);
    EXPECT_EQ(env.channels({10.0f, 2.01f, 2.0f}).temperature, 0.0f);
    // The object's bounds: the unit cube doubled, on the ground at (10, 0).
    const Bounds& b = env.objects()[0].bounds;
    EXPECT_NEAR(b.lo.x, 9.0f, 1e-4f);
    EXPECT_NEAR(b.hi.y, 1.0f, 1e-4f);
    EXPECT_NEAR(b.hi.z, 2.0f, 1e-4f);
}

TEST(EnvScene, BatchIsBitIdenticalToScalar) {
    EnvFixture f;
    EnvScene env;
    std::string error;
    std::string tree = "[";
    for (int i = 0; i < 40; ++i)
        tree += std::string(i ? "," : "") + R"({"object": "cube", "at": [)" + std::to_string(i % 8) + ", " +
                std::to_string(i / 8) + R"(, 0], "yaw_deg": )" + std::to_string(i * 17) +
                R"(, "fields": [{"channel": "occlusion", "value": 0.3, "shape": {"box": {"center": [0, 0, 0.5],
                 "half_extents": [0.3, 0.2, 0.1], "radius": 0.4}}}]})";
    tree += "]";
    ASSERT_TRUE(f.compile(R"({)" + kTypes + R"(, "tree": )" + tree + R"(, "global_fields": [{"channel": "snow", "value": 0.15}]})",
                          &env, &error))
        << error;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 9.0f);
    std::vector<glm::vec3> pts(500);
    for (glm::vec3& p : pts) p = {u(rng), u(rng) * 0.6f, u(rng) * 0.25f};
    std::vector<EnvSample> batch(pts.size());
    env.sampleBatch(pts.data(), pts.size(), batch.data());
    int touched = 0;
    for (size_t k = 0; k < pts.size(); ++k) {
        const EnvSample s = env.sample(pts[k]);
        ASSERT_TRUE(test::sameBits(s.temperature, batch[k].temperature)) << k;
        ASSERT_TRUE(test::sameBits(s.occlusion, batch[k].occlusion)) << k;
        ASSERT_TRUE(test::sameBits(s.snow, batch[k].snow)) << k;
        ASSERT_TRUE(test::sameBits(s.shelter, batch[k].shelter)) << k;
        touched += s.occlusion < 1.0f && s.temperature > 0.0f ? 1 : 0;
    }
    EXPECT_GT(touched, 20);  // the points do meet the fields
}

// channelBound (what a scattered type's tiles are culled by) is an upper bound of the channel at every
// point of the box, and follows the fields' falloff: a box near the rim of a field gets a small bound,
// not the field's peak. The masked batch sums exactly what the full one does for the channels asked.
TEST(EnvScene, ChannelBoundHoldsInEveryBoxAndFollowsTheFalloff) {
    EnvFixture f;
    EnvScene env;
    std::string error;
    const char* shapes[] = {R"({"point": {"center": [0.3, 0, 1], "radius": 1.5}})",
                            R"({"segment": {"a": [-1, 0, 0.5], "b": [1, 0.5, 1], "radius": 0.8}})",
                            R"({"box": {"center": [0, 0, 0.5], "half_extents": [0.4, 0.2, 0.1], "radius": 0.6}})",
                            R"({"disc": {"center": [0, 0, 1], "normal": [0, 0.6, 0.8], "disc_radius": 0.5, "radius": 0.7}})"};
    std::string tree = "[";
    for (int i = 0; i < 24; ++i)
        tree += std::string(i ? "," : "") + R"({"object": "cube", "at": [)" + std::to_string(1.3 * (i % 6)) + ", " +
                std::to_string(1.1 * (i / 6)) + R"(, 0], "yaw_deg": )" + std::to_string(i * 41) + R"(, "scale": )" +
                std::to_string(0.7 + 0.05 * i) + R"(, "fields": [{"channel": "leaves", "value": )" +
                std::to_string(0.5 + 0.1 * (i % 5)) + R"(, "shape": )" + shapes[i % 4] + "}]}";
    tree += "]";
    ASSERT_TRUE(f.compile(R"({)" + kTypes + R"(, "tree": )" + tree +
                              R"(, "global_fields": [{"channel": "leaves", "value": 0.05}, {"channel": "grass", "value": 1}]})",
                          &env, &error))
        << error;
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int tight = 0;
    for (int b = 0; b < 300; ++b) {
        const glm::vec3 lo(-2.0f + 11.0f * u(rng), -2.0f + 7.0f * u(rng), -0.5f + 2.5f * u(rng));
        const Bounds box{lo, lo + glm::vec3(0.05f + 0.6f * u(rng), 0.05f + 0.6f * u(rng), 0.05f + 0.4f * u(rng))};
        const float bound = env.channelBound(EnvChannel::Leaves, box);
        float peak = 0.0f;  // what the bound was before it followed the falloff
        for (const EnvWorldField& w : env.fields())
            if (w.channel == EnvChannel::Leaves && overlaps(w.bounds, box)) peak += w.value;
        tight += bound < 0.5f * peak;
        std::vector<glm::vec3> pts(60);
        for (glm::vec3& p : pts) p = glm::mix(box.lo, box.hi, glm::vec3(u(rng), u(rng), u(rng)));
        std::vector<EnvSample> masked(pts.size());
        env.channelsBatch(pts.data(), pts.size(), masked.data(), envChannelBit(EnvChannel::Leaves));
        for (size_t k = 0; k < pts.size(); ++k) {
            const EnvSample full = env.channels(pts[k]);
            ASSERT_LE(full.leaves, bound) << "box " << b << " point " << k;
            ASSERT_TRUE(test::sameBits(full.leaves, masked[k].leaves)) << "box " << b << " point " << k;
            ASSERT_EQ(masked[k].grass, 0.0f);  // not asked for
        }
    }
    EXPECT_GT(tight, 60);  // many boxes lie in the fields' outer parts
}

TEST(EnvScene, LodNodeFieldsReplaceTheSubtreesForQueries) {
    EnvFixture f;
    const std::string tree = R"("tree": [{"lod": {"fields": [{"channel": "leaves", "value": 0.4,
        "shape": {"point": {"center": [0, 0, 1], "radius": 3}}}],
        "children": [{"object": "cube"}, {"object": "cube", "at": [1, 0, 0]}]}}]})";
    std::string error;
    EnvScene with, without;
    ASSERT_TRUE(f.compile(R"({)" + kTypes + "," + tree, &with, &error)) << error;
    ASSERT_TRUE(f.compile(R"({)" + kTypes + R"(, "use_lod_nodes": false, )" + tree, &without, &error)) << error;
    EXPECT_EQ(with.objects().size(), 2u);     // geometry and effects stay
    EXPECT_EQ(with.fields().size(), 1u);      // only the LOD node's own field
    EXPECT_EQ(without.fields().size(), 3u);   // the LOD node's and both cubes' temperature
    const glm::vec3 p(0.0f, 0.0f, 1.0f);
    EXPECT_FLOAT_EQ(with.channels(p).leaves, 0.4f);
    EXPECT_EQ(with.channels(p).temperature, 0.0f);
    EXPECT_FLOAT_EQ(without.channels(p).temperature, 2.0f + 2.0f * 0.0f);  // the second cube's is 1 m away: K(1, 1) = 0
}

TEST(EnvScene, ReferencesInstanceGroupsWithInheritedOverrides) {
    EnvFixture f;
    EnvScene env;
    std::string error;
    ASSERT_TRUE(f.compile(R"({)" + kTypes + R"(,
        "groups": {"pair": {"group": {"snow": {"mode": "box"}, "children": [{"object": "cube"}, {"object": "cube", "at": [2, 0, 0]}]}}},
        "tree": [{"ref": "pair", "at": [0, 10, 0]}, {"ref": "pair", "at": [0, 20, 0], "yaw_deg": 90, "snow": {"mode": "none"}}]})",
                          &env, &error))
        << error;
    ASSERT_EQ(env.objects().size(), 4u);
    EXPECT_NEAR(env.objects()[1].placement.t.x, 2.0f, 1e-6f);
    EXPECT_NEAR(env.objects()[1].placement.t.y, 10.0f, 1e-6f);
    EXPECT_NEAR(env.objects()[3].placement.t.x, 0.0f, 1e-5f);  // (2, 0) turned 90 degrees: (0, 2)
    EXPECT_NEAR(env.objects()[3].placement.t.y, 22.0f, 1e-5f);
    EXPECT_EQ(env.objects()[0].snow.mode, SnowMode::Box);   // the group's override
    EXPECT_EQ(env.objects()[2].snow.mode, SnowMode::Box);   // the group's is nearer than the reference's
    EXPECT_EQ(env.objects()[0].where, "/environment/groups/pair/group/children/0");
}

TEST(EnvScene, ShelterAndClearanceFollowTheGeometry) {
    EnvFixture f;
    EnvScene env;
    std::string error;
    ASSERT_TRUE(f.compile(R"({)" + kTypes + R"(, "tree": [{"object": "cube"}, {"object": "roof"}]})", &env, &error)) << error;
    EXPECT_EQ(env.shelter({0.0f, 0.0f, 1.0f}), 0.0f);      // the cube's top, under the roof
    EXPECT_EQ(env.shelter({0.0f, 0.0f, 2.1f}), 1.0f);      // the roof's top
    EXPECT_EQ(env.shelter({3.0f, 0.0f, 0.0f}), 1.0f);      // beside everything
    // At the roof's edge, a third of the 3 x 3 rays pass outside it.
    EXPECT_NEAR(env.shelter({1.0f - 0.5f * kShelterCellM, 0.0f, 1.0f}), 3.0f / 9.0f, 1e-6f);
    EXPECT_NEAR(env.clearanceBelow({0.0f, 0.0f, 1.5f}), 0.5f, 1e-5f);   // down to the cube's top
    EXPECT_NEAR(env.clearanceBelow({0.0f, 0.0f, 1.99f}), 0.99f, 1e-5f);  // under the roof: the cube still
    EXPECT_TRUE(std::isinf(env.clearanceBelow({5.0f, 0.0f, 1.0f})));  // no terrain, nothing below
}

TEST(EnvScene, ShelterLooksBackAlongSlantingSnow) {
    EnvFixture f;
    EnvScene straight, slanting;
    std::string error;
    const std::string tree = R"(, "tree": [{"object": "roof"}]})";
    ASSERT_TRUE(f.compile(R"({)" + kTypes + tree, &straight, &error)) << error;
    // Snow falling at 45 degrees towards +X: looking back, a ray from x = 1.5 rises through the roof
    // (x in [-1, 1], z in [2, 2.1]) at x = 1.5 - 2 = -0.5.
    ASSERT_TRUE(f.compile(R"({"snow_direction": [1, 0, -1], )" + kTypes.substr(0) + tree, &slanting, &error)) << error;
    EXPECT_NEAR(slanting.desc().snow_direction.x, 0.70710677f, 1e-6f);
    EXPECT_EQ(straight.shelter({1.5f, 0.0f, 0.0f}), 1.0f);
    EXPECT_EQ(slanting.shelter({1.5f, 0.0f, 0.0f}), 0.0f);
    EXPECT_EQ(slanting.shelter({-1.5f, 0.0f, 0.0f}), 1.0f);  // upwind of the roof: open
    EXPECT_EQ(straight.shelter({0.0f, 0.0f, 0.0f}), 0.0f);   // under its middle, straight snow is kept off
    EXPECT_EQ(slanting.shelter({0.0f, 0.0f, 0.0f}), 1.0f);   // slanting snow comes in under it (at z = 2, x = -2)
    EXPECT_EQ(slanting.shelter({3.5f, 0.0f, 0.0f}), 1.0f);   // the ray reaches z = 2 at x = 1.5, beyond the roof
    // A wall blocks slanting snow on its lee side (the vertical lines see only its top and bottom: the
    // ray is inside the wall's solid on its way up), not straight-down snow.
    EnvScene wall_straight, wall_slanting;
    ASSERT_TRUE(f.compile(R"({)" + kTypes + R"(, "tree": [{"object": "wall"}]})", &wall_straight, &error)) << error;
    ASSERT_TRUE(f.compile(R"({"snow_direction": [1, 0, -1], )" + kTypes + R"(, "tree": [{"object": "wall"}]})",
                          &wall_slanting, &error))
        << error;
    EXPECT_EQ(wall_straight.shelter({0.5f, 0.0f, 0.0f}), 1.0f);
    EXPECT_EQ(wall_slanting.shelter({0.5f, 0.0f, 0.0f}), 0.0f);
    EXPECT_EQ(wall_slanting.shelter({-0.5f, 0.0f, 0.0f}), 1.0f);
    EXPECT_EQ(wall_slanting.shelter({3.5f, 0.0f, 0.0f}), 1.0f);  // passes over the wall's top (3 m)
    Project p;
    EXPECT_FALSE(f.load(R"({"snow_direction": [1, 0, 0], )" + kTypes + "}", &p, &error));
    EXPECT_NE(error.find("/environment/snow_direction: must point down"), std::string::npos) << error;
    EXPECT_FALSE(f.load(R"({"snow_direction": [0, 0, 0], )" + kTypes + "}", &p, &error));
    EXPECT_NE(error.find("/environment/snow_direction: must not be zero"), std::string::npos) << error;
}

// snow_spread_deg fans the 8 outer rays over a cone about the snowfall (env_scene.h): drifts of
// tan(15°) = 0.268 (at 11.25° + 90° k) and 0.55 of it (at 56.25° + 90° k), the ray k of the 3 x 3 grid
// taking the m-th (m = k, skipping the centre). Under the roof (x in [-1, 1], underside at z = 2), from
// the ground, a ray is covered when it is still over the roof at z = 2 .. 2.1.
TEST(EnvScene, ShelterFansOutAboutTheSnowfall) {
    EnvFixture f;
    EnvScene straight, fanned;
    std::string error;
    const std::string tree = R"(, "tree": [{"object": "roof"}]})";
    ASSERT_TRUE(f.compile(R"({)" + kTypes + tree, &straight, &error)) << error;
    ASSERT_TRUE(f.compile(R"({"snow_spread_deg": 15, )" + kTypes + tree, &fanned, &error)) << error;
    // x = 1.2: covered only by the rays drifting 0.1225 m (m = 3, from x - 2.5 cm) and 0.263 m (m = 4,
    // from x + 2.5 cm) back over the roof per metre: 7 of 9 open. x = 0.8: open only where the drift
    // carries it past x = 1 by z = 2 (m = 0: +0.263, from x - 2.5 cm; m = 7: +0.1225, from x + 2.5 cm).
    // Mirrored, the same.
    EXPECT_NEAR(fanned.shelter({1.2f, 0.0f, 0.0f}), 7.0f / 9.0f, 1e-6f);
    EXPECT_NEAR(fanned.shelter({-1.2f, 0.0f, 0.0f}), 7.0f / 9.0f, 1e-6f);
    EXPECT_NEAR(fanned.shelter({0.8f, 0.0f, 0.0f}), 2.0f / 9.0f, 1e-6f);
    EXPECT_NEAR(fanned.shelter({-0.8f, 0.0f, 0.0f}), 2.0f / 9.0f, 1e-6f);
    EXPECT_EQ(straight.shelter({1.2f, 0.0f, 0.0f}), 1.0f);
    EXPECT_EQ(straight.shelter({0.8f, 0.0f, 0.0f}), 0.0f);
    // Far under the middle every ray meets the roof; far enough out (0.57 m of drift up to z = 2.1) none.
    EXPECT_EQ(fanned.shelter({0.0f, 0.0f, 0.0f}), 0.0f);
    EXPECT_EQ(fanned.shelter({1.7f, 0.0f, 0.0f}), 1.0f);
    // The centre ray keeps to the snowfall (effect sharing compares it).
    EXPECT_EQ(fanned.shelterCentre({1.2f, 0.0f, 0.0f}), 1.0f);
    EXPECT_NEAR(fanned.shelterDrift(), 0.26795f, 1e-4f);
    EXPECT_EQ(straight.shelterDrift(), 0.0f);
    // The snow takes no cut at half the rays any more: it fades with the shelter itself.
    EXPECT_EQ(straight.snowMinOpen(), 0.5f);
    EXPECT_LT(fanned.snowMinOpen(), 1.0f / 9.0f);
    // Out of range or not a number: refused naming the key; 0 is not written back.
    Project p;
    EXPECT_FALSE(f.load(R"({"snow_spread_deg": 25, )" + kTypes + "}", &p, &error));
    EXPECT_NE(error.find("/environment/snow_spread_deg"), std::string::npos) << error;
    EXPECT_FALSE(f.load(R"({"snow_spread_deg": -1, )" + kTypes + "}", &p, &error));
    EXPECT_NE(error.find("/environment/snow_spread_deg"), std::string::npos) << error;
    EXPECT_FALSE(f.load(R"({"snow_spread_deg": "wide", )" + kTypes + "}", &p, &error));
    EXPECT_NE(error.find("/environment/snow_spread_deg: expected a number"), std::string::npos) << error;
    ASSERT_TRUE(f.load(R"({"snow_spread_deg": 12.5, )" + kTypes + "}", &p, &error)) << error;
    EXPECT_EQ(environmentToJson(p.environment).at("snow_spread_deg").get<double>(), 12.5);
    ASSERT_TRUE(f.load(R"({)" + kTypes + "}", &p, &error)) << error;
    EXPECT_FALSE(environmentToJson(p.environment).contains("snow_spread_deg"));
    // A description made in code is checked too.
    EnvironmentDesc wide = fanned.desc();
    wide.snow_spread_deg = std::nanf("");
    EnvScene refused;
    EXPECT_FALSE(compileEnvScene(wide, ".", "code", nullptr, &refused, &error));
    EXPECT_NE(error.find("code: /environment/snow_spread_deg: must be in [0, 20]"), std::string::npos) << error;
}

// A point on an object's own up-facing face is open to snow that slants a little (Montmartre's 10° wind):
// the ray's first half-cell step rises more than twice the 3 cm margin, and a step that reached below the
// margin looked inside the slab under the point, so every paving slab and stair tread of a part taller
// than the margin (a kerb) stayed bare.
TEST(EnvScene, AFaceIsOpenToGentlySlantingSnowOnItsOwnHeight) {
    EnvFixture f;
    std::string error;
    const std::string tree = R"(, "tree": [{"object": "kerbed_slab", "yaw_deg": 90}]})";
    for (const char* direction : {"[0.176, 0, -1]", "[0, 0.1, -1]", "[-0.05, 0.05, -1]", "[1, 0, -1]"}) {
        SCOPED_TRACE(direction);
        EnvScene env;
        ASSERT_TRUE(f.compile(std::string(R"({"snow_direction": )") + direction + ", " + kTypes + tree, &env, &error))
            << error;
        // The slab's top (turned: the kerb runs along -X), on and just above its face, well clear of the kerb.
        for (const float x : {0.0f, 0.3f, 0.6f})
            for (const float z : {0.12f, 0.1201f}) {
                EXPECT_EQ(env.shelter({x, -0.4f, z}), 1.0f) << "x " << x << ", z " << z;
                EXPECT_EQ(env.shelter({x, 0.4f, z}), 1.0f) << "x " << x << ", z " << z;
            }
        // The kerb still shelters what lies just downwind of it at its foot when the snow comes over it.
        if (std::string(direction) == "[1, 0, -1]") {
            EXPECT_EQ(env.shelter({-0.8f, 0.0f, 0.12f}), 0.0f);
        }
    }
}

TEST(EnvScene, BadTreesAreRefusedWithThePlace) {
    EnvFixture f;
    EnvScene env;
    std::string error;
    EXPECT_FALSE(f.compile(R"({)" + kTypes + R"(, "tree": [{"ref": "nowhere"}]})", &env, &error));
    EXPECT_NE(error.find("/environment/tree/0/ref"), std::string::npos) << error;
    EXPECT_NE(error.find("no group named \"nowhere\""), std::string::npos) << error;

    EXPECT_FALSE(f.compile(R"({)" + kTypes + R"(, "groups": {"a": {"group": {"children": [{"ref": "b"}]}},
                                                         "b": {"group": {"children": [{"ref": "a"}]}}},
                                               "tree": [{"ref": "a"}]})",
                           &env, &error));
    EXPECT_NE(error.find("reference cycle"), std::string::npos) << error;

    std::string deep;
    for (int i = 0; i < 100000; ++i) deep += R"({"group": {"children": [)";
    deep += R"({"object": "cube"})";
    for (int i = 0; i < 100000; ++i) deep += "]}}";
    Project p;
    EXPECT_FALSE(f.load(R"({)" + kTypes + R"(, "tree": [)" + deep + "]}", &p, &error));
    EXPECT_NE(error.find("deeper than 64 levels"), std::string::npos) << error.substr(0, 300);

    EXPECT_FALSE(f.load(R"({)" + kTypes + R"(, "global_fields": [{"channel": "snow", "value": 1e999}]})", &p, &error));
    EXPECT_NE(error.find("scene.json"), std::string::npos) << error;

    EXPECT_FALSE(f.load(R"({)" + kTypes + R"(, "global_fields": [{"channel": "occlusion", "value": 2}]})", &p, &error));
    EXPECT_NE(error.find("/environment/global_fields/0/value"), std::string::npos) << error;

    EXPECT_FALSE(f.load(R"({)" + kTypes + R"(, "global_fields": [{"channel": "rust", "value": 1}]})", &p, &error));
    EXPECT_NE(error.find("unknown channel \"rust\""), std::string::npos) << error;

    EXPECT_FALSE(f.load(R"({)" + kTypes + R"(, "tree": [{"object": "bench"}]})", &p, &error));
    EXPECT_NE(error.find("/environment/tree/0/object"), std::string::npos) << error;

    EXPECT_FALSE(f.compile(R"({"types": [{"name": "gone", "mesh": "missing.obj", "y_up": false}]})", &env, &error));
    EXPECT_NE(error.find("/environment/types/0/mesh"), std::string::npos) << error;
    EXPECT_NE(error.find("missing.obj"), std::string::npos) << error;

    std::ofstream(f.dir.path() / "corrupt.obj") << "v 0 0 0\nv 1 0 0\nf 1 2 7\n";
    EXPECT_FALSE(f.compile(R"({"types": [{"name": "bad", "mesh": "corrupt.obj", "y_up": false}]})", &env, &error));
    EXPECT_NE(error.find("corrupt.obj"), std::string::npos) << error;
}

TEST(EnvScene, ProjectRoundTripKeepsTheEnvironment) {
    EnvFixture f;
    Project p;
    std::string error;
    ASSERT_TRUE(f.load(R"({)" + kTypes + R"(,
        "groups": {"pair": {"lod": {"fields": [{"channel": "grass", "value": 0.25}], "children": [{"object": "cube"}]}}},
        "tree": [{"ref": "pair", "at": [0.1, 10, 0], "icicles": {"max_length_m": 0.2}},
                 {"group": {"yaw_deg": 33, "children": [{"object": "roof", "scale": 1.5}]}}],
        "global_fields": [{"channel": "humidity", "value": -0.5, "shape": {"disc": {"center": [1, 2, 3], "normal": [0, 0, 1], "disc_radius": 2, "radius": 0.5}}}],
        "terrain": {"snow": false, "snow_cell_m": 0.07}, "sharing_threshold": 0.002})",
                       &p, &error))
        << error;
    Project back;
    ASSERT_TRUE(parseProject(projectToJson(p), "again.json", &back, &error)) << error;
    EXPECT_EQ(environmentToJson(back.environment).dump(), environmentToJson(p.environment).dump());
    EXPECT_EQ(back.environment.roots.size(), 2u);
    EXPECT_EQ(back.environment.global_fields[0].shape.kind, PrimitiveKind::Disc);
    EXPECT_FLOAT_EQ(back.environment.terrain.snow_cell_m, 0.07f);
    ASSERT_TRUE(back.environment.roots[0].overrides.icicle_max_length_m.has_value());
    EXPECT_FLOAT_EQ(*back.environment.roots[0].overrides.icicle_max_length_m, 0.2f);
    // A project without an environment is still written as format 2.
    Project plain = p;
    plain.environment = EnvironmentDesc{};
    EXPECT_NE(projectToJson(plain).find("\"format_version\": 2"), std::string::npos);
}

}  // namespace
}  // namespace ug
