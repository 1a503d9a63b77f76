// Compiling a project into instantiation settings: fields equal to hand-built ones bit for bit, the
// terrain solid, direction and size fields, the extent, and every bundled scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

// engine_tests does not get stb's include directory; libstb itself is linked through the engine.
#include <stb/stb_image_write.h>

#include "env/env_json.h"
#include "env/env_scene.h"
#include "scene/project.h"
#include "scene/scene_compile.h"
#include "scene_test_util.h"

namespace ug {
namespace {

using test::sameBits;
using test::sameStructure;
using test::sameValues;

const std::string kHead = R"({"format": "undergrowth-project", "format_version": 2, )";
const std::string kTerrain =
    R"("terrain": {"procedural": {"origin": [-4, -4], "cell_size_m": 0.25, "width": 33, "height": 33, "seed": 3,
                                 "octaves": 3, "amplitude_m": 0.5, "feature_size_m": 4}}, )";

ProceduralTerrainDesc terrainDesc() {
    return ProceduralTerrainDesc{.origin_m = {-4, -4},
                                 .cell_size_m = 0.25f,
                                 .width = 33,
                                 .height = 33,
                                 .seed = 3,
                                 .octaves = 3,
                                 .amplitude_m = 0.5f,
                                 .feature_size_m = 4.0f};
}

bool parse(const std::string& text, Project* p) {
    std::string error;
    const bool ok = parseProject(text, "c.json", p, &error);
    EXPECT_TRUE(ok) << error;
    return ok;
}

bool compile(const Project& p, CompiledScene* out) {
    std::shared_ptr<const HeightField> terrain;
    std::string error;
    if (!loadTerrain(p, &terrain, &error)) {
        ADD_FAILURE() << error;
        return false;
    }
    // Scattered types read their density from the environment: compile it first, as loadScene does.
    auto env = std::make_shared<EnvScene>();
    if (!compileEnvScene(p.environment, p.base_dir, p.name, terrain, env.get(), &error)) {
        ADD_FAILURE() << error;
        return false;
    }
    const bool ok = compileScene(p, terrain, out, &error, env);
    EXPECT_TRUE(ok) << error;
    return ok;
}

std::string compileError(const Project& p) {
    std::shared_ptr<const HeightField> terrain;
    std::string error;
    if (!loadTerrain(p, &terrain, &error)) return error;
    CompiledScene scene;
    EXPECT_FALSE(compileScene(p, terrain, &scene, &error));
    return error;
}

const std::string kGrass = kHead + kTerrain + R"("detail_types": [
  {"name": "grass", "model": {"mesh": "g.glb"},
   "density": {"blend": [{"terrain_layer": {"thickness": 0.05, "radius": 0.1, "weight": 0.6}},
                         {"intersection": [{"terrain_layer": {"thickness": 0.05, "radius": 0.1, "weight": 0.4}},
                                           {"point": {"center": [1, 1, 0], "radius": 2}}]}]},
   "terrain_falloff_m": 0.04},
  {"name": "stones", "model": {"mesh": "s.glb"}, "subtract_terrain": false,
   "density": {"blend": [{"terrain_layer": {"thickness": 0.05, "radius": 0.1, "weight": 0.6}},
                         {"point": {"center": [-1, 0, 0.5], "radius": 1}}]}}]})";

