// Snow cover and icicles for whole environmental-object scenes (engine/env/env_effects.h): where snow and
// icicles go (up-facing, open faces; frost and ice; the open air below an edge), that snow runs on across
// the seam between two objects (snow_joints.h), that shared effects equal the individually computed ones, that an incremental update equals a full one after random edits, and that
// threads and regions do not change the result.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <set>

#include "env/env_effects.h"
#include "env/snow_joints.h"
#include "scene/project.h"
#include "scene/scene_compile.h"
#include "scene_test_util.h"

namespace ug {
namespace {

namespace fs = std::filesystem;

std::string modelPath(const std::string& name) {
    return (fs::path(UG_SOURCE_DIR) / "assets" / "env_models" / (name + ".glb")).string();
}

std::string types() {
    std::string s = R"("types": [)";
    const char* names[] = {"bench", "bus_shelter", "pavement_slab", "trash_can", "facade", "road_segment"};
    for (int i = 0; i < 6; ++i)
        s += std::string(i ? "," : "") + R"({"name": ")" + names[i] + R"(", "mesh": ")" + modelPath(names[i]) +
             R"(", "snow": {"target_edge_m": 0.05}, "icicles": {"spacing_m": 0.08}})";
    return s + "]";
}

const std::string kCold = R"({"channel": "snow", "value": 0.1}, {"channel": "icicles", "value": 1},
                              {"channel": "temperature", "value": -3})";

bool compileEnv(const std::string& env_json, EnvScene* out, std::string* error) {
    const std::string text = R"({"format": "undergrowth-project", "format_version": 3, "name": "fx",
      "detail_types": [{"name": "d", "model": {"mesh": ")" +
                             (fs::path(UG_SOURCE_DIR) / "assets/models/pebble.glb").string() +
                             R"("}, "candidates": {"count": 4}}], "environment": {)" + types() + "," + env_json + "}}";
    Project p;
    if (!parseProject(text, "fx.json", &p, error)) return false;
    return compileEnvScene(p.environment, p.base_dir, "fx.json", nullptr, out, error);
}

// The world-space snow of object o (its class's mesh placed).
std::vector<glm::vec3> worldSnow(const EnvScene& env, const EnvEffects& fx, size_t o) {
    std::vector<glm::vec3> out;
    const EffectClass& c = fx.classes[fx.class_of[o]];
    if (!c.snow) return out;
    for (glm::vec3 p : c.snow->positions) out.push_back(env.objects()[o].placement.toWorld(p));
    return out;
}

::testing::AssertionResult sameEffects(const EnvScene& env, const EnvEffects& a, const EnvEffects& b) {
    if (a.class_of.size() != b.class_of.size()) return ::testing::AssertionFailure() << "object counts differ";
    for (size_t o = 0; o < a.class_of.size(); ++o) {
        const EffectClass& ca = a.classes[a.class_of[o]];
        const EffectClass& cb = b.classes[b.class_of[o]];
        if (ca.members.empty() != cb.members.empty()) return ::testing::AssertionFailure() << "object " << o << " region";
        if (ca.members.empty()) continue;
        const size_t na = ca.snow ? ca.snow->positions.size() : 0, nb = cb.snow ? cb.snow->positions.size() : 0;
        if (na != nb) return ::testing::AssertionFailure() << "object " << o << ": " << na << " vs " << nb << " snow vertices";
        for (size_t k = 0; k < na; ++k)
            if (!test::sameBits(ca.snow->positions[k], cb.snow->positions[k]))
                return ::testing::AssertionFailure() << "object " << o << " snow vertex " << k;
        if (ca.snow && ca.snow->indices != cb.snow->indices) return ::testing::AssertionFailure() << "object " << o << " indices";
        if (ca.icicles.size() != cb.icicles.size())
            return ::testing::AssertionFailure() << "object " << o << ": " << ca.icicles.size() << " vs " << cb.icicles.size()
                                                 << " icicles";
        for (size_t k = 0; k < ca.icicles.size(); ++k)
            if (!test::sameBits(ca.icicles[k].anchor, cb.icicles[k].anchor) ||
                !test::sameBits(ca.icicles[k].length_m, cb.icicles[k].length_m) || ca.icicles[k].shape != cb.icicles[k].shape)
                return ::testing::AssertionFailure() << "object " << o << " icicle " << k;
    }
    if (a.terrain_snow.size() != b.terrain_snow.size()) return ::testing::AssertionFailure() << "terrain chunks";
    for (size_t k = 0; k < a.terrain_snow.size(); ++k)
        if (a.terrain_snow[k].mesh->positions != b.terrain_snow[k].mesh->positions)
            return ::testing::AssertionFailure() << "terrain chunk " << k;
    (void)env;
    return ::testing::AssertionSuccess();
}

