// The project's particle systems (format 4 "particles", scene/scene_particles.h): the entries round-trip
// through the project file, their files are read, renamed and moved as the entries say, errors name the
// project, the entry and the particle file's own place, a region holds each system once, and on_terrain
// generators seed on the ground.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "particles/particle_seeding.h"
#include "particles/strand_growth.h"
#include "scene/project.h"
#include "scene/scene_particles.h"
#include "scene_test_util.h"

namespace ug {
namespace {

const char* kGrass = R"({"format": "undergrowth-particles", "format_version": 1, "name": "grass",
  "generators": [{"kind": "rectangle", "center_m": [0, 0, 0], "axis_u_m": [0.2, 0, 0], "axis_v_m": [0, 0.2, 0],
                  "count": 40, "heading_cone_deg": 5}],
  "walk": {"seed": 3, "steps": 6, "trials": 4, "cone_deg": 10, "step_length_m": 0.01, "strand_radius_m": 0.001}})";

std::string projectText(const std::string& particles, int version = 4) {
    return R"({"format": "undergrowth-project", "format_version": )" + std::to_string(version) +
           R"(, "name": "p",
  "ghost_tile": {"tile_size_m": 0.5, "delta_m": 0},
  "detail_types": [{"name": "pebble", "model": {"mesh": "pebble.glb"},
                    "candidates": {"count": 10}}],
  "particles": )" + particles + "}";
}

void writeFile(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

// Parses `particles` into a project whose folder is `dir` (the entries' files are relative to it).
Project projectIn(const test::TempDir& dir, const std::string& particles) {
    Project p;
    std::string error;
    EXPECT_TRUE(parseProject(projectText(particles), (dir.path() / "p.json").string(), &p, &error)) << error;
    p.base_dir = dir.path().string();
    return p;
}

TEST(SceneParticles, EntriesRoundTripThroughTheProjectFile) {
    Project p;
    std::string error;
    ASSERT_TRUE(parseProject(projectText(R"([{"file": "a.json"},
        {"file": "sub/b.json", "name": "b2", "offset_m": [1.5, -2, 0.25]}])"),
                             "p.json", &p, &error))
        << error;
    ASSERT_EQ(p.particles.size(), 2u);
    EXPECT_EQ(p.particles[1].file, "sub/b.json");
    EXPECT_EQ(p.particles[1].name, "b2");
    EXPECT_EQ(p.particles[1].offset_m, glm::vec3(1.5f, -2.0f, 0.25f));
    const std::string saved = projectToJson(p);
    EXPECT_NE(saved.find("\"format_version\": 4"), std::string::npos) << saved;
    Project back;
    ASSERT_TRUE(parseProject(saved, "saved.json", &back, &error)) << error;
    EXPECT_EQ(back.particles, p.particles);
    // Without particles the file stays at the older format that older builds read.
    back.particles.clear();
    EXPECT_EQ(projectToJson(back).find("\"format_version\": 4"), std::string::npos);
}

TEST(SceneParticles, BadEntriesAreRefusedNamingThePlace) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"({"file": "a.json"})", "/particles: expected an array"},
        {R"([{"name": "x"}])", "/particles/0/file"},
        {R"([{"file": ""}])", "/particles/0/file: expected a particle system file"},
        {R"([{"file": "a.json", "offset_m": [0, 0]}])", "/particles/0/offset_m"},
        {R"([{"file": "a.json", "offset_m": [1e9, 0, 0]}])", "/particles/0/offset_m"},
        {R"([{"file": "a.json", "scale": 2}])", "/particles/0/scale: unknown field"},
    };
    for (const auto& [json, expected] : cases) {
        SCOPED_TRACE(json);
        Project p;
        std::string error;
        EXPECT_FALSE(parseProject(projectText(json), "p.json", &p, &error));
        EXPECT_NE(error.find("p.json: " + expected), std::string::npos) << error;
    }
    std::string many = "[";
    for (size_t i = 0; i <= kMaxParticleSystems; ++i) many += std::string(i ? "," : "") + R"({"file": "a.json"})";
    Project p;
    std::string error;
    EXPECT_FALSE(parseProject(projectText(many + "]"), "p.json", &p, &error));
    EXPECT_NE(error.find("/particles: 65 particle systems; at most 64"), std::string::npos) << error;
    // A format 3 file cannot hold them.
    EXPECT_FALSE(parseProject(projectText(R"([{"file": "a.json"}])", 3), "p.json", &p, &error));
    EXPECT_NE(error.find("/particles: needs format_version 4"), std::string::npos) << error;
}