TEST(SceneCompile, CompiledFieldEqualsTheHandBuiltField) {
    Project p;
    ASSERT_TRUE(parse(kGrass, &p));
    CompiledScene scene;
    ASSERT_TRUE(compile(p, &scene));
    ASSERT_TRUE(scene.terrain);
    ASSERT_EQ(scene.types.size(), 2u);

    HeightField hf;
    std::string error;
    ASSERT_TRUE(makeProceduralHeightField(terrainDesc(), &hf, &error)) << error;
    auto terrain = std::make_shared<const HeightField>(std::move(hf));
    EXPECT_EQ(terrain->heights(), scene.terrain->heights());

    // Type 0: the terrain attached as height field 0, then the ground solid subtracted.
    DensityField grass;
    addHeightField(&grass, terrain);
    const uint32_t l0 = primitiveChild(addPrimitive(&grass, makeTerrainLayer(0, 0.05f, 0.1f, 0.6f)));
    const uint32_t l1 = primitiveChild(addPrimitive(&grass, makeTerrainLayer(0, 0.05f, 0.1f, 0.4f)));
    const uint32_t pt = primitiveChild(addPrimitive(&grass, makePoint({1, 1, 0}, 2.0f)));
    const uint32_t in = nodeChild(addNode(&grass, FieldOp::Intersection, std::vector<uint32_t>{l1, pt}));
    grass.root = addNode(&grass, FieldOp::Blend, std::vector<uint32_t>{l0, in});
    subtractSolids(&grass, {makeTerrainSolid(0, 0.04f)});
    const DensityField& compiled = *scene.types[0].field;
    EXPECT_TRUE(sameStructure(compiled, grass));
    ASSERT_EQ(compiled.height_fields.size(), 1u);
    EXPECT_EQ(compiled.height_fields[0], scene.terrain);
    const Bounds box{glm::vec3(-4, -4, -0.7f), glm::vec3(4, 4, 0.8f)};
    EXPECT_TRUE(sameValues(compiled, grass, box, 20));  // a separately made terrain with the same heights

    // Type 1: no subtraction asked.
    DensityField stones =
        makeBlendField({makeTerrainLayer(0, 0.05f, 0.1f, 0.6f), makePoint({-1, 0, 0.5f}, 1.0f)});
    addHeightField(&stones, scene.terrain);
    EXPECT_TRUE(sameStructure(*scene.types[1].field, stones));
    EXPECT_TRUE(sameValues(*scene.types[1].field, stones, box, 20));

    // The document is untouched: nothing attached there.
    EXPECT_TRUE(p.detail_types[0].density.height_fields.empty());
}

TEST(SceneCompile, TerrainSubtractionMakesTheFieldNonPositiveBelowTheGroundAndChangesNothingAbove) {
    Project p;
    ASSERT_TRUE(parse(kGrass, &p));
    p.detail_types[1].subtract_terrain = true;
    p.detail_types[1].terrain_falloff_m = 0.05f;
    CompiledScene with, without;
    ASSERT_TRUE(compile(p, &with));
    p.detail_types[1].subtract_terrain = false;
    ASSERT_TRUE(compile(p, &without));
    const DensityField& f = *with.types[1].field;
    const DensityField& g = *without.types[1].field;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-4.0f, 4.0f), depth(0.01f, 2.0f), height(0.0f, 1.5f);
    int positive_without = 0;
    for (int k = 0; k < 4000; ++k) {
        const float x = u(rng), y = u(rng);
        const float h = with.terrain->sample(x, y);
        const glm::vec3 below(x, y, h - depth(rng));
        ASSERT_LE(evaluate(f, below), 0.0f) << x << " " << y << " " << below.z;
        positive_without += evaluate(g, below) > 0.0f;
        const glm::vec3 above(x, y, h + height(rng));
        ASSERT_TRUE(sameBits(evaluate(f, above), evaluate(g, above))) << x << " " << y << " " << above.z;
    }
    EXPECT_GT(positive_without, 100);  // the layer does reach below the ground before subtraction
}