TEST(EnvEffects, SnowOnlyOnOpenUpFacingFacesNoneUnderTheShelter) {
    EnvScene env;
    std::string error;
    ASSERT_TRUE(compileEnv(R"("tree": [{"object": "bus_shelter"}, {"object": "bench", "at": [4, 0, 0]},
                                       {"object": "bench", "at": [0, 0.2, 0], "scale": 0.9}],
                              "global_fields": [)" + kCold + "]",
                           &env, &error))
        << error;
    EnvEffects fx;
    ASSERT_TRUE(computeEnvEffects(env, {}, &fx, &error)) << error;
    // The shelter's roof carries snow; nothing below it (the roof's underside is at 2.4 m).
    const std::vector<glm::vec3> shelter_snow = worldSnow(env, fx, 0);
    ASSERT_FALSE(shelter_snow.empty());
    for (glm::vec3 p : shelter_snow) EXPECT_GE(p.z, 2.45f) << p.x << " " << p.y;
    // The bench in the open takes snow on its seat; the one under the roof takes none.
    EXPECT_FALSE(worldSnow(env, fx, 1).empty());
    EXPECT_TRUE(worldSnow(env, fx, 2).empty());
    // Icicles need meltwater from an open top: the eave and the open bench drip, the bench under the roof not.
    EXPECT_GT(fx.classes[fx.class_of[0]].icicles.size(), 10u);
    EXPECT_GT(fx.classes[fx.class_of[1]].icicles.size(), 0u);
    EXPECT_EQ(fx.classes[fx.class_of[2]].icicles.size(), 0u);
    for (const IcicleInstance& ic : fx.classes[fx.class_of[0]].icicles)  // the shelter's own bench stays dry
        EXPECT_GT(ic.anchor.z, 2.0f) << ic.anchor.x << " " << ic.anchor.y;
    // Snow lies on top: every snow vertex is at or above the base's bottom, and the open bench's seat snow
    // rises at most s = 0.1 m above the seat (z = 0.45).
    for (glm::vec3 p : worldSnow(env, fx, 1)) EXPECT_LE(p.z, 0.89f + 0.1f + 1e-4f);
    EXPECT_GT(fx.stats.snow_triangles, 0u);
}

TEST(EnvEffects, IciclesNeedFrostAndIceAndHangBelowTheirEdge) {
    std::string error;
    EnvScene cold, warm, dry;
    ASSERT_TRUE(compileEnv(R"("tree": [{"object": "bus_shelter"}], "global_fields": [)" + kCold + "]", &cold, &error)) << error;
    ASSERT_TRUE(compileEnv(R"("tree": [{"object": "bus_shelter"}], "global_fields": [{"channel": "snow", "value": 0.1},
        {"channel": "icicles", "value": 1}, {"channel": "temperature", "value": 2}])",
                           &warm, &error));
    ASSERT_TRUE(compileEnv(R"("tree": [{"object": "bus_shelter"}], "global_fields": [{"channel": "temperature", "value": -3}])",
                           &dry, &error));
    EnvEffects a, b, c;
    ASSERT_TRUE(computeEnvEffects(cold, {}, &a, &error)) << error;
    ASSERT_TRUE(computeEnvEffects(warm, {}, &b, &error)) << error;
    ASSERT_TRUE(computeEnvEffects(dry, {}, &c, &error)) << error;
    EXPECT_GT(a.stats.icicles, 10u);
    EXPECT_EQ(b.stats.icicles, 0u);  // θ >= 0
    EXPECT_EQ(c.stats.icicles, 0u);  // i = 0
    const float cap = 0.35f;         // the types' default max_length_m
    for (const IcicleInstance& ic : a.classes[0].icicles) {
        EXPECT_LE(ic.length_m, cap + 1e-6f);
        EXPECT_GT(ic.length_m, 0.0f);
        // In the open below: nothing of the scene within the icicle's length under its anchor.
        EXPECT_GE(cold.clearanceBelow(cold.objects()[0].placement.toWorld(ic.anchor)), ic.length_m);
    }
}

