// Attractors on a mesh's surface points (AttractorKind::Mesh, Fig. 10-11's attracting points): the points
// lie on the model's surface, one per stratum, the same for the same file; the distance is the nearest
// placed point's; a positive charge draws the strands to the model and a negative one pushes them off; a
// moved mesh attractor re-grows incrementally into a full growth's strands; bad files are refused naming
// the JSON Pointer.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>

#include <unistd.h>

#include "particles/particle_json.h"
#include "particles/strand_growth.h"

namespace ug {
namespace {

namespace fs = std::filesystem;

class MeshAttractor : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("ug_mesh_attractor_" + std::to_string(::getpid()));
        fs::create_directories(dir_ / "p");
        fs::create_directories(dir_ / "models");
        fs::copy_file(fs::path(UG_SOURCE_DIR) / "assets" / "models" / "pebble.glb", dir_ / "models" / "pebble.glb",
                      fs::copy_options::overwrite_existing);
    }
    void TearDown() override { fs::remove_all(dir_); }
    // Grass on a 0.6 m square under a pebble scaled 3x held 0.3 m up; `attractor` is the mesh attractor's JSON.
    std::string write(const std::string& attractor) {
        std::ofstream(dir_ / "p" / "sys.json") << R"({"format": "undergrowth-particles", "format_version": 1,
          "name": "reach", "generators": [{"kind": "rectangle", "axis_u_m": [0.3, 0, 0], "axis_v_m": [0, 0.3, 0],
          "count": 300, "heading_cone_deg": 20}],
          "walk": {"steps": 20, "step_length_m": 0.01, "strand_radius_m": 0.001, "seed": 5},
          "attractors": [)" << attractor << "]}";
        return (dir_ / "p" / "sys.json").string();
    }
    ParticleSystemFile load(const std::string& attractor) {
        ParticleSystemFile s;
        std::string error;
        EXPECT_TRUE(loadParticleSystem(write(attractor), &s, &error)) << error;
        return s;
    }
    fs::path dir_;
};

const char* const kPebble =
    R"({"kind": "mesh", "mesh": "../models/pebble.glb", "scale": 3, "a_m": [0, 0, 0.3], "points": 40, "charge": %s})";

std::string pebble(const char* charge) {
    char text[256];
    std::snprintf(text, sizeof text, kPebble, charge);
    return text;
}

// Distance from q to triangle t of the mesh when q projects inside it, else infinity.
float distanceInside(const TriangleMesh& m, size_t t, glm::vec3 q) {
    const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                    c = m.positions[m.indices[3 * t + 2]];
    const glm::vec3 n = glm::cross(b - a, c - a);
    const float area2 = glm::dot(n, n);
    if (!(area2 > 0.0f)) return INFINITY;
    const float d = glm::dot(q - a, n) / std::sqrt(area2);
    const glm::vec3 p = q - d * n / std::sqrt(area2);
    const float u = glm::dot(glm::cross(c - b, p - b), n) / area2, v = glm::dot(glm::cross(a - c, p - c), n) / area2;
    const float eps = 1e-4f;
    return (u >= -eps && v >= -eps && u + v <= 1.0f + eps) ? std::abs(d) : INFINITY;
}

float meanTipDistance(const Strands& s, const Attractor& a) {
    double sum = 0.0;
    for (size_t k = 0; k < s.size(); ++k) sum += attractorDistance(a, s.points[s.offsets[k + 1] - 1]);
    return float(sum / double(s.size()));
}

TEST_F(MeshAttractor, ItsPointsLieOnTheSurfaceAndItsDistanceIsTheNearestPlacedPoints) {
    const ParticleSystemFile s = load(pebble("1"));
    const Attractor& a = s.scene.attractors[0];
    ASSERT_EQ(a.kind, AttractorKind::Mesh);
    ASSERT_TRUE(a.points);
    ASSERT_EQ(a.points->size(), 40u);
    for (const glm::vec3& q : *a.points) {
        float nearest = INFINITY;
        for (size_t t = 0; t < a.mesh->triangleCount(); ++t) nearest = std::min(nearest, distanceInside(*a.mesh, t, q));
        EXPECT_LT(nearest, 1e-4f) << "a point off the surface";
    }
    // The same file gives the same points.
    const ParticleSystemFile again = load(pebble("1"));
    EXPECT_EQ(*again.scene.attractors[0].points, *a.points);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int k = 0; k < 50; ++k) {
        const glm::vec3 p(u(rng), u(rng), 0.3f + u(rng));
        float expected = INFINITY;
        for (const glm::vec3& q : *a.points) expected = std::min(expected, glm::length(p - (glm::vec3(0, 0, 0.3f) + 3.0f * q)));
        EXPECT_NEAR(attractorDistance(a, p), expected, 1e-5f);
    }
    // Written back as the file said; read back to the same points.
    const nlohmann::json j = particleSystemToJson(s);
    EXPECT_EQ(j["attractors"][0]["mesh"], "../models/pebble.glb");
    EXPECT_EQ(j["attractors"][0]["scale"], 3.0f);
    EXPECT_EQ(j["attractors"][0]["points"], 40u);
    ParticleSystemFile back;
    std::string error;
    ASSERT_TRUE(parseParticleSystem(j, (dir_ / "p" / "sys.json").string(), &back, &error)) << error;
    EXPECT_EQ(*back.scene.attractors[0].points, *a.points);
    EXPECT_EQ(particleSystemToJson(back), j);
}