TEST(SceneCompile, GradientDirectionUsesTheCompiledField) {
    Project p;
    ASSERT_TRUE(parse(kHead + kTerrain + R"("detail_types": [
      {"name": "hay", "model": {"mesh": "h.glb"},
       "density": {"segment": {"a": [0, 0, -1], "b": [0, 0, 2], "radius": 1.2, "weight": 1.5}},
       "instancing": {"strategy": "elevation", "layer_m": 0.03,
                      "orientation": {"direction": "gradient", "max_angle_deg": 35}}},
      {"name": "grass", "model": {"mesh": "g.glb"},
       "density": {"terrain_layer": {"thickness": 0.05, "radius": 0.1}},
       "instancing": {"orientation": {"direction": [0, 3, 4], "max_angle_deg": 90}}}]})",
                      &p));
    CompiledScene scene;
    ASSERT_TRUE(compile(p, &scene));
    const InstanceTypeSettings& hay = scene.types[0];
    EXPECT_EQ(hay.strategy, PriorityStrategy::Elevation);
    EXPECT_EQ(hay.layer_m, 0.03f);
    ASSERT_TRUE(hay.orientation.enabled);
    EXPECT_EQ(hay.orientation.direction.kind, DirectionFieldKind::Gradient);
    EXPECT_EQ(hay.orientation.direction.field, hay.field);  // the same compiled object, terrain subtracted
    EXPECT_FLOAT_EQ(hay.orientation.min_cos, std::cos(35.0f * std::numbers::pi_v<float> / 180.0f));
    const glm::vec3 q(0.6f, 0.2f, 0.8f);
    const glm::vec4 g = evaluateWithGradient(*hay.field, q);
    const glm::vec3 expect = glm::vec3(g) / glm::length(glm::vec3(g));
    EXPECT_TRUE(test::sameBits(evaluateDirection(hay.orientation.direction, nullptr, q), expect));
    EXPECT_LT(expect.x, -0.9f);  // a capsule's density grows towards its axis

    const InstanceTypeSettings& grass = scene.types[1];
    ASSERT_TRUE(grass.orientation.enabled);
    EXPECT_EQ(grass.orientation.direction.kind, DirectionFieldKind::Constant);
    EXPECT_NEAR(grass.orientation.direction.direction.y, 0.6f, 1e-7f);
    EXPECT_NEAR(grass.orientation.min_cos, 0.0f, 1e-7f);
    EXPECT_FALSE(grass.size.enabled);
}

TEST(SceneCompile, SizeFieldsCompile) {
    Project p;
    ASSERT_TRUE(parse(kHead + kTerrain + R"("detail_types": [
      {"name": "stone", "model": {"mesh": "s.glb"},
       "density": {"point": {"center": [0, 0, 1], "radius": 2}},
       "instancing": {"size": {"target": {"field": {"blend": [{"point": {"center": [1, 0, 1], "radius": 1}},
                                                              {"terrain_layer": {"thickness": 0, "radius": 0.5}}]},
                                          "value_lo": 0, "value_hi": 1, "scale_lo": 1.1, "scale_hi": 0.7},
                               "tolerance": 0.2}}},
      {"name": "pebble", "model": {"mesh": "p.glb"},
       "density": {"point": {"center": [0, 0, 1], "radius": 2}},
       "instancing": {"size": {"target": 0.8}}}]})",
                      &p));
    CompiledScene scene;
    ASSERT_TRUE(compile(p, &scene));
    const SizeConstraint& ramp = scene.types[0].size;
    ASSERT_TRUE(ramp.enabled);
    EXPECT_EQ(ramp.tolerance, 0.2f);
    EXPECT_EQ(ramp.target.kind, SizeFieldKind::Ramp);
    ASSERT_TRUE(ramp.target.field);
    DensityField hand = makeBlendField({makePoint({1, 0, 1}, 1.0f), makeTerrainLayer(0, 0.0f, 0.5f)});
    addHeightField(&hand, scene.terrain);
    EXPECT_TRUE(sameStructure(*ramp.target.field, hand));  // no terrain subtraction for size fields
    EXPECT_TRUE(sameValues(*ramp.target.field, hand, Bounds{glm::vec3(-4, -4, -1), glm::vec3(4, 4, 2)}, 20));
    EXPECT_EQ(ramp.target.scale_lo, 1.1f);
    EXPECT_EQ(ramp.target.scale_hi, 0.7f);
    EXPECT_NEAR(evaluateSize(ramp.target, nullptr, {1, 0, 1}), 0.7f, 1e-6f);  // the field is >= 1 there

    const SizeConstraint& constant = scene.types[1].size;
    ASSERT_TRUE(constant.enabled);
    EXPECT_EQ(constant.target.kind, SizeFieldKind::Constant);
    EXPECT_EQ(constant.target.scale, 0.8f);
    EXPECT_EQ(constant.tolerance, 0.25f);
}