TEST(EnvEffects, SharedEffectsEqualTheIndividuallyComputedOnes) {
    std::string error;
    std::string tree = "[";
    for (int i = 0; i < 6; ++i) tree += std::string(i ? "," : "") + R"({"object": "trash_can", "at": [)" + std::to_string(3 * i) + R"(, 0, 0]})";
    tree += "]";
    EnvScene shared, alone;
    ASSERT_TRUE(compileEnv(R"("tree": )" + tree + R"(, "global_fields": [)" + kCold + "]", &shared, &error)) << error;
    ASSERT_TRUE(compileEnv(R"("tree": )" + tree + R"(, "sharing_threshold": -1, "global_fields": [)" + kCold + "]", &alone, &error));
    EnvEffects a, b;
    ASSERT_TRUE(computeEnvEffects(shared, {}, &a, &error)) << error;
    ASSERT_TRUE(computeEnvEffects(alone, {}, &b, &error)) << error;
    EXPECT_EQ(a.stats.effect_computations, 1u);
    EXPECT_EQ(b.stats.effect_computations, 6u);
    EXPECT_EQ(a.stats.snow_triangles, b.stats.snow_triangles);
    EXPECT_TRUE(sameEffects(shared, a, b));
}

// Random edits (moves, footprints, warm spots, turns, the global snow), each updated incrementally and
// compared with a full computation; `extra` adds settings to the environment.
void checkIncrementalEqualsFull(const std::string& extra) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 8.0f);
    struct Obj {
        std::string type;
        float x, y, yaw;
    };
    std::vector<Obj> objs = {{"bench", 1, 1, 0}, {"trash_can", 3, 1, 0}, {"pavement_slab", 5, 1, 0},
                             {"bench", 1, 4, 90}, {"trash_can", 6, 5, 0}, {"pavement_slab", 1, 7, 0}};
    std::vector<std::string> locals;
    float global_snow = 0.1f;
    auto json = [&]() {
        std::string t = "[";
        for (size_t i = 0; i < objs.size(); ++i)
            t += std::string(i ? "," : "") + R"({"object": ")" + objs[i].type + R"(", "at": [)" + std::to_string(objs[i].x) +
                 ", " + std::to_string(objs[i].y) + R"(, 0], "yaw_deg": )" + std::to_string(objs[i].yaw) + "}";
        std::string g = R"({"channel": "snow", "value": )" + std::to_string(global_snow) +
                        R"(}, {"channel": "icicles", "value": 1}, {"channel": "temperature", "value": -3})";
        for (const std::string& l : locals) g += "," + l;
        return extra + R"("tree": )" + t + R"(], "global_fields": [)" + g + "]";
    };
    std::string error;
    EnvScene before;
    ASSERT_TRUE(compileEnv(json(), &before, &error)) << error;
    EnvEffects fx;
    ASSERT_TRUE(computeEnvEffects(before, {}, &fx, &error)) << error;
    size_t reused_total = 0;
    for (int edit = 0; edit < 12; ++edit) {
        const int kind = edit % 4;
        if (kind == 0) {  // move an object
            Obj& o = objs[rng() % objs.size()];
            o.x = u(rng), o.y = u(rng);
        } else if (kind == 1) {  // a footprint
            locals.push_back(R"({"channel": "occlusion", "value": 0.9, "shape": {"point": {"center": [)" +
                             std::to_string(u(rng)) + ", " + std::to_string(u(rng)) + R"(, 0.4], "radius": 0.3}}})");
        } else if (kind == 2) {  // a warm spot
            locals.push_back(R"({"channel": "temperature", "value": 5, "shape": {"point": {"center": [)" +
                             std::to_string(u(rng)) + ", " + std::to_string(u(rng)) + R"(, 0.5], "radius": 0.6}}})");
        } else if (edit == 11) {  // the global snow
            global_snow = 0.14f;
        } else {  // turn one
            objs[rng() % objs.size()].yaw += 30.0f;
        }
        EnvScene after;
        ASSERT_TRUE(compileEnv(json(), &after, &error)) << error;
        EnvEffects incremental, full;
        ASSERT_TRUE(updateEnvEffects(after, fx, envDirtyRegion(before, after), {}, &incremental, &error)) << error;
        ASSERT_TRUE(computeEnvEffects(after, {}, &full, &error)) << error;
        ASSERT_TRUE(sameEffects(after, incremental, full)) << "edit " << edit;
        reused_total += incremental.stats.classes_reused;
        before = std::move(after);
        fx = std::move(incremental);
    }
    EXPECT_GT(reused_total, 20u);  // the updates did reuse most of the unchanged objects' effects
}

