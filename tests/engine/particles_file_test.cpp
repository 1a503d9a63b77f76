// Particle system files (particles/particle_json.h) and strand tubes (particles/strand_mesh.h): a file
// round-trips field for field, bad files are refused naming the JSON Pointer, and the tubes are closed,
// outward, at the strands' radius, with the counted number of triangles.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include <unistd.h>

#include "particles/particle_json.h"
#include "particles/particle_output.h"
#include "particles/strand_mesh.h"

namespace ug {
namespace {

ParticleSystemFile everyKind() {
    ParticleSystemFile s;
    s.name = "every_kind";
    ParticleGenerator rect;
    rect.count = 40;
    rect.heading_cone_deg = 12.5f;
    ParticleGenerator ball;
    ball.kind = GeneratorKind::Sphere;
    ball.center_m = {1.0f, 2.0f, 3.0f};
    ball.radius_m = 0.25f;
    ball.count = 7;
    ParticleGenerator box;
    box.kind = GeneratorKind::Box;
    box.half_extents_m = {0.1f, 0.2f, 0.3f};
    box.count = 9;
    s.scene.generators = {rect, ball, box};
    Attractor seg;
    seg.kind = AttractorKind::Segment;
    seg.a_m = {0.0f, 0.0f, 1.0f};
    seg.b_m = {0.5f, 0.0f, 1.0f};
    seg.influence_m = 0.7f;
    seg.charge = {ChargeKey{0, 1.0f}, ChargeKey{10, -0.3f}};
    Attractor sphere;
    sphere.kind = AttractorKind::Sphere;
    sphere.radius_m = 0.4f;
    s.scene.attractors = {seg, sphere};
    Cutter plane;
    plane.threshold_m = 0.3f;
    plane.action.kind = StrandActionKind::Split;
    plane.action.split_count = 3;
    plane.action.split_angle_deg = 33.0f;
    Cutter ball_cut;
    ball_cut.kind = CutterKind::Sphere;
    ball_cut.side = CutterSide::Below;
    ball_cut.action.kind = StrandActionKind::Countdown;
    ball_cut.action.countdown_steps = 5;
    ball_cut.action.countdown_then = StrandActionKind::Stop;
    s.scene.cutters = {plane, ball_cut};
    s.scene.walk.seed = 0xfeedface12345ull;
    s.scene.walk.steps = 21;
    s.scene.walk.step_length_m = 0.013f;
    s.scene.walk.on_collision.kind = StrandActionKind::Kill;
    s.scene.walk.max_age_steps = 9;
    s.scene.walk.on_age.kind = StrandActionKind::Split;
    s.mesh.sides = 7;
    s.mesh.shape = StrandShape::Blade;
    s.mesh.blade_width_m = 0.006f;
    s.mesh.blade_tip = 0.35f;
    s.material.roughness = 0.55f;
    return s;
}

TEST(ParticleFile, RoundTripsEveryFieldAndGrowsTheSameStrands) {
    const ParticleSystemFile s = everyKind();
    const nlohmann::json j = particleSystemToJson(s);
    ParticleSystemFile back;
    std::string error;
    ASSERT_TRUE(parseParticleSystem(nlohmann::json::parse(j.dump()), "mem", &back, &error)) << error;
    EXPECT_EQ(particleSystemToJson(back), j);
    EXPECT_EQ(back.scene.walk.seed, 0xfeedface12345ull);
    EXPECT_EQ(back.scene.cutters[1].side, CutterSide::Below);
    EXPECT_EQ(back.scene.attractors[0].charge[1].step, 10u);
    EXPECT_EQ(back.scene.attractors[0].charge[1].charge, -0.3f);
    EXPECT_EQ(back.scene.walk.step_length_m, 0.013f);
    EXPECT_EQ(back.mesh.sides, 7u);
    EXPECT_EQ(back.mesh.shape, StrandShape::Blade);
    EXPECT_EQ(back.mesh.blade_width_m, 0.006f);
    EXPECT_EQ(back.mesh.blade_tip, 0.35f);
    EXPECT_EQ(back.scene.cutters[1].action.countdown_then, StrandActionKind::Stop);
    // Same scene, same strands: the file holds everything that decides them.
    Strands a, b;
    ASSERT_TRUE(growStrands(s.scene, {.threads = 2}, &a, &error)) << error;
    ASSERT_TRUE(growStrands(back.scene, {.threads = 1}, &b, &error)) << error;
    EXPECT_EQ(a.points, b.points);
    EXPECT_EQ(a.offsets, b.offsets);
}

TEST(ParticleFile, BadFilesAreRefusedNamingThePlace) {
    const nlohmann::json good = nlohmann::json::parse(particleSystemToJson(everyKind()).dump());
    const std::map<std::string, std::pair<std::string, std::string>> cases = {
        // name: (JSON Patch-like edit as "pointer=value", expected message piece)
        {"unknown key", {"/walk/tirals=8", "/walk/tirals: unknown field"}},
        {"zero trials", {"/walk/trials=0", "/walk/trials: 0 is out of range [1, 256]"}},
        {"a billion particles", {"/generators/0/count=1000000000", "/generators/0/count: 1e+09 is out of range"}},
        {"a cone of 0", {"/walk/cone_deg=0", "/walk/cone_deg: 0 is out of range"}},
        {"a charge that is text", {"/attractors/1/charge=\"strong\"", "/attractors/1/charge: expected a number"}},
        {"an unknown kind", {"/cutters/0/kind=\"cube\"", "/cutters/0/kind: 'cube' is not one of plane, sphere, box"}},
        {"a negative step", {"/attractors/0/charge/1/0=-3", "/attractors/0/charge/1: expected [step, charge]"}},
        {"keys out of order", {"/attractors/0/charge/1/0=0", "attractors[0].charge"}},
        {"a coordinate too far", {"/generators/1/center_m/2=1e9", "/generators/1/center_m/2: not a finite coordinate"}},
        {"no generator", {"/generators=[]", "/generators: at least one generator"}},
        {"other format", {"/format=\"undergrowth-project\"", "/format: expected \"undergrowth-particles\""}},
        {"too many sides", {"/mesh/sides=64", "/mesh/sides: 64 is out of range [3, 32]"}},
        {"an unknown shape", {"/mesh/shape=\"card\"", "/mesh/shape: 'card' is not one of tube, blade"}},
        {"a tip wider than the root", {"/mesh/blade_tip=1.5", "/mesh/blade_tip"}},
        {"a countdown ending in a split",
         {"/cutters/1/action/countdown_then=\"split\"", "/cutters/1/action/countdown_then: 'split' is not one of stop, kill"}},
        {"an empty side", {"/cutters/1/side=\"\"", "/cutters/1/side: '' is not one of above, below"}},
    };
    for (const auto& [name, c] : cases) {
        SCOPED_TRACE(name);
        nlohmann::json j = good;
        const size_t eq = c.first.find('=');
        j[nlohmann::json::json_pointer(c.first.substr(0, eq))] = nlohmann::json::parse(c.first.substr(eq + 1));
        ParticleSystemFile out;
        out.name = "untouched";
        std::string error;
        EXPECT_FALSE(parseParticleSystem(j, "bad.json", &out, &error));
        EXPECT_NE(error.find("bad.json: "), std::string::npos) << error;
        EXPECT_NE(error.find(c.second), std::string::npos) << error;
        EXPECT_EQ(out.name, "untouched") << error;  // nothing half-read
    }
    ParticleSystemFile out;
    std::string error;
    EXPECT_FALSE(loadParticleSystem("/nonexistent/fur.json", &out, &error));
    EXPECT_NE(error.find("/nonexistent/fur.json"), std::string::npos) << error;
}

TEST(ParticleFile, MeshGeneratorsLoadTheirModelRelativeToTheFile) {
    // A particle file in p/ naming ../models/pebble.glb: found beside it, wherever the process runs.
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("ug_mesh_gen_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir / "p");
    std::filesystem::create_directories(dir / "models");
    std::filesystem::copy_file(std::filesystem::path(UG_SOURCE_DIR) / "assets" / "models" / "pebble.glb",
                               dir / "models" / "pebble.glb", std::filesystem::copy_options::overwrite_existing);
    const std::string head = R"({"format": "undergrowth-particles", "format_version": 1, "name": "moss",
      "walk": {"steps": 3, "step_length_m": 0.002, "strand_radius_m": 0.0002}, "generators": [)";
    auto write = [&](const std::string& generator) {
        std::ofstream(dir / "p" / "sys.json") << head << generator << "]}";
        return (dir / "p" / "sys.json").string();
    };
    ParticleSystemFile s;
    std::string error;
    ASSERT_TRUE(loadParticleSystem(
        write(R"({"kind": "mesh", "mesh": "../models/pebble.glb", "scale": 3, "center_m": [0, 0, 1], "count": 50})"), &s,
        &error))
        << error;
    ASSERT_TRUE(s.scene.generators[0].mesh);
    EXPECT_GT(s.scene.generators[0].mesh->triangleCount(), 10u);
    const nlohmann::json j = particleSystemToJson(s);
    EXPECT_EQ(j["generators"][0]["mesh"], "../models/pebble.glb");
    EXPECT_EQ(j["generators"][0]["scale"], 3.0f);
    Strands strands;
    MeshInstances tubes;
    ASSERT_TRUE(growParticleSystem(s, 1, &strands, &tubes, &error)) << error;
    EXPECT_GT(strands.size(), 40u);
    const std::vector<MeshInstances> surfaces = generatorSurfaces(s);
    ASSERT_EQ(surfaces.size(), 1u);
    EXPECT_EQ(surfaces[0].name, "strands/moss/surface_0");
    EXPECT_EQ(surfaces[0].instances[0].scale, 3.0f);
    EXPECT_EQ(surfaces[0].instances[0].position, glm::vec3(0.0f, 0.0f, 1.0f));

    const std::map<std::string, std::string> refused = {
        {R"({"kind": "mesh", "mesh": "../models/none.glb", "count": 5})", "sys.json: /generators/0/mesh: "},
        {R"({"kind": "mesh", "count": 5})", "/generators/0/mesh: missing"},
        {R"({"kind": "sphere", "mesh": "../models/pebble.glb", "count": 5})", "/generators/0/mesh: only a \"mesh\" generator"},
        {R"({"kind": "mesh", "mesh": "../models/pebble.glb", "scale": 0, "count": 5})", "/generators/0/scale"},
    };
    for (const auto& [generator, piece] : refused) {
        SCOPED_TRACE(generator);
        ParticleSystemFile out;
        EXPECT_FALSE(loadParticleSystem(write(generator), &out, &error));
        EXPECT_NE(error.find(piece), std::string::npos) << error;
    }
    std::filesystem::remove_all(dir);
}

TEST(ParticleFile, TheBundledSamplesLoad) {
    const std::filesystem::path dir = std::filesystem::path(UG_SOURCE_DIR) / "assets" / "particles";
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".json") continue;
        SCOPED_TRACE(entry.path().string());
        ParticleSystemFile s;
        std::string error;
        EXPECT_TRUE(loadParticleSystem(entry.path().string(), &s, &error)) << error;
        EXPECT_FALSE(s.name.empty());
        ++files;
    }
    EXPECT_GE(files, 8);
}

// One straight strand and one bent one, radius 0.1 and 0.05.
Strands twoStrands() {
    Strands s;
    s.points = {{0, 0, 0}, {0, 0, 1}, {0, 0, 2}, {0, 0, 3}, {5, 0, 0}, {5, 0, 1}, {6, 0, 1.5f}};
    s.radii = {0.1f, 0.1f, 0.1f, 0.1f, 0.05f, 0.05f, 0.05f};
    s.offsets = {0, 4, 7};
    s.parent = {-1, -1};
    s.particle = {0, 1};
    return s;
}

TEST(StrandTubes, AreClosedOutwardAtTheRadiusWithTheCountedTriangles) {
    const Strands s = twoStrands();
    const uint32_t sides = 6;
    TriangleMesh m;
    std::string error;
    ASSERT_TRUE(strandTubeMesh(s, {.sides = sides}, &m, &error)) << error;
    const uint64_t expected = 2 * sides * 3 + 2 * (sides - 2) + 2 * sides * 2 + 2 * (sides - 2);
    EXPECT_EQ(strandTubeTriangles(s, sides), expected);
    EXPECT_EQ(m.triangleCount(), expected);
    ASSERT_TRUE(validateMesh(m, &error)) << error;
    // Closed: every edge is used by exactly two triangles, once in each direction.
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (size_t t = 0; t < m.indices.size(); t += 3)
        for (int e = 0; e < 3; ++e) ++directed[{m.indices[t + e], m.indices[t + (e + 1) % 3]}];
    for (const auto& [edge, n] : directed) {
        EXPECT_EQ(n, 1) << edge.first << "-" << edge.second;
        EXPECT_EQ(directed.count({edge.second, edge.first}), 1u) << edge.first << "-" << edge.second;
    }
    // Every vertex of the straight tube lies at r from the axis, its normal radial and unit.
    for (uint32_t v = 0; v < 4 * sides; ++v) {
        const glm::vec3 p = m.positions[v];
        EXPECT_NEAR(std::hypot(p.x, p.y), 0.1f, 1e-6f);
        EXPECT_NEAR(glm::length(m.normals[v]), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(m.normals[v], glm::vec3(p.x, p.y, 0.0f) / 0.1f), 1.0f, 1e-5f);
    }
    // Outward: the straight tube's signed volume is that of its hexagonal prism (positive).
    double volume = 0.0;
    for (size_t t = 0; t < m.indices.size(); t += 3) {
        const glm::dvec3 a(m.positions[m.indices[t]]), b(m.positions[m.indices[t + 1]]), c(m.positions[m.indices[t + 2]]);
        if (m.indices[t] < 4 * sides) volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    const double hexagon = 1.5 * std::sqrt(3.0) * 0.1 * 0.1;
    EXPECT_NEAR(volume, hexagon * 3.0, 1e-5);
}

// A zigzag of 17 points in the xz plane: x = i, z = 0.1 at odd i (0 at even), radius 0.02.
Strands zigzag() {
    Strands s;
    for (int i = 0; i < 17; ++i) {
        s.points.push_back({float(i), 0.0f, (i % 2) ? 0.1f : 0.0f});
        s.radii.push_back(0.02f);
    }
    s.offsets = {0, 17};
    s.parent = {-1};
    s.particle = {0};
    return s;
}

TEST(StrandLevels, TubesThroughEverySecondFourthAndEighthPointStayClosedWithTheirChordError) {
    const Strands s = zigzag();
    const uint32_t sides = 4;
    TriangleMesh m;
    std::string error;
    ASSERT_TRUE(strandTubeMesh(s, {.sides = sides}, &m, &error)) << error;
    std::vector<MeshLodLevel> levels;
    strandMeshLevels(s, {.sides = sides}, &levels);
    ASSERT_EQ(levels.size(), 3u);
    // Level k keeps points 0, 2^k, 2·2^k, ..., 16: 16 / 2^k segments of 2·sides triangles, the two end fans.
    for (size_t k = 0; k < 3; ++k) {
        const uint32_t segments = 16u >> (k + 1);
        EXPECT_EQ(levels[k].indices.size(), 3u * (2 * sides * segments + 2 * (sides - 2))) << "level " << k + 1;
        // Only the kept points' rings are used.
        for (uint32_t v : levels[k].indices) EXPECT_EQ((v / sides) % (2u << k), 0u) << "level " << k + 1 << " vertex " << v;
        // Closed: every edge used once in each direction.
        std::map<std::pair<uint32_t, uint32_t>, int> directed;
        for (size_t t = 0; t < levels[k].indices.size(); t += 3)
            for (int e = 0; e < 3; ++e) ++directed[{levels[k].indices[t + e], levels[k].indices[t + (e + 1) % 3]}];
        for (const auto& [edge, n] : directed) {
            EXPECT_EQ(n, 1);
            EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
        }
    }
    // Level 1 drops the odd points, 0.1 off the chord z = 0; level 2's chords (0 to 4, ...) lie on z = 0
    // too, as do level 3's: every level departs by exactly the zigzag's height.
    EXPECT_FLOAT_EQ(levels[0].error_m, 0.1f);
    EXPECT_FLOAT_EQ(levels[1].error_m, 0.1f);
    EXPECT_FLOAT_EQ(levels[2].error_m, 0.1f);
    // A straight strand loses nothing; a strand of two points has no coarser level to give.
    Strands straight = zigzag();
    for (glm::vec3& p : straight.points) p.z = 0.0f;
    strandMeshLevels(straight, {.sides = sides}, &levels);
    ASSERT_EQ(levels.size(), 3u);
    for (const MeshLodLevel& l : levels) EXPECT_EQ(l.error_m, 0.0f);
    Strands two;
    two.points = {{0, 0, 0}, {0, 0, 1}};
    two.radii = {0.1f, 0.1f};
    two.offsets = {0, 2};
    two.parent = {-1};
    strandMeshLevels(two, {.sides = sides}, &levels);
    EXPECT_TRUE(levels.empty());
}

TEST(StrandLevels, BladesKeepTheirTwoFacesThroughTheKeptPoints) {
    const Strands s = zigzag();
    const StrandMeshSettings settings{.shape = StrandShape::Blade, .blade_width_m = 0.04f};
    TriangleMesh m;
    std::string error;
    ASSERT_TRUE(strandMesh(s, settings, &m, &error)) << error;
    std::vector<MeshLodLevel> levels;
    strandMeshLevels(s, settings, &levels);
    ASSERT_EQ(levels.size(), 3u);
    EXPECT_EQ(levels[0].indices.size(), 3u * 4u * 8u);
    EXPECT_FLOAT_EQ(levels[0].error_m, 0.1f);
    // Each triangle still winds counter-clockwise around its vertices' normal (front and back faces).
    for (size_t t = 0; t < levels[0].indices.size(); t += 3) {
        const uint32_t* i = &levels[0].indices[t];
        const glm::vec3 a = m.positions[i[0]], b = m.positions[i[1]], c = m.positions[i[2]];
        EXPECT_GT(glm::dot(glm::cross(b - a, c - a), m.normals[i[0]]), 0.0f) << "triangle " << t / 3;
    }
}

TEST(StrandTubes, TooManyTrianglesAreRefusedBeforeMeshing) {
    const Strands s = twoStrands();
    TriangleMesh m;
    m.positions = {{1, 2, 3}};
    std::string error;
    EXPECT_FALSE(strandTubeMesh(s, {.sides = 6, .max_triangles = 40}, &m, &error));
    EXPECT_NE(error.find("mesh.max_triangles: the tubes need 76 triangles"), std::string::npos) << error;
    EXPECT_EQ(m.positions.size(), 1u);  // untouched
    EXPECT_FALSE(strandTubeMesh(s, {.sides = 2}, &m, &error));
    EXPECT_NE(error.find("mesh.sides"), std::string::npos) << error;
}

TEST(StrandBlades, AreTwoFacedRibbonsTaperingAcrossTheStrandWithTheCountedTriangles) {
    const Strands s = twoStrands();
    const StrandMeshSettings settings{.shape = StrandShape::Blade, .blade_width_m = 0.04f, .blade_tip = 0.25f};
    TriangleMesh m;
    std::string error;
    ASSERT_TRUE(strandMesh(s, settings, &m, &error)) << error;
    EXPECT_EQ(strandBladeTriangles(s), 4u * 3u + 4u * 2u);
    EXPECT_EQ(m.triangleCount(), strandBladeTriangles(s));
    ASSERT_TRUE(validateMesh(m, &error)) << error;
    // The straight strand (points 0..3 on the z axis): vertices come in (left, right) pairs per face, the
    // pair's midpoint on the strand, its width tapering linearly from 4 cm to a quarter of that.
    for (uint32_t i = 0; i < 4; ++i)
        for (uint32_t face = 0; face < 2; ++face) {
            const glm::vec3 l = m.positions[4 * i + 2 * face], r = m.positions[4 * i + 2 * face + 1];
            const glm::vec3 mid = 0.5f * (l + r);
            EXPECT_NEAR(glm::length(mid - s.points[i]), 0.0f, 1e-6f);
            EXPECT_NEAR(glm::length(r - l), 0.04f * (1.0f - 0.75f * float(i) / 3.0f), 1e-6f);
            EXPECT_NEAR((r - l).z, 0.0f, 1e-6f);  // across the strand
        }
    // Every triangle winds counter-clockwise around its vertices' normal: front faces one way, back faces
    // the other, each normal unit and perpendicular to the strand.
    size_t front = 0, back = 0;
    for (size_t t = 0; t < m.indices.size(); t += 3) {
        const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]], c = m.positions[m.indices[t + 2]];
        const glm::vec3 n = m.normals[m.indices[t]];
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
        EXPECT_GT(glm::dot(glm::cross(b - a, c - a), n), 0.0f) << "triangle " << t / 3;
        (m.indices[t] % 4 < 2 ? front : back) += 1;
    }
    EXPECT_EQ(front, back);
    // The bent strand's blade is across it at every point.
    for (uint32_t i = 0; i < 3; ++i) {
        const glm::vec3 l = m.positions[16 + 4 * i], r = m.positions[16 + 4 * i + 1];
        const glm::vec3 tangent = glm::normalize(s.points[4 + std::min(i + 1, 2u)] - s.points[4 + (i > 0 ? i - 1 : 0)]);
        EXPECT_NEAR(glm::dot(glm::normalize(r - l), tangent), 0.0f, 1e-4f) << "point " << i;
    }
    // Refused by count before anything is made.
    TriangleMesh untouched;
    untouched.positions = {{1, 2, 3}};
    EXPECT_FALSE(strandMesh(s, {.shape = StrandShape::Blade, .max_triangles = 19}, &untouched, &error));
    EXPECT_NE(error.find("the blades need 20 triangles"), std::string::npos) << error;
    EXPECT_EQ(untouched.positions.size(), 1u);
}

}  // namespace
}  // namespace ug