TEST(SceneCompile, CompileDetailTypeMatchesCompileScene) {
    Project p;
    ASSERT_TRUE(parse(kGrass, &p));
    std::shared_ptr<const HeightField> terrain;
    std::string error;
    ASSERT_TRUE(loadTerrain(p, &terrain, &error)) << error;
    CompiledScene scene;
    ASSERT_TRUE(compileScene(p, terrain, &scene, &error)) << error;
    // An edit of type 1, recompiled alone.
    p.detail_types[1].density = makeBlendField({makePoint({0, 0, 0.2f}, 0.5f)});
    InstanceTypeSettings one;
    ASSERT_TRUE(compileDetailType(p, 1, terrain, &one, &error)) << error;
    CompiledScene full;
    ASSERT_TRUE(compileScene(p, terrain, &full, &error)) << error;
    EXPECT_TRUE(sameStructure(*one.field, *full.types[1].field));
    EXPECT_TRUE(sameValues(*one.field, *full.types[1].field, Bounds{glm::vec3(-1), glm::vec3(1)}, 20));
    EXPECT_FALSE(compileDetailType(p, 2, terrain, &one, &error));
    EXPECT_NE(error.find("c.json: /detail_types: no detail type 2"), std::string::npos) << error;
}

TEST(SceneCompile, ExtentIsDerivedFromTheFields) {
    // No terrain: the union of the positive bounds.
    Project p;
    ASSERT_TRUE(parse(kHead + R"("detail_types": [
      {"name": "a", "model": {"mesh": "a.glb"}, "density": {"point": {"center": [1, 2, 3], "radius": 0.5}}},
      {"name": "b", "model": {"mesh": "b.glb"},
       "density": {"difference": [{"segment": {"a": [-1, 0, 0], "b": [1, 0, 0], "radius": 0.25}},
                                  {"half_space": {"point": [0, 0, 0], "normal": [0, 0, 1], "radius": 0.1}}]}},
      {"name": "c", "model": {"mesh": "c.glb"}}]})",
                      &p));
    CompiledScene scene;
    ASSERT_TRUE(compile(p, &scene));
    Bounds expect = unite(positiveBounds(*scene.types[0].field), positiveBounds(*scene.types[1].field));
    EXPECT_EQ(scene.extent.lo, expect.lo);
    EXPECT_EQ(scene.extent.hi, expect.hi);
    EXPECT_NEAR(scene.extent.lo.x, -1.25f, 1e-4f);
    EXPECT_NEAR(scene.extent.hi.z, 3.5f, 1e-4f);
    EXPECT_EQ(computeSceneExtent(p, scene).lo, scene.extent.lo);

    // With a terrain: a layer is clipped to the terrain's rectangle; an unbounded Z gets the padded
    // height range, a bounded one is kept.
    Project t;
    ASSERT_TRUE(parse(kHead + kTerrain + R"("detail_types": [
      {"name": "grass", "model": {"mesh": "g.glb"}, "density": {"terrain_layer": {"thickness": 0.05, "radius": 0.1}}},
      {"name": "wall", "model": {"mesh": "w.glb"}, "subtract_terrain": false,
       "density": {"half_space": {"point": [0, 0, 0], "normal": [1, 1, 0], "radius": 0.1}}}]})",
                      &t));
    CompiledScene ts;
    ASSERT_TRUE(compile(t, &ts));
    EXPECT_EQ(ts.extent.lo.x, -4.0f);
    EXPECT_EQ(ts.extent.lo.y, -4.0f);
    EXPECT_EQ(ts.extent.hi.x, 4.0f);
    EXPECT_EQ(ts.extent.hi.y, 4.0f);
    EXPECT_EQ(ts.extent.lo.z, ts.terrain->minHeight() - kTerrainExtentPadM);
    EXPECT_EQ(ts.extent.hi.z, ts.terrain->maxHeight() + kTerrainExtentPadM);
    t.detail_types.pop_back();
    ASSERT_TRUE(compile(t, &ts));
    EXPECT_EQ(ts.extent.hi.z, positiveBounds(*ts.types[0].field).hi.z);  // the layer's own top
    EXPECT_LT(ts.extent.hi.z, ts.terrain->maxHeight() + 0.2f);

    // An explicit extent wins.
    t.extent = Bounds{glm::vec3(-1), glm::vec3(1)};
    ASSERT_TRUE(compile(t, &ts));
    EXPECT_EQ(ts.extent.lo, glm::vec3(-1));
    EXPECT_EQ(ts.extent.hi, glm::vec3(1));
}

