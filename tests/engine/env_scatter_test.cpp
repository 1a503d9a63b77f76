// Scattered environmental effects (engine/env/env_scatter.h; Grosbellet et al. 2016 §5.3-5.4): the
// density (α·c·h − d)/s against hand-computed values on flat ground, a bench that receives leaves on its
// seat and keeps them off the ground below, layers whose thickness follows c, variants chosen from the
// environment without changing the selection, no two instances of any type closer than δ, exact
// incremental updates after environment edits, threads and regions, and the project's JSON.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <random>

#include "env/env_scatter.h"
#include "env/env_scene.h"
#include "instancer/instantiator.h"
#include "instancer/settling.h"
#include "instancer/tile_coord.h"
#include "instancer_test_util.h"
#include "scene/project.h"
#include "scene/scene_compile.h"
#include "scene/scene_load.h"
#include "scene_test_util.h"

namespace ug {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

std::string asset(const std::string& rel) { return (fs::path(UG_SOURCE_DIR) / "assets" / rel).string(); }

// The bench (assets/env_models/README.md, engine/env/env_models_street.cpp): four seat slats 1.6 m long
// in x, 0.095 m deep in y, their tops at 0.45 m and 0.035 m thick; slat k spans y in
// [0.32 - 0.11 k - 0.095, 0.32 - 0.11 k]. The slats' centres in y:
constexpr float kSeatTop = 0.45f, kSeatBottom = 0.415f;
constexpr float kSlatCentreY[4] = {0.2725f, 0.1625f, 0.0525f, -0.0575f};
constexpr float kSeatHalfX = 0.8f, kSeatYLo = -0.105f, kSeatYHi = 0.32f;

// A flat procedural terrain at z = 0 over [x0, x0 + w] x [y0, y0 + h].
json flatTerrain(float x0, float y0, float w, float h) {
    const float cell = 0.25f;
    return {{"procedural",
             {{"origin", {x0, y0}}, {"cell_size_m", cell}, {"width", int(w / cell) + 1}, {"height", int(h / cell) + 1},
              {"seed", 3}, {"octaves", 1}, {"base_height_m", 0.0}, {"amplitude_m", 0.0}}}};
}

json pointShape(glm::vec3 c, float radius) { return {{"point", {{"center", {c.x, c.y, c.z}}, {"radius", radius}}}}; }
json boxShape(glm::vec3 c, glm::vec3 half, float radius) {
    return {{"box", {{"center", {c.x, c.y, c.z}}, {"half_extents", {half.x, half.y, half.z}}, {"radius", radius}}}};
}
json field(const char* channel, float value, json shape = nullptr) {
    json f = {{"channel", channel}, {"value", value}};
    if (!shape.is_null()) f["shape"] = shape;
    return f;
}

// A scattered type: one anchor at the origin (the layer is tested where each candidate is), lying nearly
// flat.
json scatterType(const std::string& name, const std::string& model, const char* channel, uint32_t count,
                 float thickness, float ramp) {
    return {{"name", name},
            {"model", {{"mesh", asset("models/" + model + ".glb")}, {"anchors", {{"mode", "center"}}}}},
            {"candidates",
             {{"count", count}, {"scale", {0.8, 1.2}}, {"orientation", {{"mode", "tilt"}, {"tilt_ranges", {{0, 25, 1}}}}}}},
            {"scatter", {{"channel", channel}, {"thickness_m", thickness}, {"ramp_m", ramp}}}};
}

json benchType(bool receives) {
    json t = {{"name", "bench"}, {"mesh", asset("env_models/bench.glb")}};
    if (receives) t["receives"] = {"leaves", "grass"};
    return t;
}
json treeType() {
    return {{"name", "tree"},
            {"mesh", asset("env_models/tree.glb")},
            {"shelters", false},
            {"fields", {field("leaves", 1.0f, pointShape({0, 0, 2.0f}, 3.0f))}}};
}
json object(const char* type, glm::vec3 at, float yaw = 0.0f) {
    return {{"object", type}, {"at", {at.x, at.y, at.z}}, {"yaw_deg", yaw}};
}

json project(glm::vec3 lo, glm::vec3 hi, json types, json environment, float delta = -0.002f, int variants = 1) {
    json p = {{"format", "undergrowth-project"},
              {"format_version", 3},
              {"name", "scatter"},
              {"ghost_tile", {{"tile_size_m", 0.5}, {"delta_m", delta}, {"seed", 7}, {"variants", variants}}},
              {"terrain", flatTerrain(lo.x - 1.0f, lo.y - 1.0f, hi.x - lo.x + 2.0f, hi.y - lo.y + 2.0f)},
              {"extent", {{"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}}},
              {"detail_types", types}};
    if (!environment.is_null()) p["environment"] = environment;
    return p;
}

// Shared by the tests of one run: the Ghost Tiles of identical projects are built once.
std::string cacheDir() {
    static test::TempDir dir("ug_env_scatter_");
    return dir.path().string();
}

struct Loaded {
    Project project;
    LoadedScene scene;
    InstancerInput input(uint64_t seed = 3) const {
        InstancerInput in;
        in.tile = scene.tile.get();
        for (const DetailModel& m : *scene.models) in.models.push_back(&m);
        in.types = scene.compiled.types;
        in.extent = scene.compiled.extent;
        in.seed = seed;
        return in;
    }
};

::testing::AssertionResult load(const json& j, Loaded* out) {
    std::string error;
    if (!parseProject(j.dump(), "scatter.json", &out->project, &error) ||
        !loadScene(out->project, SceneLoadOptions{.cache_dir = cacheDir(), .threads = 2}, &out->scene, &error))
        return ::testing::AssertionFailure() << error;
    return ::testing::AssertionSuccess();
}

// The environment alone (with the project's terrain), for value tests.
::testing::AssertionResult compileEnv(const json& environment, std::shared_ptr<const EnvScene>* out) {
    const json p = project({-2, -2, -1}, {2, 2, 2}, json::array({scatterType("leaf", "leaf_oak", "leaves", 4, 0.05f, 0.01f)}),
                           environment);
    Project proj;
    std::string error;
    std::shared_ptr<const HeightField> terrain;
    auto env = std::make_shared<EnvScene>();
    if (!parseProject(p.dump(), "scatter.json", &proj, &error) || !loadTerrain(proj, &terrain, &error) ||
        !compileEnvScene(proj.environment, proj.base_dir, "scatter.json", terrain, env.get(), &error))
        return ::testing::AssertionFailure() << error;
    *out = std::move(env);
    return ::testing::AssertionSuccess();
}

std::vector<test::InstanceKey> run(const InstancerInput& input, int threads, InstanceStats* stats = nullptr) {
    Instantiator inst;
    std::string error;
    InstanceStats st;
    EXPECT_TRUE(inst.setInput(input, &error) && inst.instantiateAll({.threads = threads}, &st, &error)) << error;
    if (stats) *stats = st;
    auto keys = test::instancesOf(inst.store());
    std::sort(keys.begin(), keys.end());
    return keys;
}

glm::vec3 originOf(const GhostTile& tile, const test::InstanceKey& k) {
    return tileOrigin(unpackTile(k.first), tile.settings.tile_size_m) + tile.candidates.position[k.second];
}

ScatterField scatterField(const std::shared_ptr<const EnvScene>& env, float h, float s, EnvChannel c = EnvChannel::Leaves,
                   bool sheltered = true) {
    return ScatterField(env, ScatterSettings{.channel = c, .thickness_m = h, .ramp_m = s, .sheltered = sheltered});
}

}  // namespace

// 1. f = max(0, (α·c·h − d)/s) on flat ground, by hand; values chosen exact in binary so the 0 at the layer's
// top is exact.
TEST(EnvScatter, ValueOnFlatGroundIsTheHandComputedRamp) {
    std::shared_ptr<const EnvScene> env;
    ASSERT_TRUE(compileEnv({{"global_fields", {field("leaves", 0.5f)}}}, &env));
    const float h = 0.125f, s = 0.03125f;  // c·h = 0.0625
    const ScatterField f = scatterField(env, h, s);
    for (const float d : {0.0f, 0.01f, 0.015625f, 0.03125f, 0.05f, 0.06f}) {
        SCOPED_TRACE(d);
        EXPECT_FLOAT_EQ(f.value({0.3f, -0.7f, d}), (0.0625f - d) / s);
        EXPECT_FLOAT_EQ(f.value({-1.2f, 1.1f, d}), (0.0625f - d) / s);
    }
    for (const float d : {0.0625f, 0.07f, 0.5f, 1.5f}) EXPECT_EQ(f.value({0.3f, -0.7f, d}), 0.0f) << d;
    EXPECT_EQ(f.value({0.3f, -0.7f, -0.01f}), 0.0f);  // below the ground: nothing to rest on
    // Another channel's type sees none of it.
    EXPECT_EQ(scatterField(env, h, s, EnvChannel::Grass, false).value({0.3f, -0.7f, 0.0f}), 0.0f);

    // Occlusion: a global α = 1 − 0.5 and a point trail of value 0.8, radius 1 at (1, 0, 0.01); half a radius
    // out K = (1 − 1/4)^3 = 0.421875, so α = 0.5 (1 − 0.8 · 0.421875) = 0.33125.
    ASSERT_TRUE(compileEnv({{"global_fields",
                             {field("leaves", 0.5f), field("occlusion", 0.5f),
                              field("occlusion", 0.8f, pointShape({1.0f, 0.0f, 0.01f}, 1.0f))}}},
                           &env));
    const ScatterField g = scatterField(env, h, s);
    EXPECT_FLOAT_EQ(g.value({-1.5f, 0.0f, 0.01f}), (0.5f * 0.0625f - 0.01f) / s);
    EXPECT_FLOAT_EQ(g.value({1.5f, 0.0f, 0.01f}), (0.33125f * 0.0625f - 0.01f) / s);
    EXPECT_FLOAT_EQ(g.value({1.0f, 0.5f, 0.01f}), (0.33125f * 0.0625f - 0.01f) / s);
    // 1 cm below the centre K = (1 − 1e-4)^3: α = 0.5 (1 − 0.8 K) ≈ 0.10012.
    EXPECT_NEAR(g.value({1.0f, 0.0f, 0.0f}), 0.5 * (1.0 - 0.8 * std::pow(1.0 - 1e-4, 3.0)) * 0.0625 / s, 1e-4);
    EXPECT_EQ(g.value({1.0f, 0.0f, 0.01f}), 0.0f);  // α·c·h = 0.1 · 0.0625 = 0.00625 ≤ d
    EXPECT_EQ(g.value({1.5f, 0.0f, 0.021f}), 0.0f);  // α·c·h ≈ 0.0207 ≤ d
    EXPECT_EQ(g.value({-1.5f, 0.0f, 0.03125f}), 0.0f);  // exactly at the open layer's top: 0.5 · 0.0625

    // Grass (not sheltered) ignores the bench above it; leaves do not.
    ASSERT_TRUE(compileEnv({{"types", {benchType(false)}},
                            {"tree", {object("bench", {0, 0, 0})}},
                            {"global_fields", {field("leaves", 0.5f), field("grass", 0.5f)}}},
                           &env));
    const glm::vec3 under(0.0f, kSlatCentreY[1], 0.01f);
    EXPECT_EQ(env->shelter(under), 0.0f);
    EXPECT_FLOAT_EQ(scatterField(env, h, s, EnvChannel::Grass, false).value(under), (0.0625f - 0.01f) / s);
    EXPECT_EQ(scatterField(env, h, s, EnvChannel::Grass, true).value(under), 0.0f);
    EXPECT_EQ(scatterField(env, h, s).value(under), 0.0f);
    // In the open beside it both have the full layer.
    EXPECT_FLOAT_EQ(scatterField(env, h, s).value({0.0f, 1.2f, 0.01f}), (0.0625f - 0.01f) / s);
}

// 2. A bench that receives leaves: a layer on its seat, none under it or inside it; a bench that does not
// receive them holds none.
TEST(EnvScatter, BenchSeatReceivesLeavesAndKeepsThemOffTheGroundBelow) {
    const float h = 0.05f, s = 0.01f;
    for (const bool receives : {true, false}) {
        SCOPED_TRACE(receives);
        std::shared_ptr<const EnvScene> env;
        ASSERT_TRUE(compileEnv({{"types", {benchType(receives)}},
                                {"tree", {object("bench", {0, 0, 0})}},
                                {"global_fields", {field("leaves", 1.0f)}}},
                               &env));
        const ScatterField f = scatterField(env, h, s);
        for (const float y : kSlatCentreY)
            for (const float x : {-0.7f, -0.3f, 0.0f, 0.4f}) {
                SCOPED_TRACE(testing::Message() << x << ", " << y);
                // Just above the slat's top: d = 0.01, nothing above.
                if (receives)
                    EXPECT_NEAR(f.value({x, y, kSeatTop + 0.01f}), (h - 0.01f) / s, 1e-3f);
                else
                    EXPECT_EQ(f.value({x, y, kSeatTop + 0.01f}), 0.0f);
                EXPECT_EQ(f.value({x, y, kSeatTop + h + 1e-3f}), 0.0f);  // above the layer
                EXPECT_EQ(f.value({x, y, 0.5f * (kSeatTop + kSeatBottom)}), 0.0f);  // inside the slat
                for (const float z : {0.0f, 0.005f, 0.02f, 0.04f}) EXPECT_EQ(f.value({x, y, z}), 0.0f) << z;  // sheltered
            }
        // The ground in the open is the terrain's and takes leaves either way.
        EXPECT_FLOAT_EQ(f.value({0.0f, 1.0f, 0.01f}), (h - 0.01f) / s);
    }

    // Through the real pipeline: leaves on the seat, none under it.
    const json env = {{"types", {benchType(true)}},
                      {"tree", {object("bench", {0, 0, 0})}},
                      {"global_fields", {field("leaves", 1.0f)}}};
    Loaded l;
    ASSERT_TRUE(load(project({-1.0f, -0.5f, -0.1f}, {1.0f, 0.5f, 0.6f},
                             json::array({scatterType("leaf", "leaf_oak", "leaves", 200, h, s)}), env),
                     &l));
    const auto keys = run(l.input(), 2);
    // Under the seat the shelter's 3 x 3 rays, kShelterCellM apart, meet the slats, except where a row of
    // them falls into a gap between slats: gaps are 15 mm, narrower than the height-span map's 25 mm cells,
    // and a cell whose centre lies in one sees no slat (height_span_map.h). At most one row of three rays
    // can (the gaps are 11 cm apart): there α <= 1/3 and the layer is at most c·h/3 thick. A point within
    // 1 cm of a slat's centre line has all its rays (±25 mm, their cells ±12.5 mm more) on that slat.
    size_t on_seat = 0, under_seat = 0, on_ground = 0, under_slat_centres = 0;
    for (const auto& k : keys) {
        const glm::vec3 o = originOf(*l.scene.tile, k);
        const bool in_footprint = std::abs(o.x) < kSeatHalfX && o.y > kSeatYLo && o.y < kSeatYHi;
        if (!in_footprint) {
            on_ground += o.z < 0.1f;
            continue;
        }
        EXPECT_TRUE(o.z < kSeatBottom || o.z >= kSeatTop - 1e-3f) << "in the seat at " << o.x << ", " << o.y << ", " << o.z;
        EXPECT_LE(o.z, kSeatTop + h + 1e-3f);
        if (o.z >= kSeatTop - 1e-3f) {
            ++on_seat;
            continue;
        }
        ++under_seat;
        const bool inner = std::abs(o.x) < kSeatHalfX - 0.05f && o.y > kSeatYLo + 0.05f && o.y < kSeatYHi - 0.05f;
        if (inner) {
            EXPECT_LT(o.z, h / 3.0f + 1e-4f) << "under the seat at " << o.x << ", " << o.y << ", " << o.z;
        }
        for (const float y : kSlatCentreY)
            if (std::abs(o.x) < kSeatHalfX - 0.05f && std::abs(o.y - y) < 0.01f) {
                ++under_slat_centres;
                ADD_FAILURE() << "leaf under a slat at " << o.x << ", " << o.y << ", " << o.z;
            }
    }
    EXPECT_EQ(under_slat_centres, 0u);
    EXPECT_GE(on_seat, 10u);
    EXPECT_GE(on_ground, 10u);
    // Open ground over the extent's 2 m² less the seat's 0.68 m²: the seat's footprint would hold about
    // 0.68 / 1.32 as many; it holds far fewer.
    EXPECT_LT(double(under_seat), 0.25 * double(on_ground) * 0.68 / 1.32);
    std::printf("bench: %zu leaves, %zu on the seat, %zu on the open ground, %zu under the seat (by its gaps)\n",
                keys.size(), on_seat, on_ground, under_seat);
}

// 3. The layer is c·h thick, so with acceptance min(1, (c·h − d)/s) over candidates uniform in height the
// expected count per unit area is ∫ min(1, max(0, (c·h − d)/s)) dd = c·h − s/2.
// Settling (on two threads) with the environment's surfaces (RestSupport::surfaces): a thick, sparse layer over the seat
// comes down onto the slats and stops there, never into them. With the terrain alone as support the seat
// is not there for settling: with nothing to land on within max_drop the leaves are held where they were,
// hovering (what the test tells apart).
TEST(EnvScatterThreads, SettlingRestsLeavesOnTheSeatNotThroughIt) {
    const json env = {{"types", {benchType(true)}},
                      {"tree", {object("bench", {0, 0, 0})}},
                      {"global_fields", {field("leaves", 1.0f)}}};
    json p = project({-1.0f, -0.5f, -0.1f}, {1.0f, 0.5f, 0.7f},
                     json::array({scatterType("leaf", "leaf_oak", "leaves", 120, 0.12f, 0.01f)}), env);
    p["settling"] = {{"enabled", true}, {"passes", 8}, {"max_drop_m", 0.2}};
    Loaded l;
    ASSERT_TRUE(load(p, &l));
    Instantiator inst;
    std::string error;
    InstanceStats st;
    ASSERT_TRUE(inst.setInput(l.input(), &error) && inst.instantiateAll({.threads = 2}, &st, &error)) << error;
    const GhostTile& tile = *l.scene.tile;
    const DetailModel& model = (*l.scene.models)[0];
    // The lowest point of each leaf over the slats after settling (its spheres' bottoms less the drop), in
    // store order; a leaf over a gap may rest lower, on the slats' sides.
    auto seatLeafBottoms = [&](const SettleInput& settle) {
        SettledDrops drops;
        settleAll(settle, inst.store(), 2, &drops);
        std::vector<float> out;
        forEachSettled(inst.store(), &drops, [&](uint64_t key, uint32_t j, float drop) {
            const glm::vec3 o = originOf(tile, {key, j});
            if (std::abs(o.x) > kSeatHalfX - 0.1f || o.y < kSeatYLo + 0.05f || o.y > kSeatYHi - 0.05f ||
                o.z < kSeatTop)
                return;
            float bottom = std::numeric_limits<float>::infinity();
            for (const Sphere& sp : model.spheres) {
                const glm::vec3 c = o + tile.candidates.rotation[j] * (tile.candidates.scale[j] * sp.center);
                bottom = std::min(bottom, c.z - tile.candidates.scale[j] * sp.radius - drop);
            }
            out.push_back(bottom);
        });
        return out;
    };
    SettleInput with = settleInput(l.project, l.scene.compiled.terrain, tile, *l.scene.models, l.scene.environment.get());
    ASSERT_NE(with.support.surfaces, nullptr);
    SettleInput terrain_only = with;
    terrain_only.support.surfaces = nullptr;
    const std::vector<float> rested = seatLeafBottoms(with), held = seatLeafBottoms(terrain_only);
    ASSERT_EQ(rested.size(), held.size());
    ASSERT_GT(rested.size(), 20u);
    size_t came_down = 0, on_slats = 0;
    for (size_t k = 0; k < rested.size(); ++k) {
        // Sphere sets cover the leaf within the fit's tolerance, and the slats' height-span cells are 25 mm
        // wide: a few mm into a slat's rounded edge at most.
        EXPECT_GT(rested[k], kSeatTop - 0.006f) << k;
        came_down += rested[k] < held[k] - 0.01f;
        on_slats += rested[k] < kSeatTop + 0.004f;
    }
    EXPECT_GT(came_down, rested.size() / 4);  // the seat let them come down
    EXPECT_GT(on_slats, rested.size() / 4);   // and they lie on it (the others on those)
}

TEST(EnvScatter, DenserWhereTheChannelIsLarger) {
    const float h = 0.04f, s = 0.004f, c1 = 0.5f, c2 = 1.0f;
    const glm::vec3 half(1.0f, 1.0f, 0.5f);
    const glm::vec3 centre1(-1.5f, 0.0f, 0.0f), centre2(1.5f, 0.0f, 0.0f);
    // Box fields with a tiny falloff: c is c1 or c2 inside, 0 a centimetre out; no leaves at all between.
    const json env = {{"global_fields", {field("leaves", c1, boxShape(centre1, half, 0.01f)),
                                         field("leaves", c2, boxShape(centre2, half, 0.01f))}}};
    Loaded l;
    ASSERT_TRUE(load(project({-3.0f, -1.5f, -0.1f}, {3.0f, 1.5f, 0.3f},
                             json::array({scatterType("leaf", "leaf_oak", "leaves", 150, h, s)}), env, -0.002f, 4),
                     &l));
    const InstancerInput input = l.input();
    Instantiator inst;
    std::string error;
    InstanceStats stats;
    ASSERT_TRUE(inst.setInput(input, &error) && inst.instantiateAll({.threads = 2}, &stats, &error)) << error;
    const GhostTile& tile = *l.scene.tile;
    // 1: where c = c1, 2: c = c2, 0: in neither box's falloff (c = 0), -1: in a falloff band.
    const auto region = [&](glm::vec3 o) {
        for (int r = 0; r < 2; ++r) {
            const glm::vec3 c = r == 0 ? centre1 : centre2;
            if (std::abs(o.x - c.x) < half.x && std::abs(o.y - c.y) < half.y) return r + 1;
            if (std::abs(o.x - c.x) < half.x + 0.011f && std::abs(o.y - c.y) < half.y + 0.011f) return -1;
        }
        return 0;
    };
    double n[3] = {0, 0, 0}, alive[3] = {0, 0, 0};
    for (const auto& k : test::instancesOf(inst.store())) {
        const glm::vec3 o = originOf(tile, k);
        const int r = region(o);
        if (r >= 0) ++n[r];
        if (r == 0) ADD_FAILURE() << "a leaf where c = 0, at " << o.x << ", " << o.y << ", " << o.z;
    }
    for (const auto& a : inst.aliveCandidates()) {
        const int r = region(originOf(tile, {a.tile_key, a.candidate}));
        if (r >= 0) ++alive[r];
    }
    EXPECT_EQ(alive[0], 0.0);
    // The expectation from the candidates themselves: each candidate of each tile's variant whose origin
    // lies in a region is alive with probability clamp((c·h − z)/s, 0, 1) (z the height above the ground).
    double e[3] = {0, 0, 0};
    const CandidateSet& cs = tile.candidates;
    for (int tx = -6; tx < 6; ++tx)
        for (int ty = -3; ty < 3; ++ty)
            for (int tz = -1; tz < 1; ++tz) {
                const glm::ivec3 t(tx, ty, tz);
                const uint32_t v = tileVariant(input.seed, packTile(t), cs.variants);
                for (uint32_t j = cs.variantBegin(0, v); j < cs.variantEnd(0, v); ++j) {
                    const glm::vec3 o = tileOrigin(t, 0.5f) + cs.position[j];
                    const int r = region(o);
                    if (r <= 0 || !contains(input.extent, o) || o.z < 0.0f) continue;
                    e[r] += std::clamp(((r == 1 ? c1 : c2) * h - o.z) / s, 0.0f, 1.0f);
                }
            }
    const double layer_ratio = (c2 * h - s / 2) / (c1 * h - s / 2);
    std::printf("dense: %g and %g leaves, %g and %g alive (expected %g and %g), %llu collision-rejected; ratio %g, "
                "expected %g (candidates) / %g (layers)\n",
                n[1], n[2], alive[1], alive[2], e[1], e[2], (unsigned long long)stats.collision_rejected, n[2] / n[1],
                e[2] / e[1], layer_ratio);
    ASSERT_GT(e[1], 80.0);
    // 4σ of a sum of Bernoulli draws (σ² ≤ E).
    EXPECT_NEAR(alive[1], e[1], 4.0 * std::sqrt(e[1]) + 1.0);
    EXPECT_NEAR(alive[2], e[2], 4.0 * std::sqrt(e[2]) + 1.0);
    EXPECT_NEAR(e[2] / e[1], layer_ratio, 0.15 * layer_ratio);
    // Collisions are rare in layers this thin, so the instances keep the ratio.
    EXPECT_LT(double(stats.collision_rejected), 0.15 * double(stats.instances));
    EXPECT_NEAR(n[2] / n[1], layer_ratio, 0.2 * layer_ratio);
}

// 4. Variants: the first condition the environment at the origin meets; the selection never sees them.
TEST(EnvScatter, VariantsFollowTheHumidityAndLeaveTheSelectionAlone) {
    // η = −0.5 + 1.0·K(r), K = (1 − r²/R²)^3 with R = 0.5 around (1, 0, 0): η ≥ 0 where K ≥ 1/2, i.e.
    // r ≤ R·sqrt(1 − 2^(−1/3)).
    const json env = {{"global_fields",
                       {field("leaves", 1.0f), field("humidity", -0.5f), field("humidity", 1.0f, pointShape({1, 0, 0}, 0.5f))}}};
    std::shared_ptr<const EnvScene> e;
    ASSERT_TRUE(compileEnv(env, &e));
    const ScatterCondition wet{.channel = EnvChannel::Humidity, .min = 0.0f};
    const double r0 = 0.5 * std::sqrt(1.0 - std::pow(2.0, -1.0 / 3.0));
    EXPECT_EQ(scatterVariantAt(*e, std::span(&wet, 1), {1.0f + float(r0) - 1e-3f, 0.0f, 0.0f}), 1u);
    EXPECT_EQ(scatterVariantAt(*e, std::span(&wet, 1), {1.0f + float(r0) + 1e-3f, 0.0f, 0.0f}), 0u);
    EXPECT_EQ(scatterVariantAt(*e, std::span(&wet, 1), {1.0f, 0.0f, 0.0f}), 1u);
    EXPECT_EQ(scatterVariantAt(*e, std::span(&wet, 1), {-1.0f, 0.0f, 0.0f}), 0u);
    EXPECT_EQ(scatterVariantAt(*e, {}, {1.0f, 0.0f, 0.0f}), 0u);
    // Two conditions, the first that holds wins: [0, 0.25) -> 1, [0.25, inf) -> 2.
    const ScatterCondition two[2] = {{.channel = EnvChannel::Humidity, .min = 0.0f, .max = 0.25f},
                                     {.channel = EnvChannel::Humidity, .min = 0.25f}};
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    int wet_points = 0, very_wet = 0;
    for (int k = 0; k < 4000; ++k) {
        const glm::vec3 p(1.0f + 0.6f * u(rng), 0.6f * u(rng), 0.3f * u(rng));
        const double r2 = double(p.x - 1.0f) * (p.x - 1.0f) + double(p.y) * p.y + double(p.z) * p.z;
        const double K = r2 < 0.25 ? std::pow(1.0 - r2 / 0.25, 3.0) : 0.0;
        const double eta = -0.5 + K;
        if (std::abs(eta) < 1e-5 || std::abs(eta - 0.25) < 1e-5) continue;  // too close to a boundary for floats
        EXPECT_EQ(scatterVariantAt(*e, std::span(&wet, 1), p), eta >= 0.0 ? 1u : 0u) << eta;
        EXPECT_EQ(scatterVariantAt(*e, two, p), eta >= 0.25 ? 2u : eta >= 0.0 ? 1u : 0u) << eta;
        wet_points += eta >= 0.0;
        very_wet += eta >= 0.25;
    }
    EXPECT_GT(wet_points, 50);
    EXPECT_GT(very_wet, 20);

    // The same project with and without a variant: the same instances.
    json plain = project({-0.5f, -1.0f, -0.1f}, {2.0f, 1.0f, 0.3f},
                         json::array({scatterType("leaf", "leaf_oak", "leaves", 120, 0.05f, 0.01f)}), env);
    json with = plain;
    with["detail_types"][0]["scatter"]["variants"] = {
        {{"name", "leaf_wet"}, {"model", {{"mesh", asset("models/leaf_birch.glb")}}}, {"when", {{"channel", "humidity"}, {"min", 0}}}}};
    Loaded a, b;
    ASSERT_TRUE(load(plain, &a));
    ASSERT_TRUE(load(with, &b));
    ASSERT_EQ(b.scene.variant_models->size(), 1u);
    ASSERT_EQ((*b.scene.variant_models)[0].size(), 1u);
    const auto ka = run(a.input(), 2), kb = run(b.input(), 2);
    EXPECT_GT(ka.size(), 20u);
    EXPECT_EQ(ka, kb);
    // Some of them lie in the puddle and would take the variant.
    const auto& conds = b.project.detail_types[0].scatter.variants;
    ASSERT_EQ(conds.size(), 1u);
    size_t wet_leaves = 0;
    for (const auto& k : kb) wet_leaves += scatterVariantAt(*b.scene.environment, std::span(&conds[0].when, 1),
                                                            originOf(*b.scene.tile, k)) == 1;
    EXPECT_GT(wet_leaves, 0u);
    EXPECT_LT(wet_leaves, kb.size());
}

// 5. Every pair of instances, of any types, in a tile or across tiles: their sphere sets are more than δ
// apart (ghost_tile.h: d(A,B) <= δ collides).
TEST(EnvScatter, NoTwoInstancesCloserThanDeltaAcrossTypes) {
    const float delta = 0.004f;
    json types = json::array({scatterType("leaf", "leaf_oak", "leaves", 120, 0.06f, 0.01f),
                              scatterType("birch", "leaf_birch", "leaves", 80, 0.06f, 0.01f),
                              scatterType("grass", "grass_tuft", "grass", 60, 0.04f, 0.01f)});
    types.push_back({{"name", "pebble"},
                     {"model", {{"mesh", asset("models/pebble.glb")}}},
                     {"candidates", {{"count", 60}}},
                     {"density", {{"point", {{"center", {0.0, 0.0, 0.0}}, {"radius", 0.8}, {"weight", 1.5}}}}}});
    const json env = {{"types", {benchType(true)}},
                      {"tree", {object("bench", {0.3f, 0.2f, 0.0f}, 30.0f)}},
                      {"global_fields", {field("leaves", 1.0f), field("grass", 1.0f)}}};
    Loaded l;
    ASSERT_TRUE(load(project({-0.9f, -0.9f, -0.1f}, {0.9f, 0.9f, 0.6f}, types, env, delta), &l));
    const auto keys = run(l.input(), 2);
    const GhostTile& tile = *l.scene.tile;
    struct Inst {
        std::vector<Sphere> spheres;
        Sphere bound;
        uint64_t tile;
        uint16_t type;
    };
    std::vector<Inst> inst;
    std::vector<size_t> per_type(4, 0);
    for (const auto& k : keys) {
        const uint16_t t = tile.candidates.type[k.second];
        const DetailModel& m = (*l.scene.models)[t];
        Inst i{test::worldSpheres(tile, m, k.first, k.second), {}, k.first, t};
        glm::vec3 c(0.0f);
        for (const Sphere& s : i.spheres) c += s.center;
        c /= float(i.spheres.size());
        float r = 0.0f;
        for (const Sphere& s : i.spheres) r = std::max(r, glm::length(s.center - c) + s.radius);
        i.bound = {c, r};
        inst.push_back(std::move(i));
        ++per_type[t];
    }
    for (size_t t = 0; t < 4; ++t) EXPECT_GT(per_type[t], 5u) << "type " << t;
    size_t pairs_near = 0, across_tiles = 0, across_types = 0;
    for (size_t a = 0; a < inst.size(); ++a)
        for (size_t b = a + 1; b < inst.size(); ++b) {
            if (glm::length(inst[a].bound.center - inst[b].bound.center) - inst[a].bound.radius - inst[b].bound.radius >
                delta)
                continue;
            ++pairs_near;
            across_tiles += inst[a].tile != inst[b].tile;
            across_types += inst[a].type != inst[b].type;
            float d = INFINITY;
            for (const Sphere& sa : inst[a].spheres)
                for (const Sphere& sb : inst[b].spheres)
                    d = std::min(d, glm::length(sa.center - sb.center) - sa.radius - sb.radius);
            EXPECT_GT(d, delta) << "instances " << a << " (type " << inst[a].type << ") and " << b << " (type "
                                << inst[b].type << ")";
        }
    // The check looked at close pairs, across tiles and types (not a vacuous pass).
    EXPECT_GT(across_tiles, 0u);
    EXPECT_GT(across_types, 0u);
    std::printf("delta: %zu instances (%zu %zu %zu %zu), %zu pairs with touching bounds (%zu across tiles, %zu across types)\n",
                inst.size(), per_type[0], per_type[1], per_type[2], per_type[3], pairs_near, across_tiles, across_types);
}

// 6. After random environment edits, Instantiator::update over scatterDirtyRegion equals a fresh
// instantiateAll, bit for bit.
TEST(EnvScatter, IncrementalEqualsFullAfterEnvironmentEdits) {
    json types = json::array({scatterType("leaf", "leaf_oak", "leaves", 100, 0.06f, 0.01f),
                              scatterType("grass", "grass_tuft", "grass", 50, 0.04f, 0.01f)});
    types.push_back({{"name", "pebble"},
                     {"model", {{"mesh", asset("models/pebble.glb")}}},
                     {"candidates", {{"count", 40}}},
                     {"density", {{"point", {{"center", {0.5, 0.5, 0.0}}, {"radius", 1.0}, {"weight", 1.0}}}}}});
    const json env = {{"types", {benchType(true), treeType()}},
                      {"tree", {object("bench", {-0.8f, 0.0f, 0.0f}), object("tree", {1.0f, 0.8f, 0.0f})}},
                      {"global_fields", {field("leaves", 0.3f), field("grass", 0.6f), field("humidity", -0.2f)}}};
    Loaded l;
    ASSERT_TRUE(load(project({-2.0f, -1.5f, -0.1f}, {2.0f, 1.5f, 0.6f}, types, env), &l));
    Instantiator inst;
    std::string error;
    InstanceStats stats;
    ASSERT_TRUE(inst.setInput(l.input(), &error) && inst.instantiateAll({.threads = 2}, &stats, &error)) << error;
    EnvironmentDesc desc = l.project.environment;
    std::shared_ptr<const EnvScene> before = l.scene.environment;
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    size_t changed_edits = 0;
    for (int edit = 0; edit < 10; ++edit) {
        const int kind = edit % 5;
        SCOPED_TRACE(testing::Message() << "edit " << edit << " kind " << kind);
        EnvFieldDesc f;
        f.everywhere = false;
        switch (kind) {
            case 0:  // move the tree (its leaf field moves with it)
                desc.roots[1].transform.translation = glm::vec3(1.5f * u(rng), 1.0f * u(rng), 0.0f);
                break;
            case 1:  // a leaf pile
                f.channel = EnvChannel::Leaves;
                f.value = 1.0f + u(rng);
                f.shape = makePoint(glm::vec3(1.5f * u(rng), 1.0f * u(rng), 0.0f), 0.3f + 0.2f * u(rng), f.value);
                desc.global_fields.push_back(f);
                break;
            case 2:  // a puddle (only the variants read it)
                f.channel = EnvChannel::Humidity;
                f.value = 1.0f;
                f.shape = makePoint(glm::vec3(1.5f * u(rng), 1.0f * u(rng), 0.0f), 0.4f, f.value);
                desc.global_fields.push_back(f);
                break;
            case 3:  // an occlusion trail
                f.channel = EnvChannel::Occlusion;
                f.value = 0.8f;
                f.shape = makeSegment(glm::vec3(1.5f * u(rng), -1.5f, 0.0f), glm::vec3(1.5f * u(rng), 1.5f, 0.0f),
                                      0.25f, f.value);
                desc.global_fields.push_back(f);
                break;
            case 4:  // move and turn the bench
                desc.roots[0].transform.translation = glm::vec3(1.2f * u(rng), 0.8f * u(rng), 0.0f);
                desc.roots[0].transform.yaw_deg = 180.0f * u(rng);
                break;
        }
        auto after = std::make_shared<EnvScene>();
        ASSERT_TRUE(compileEnvScene(desc, l.project.base_dir, "scatter.json", l.scene.terrain, after.get(), &error,
                                    before.get()))
            << error;
        Project edited = l.project;
        edited.environment = desc;
        std::vector<InstanceTypeSettings> settings = inst.input().types;
        for (size_t t = 0; t < edited.detail_types.size(); ++t)
            if (edited.detail_types[t].scatter.enabled) {
                ASSERT_TRUE(compileDetailType(edited, t, l.scene.terrain, &settings[t], &error, after)) << error;
            }
        auto old_keys = test::instancesOf(inst.store());
        std::sort(old_keys.begin(), old_keys.end());
        const std::vector<Bounds> dirty = scatterDirtyRegion(*before, *after);
        ASSERT_TRUE(inst.update(settings, dirty, {.threads = 2}, &stats, nullptr, &error)) << error;
        InstancerInput fresh = l.input();
        fresh.types = settings;
        const auto full = run(fresh, 2);
        auto incremental = test::instancesOf(inst.store());
        std::sort(incremental.begin(), incremental.end());
        EXPECT_EQ(incremental, full);
        changed_edits += full != old_keys;
        before = after;
    }
    EXPECT_GE(changed_edits, 6u);  // the edits did change the scattered layers
}

// 8. The scatter settings and variants through the project's JSON, and bad inputs refused with the place.
TEST(EnvScatter, JsonRoundTripAndRefusals) {
    json types = json::array({scatterType("leaf", "leaf_oak", "leaves", 10, 0.07f, 0.02f),
                              scatterType("grass", "grass_tuft", "grass", 10, 0.04f, 0.01f)});
    types[0]["scatter"]["variants"] = {
        {{"name", "leaf_wet"},
         {"model", {{"mesh", asset("models/leaf_birch.glb")}, {"scale", 1.5}}},
         {"material", {{"base_color", {0.3, 0.1, 0.05}}, {"roughness", 0.35}}},
         {"when", {{"channel", "humidity"}, {"min", 0}}}},
        {{"name", "leaf_dry"}, {"model", {{"mesh", asset("models/leaf_oak.glb")}}},
         {"when", {{"channel", "temperature"}, {"min", 20}, {"max", 40}}}}};
    types[1]["scatter"]["sheltered"] = true;  // not grass's default
    json env = {{"types", {benchType(true)}}, {"tree", {object("bench", {0, 0, 0})}},
                {"global_fields", {field("leaves", 1.0f)}}, {"terrain", {{"snow", false}, {"receives", {"leaves"}}}}};
    const json j = project({-1, -1, -0.1f}, {1, 1, 0.5f}, types, env);
    Project a, b;
    std::string error;
    ASSERT_TRUE(parseProject(j.dump(), "scatter.json", &a, &error)) << error;
    // What was read: the values written above.
    const ScatterDesc& sa = a.detail_types[0].scatter;
    ASSERT_TRUE(sa.enabled);
    EXPECT_EQ(sa.settings.channel, EnvChannel::Leaves);
    EXPECT_FLOAT_EQ(sa.settings.thickness_m, 0.07f);
    EXPECT_FLOAT_EQ(sa.settings.ramp_m, 0.02f);
    EXPECT_TRUE(sa.settings.sheltered);
    ASSERT_EQ(sa.variants.size(), 2u);
    EXPECT_EQ(sa.variants[0].model.name, "leaf_wet");
    EXPECT_FLOAT_EQ(sa.variants[0].model.scale, 1.5f);
    EXPECT_FLOAT_EQ(sa.variants[0].material.roughness, 0.35f);
    EXPECT_EQ(sa.variants[0].when.channel, EnvChannel::Humidity);
    EXPECT_EQ(sa.variants[0].when.min, 0.0f);
    EXPECT_EQ(sa.variants[0].when.max, INFINITY);
    EXPECT_EQ(sa.variants[1].when.channel, EnvChannel::Temperature);
    EXPECT_EQ(sa.variants[1].when.min, 20.0f);
    EXPECT_EQ(sa.variants[1].when.max, 40.0f);
    EXPECT_EQ(a.detail_types[1].scatter.settings.channel, EnvChannel::Grass);
    EXPECT_TRUE(a.detail_types[1].scatter.settings.sheltered);
    EXPECT_EQ(a.environment.types[0].receives, envChannelBit(EnvChannel::Leaves) | envChannelBit(EnvChannel::Grass));
    EXPECT_EQ(a.environment.terrain.receives, envChannelBit(EnvChannel::Leaves));
    // Grass defaults to unsheltered, leaves to sheltered.
    {
        json d = j;
        d["detail_types"][1]["scatter"].erase("sheltered");
        d["detail_types"][0]["scatter"].erase("sheltered");
        Project p;
        ASSERT_TRUE(parseProject(d.dump(), "scatter.json", &p, &error)) << error;
        EXPECT_TRUE(p.detail_types[0].scatter.settings.sheltered);
        EXPECT_FALSE(p.detail_types[1].scatter.settings.sheltered);
    }
    // Round trip: written and read again, the same settings; written again, the same text.
    const std::string text = projectToJson(a);
    ASSERT_TRUE(parseProject(text, "scatter.json", &b, &error)) << error << "\n" << text;
    ASSERT_EQ(b.detail_types.size(), a.detail_types.size());
    for (size_t t = 0; t < a.detail_types.size(); ++t) {
        const ScatterDesc &x = a.detail_types[t].scatter, &y = b.detail_types[t].scatter;
        EXPECT_EQ(x.enabled, y.enabled);
        EXPECT_EQ(x.settings.channel, y.settings.channel);
        EXPECT_TRUE(test::sameBits(x.settings.thickness_m, y.settings.thickness_m));
        EXPECT_TRUE(test::sameBits(x.settings.ramp_m, y.settings.ramp_m));
        EXPECT_EQ(x.settings.sheltered, y.settings.sheltered);
        ASSERT_EQ(x.variants.size(), y.variants.size());
        for (size_t k = 0; k < x.variants.size(); ++k) {
            EXPECT_EQ(x.variants[k].model.name, y.variants[k].model.name);
            EXPECT_EQ(x.variants[k].model.mesh_path, y.variants[k].model.mesh_path);
            EXPECT_TRUE(test::sameBits(x.variants[k].model.scale, y.variants[k].model.scale));
            EXPECT_TRUE(x.variants[k].material == y.variants[k].material);
            EXPECT_EQ(x.variants[k].when.channel, y.variants[k].when.channel);
            EXPECT_EQ(x.variants[k].when.min, y.variants[k].when.min);
            EXPECT_EQ(x.variants[k].when.max, y.variants[k].when.max);
        }
    }
    EXPECT_EQ(b.environment.types[0].receives, a.environment.types[0].receives);
    EXPECT_EQ(b.environment.terrain.receives, a.environment.terrain.receives);
    EXPECT_EQ(projectToJson(b), text);
    // A project with only a scattered type and no environment is still written as format 3.
    {
        Project p = a;
        p.environment = EnvironmentDesc{};
        EXPECT_EQ(json::parse(projectToJson(p))["format_version"], 3);
    }

    // Refusals name the place.
    const auto refused = [&](json bad, const std::string& pointer) {
        Project p;
        std::string why;
        EXPECT_FALSE(parseProject(bad.dump(), "scatter.json", &p, &why)) << pointer;
        EXPECT_NE(why.find("scatter.json: " + pointer + ":"), std::string::npos) << why;
    };
    {
        json d = j;
        d["detail_types"][0]["scatter"]["channel"] = "snow";
        refused(d, "/detail_types/0/scatter/channel");
        d["detail_types"][0]["scatter"]["channel"] = "confetti";
        refused(d, "/detail_types/0/scatter/channel");
    }
    for (const float bad : {0.0f, -0.05f}) {
        json d = j;
        d["detail_types"][1]["scatter"]["thickness_m"] = bad;
        refused(d, "/detail_types/1/scatter/thickness_m");
    }
    {
        json d = j;
        d["detail_types"][0]["scatter"]["variants"][1]["name"] = "grass";
        refused(d, "/detail_types/0/scatter/variants/1/name");
        d["detail_types"][0]["scatter"]["variants"][1]["name"] = "leaf_wet";
        refused(d, "/detail_types/0/scatter/variants/1/name");
    }
    {
        json d = j;
        d["environment"]["types"][0]["receives"] = {"snow"};
        refused(d, "/environment/types/0/receives/0");
        d["environment"]["types"][0]["receives"] = {"leaves", "leaves"};
        refused(d, "/environment/types/0/receives/1");
    }
    {
        json d = j;
        d["format_version"] = 2;
        d.erase("environment");
        refused(d, "/detail_types/0/scatter");
    }
    // A scattered type compiled without an environment is refused, naming it.
    {
        std::shared_ptr<const HeightField> terrain;
        ASSERT_TRUE(loadTerrain(a, &terrain, &error)) << error;
        InstanceTypeSettings s;
        EXPECT_FALSE(compileDetailType(a, 0, terrain, &s, &error));
        EXPECT_NE(error.find("/detail_types/0/scatter"), std::string::npos) << error;
    }
}

// 7. The scattered scene does not depend on the thread count, and regions partitioning the extent union
// to the whole.
TEST(EnvScatterThreads, ThreadsAndRegionsGiveTheSameInstances) {
    json types = json::array({scatterType("leaf", "leaf_oak", "leaves", 100, 0.06f, 0.01f),
                              scatterType("grass", "grass_tuft", "grass", 50, 0.04f, 0.01f)});
    types.push_back({{"name", "pebble"},
                     {"model", {{"mesh", asset("models/pebble.glb")}}},
                     {"candidates", {{"count", 40}}},
                     {"density", {{"point", {{"center", {0.3, -0.2, 0.0}}, {"radius", 0.9}, {"weight", 1.0}}}}}});
    const json env = {{"types", {benchType(true), treeType()}},
                      {"tree", {object("bench", {-0.5f, 0.1f, 0.0f}, 15.0f), object("tree", {0.9f, -0.5f, 0.0f})}},
                      {"global_fields", {field("leaves", 0.4f), field("grass", 0.7f),
                                         field("occlusion", 0.7f, pointShape({0.0f, 0.0f, 0.0f}, 0.6f))}}};
    Loaded l;
    ASSERT_TRUE(load(project({-1.5f, -1.2f, -0.1f}, {1.5f, 1.2f, 0.6f}, types, env), &l));
    const InstancerInput input = l.input();
    const auto one = run(input, 1);
    EXPECT_GT(one.size(), 50u);
    EXPECT_EQ(run(input, 2), one);
    EXPECT_EQ(run(input, 8), one);
    // 2 x 2 regions split off-centre, not on tile borders.
    const Bounds& e = input.extent;
    const float xs[3] = {e.lo.x, 0.13f, e.hi.x}, ys[3] = {e.lo.y, -0.37f, e.hi.y};
    std::vector<test::InstanceKey> united;
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
            const Bounds region{glm::vec3(xs[i], ys[j], e.lo.z), glm::vec3(xs[i + 1], ys[j + 1], e.hi.z)};
            InstanceStore store;
            InstanceStats st;
            std::string error;
            ASSERT_TRUE(instantiateRegion(input, region, {.threads = 2}, &store, &st, &error)) << error;
            const auto part = test::instancesOf(store);
            EXPECT_FALSE(part.empty());
            united.insert(united.end(), part.begin(), part.end());
        }
    std::sort(united.begin(), united.end());
    EXPECT_EQ(united, one);
}

}  // namespace ug