TEST(EnvEffects, IncrementalEqualsFullAfterRandomEdits) { checkIncrementalEqualsFull(""); }

TEST(EnvEffects, IncrementalEqualsFullWithSlantingSnow) {
    checkIncrementalEqualsFull(R"("snow_direction": [0.3, 0.2, -1], )");
}

TEST(EnvEffects, IncrementalEqualsFullWithFannedSnow) {
    checkIncrementalEqualsFull(R"("snow_direction": [0.3, 0.2, -1], "snow_spread_deg": 12, )");
}

// A footprint smaller than the gaps between the 18 signature points (slabs of 2 x 2 m: points 0.8 m apart)
// that falls between them: the slab must not take the snow of its untrodden twin (Montmartre's trail
// vanished from the pavement that way).
TEST(EnvEffects, AFootprintBetweenTheSignaturePointsKeepsItsDent) {
    // The slab's bounds span x, y in [-1, 1]: points at -0.8, 0, 0.8; the footprint at (0.4, 0.4), 0.13 m.
    const std::string tree = R"("tree": [{"object": "pavement_slab"}, {"object": "pavement_slab", "at": [5, 0, 0]}])";
    const std::string step = R"(, {"channel": "occlusion", "value": 0.85, "shape": {"point": {"center": [0.4, 0.4, 0.12], "radius": 0.13}}})";
    std::string error;
    EnvScene trodden;
    ASSERT_TRUE(compileEnv(tree + R"(, "global_fields": [)" + kCold + step + "]", &trodden, &error)) << error;
    EnvEffects fx;
    ASSERT_TRUE(computeEnvEffects(trodden, {}, &fx, &error)) << error;
    EXPECT_EQ(fx.stats.effect_computations, 2u);
    // Inside the footprint the snow is lower on the trodden slab than at the same place on the other.
    const auto lowestNear = [&](size_t o, glm::vec2 at) {
        float z = INFINITY;
        for (glm::vec3 p : worldSnow(trodden, fx, o))
            if (glm::length(glm::vec2(p) - at) < 0.05f) z = std::min(z, p.z);
        return z;
    };
    const float dent = lowestNear(0, {0.4f, 0.4f}), plain = lowestNear(1, {5.4f, 0.4f});
    ASSERT_TRUE(std::isfinite(dent) && std::isfinite(plain));
    EXPECT_LT(dent, plain - 0.05f);
}