TEST(SceneCompile, UnboundedOrEmptyDensityNeedsAnExtent) {
    Project p;
    ASSERT_TRUE(parse(kHead + R"("detail_types": [
      {"name": "rock", "model": {"mesh": "r.glb"}, "density": {"point": {"center": [0, 0, 0], "radius": 1}}},
      {"name": "sand", "model": {"mesh": "s.glb"},
       "density": {"half_space": {"point": [0, 0, 0], "normal": [0, 0, 1], "radius": 0.1}}}]})",
                      &p));
    EXPECT_EQ(compileError(p), "c.json: /extent: required because the density of 'sand' is unbounded");
    p.extent = Bounds{glm::vec3(-2), glm::vec3(2)};
    CompiledScene scene;
    EXPECT_TRUE(compile(p, &scene));

    Project empty;
    ASSERT_TRUE(parse(kHead + R"("detail_types": [{"name": "rock", "model": {"mesh": "r.glb"}}]})", &empty));
    EXPECT_EQ(compileError(empty), "c.json: /extent: required because no detail type has any density");
    // A version 1 file has no density at all: it compiles once it says where.
    empty.extent = Bounds{glm::vec3(0), glm::vec3(1)};
    ASSERT_TRUE(compile(empty, &scene));
    EXPECT_EQ(evaluate(*scene.types[0].field, glm::vec3(0.5f)), 0.0f);
}