TEST(SceneParticles, FilesAreReadRenamedAndMoved) {
    test::TempDir dir("ug_scene_particles_");
    writeFile(dir.path() / "grass.json", kGrass);
    const Project p = projectIn(dir, R"([{"file": "grass.json"},
        {"file": "grass.json", "name": "grass_east", "offset_m": [3, 0, 0.5]}])");
    std::vector<ParticleSystemFile> systems;
    std::string error;
    ASSERT_TRUE(loadSceneParticles(p, nullptr, nullptr, &systems, &error)) << error;
    ASSERT_EQ(systems.size(), 2u);
    EXPECT_EQ(systems[0].name, "grass");
    EXPECT_EQ(systems[1].name, "grass_east");
    EXPECT_EQ(systems[1].scene.generators[0].center_m, glm::vec3(3.0f, 0.0f, 0.5f));
    // The moved system's seeds are the first's, moved (the strata and the jitter do not depend on where).
    ParticleSeeds a, b;
    seedGenerator(systems[0].scene.generators[0], 0, 3, &a);
    seedGenerator(systems[1].scene.generators[0], 0, 3, &b);
    ASSERT_EQ(a.positions.size(), 40u);
    for (size_t i = 0; i < a.positions.size(); ++i) {
        EXPECT_NEAR(b.positions[i].x, a.positions[i].x + 3.0f, 1e-5f);
        EXPECT_NEAR(b.positions[i].z, a.positions[i].z + 0.5f, 1e-6f);
    }

    std::vector<MeshInstances> meshes;
    SceneStrandStats st;
    ASSERT_TRUE(growSceneParticles(systems, "p.json", 2, nullptr, &meshes, &st, &error)) << error;
    ASSERT_EQ(meshes.size(), 2u);
    EXPECT_EQ(meshes[0].name, "strands/grass");
    EXPECT_EQ(meshes[1].name, "strands/grass_east");
    EXPECT_EQ(st.systems, 2u);
    EXPECT_EQ(st.triangles, meshes[0].mesh->triangleCount() + meshes[1].mesh->triangleCount());
    // Two regions split at x = 1.5: each system lands in exactly one, the one holding its centre.
    const float inf = std::numeric_limits<float>::infinity();
    const Bounds west{glm::vec3(-inf), glm::vec3(1.5f, inf, inf)}, east{glm::vec3(1.5f, -inf, -inf), glm::vec3(inf)};
    std::vector<MeshInstances> in_west, in_east;
    SceneStrandStats sw, se;
    ASSERT_TRUE(growSceneParticles(systems, "p.json", 1, &west, &in_west, &sw, &error)) << error;
    ASSERT_TRUE(growSceneParticles(systems, "p.json", 1, &east, &in_east, &se, &error)) << error;
    ASSERT_EQ(in_west.size(), 1u);
    ASSERT_EQ(in_east.size(), 1u);
    EXPECT_EQ(in_west[0].name, "strands/grass");
    EXPECT_EQ(in_east[0].name, "strands/grass_east");
    EXPECT_EQ(in_east[0].mesh->positions, meshes[1].mesh->positions);  // any thread count, the same strands
}