TEST_F(MeshAttractor, PullsOrPushesTheStrandsByItsCharge) {
    std::map<std::string, float> mean;
    for (const char* charge : {"-1", "0", "1"}) {
        const ParticleSystemFile s = load(pebble(charge));
        Strands strands;
        std::string error;
        ASSERT_TRUE(growStrands(s.scene, {.threads = 2}, &strands, &error)) << error;
        mean[charge] = meanTipDistance(strands, s.scene.attractors[0]);
    }
    EXPECT_LT(mean["1"], 0.8f * mean["0"]) << mean["1"] << " vs " << mean["0"];
    EXPECT_GT(mean["-1"], 1.1f * mean["0"]) << mean["-1"] << " vs " << mean["0"];
}

TEST_F(MeshAttractor, AMovedMeshAttractorReGrowsIntoAFullGrowth) {
    ParticleSystemFile s = load(R"({"kind": "mesh", "mesh": "../models/pebble.glb", "scale": 2, "a_m": [0.2, 0, 0.15],
                                    "points": 30, "influence_m": 0.15, "charge": 2})");
    StrandRegrower regrower;
    Strands out;
    std::string error;
    ASSERT_TRUE(regrower.grow(s.scene, {.threads = 2}, &out, &error)) << error;
    s.scene.attractors[0].a_m.x -= 0.05f;
    ASSERT_TRUE(regrower.grow(s.scene, {.threads = 2}, &out, &error)) << error;
    EXPECT_TRUE(regrower.lastReport().incremental);
    EXPECT_GT(regrower.lastReport().reused, 0u);
    Strands full;
    ASSERT_TRUE(growStrands(s.scene, {.threads = 1}, &full, &error)) << error;
    ASSERT_EQ(out.offsets, full.offsets);
    ASSERT_EQ(out.points.size(), full.points.size());
    EXPECT_EQ(std::memcmp(out.points.data(), full.points.data(), out.points.size() * sizeof(glm::vec3)), 0);
}

TEST_F(MeshAttractor, BadFilesAreRefusedNamingThePointer) {
    const std::map<std::string, std::string> refused = {
        {R"({"kind": "mesh", "mesh": "../models/none.glb"})", "sys.json: /attractors/0/mesh: "},
        {R"({"kind": "mesh"})", "/attractors/0/mesh: missing"},
        {R"({"kind": "point", "mesh": "../models/pebble.glb"})", "/attractors/0/mesh: only a \"mesh\" attractor"},
        {R"({"kind": "mesh", "mesh": "../models/pebble.glb", "points": 0})", "/attractors/0/points"},
        {R"({"kind": "mesh", "mesh": "../models/pebble.glb", "points": 5000})", "/attractors/0/points"},
        {R"({"kind": "mesh", "mesh": "../models/pebble.glb", "scale": 0})", "/attractors/0/scale"},
    };
    for (const auto& [attractor, piece] : refused) {
        SCOPED_TRACE(attractor);
        ParticleSystemFile out;
        std::string error;
        EXPECT_FALSE(loadParticleSystem(write(attractor), &out, &error));
        EXPECT_NE(error.find(piece), std::string::npos) << error;
    }
    // Built in code without its points: validation names the field.
    ParticleScene scene = load(pebble("1")).scene;
    scene.attractors[0].points.reset();
    std::string error;
    EXPECT_FALSE(validateParticleScene(scene, &error));
    EXPECT_NE(error.find("attractors[0].mesh"), std::string::npos) << error;
}

}  // namespace
}  // namespace ug