TEST(SceneCompile, ErrorsNameTheSceneAndThePlace) {
    Project p;
    ASSERT_TRUE(parse(kGrass, &p));
    std::string error;
    CompiledScene scene;
    EXPECT_FALSE(compileScene(p, nullptr, &scene, &error));
    EXPECT_EQ(error, "c.json: /terrain: the terrain is not loaded (call loadTerrain first)");

    // Settings the parser would refuse, set in memory (as an editor could).
    std::shared_ptr<const HeightField> terrain;
    ASSERT_TRUE(loadTerrain(p, &terrain, &error)) << error;
    Project bad = p;
    bad.detail_types[1].density.primitives[1].radius_m = std::nanf("");
    EXPECT_FALSE(compileScene(bad, terrain, &scene, &error));
    EXPECT_NE(
        error.find(
            "c.json: /detail_types/1/density: primitive 1 (point): radius_m nan must be finite and > 0"),
        std::string::npos)
        << error;
    bad = p;
    bad.detail_types[0].instancing.orientation.enabled = true;
    bad.detail_types[0].instancing.orientation.direction = glm::vec3(0, 0, 2);
    EXPECT_FALSE(compileScene(bad, terrain, &scene, &error));
    EXPECT_NE(error.find(
                  "c.json: /detail_types/0/instancing/orientation/direction: direction field: direction must "
                  "be unit length"),
              std::string::npos)
        << error;
    bad = p;
    bad.detail_types[0].instancing.size.enabled = true;
    bad.detail_types[0].instancing.size.kind = SizeFieldKind::Ramp;
    bad.detail_types[0].instancing.size.value_lo = 1.0f;  // == value_hi
    EXPECT_FALSE(compileScene(bad, terrain, &scene, &error));
    EXPECT_NE(error.find("c.json: /detail_types/0/instancing/size/target: size field: value_lo and value_hi"),
              std::string::npos)
        << error;
    bad = p;
    addHeightField(&bad.detail_types[0].density, terrain);
    EXPECT_FALSE(compileScene(bad, terrain, &scene, &error));
    EXPECT_NE(error.find("c.json: /detail_types/0/density: the document's field has height fields attached"),
              std::string::npos)
        << error;
    bad = p;
    bad.detail_types[1].instancing.layer_m = 0.0f;
    EXPECT_FALSE(compileScene(bad, terrain, &scene, &error));
    EXPECT_NE(error.find("c.json: /detail_types/1/instancing/layer_m: must be finite and > 0"),
              std::string::npos)
        << error;

    // A project without terrain given one, and an in-memory project named by its name.
    Project plain;
    plain.name = "memory";
    plain.detail_types.push_back({});
    plain.detail_types[0].model.name = "x";
    EXPECT_FALSE(compileScene(plain, terrain, &scene, &error));
    EXPECT_EQ(error, "project 'memory': /terrain: a terrain was given but the project has none");
}

TEST(SceneCompile, ImageTerrainLoadsRelativeToTheProject) {
    const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "ug_scene_compile_test";
    std::filesystem::create_directories(dir / "maps");
    const unsigned char pixels[9] = {0, 128, 255, 0, 128, 255, 0, 128, 255};
    ASSERT_NE(stbi_write_png((dir / "maps" / "h.png").string().c_str(), 3, 3, 1, pixels, 3), 0);
    const std::string scene_path = (dir / "scene.json").string();
    {
        FILE* f = std::fopen(scene_path.c_str(), "w");
        ASSERT_TRUE(f);
        const std::string text = kHead + R"("terrain": {"image": {"path": "maps/h.png", "origin": [10, 20],
            "cell_size_m": 2, "min_height_m": 0, "max_height_m": 3}},
          "detail_types": [{"name": "g", "model": {"mesh": "g.glb"},
                            "density": {"terrain_layer": {"thickness": 0.1, "radius": 0.1}}}]})";
        std::fputs(text.c_str(), f);
        std::fclose(f);
    }
    Project p;
    std::string error;
    ASSERT_TRUE(loadProject(scene_path, &p, &error)) << error;
    CompiledScene scene;
    ASSERT_TRUE(compile(p, &scene));
    EXPECT_EQ(scene.terrain->width(), 3);
    EXPECT_EQ(scene.terrain->maxHeight(), 3.0f);
    EXPECT_EQ(scene.extent.lo.x, 10.0f);
    EXPECT_EQ(scene.extent.hi.x, 14.0f);
    EXPECT_EQ(scene.extent.hi.y, 24.0f);

    p.terrain.image_path = "maps/missing.png";
    std::shared_ptr<const HeightField> terrain;
    EXPECT_FALSE(loadTerrain(p, &terrain, &error));
    EXPECT_EQ(error.rfind(scene_path + ": /terrain/image/path: ", 0), 0u) << error;
    EXPECT_NE(error.find("missing.png: cannot open"), std::string::npos) << error;
    std::filesystem::remove_all(dir);
}