// Shelter rays fanned about the snowfall fade the snow under a roof's edge in ninths over decimetres. A
// floor of cobbles (box snow, jointed to each other) across the bus shelter's roof line: a cobble's snow
// must be what it would get alone, or two neighbours meet at a step across their joint (a crack;
// Montmartre's cobbles showed dashes of them when they shared by the centre ray's signature).
TEST(EnvEffects, FannedSnowGivesJointedObjectsTheirOwnSnow) {
    const float side = 4.0f / 11.0f;
    std::string tree = R"([{"object": "bus_shelter"})";
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 12; ++i)
            tree += R"(, {"object": "road_segment", "scale": 0.0909090909, "snow": {"mode": "box"}, "at": [)" +
                    std::to_string(-2.0f + side * float(i)) + ", " + std::to_string(-0.2f + side * float(j)) + ", 0]}";
    tree += "]";
    const std::string fields = R"(, "global_fields": [)" + kCold + "]";
    std::string error;
    EnvScene shared, alone, straight;
    ASSERT_TRUE(compileEnv(R"("snow_spread_deg": 15, "tree": )" + tree + fields, &shared, &error)) << error;
    ASSERT_TRUE(compileEnv(R"("snow_spread_deg": 15, "sharing_threshold": -1, "tree": )" + tree + fields, &alone, &error)) << error;
    ASSERT_TRUE(compileEnv(R"("tree": )" + tree + fields, &straight, &error)) << error;
    EnvEffects a, b, c;
    ASSERT_TRUE(computeEnvEffects(shared, {}, &a, &error)) << error;
    ASSERT_TRUE(computeEnvEffects(alone, {}, &b, &error)) << error;
    ASSERT_TRUE(computeEnvEffects(straight, {}, &c, &error)) << error;
    // Objects whose snow ramps to the base at every side (g(0) = 0) meet no one's and may share.
    const std::vector<std::vector<SnowSegment>> joints = findSnowJoints(shared, 1);
    size_t jointed = 0;
    for (size_t o = 0; o < shared.objects().size(); ++o) {
        if (joints[o].empty()) continue;
        ++jointed;
        const EffectClass& ca = a.classes[a.class_of[o]];
        const EffectClass& cb = b.classes[b.class_of[o]];
        ASSERT_EQ(ca.members.size(), 1u) << o;
        ASSERT_EQ(bool(ca.snow), bool(cb.snow)) << o;
        if (!ca.snow) continue;
        ASSERT_EQ(ca.snow->positions.size(), cb.snow->positions.size()) << o;
        for (size_t k = 0; k < ca.snow->positions.size(); ++k)
            ASSERT_TRUE(test::sameBits(ca.snow->positions[k], cb.snow->positions[k])) << o << " " << k;
    }
    EXPECT_GT(jointed, 60u);
    EXPECT_LT(c.stats.effect_computations, 40u);  // straight snow shares them
    // The fan softens the roof's line: some cobbles take part of the snow, where straight snow gave each
    // either all of it or none.
    const auto depths = [&](const EnvScene& env, const EnvEffects& fx) {
        std::set<int> cm;  // the highest snow point over each cobble, in millimetres above its top
        for (size_t o = 1; o < env.objects().size(); ++o) {
            float top = -INFINITY;
            for (glm::vec3 p : worldSnow(env, fx, o)) top = std::max(top, p.z);
            cm.insert(std::isfinite(top) ? int(std::lround(1000.0f * (top - env.objects()[o].bounds.hi.z))) : -1);
        }
        return cm;
    };
    EXPECT_GT(depths(shared, a).size(), depths(straight, c).size() + 2);
}

// Snow at 45 degrees: a shelter moved in upwind of a bench covers it from 2 m away (outside the bench's
// vertical column), so the update must look back along the snowfall to see that the bench changed.
TEST(EnvEffects, AnUpwindEditReachesAlongSlantingSnow) {
    const std::string head = R"("snow_direction": [1, 0, -1], "tree": [{"object": "bench"}, {"object": "bus_shelter", "at": [)";
    const std::string tail = R"(, 0, 0]}], "global_fields": [)" + kCold + "]";
    std::string error;
    EnvScene before, after;
    ASSERT_TRUE(compileEnv(head + "-20" + tail, &before, &error)) << error;
    ASSERT_TRUE(compileEnv(head + "-2.5" + tail, &after, &error)) << error;
    EnvEffects fx, incremental, full;
    ASSERT_TRUE(computeEnvEffects(before, {}, &fx, &error)) << error;
    ASSERT_TRUE(updateEnvEffects(after, fx, envDirtyRegion(before, after), {}, &incremental, &error)) << error;
    ASSERT_TRUE(computeEnvEffects(after, {}, &full, &error)) << error;
    EXPECT_TRUE(sameEffects(after, incremental, full));
    // The bench's seat went under the roof's lee: less snow than in the open.
    const auto tris = [](const EnvEffects& e) {
        const EffectClass& c = e.classes[e.class_of[0]];
        return c.snow ? c.snow->triangleCount() : size_t(0);
    };
    EXPECT_LT(tris(full), tris(fx));
}