TEST(SceneParticles, LoadErrorsNameTheProjectTheEntryAndTheFile) {
    test::TempDir dir("ug_scene_particles_");
    writeFile(dir.path() / "grass.json", kGrass);
    std::string bad = kGrass;
    bad.replace(bad.find("\"trials\": 4"), 11, "\"trials\": 0");
    writeFile(dir.path() / "bad.json", bad);
    const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
        {R"([{"file": "missing.json"}])", {"p.json: /particles/0/file: ", "missing.json"}},
        {R"([{"file": "grass.json"}, {"file": "bad.json"}])",
         {"p.json: /particles/1/file: ", "bad.json", "/walk/trials: 0 is out of range"}},
        {R"([{"file": "grass.json"}, {"file": "grass.json"}])",
         {"p.json: /particles/1: a particle system named 'grass' is already in the scene"}},
    };
    for (const auto& [json, pieces] : cases) {
        SCOPED_TRACE(json);
        std::vector<ParticleSystemFile> systems;
        std::string error;
        EXPECT_FALSE(loadSceneParticles(projectIn(dir, json), nullptr, nullptr, &systems, &error));
        for (const std::string& piece : pieces) EXPECT_NE(error.find(piece), std::string::npos) << error;
    }
}

TEST(SceneParticles, OnTerrainGeneratorsSeedOnTheGround) {
    // A tilted plane h = 0.5 x - 0.25 y + 1: seeds must sit on it with its normal.
    std::vector<float> heights;
    for (int j = 0; j < 9; ++j)
        for (int i = 0; i < 9; ++i) heights.push_back(0.5f * (-2.0f + 0.5f * i) - 0.25f * (-2.0f + 0.5f * j) + 1.0f);
    const auto terrain = std::make_shared<const HeightField>(glm::vec2(-2.0f), 0.5f, 9, 9, heights);
    ParticleScene scene;
    ParticleGenerator g;
    g.axis_u_m = {1.0f, 0.0f, 0.0f};
    g.axis_v_m = {0.0f, 1.0f, 0.0f};
    g.count = 200;
    g.on_terrain = true;
    scene.generators.push_back(g);
    scene.walk.steps = 3;
    ParticleSeeds seeds;
    seedGenerator(g, 0, 9, &seeds, terrain.get());
    ASSERT_EQ(seeds.positions.size(), 200u);
    const glm::vec3 n = glm::normalize(glm::vec3(-0.5f, 0.25f, 1.0f));
    for (size_t i = 0; i < seeds.positions.size(); ++i) {
        const glm::vec3 p = seeds.positions[i];
        EXPECT_NEAR(p.z, 0.5f * p.x - 0.25f * p.y + 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(seeds.normals[i], n), 1.0f, 1e-5f);
        EXPECT_EQ(locateStratum(g, p), uint32_t(i));  // still one seed per stratum (in plan view)
    }
    // Growing needs the terrain; only a horizontal rectangle can be dropped onto it.
    Strands strands;
    std::string error;
    EXPECT_FALSE(growStrands(scene, {}, &strands, &error));
    EXPECT_NE(error.find("generators[0].on_terrain: needs a terrain"), std::string::npos) << error;
    scene.terrain = terrain;
    EXPECT_TRUE(growStrands(scene, {}, &strands, &error)) << error;
    EXPECT_NEAR(strands.points[0].z, 0.5f * strands.points[0].x - 0.25f * strands.points[0].y + 1.0f, 1e-5f);
    scene.generators[0].axis_v_m = {0.0f, 0.6f, 0.8f};
    EXPECT_FALSE(validateParticleScene(scene, &error));
    EXPECT_NE(error.find("generators[0].on_terrain: needs horizontal axes"), std::string::npos) << error;
    scene.generators[0].kind = GeneratorKind::Sphere;
    EXPECT_FALSE(validateParticleScene(scene, &error));
    EXPECT_NE(error.find("generators[0].on_terrain: only a rectangle"), std::string::npos) << error;
}

}  // namespace
}  // namespace ug