// Every scene under assets/scenes loads, compiles, has its models on disk, and round-trips to the same
// compiled fields.
TEST(SceneCompile, EveryBundledSceneLoadsAndCompiles) {
    const std::filesystem::path dir = std::filesystem::path(UG_SOURCE_DIR) / "assets" / "scenes";
    std::vector<std::string> seen;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".json") continue;
        const std::string path = entry.path().string();
        SCOPED_TRACE(path);
        seen.push_back(entry.path().stem().string());
        Project p;
        std::string error;
        ASSERT_TRUE(loadProject(path, &p, &error)) << error;
        CompiledScene scene;
        ASSERT_TRUE(compile(p, &scene));
        for (int a = 0; a < 3; ++a) {
            EXPECT_TRUE(std::isfinite(scene.extent.lo[a]) && std::isfinite(scene.extent.hi[a]));
            EXPECT_LT(scene.extent.lo[a], scene.extent.hi[a]);
        }
        for (size_t t = 0; t < p.detail_types.size(); ++t) {
            EXPECT_TRUE(std::filesystem::exists(resolveProjectPath(p, p.detail_types[t].model.mesh_path)))
                << p.detail_types[t].model.mesh_path;
            // A scattered type's density is its effect's term (env_scatter.h).
            EXPECT_TRUE(p.detail_types[t].density.root != kNoNode || p.detail_types[t].scatter.enabled)
                << p.detail_types[t].model.name << " has no density";
        }
        Project back;
        ASSERT_TRUE(parseProject(projectToJson(p), path, &back, &error)) << error;
        back.base_dir = p.base_dir;
        CompiledScene again;
        ASSERT_TRUE(compile(back, &again));
        for (size_t t = 0; t < scene.types.size(); ++t) {
            EXPECT_TRUE(sameStructure(*scene.types[t].field, *again.types[t].field));
            EXPECT_TRUE(sameValues(*scene.types[t].field, *again.types[t].field, scene.extent, 0, 500));
        }
        // The environment (format 3): its meshes load, its tree expands, and it is saved as it was read.
        EXPECT_EQ(environmentToJson(back.environment).dump(), environmentToJson(p.environment).dump());
        if (!p.environment.empty()) {
            EnvScene env;
            ASSERT_TRUE(compileEnvScene(p.environment, p.base_dir, path, scene.terrain, &env, &error)) << error;
            // The Fig. 3 starting point has the library and nothing placed yet; the bus stop has its
            // shelter and two slabs.
            if (entry.path().stem() == "bus_stop_vines") {
                EXPECT_EQ(env.objects().size(), 3u);
            } else if (entry.path().stem() != "street_winter_start") {
                EXPECT_GT(env.objects().size(), 10u);
            }
        }
        // The particle systems (format 4): saved as read, and every file is there.
        EXPECT_EQ(back.particles, p.particles);
        for (const ParticleSystemRef& ref : p.particles)
            EXPECT_TRUE(std::filesystem::exists(resolveProjectPath(p, ref.file))) << ref.file;
    }
    std::sort(seen.begin(), seen.end());
    EXPECT_EQ(seen, (std::vector<std::string>{"beaver_dam", "bus_stop_vines", "default", "haystack_field", "meadow", "meadow_strands", "montmartre_winter",
                                              "park_autumn", "road_autumn", "road_winter", "rock_pile", "rock_pile_moss", "stone_hut",
                                              "street_autumn", "street_winter", "street_winter_start", "world_1km",
                                              "world_250m"}));
}