TEST(EnvEffects, SameForAnyThreadCountAndRegionSplit) {
    const fs::path scene = fs::path(UG_SOURCE_DIR) / "assets/scenes/street_winter.json";
    Project p;
    std::string error;
    ASSERT_TRUE(loadProject(scene.string(), &p, &error)) << error;
    std::shared_ptr<const HeightField> terrain;
    ASSERT_TRUE(loadTerrain(p, &terrain, &error)) << error;
    EnvScene env;
    ASSERT_TRUE(compileEnvScene(p.environment, p.base_dir, scene.string(), terrain, &env, &error)) << error;
    EnvEffects one, two, eight;
    ASSERT_TRUE(computeEnvEffects(env, {.threads = 1}, &one, &error)) << error;
    ASSERT_TRUE(computeEnvEffects(env, {.threads = 2}, &two, &error)) << error;
    ASSERT_TRUE(computeEnvEffects(env, {.threads = 8}, &eight, &error)) << error;
    EXPECT_TRUE(sameEffects(env, one, two));
    EXPECT_TRUE(sameEffects(env, one, eight));
    EXPECT_GT(one.stats.icicles, 0u);
    EXPECT_GT(one.stats.snow_triangles, 100000u);
    // Four quadrants: each object and terrain chunk in exactly one, with the whole's effects.
    const Bounds quads[4] = {{{-1, -1, -10}, {5, 5, 10}}, {{5, -1, -10}, {11, 5, 10}},
                             {{-1, 5, -10}, {5, 11, 10}}, {{5, 5, -10}, {11, 11, 10}}};
    std::vector<int> seen(env.objects().size(), 0);
    size_t chunks = 0;
    uint64_t triangles = 0;
    for (const Bounds& q : quads) {
        // Half-open quadrants: nudge the shared edges so a point on one belongs to one side only.
        Bounds r = q;
        r.hi.x -= 1e-4f, r.hi.y -= 1e-4f;
        EnvEffects part;
        ASSERT_TRUE(computeEnvEffects(env, {.threads = 2, .region = &r}, &part, &error)) << error;
        for (const EffectClass& c : part.classes)
            for (uint32_t o : c.members) {
                ++seen[o];
                const EffectClass& whole = one.classes[one.class_of[o]];
                ASSERT_EQ(c.snow ? c.snow->positions : std::vector<glm::vec3>{},
                          whole.snow ? whole.snow->positions : std::vector<glm::vec3>{});
                ASSERT_EQ(c.icicles.size(), whole.icicles.size());
            }
        chunks += part.terrain_snow.size();
        triangles += part.stats.snow_triangles;
    }
    for (size_t o = 0; o < seen.size(); ++o) EXPECT_EQ(seen[o], 1) << env.objects()[o].where;
    EXPECT_EQ(chunks, one.terrain_snow.size());
    EXPECT_EQ(triangles, one.stats.snow_triangles);
}

// The world-space snow of object o whose x lies within 1e-4 of x.
std::vector<glm::vec3> snowAtX(const EnvScene& env, const EnvEffects& fx, size_t o, float x) {
    std::vector<glm::vec3> out;
    for (glm::vec3 p : worldSnow(env, fx, o))
        if (std::fabs(p.x - x) <= 1e-4f) out.push_back(p);
    return out;
}

// Road segments 4 m square, 0.1 m thick; 0.1 m of snow everywhere; their own geometry snow, or box snow
// over their bounds (the same top).
TEST(EnvEffects, SnowRunsOnAcrossTheSeamBetweenTwoObjects) {
    for (const std::string mode : {"geometry", "box"}) {
        SCOPED_TRACE(mode);
        const std::string snow = R"(, "snow": {"mode": ")" + mode + R"("}})";
        EnvScene env;
        std::string error;
        ASSERT_TRUE(compileEnv(R"("tree": [{"object": "road_segment")" + snow + R"(, {"object": "road_segment", "at": [4, 0, 0])" +
                                   snow + R"(, {"object": "road_segment", "at": [20, 0, 0])" + snow +
                                   R"(], "global_fields": [)" + kCold + "]",
                               &env, &error))
            << error;
        EnvEffects fx;
        ASSERT_TRUE(computeEnvEffects(env, {}, &fx, &error)) << error;
        // Over the seam at x = 2 both segments' snow keeps its full depth (the road's top is at 0.1 m)
        // beyond d0 = 5 cm of the outer edges at y = -2 and 2...
        for (size_t o : {0, 1}) {
            const std::vector<glm::vec3> seam = snowAtX(env, fx, o, 2.0f);
            ASSERT_GT(seam.size(), 40u) << o;
            for (glm::vec3 p : seam) {
                if (std::fabs(p.y) < 2.0f - 0.05f) {
                    EXPECT_NEAR(p.z, 0.2f, 1e-4f) << o << ": " << p.x << " " << p.y;
                }
            }
        }
        // ...while every outer edge, and every edge of the segment alone, falls to the road (d = 0).
        for (auto [o, x] : {std::pair{0, -2.0f}, std::pair{1, 6.0f}, std::pair{2, 18.0f}, std::pair{2, 22.0f}}) {
            const std::vector<glm::vec3> edge = snowAtX(env, fx, size_t(o), x);
            ASSERT_GT(edge.size(), 40u) << o << " " << x;
            for (glm::vec3 p : edge) EXPECT_NEAR(p.z, 0.1f, 1e-5f) << o << ": " << p.x << " " << p.y;
        }
        // So the three share no snow mesh, although their environments are the same.
        EXPECT_NE(fx.class_of[0], fx.class_of[1]);
        EXPECT_NE(fx.class_of[0], fx.class_of[2]);
        EXPECT_NE(fx.class_of[1], fx.class_of[2]);
    }
}