TEST(SceneCompile, BundledScenesHaveTheirDesignedShape) {
    const std::filesystem::path dir = std::filesystem::path(UG_SOURCE_DIR) / "assets" / "scenes";
    auto load = [&](const char* name, Project* p, CompiledScene* s) {
        std::string error;
        ASSERT_TRUE(loadProject((dir / name).string(), p, &error)) << error;
        ASSERT_TRUE(compile(*p, s));
    };
    for (const auto& [name, side] : {std::pair{"world_1km.json", 1000.0f}, std::pair{"world_250m.json", 250.0f}}) {
        // The region-job worlds (docs/worlds.md): the large one at least a square kilometre, every type
        // in it, the terrain under the whole extent.
        Project p;
        CompiledScene s;
        load(name, &p, &s);
        EXPECT_EQ(s.extent.hi.x - s.extent.lo.x, side) << name;
        EXPECT_EQ(s.extent.hi.y - s.extent.lo.y, side) << name;
        EXPECT_EQ(p.detail_types.size(), 3u) << name;
        ASSERT_TRUE(s.terrain) << name;
        EXPECT_LE(s.terrain->origin().x, s.extent.lo.x) << name;
        EXPECT_GE(s.terrain->origin().y + s.terrain->cellSize() * float(s.terrain->height() - 1), s.extent.hi.y)
            << name;
    }
    {
        // The haystack field is the global-instantiation benchmark: its grass covers the whole terrain.
        Project p;
        CompiledScene s;
        load("haystack_field.json", &p, &s);
        EXPECT_EQ(s.extent.lo.x, -40.0f);
        EXPECT_EQ(s.extent.hi.x, 40.0f);
        EXPECT_EQ(s.extent.hi.y, 40.0f);
        for (float x : {-39.5f, 0.0f, 39.5f})
            for (float y : {-39.5f, 0.0f, 39.5f})
                EXPECT_GT(evaluate(*s.types[0].field, {x, y, s.terrain->sample(x, y) + 0.03f}), 0.5f)
                    << x << " " << y;
        EXPECT_EQ(s.types[1].orientation.direction.kind, DirectionFieldKind::Gradient);
    }
    {
        // The rock pile never goes below its floor.
        Project p;
        CompiledScene s;
        load("rock_pile.json", &p, &s);
        EXPECT_EQ(s.types[0].strategy, PriorityStrategy::Elevation);
        EXPECT_GT(evaluate(*s.types[0].field, {0, 0, 0.3f}), 0.0f);
        for (float z : {-0.05f, -0.3f, -0.8f}) EXPECT_LE(evaluate(*s.types[0].field, {0, 0, z}), 0.0f);
    }
    {
        // The stone hut is a corbelled cone (its inner face 58 degrees steep, so every course rests on the
        // one below), with a door and a window, and smaller stones near the openings.
        Project p;
        CompiledScene s;
        load("stone_hut.json", &p, &s);
        const DensityField& f = *s.types[0].field;
        EXPECT_LE(evaluate(f, {0, 0, 0.5f}), 0.0f);        // inside
        EXPECT_LE(evaluate(f, {0, 0, 3.4f}), 0.0f);        // inside, under the top
        EXPECT_GT(evaluate(f, {0, 2.7f, 0.3f}), 0.0f);     // the wall
        EXPECT_GT(evaluate(f, {-1.45f, 0, 2.3f}), 0.0f);   // the wall, higher up
        EXPECT_GT(evaluate(f, {0, 0, 4.2f}), 0.0f);        // the top
        EXPECT_LE(evaluate(f, {0, 3.25f, 0.3f}), 0.0f);    // outside the foot
        EXPECT_LE(evaluate(f, {2.6f, 0, 0.6f}), 0.0f);     // the door
        EXPECT_LE(evaluate(f, {0, -2.08f, 1.3f}), 0.0f);   // the window
        EXPECT_LE(evaluate(f, {0, 3.25f, 4.0f}), 0.0f);    // outside
        const SizeConstraint& size = s.types[0].size;
        ASSERT_TRUE(size.enabled);
        EXPECT_LT(evaluateSize(size.target, nullptr, {2.45f, 0, 0.7f}), 0.75f);
        EXPECT_EQ(evaluateSize(size.target, nullptr, {-3.2f, 0, 0.9f}), 1.1f);
    }
}

}  // namespace
}  // namespace ug