// Two pavement pieces (2 m long along x) with a joint between them: narrow, each cover reaches its middle;
// 3 cm wide, both end at their own edge. Geometry snow (slabs at 0.12 m, the kerb at 0.15 m) or box snow
// (the bounds' top, 0.15 m).
TEST(EnvEffects, CoversOfTwoObjectsMeetHalfWayAcrossANarrowJoint) {
    for (const std::string mode : {"geometry", "box"})
        for (const auto& [at, bridged] : {std::pair{"2.01", true}, std::pair{"2.03", false}}) {
            SCOPED_TRACE(mode + " " + at);
            const std::string snow = R"(, "snow": {"mode": ")" + mode + R"("}})";
            EnvScene env;
            std::string error;
            ASSERT_TRUE(compileEnv(R"("tree": [{"object": "pavement_slab")" + snow + R"(, {"object": "pavement_slab", "at": [)" +
                                       at + ", 0, 0]" + snow + R"(], "global_fields": [)" + kCold + "]",
                                   &env, &error))
                << error;
            EnvEffects fx;
            ASSERT_TRUE(computeEnvEffects(env, {}, &fx, &error)) << error;
            float right_of_first = -INFINITY, left_of_second = INFINITY;
            for (glm::vec3 p : worldSnow(env, fx, 0)) right_of_first = std::max(right_of_first, p.x);
            for (glm::vec3 p : worldSnow(env, fx, 1)) left_of_second = std::min(left_of_second, p.x);
            const float edge = 1.0f, far_edge = std::stof(at) - 1.0f;
            if (bridged) {
                EXPECT_NEAR(right_of_first, 0.5f * (edge + far_edge), 1e-4f);
                EXPECT_NEAR(left_of_second, 0.5f * (edge + far_edge), 1e-4f);
                // Full depth there, beyond d0 = 5 cm of the outer edges (y = -1 and 1; for geometry snow
                // the slabs end at 0.846, where the kerb rises 3 cm: a step, no joint).
                const float top = mode == "box" ? 0.15f : 0.12f, y_end = mode == "box" ? 1.0f : 0.846f;
                size_t deep = 0;
                for (glm::vec3 p : snowAtX(env, fx, 0, right_of_first)) {
                    if (p.y > -1.0f + 0.05f && p.y < y_end - 0.05f) {
                        EXPECT_NEAR(p.z, top + 0.1f, 1e-4f) << p.y;
                        ++deep;
                    }
                }
                EXPECT_GT(deep, 10u);
            } else {
                EXPECT_NEAR(right_of_first, edge, 1e-4f);
                EXPECT_NEAR(left_of_second, far_edge, 1e-4f);
                for (glm::vec3 p : snowAtX(env, fx, 0, edge)) EXPECT_LE(p.z, 0.15f + 1e-5f) << p.y;
            }
        }
}

// With a wind, a seam is bridged whichever way it runs: two road segments a centimetre apart along X, then
// along Y, under snow slanting 10° along X, along Y and diagonally (Montmartre's cobbles under its west
// wind: the joints running along the wind were taken as several centimetres out of level, so every row of
// cobbles ramped to nothing at its sides, a groove between every two rows). Geometry and box snow.
TEST(EnvEffects, AWindBridgesSeamsRunningEitherWay) {
    const std::string winds[] = {"[0, 0, -1]", "[0.176, 0, -1]", "[0, 0.176, -1]", "[-0.125, 0.125, -1]"};
    for (const std::string mode : {"geometry", "box"})
        for (const std::string& wind : winds)
            for (const char* second : {"[4.01, 0, 0]", "[0, 4.01, 0]"}) {
                SCOPED_TRACE(mode + ", wind " + wind + ", second at " + second);
                const std::string snow = R"(, "snow": {"mode": ")" + mode + R"("}})";
                EnvScene env;
                std::string error;
                ASSERT_TRUE(compileEnv(R"("snow_direction": )" + wind + R"(, "tree": [{"object": "road_segment")" + snow +
                                           R"(, {"object": "road_segment", "at": )" + second + snow +
                                           R"(], "global_fields": [)" + kCold + "]",
                                       &env, &error))
                    << error;
                const std::vector<std::vector<SnowSegment>> joints = findSnowJoints(env, 1);
                ASSERT_EQ(joints.size(), 2u);
                for (size_t o = 0; o < 2; ++o) {
                    // The whole seam side (the top's grid edges along it, or the box's one side): the edge
                    // at x = ±2 (second along X) or y = ±2 (along Y), object space, 4 m long.
                    const bool along_x = second[1] == '4';
                    const float side = o == 0 ? 2.0f : -2.0f;
                    float length = 0.0f;
                    for (const SnowSegment& j : joints[o]) {
                        EXPECT_NEAR(j.gap_m, 0.01f, 2e-4f);
                        for (const glm::vec3 end : {j.a, j.b}) EXPECT_NEAR(along_x ? end.x : end.y, side, 1e-5f);
                        length += glm::length(j.b - j.a);
                    }
                    EXPECT_NEAR(length, 4.0f, 1e-4f) << "object " << o;
                }
            }
}

// Moving one of two abutting segments away: the update recomputes the other (its seam is a border now)
// and equals a full computation; moving it back restores the bridged snow.
TEST(EnvEffects, AnUpdateFollowsTheSeamsWhenANeighbourMoves) {
    const auto scene = [](const char* at) {
        return std::string(R"("tree": [{"object": "road_segment"}, {"object": "road_segment", "at": [)") + at +
               R"(, 0, 0]}], "global_fields": [)" + kCold + "]";
    };
    std::string error;
    EnvScene joined, apart, back;
    ASSERT_TRUE(compileEnv(scene("4"), &joined, &error)) << error;
    ASSERT_TRUE(compileEnv(scene("7"), &apart, &error)) << error;
    ASSERT_TRUE(compileEnv(scene("4"), &back, &error)) << error;
    EnvEffects fx_joined, fx_apart, fx_back, full_apart, full_back;
    ASSERT_TRUE(computeEnvEffects(joined, {}, &fx_joined, &error)) << error;
    ASSERT_TRUE(updateEnvEffects(apart, fx_joined, envDirtyRegion(joined, apart), {}, &fx_apart, &error)) << error;
    ASSERT_TRUE(computeEnvEffects(apart, {}, &full_apart, &error)) << error;
    EXPECT_TRUE(sameEffects(apart, fx_apart, full_apart));
    for (glm::vec3 p : snowAtX(apart, fx_apart, 0, 2.0f)) EXPECT_NEAR(p.z, 0.1f, 1e-5f) << p.y;
    ASSERT_TRUE(updateEnvEffects(back, fx_apart, envDirtyRegion(apart, back), {}, &fx_back, &error)) << error;
    ASSERT_TRUE(computeEnvEffects(back, {}, &full_back, &error)) << error;
    EXPECT_TRUE(sameEffects(back, fx_back, full_back));
    EXPECT_TRUE(sameEffects(back, fx_back, fx_joined));
    for (glm::vec3 p : snowAtX(back, fx_back, 0, 2.0f)) {
        if (std::fabs(p.y) < 2.0f - 0.05f) {
            EXPECT_NEAR(p.z, 0.2f, 1e-4f) << p.y;
        }
    }
}

}  // namespace
}  // namespace ug
