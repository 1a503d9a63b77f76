// Strands among the project's environmental objects (scene/scene_particles.h placeAmongObjects): the
// objects' base geometry is a solid the strands never cross, moved and turned as the object is; an
// "objects" generator seeds on their sides below a height, an "objects" attractor pulls to points on
// every object of its type within reach; the vines of the bus-stop sample climb the shelter without
// entering it; moving the shelter in the document places the system again, and undo puts it back.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "particles/strand_growth.h"
#include "segment_test_util.h"
#include "scene/document.h"
#include "scene/project.h"
#include "scene/scene_particles.h"

namespace ug {
namespace {

namespace fs = std::filesystem;

const fs::path kVinesScene = fs::path(UG_SOURCE_DIR) / "assets/scenes/bus_stop_vines.json";

// An axis-aligned box as 12 triangles, outward winding.
std::shared_ptr<const TriangleMesh> boxMesh(glm::vec3 lo, glm::vec3 hi) {
    auto m = std::make_shared<TriangleMesh>();
    for (int c = 0; c < 8; ++c)
        m->positions.push_back({(c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z});
    const uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces)
        for (uint32_t i : {f[0], f[1], f[2], f[0], f[2], f[3]}) m->indices.push_back(i);
    return m;
}

using test::segmentHitsTriangle;

// Strands from a square facing +x, pulled towards +x through where the wall stands.
ParticleScene pulledThroughWall() {
    ParticleScene s;
    ParticleGenerator g;
    g.kind = GeneratorKind::Rectangle;
    g.axis_u_m = {0.0f, 0.1f, 0.0f};
    g.axis_v_m = {0.0f, 0.0f, 0.1f};  // normal u × v = +x
    g.count = 64;
    g.heading_cone_deg = 10.0f;
    s.generators.push_back(g);
    Attractor a;
    a.a_m = {1.0f, 0.0f, 0.0f};
    s.attractors.push_back(a);
    s.walk.steps = 60;
    s.walk.step_length_m = 0.01f;
    s.walk.strand_radius_m = 0.002f;
    s.walk.collisions = false;
    s.walk.on_collision.kind = StrandActionKind::Stop;
    return s;
}

TEST(ParticleObstacles, AMovedAndTurnedWallStopsEveryStrandThatWouldCrossIt) {
    // The wall in its own frame lies along x; turned 90° about z and moved to x = 0.3 it stands across
    // the strands' way: world x in [0.29, 0.31], y in [-0.5, 0.5], z in [-1, 1].
    const auto wall = boxMesh({-0.5f, -0.01f, -1.0f}, {0.5f, 0.01f, 1.0f});
    ParticleScene free = pulledThroughWall();
    Strands through;
    std::string error;
    ASSERT_TRUE(growStrands(free, {.threads = 2}, &through, &error)) << error;
    size_t beyond = 0;
    for (const glm::vec3& p : through.points) beyond += p.x > 0.31f;
    ASSERT_GT(beyond, 100u) << "without the wall the strands must reach past it, or the test shows nothing";

    ParticleScene walled = free;
    walled.obstacles.push_back(
        ParticleObstacle{.mesh = wall, .translation = {0.3f, 0.0f, 0.0f}, .cos_yaw = 0.0f, .sin_yaw = 1.0f});
    ASSERT_TRUE(validateParticleScene(walled, &error)) << error;
    Strands stopped;
    ASSERT_TRUE(growStrands(walled, {.threads = 2}, &stopped, &error)) << error;
    EXPECT_GT(stopped.stats.solid_hits, 0u);
    for (const glm::vec3& p : stopped.points) ASSERT_LE(p.x, 0.29f) << "a strand point inside or past the wall";
    // The same with 1 and 8 threads.
    for (int threads : {1, 8}) {
        Strands again;
        ASSERT_TRUE(growStrands(walled, {.threads = threads}, &again, &error)) << error;
        EXPECT_EQ(again.points, stopped.points) << threads << " threads";
    }
}

TEST(ParticleObstacles, TheBusStopVinesTakeTheShelterAsASolidAndItsSurfaceAsTheirPull) {
    Project project;
    std::string error;
    ASSERT_TRUE(loadProject(kVinesScene.string(), &project, &error)) << error;
    std::shared_ptr<const HeightField> terrain;
    ASSERT_TRUE(loadTerrain(project, &terrain, &error)) << error;
    EnvScene env;
    ASSERT_TRUE(compileEnvScene(project.environment, project.base_dir, kVinesScene.string(), terrain, &env, &error))
        << error;
    std::vector<ParticleSystemFile> systems;
    ASSERT_TRUE(loadSceneParticles(project, terrain, &env, &systems, &error)) << error;
    ASSERT_EQ(systems.size(), 1u);
    const ParticleScene& scene = systems[0].scene;
    // The shelter and the two pavement slabs are within the vines' reach.
    ASSERT_EQ(scene.obstacles.size(), env.objects().size());
    const EnvObject& shelter = env.objects()[0];
    ASSERT_EQ(env.types()[shelter.type].desc.name, "bus_shelter");
    EXPECT_EQ(scene.obstacles[0].mesh, env.types()[shelter.type].mesh);
    // The shelter stands at the origin unturned: its surface points are the model's own, on its bounds.
    const Attractor& pull = scene.attractors[0];
    ASSERT_EQ(pull.kind, AttractorKind::Objects);
    ASSERT_TRUE(pull.points);
    ASSERT_EQ(pull.points->size(), 1024u);
    for (const glm::vec3& q : *pull.points)
        for (int a = 0; a < 3; ++a) {
            ASSERT_GE(q[a], shelter.bounds.lo[a] - 1e-4f);
            ASSERT_LE(q[a], shelter.bounds.hi[a] + 1e-4f);
        }

    Strands vines;
    ASSERT_TRUE(growStrands(scene, {.threads = 2}, &vines, &error)) << error;
    EXPECT_GT(vines.stats.solid_hits, 0u);
    // They start on the shelter's sides, in its lowest 30 cm (the "objects" generator's band); a seed on a
    // face inside another part (the glass's end in a post) is dropped.
    ASSERT_EQ(scene.generators[0].kind, GeneratorKind::Objects);
    EXPECT_EQ(vines.stats.seeded, 120u);
    size_t roots = 0;
    for (size_t s = 0; s + 1 < vines.offsets.size(); ++s) {
        if (vines.parent[s] >= 0) continue;
        ++roots;
        const glm::vec3 seed = vines.points[vines.offsets[s]];
        EXPECT_LE(seed.z, 0.3f + 1e-4f);
        for (int a = 0; a < 2; ++a) {
            EXPECT_GE(seed[a], shelter.bounds.lo[a] - 1e-4f);
            EXPECT_LE(seed[a], shelter.bounds.hi[a] + 1e-4f);
        }
    }
    EXPECT_GT(roots, 80u);
    // They climb: some reach the roof's underside region, and none passes through the shelter (every
    // segment against every triangle of the model, which stands in the world as it is in its file).
    float top = 0.0f;
    for (const glm::vec3& p : vines.points) top = std::max(top, p.z);
    EXPECT_GT(top, 1.5f);
    const TriangleMesh& m = *env.types()[shelter.type].mesh;
    for (size_t s = 0; s + 1 < vines.offsets.size(); ++s)
        for (uint32_t i = vines.offsets[s]; i + 1 < vines.offsets[s + 1]; ++i) {
            const bool from_seed = vines.parent[s] < 0 && i == vines.offsets[s];
            for (size_t t = 0; t < m.triangleCount(); ++t)
                ASSERT_FALSE(segmentHitsTriangle(vines.points[i], vines.points[i + 1], m.positions[m.indices[3 * t]],
                                                 m.positions[m.indices[3 * t + 1]], m.positions[m.indices[3 * t + 2]],
                                                 from_seed ? 1e-3 : 0.0))
                    << "strand " << s << " segment " << i << " crosses triangle " << t;
        }

    // A type the project does not have is named.
    ParticleScene wrong = scene;
    wrong.attractors[0].object_type = "kiosk";
    EXPECT_FALSE(placeAmongObjects(&env, &wrong, &error));
    EXPECT_NE(error.find("attractors[0].object_type"), std::string::npos) << error;
    EXPECT_NE(error.find("'kiosk'"), std::string::npos) << error;
    // Grown alone (no project), the attractor has no points and pulls nowhere; the walk still runs.
    ParticleScene alone = scene;
    alone.obstacles.clear();
    alone.attractors[0].points.reset();
    ASSERT_TRUE(validateParticleScene(alone, &error)) << error;
    EXPECT_EQ(attractorDistance(alone.attractors[0], glm::vec3(1.0f)), 0.0f);
}

TEST(ParticleObstacles, MovingTheShelterPlacesTheVinesAgainAndUndoPutsThemBack) {
    std::random_device rd;
    const fs::path dir = fs::temp_directory_path() / ("ug_particle_obstacles_" + std::to_string(rd()));
    std::string error;
    auto doc = Document::open(kVinesScene.string(), DocumentOptions{.cache_dir = (dir / "cache").string(), .threads = 2},
                              &error);
    ASSERT_TRUE(doc) << error;
    const ParticleScene before = (*doc->particles())[0].scene;
    ASSERT_FALSE(before.obstacles.empty());
    const uint64_t generation = doc->particlesGeneration();

    EnvironmentDesc moved = doc->project().environment;
    ASSERT_EQ(doc->environment()->types()[doc->environment()->objects()[0].type].desc.name, "bus_shelter");
    moved.roots[0].transform.translation.x += 0.5f;
    ASSERT_TRUE(doc->setEnvironment(moved, "Move bus_shelter", &error)) << error;
    const ParticleScene after = (*doc->particles())[0].scene;
    EXPECT_GT(doc->particlesGeneration(), generation);
    EXPECT_EQ(after.obstacles[0].translation, before.obstacles[0].translation + glm::vec3(0.5f, 0.0f, 0.0f));
    // The vines' seeding surfaces went with it.
    ASSERT_TRUE(after.generators[0].mesh && before.generators[0].mesh);
    ASSERT_EQ(after.generators[0].mesh->positions.size(), before.generators[0].mesh->positions.size());
    for (size_t i = 0; i < after.generators[0].mesh->positions.size(); ++i)
        ASSERT_NEAR(after.generators[0].mesh->positions[i].x, before.generators[0].mesh->positions[i].x + 0.5f, 1e-5f);
    ASSERT_EQ(after.attractors[0].points->size(), before.attractors[0].points->size());
    for (size_t i = 0; i < after.attractors[0].points->size(); ++i)
        ASSERT_NEAR((*after.attractors[0].points)[i].x, (*before.attractors[0].points)[i].x + 0.5f, 1e-5f);
    // One undo step takes the shelter, and with it the vines' solids and pull, back.
    ASSERT_TRUE(doc->undo());
    const ParticleScene undone = (*doc->particles())[0].scene;
    EXPECT_EQ(undone.obstacles, before.obstacles);
    EXPECT_EQ(undone.generators[0].mesh->positions, before.generators[0].mesh->positions);
    EXPECT_EQ(*undone.attractors[0].points, *before.attractors[0].points);
    doc.reset();
    std::error_code ec;
    fs::remove_all(dir, ec);
}

}  // namespace
}  // namespace ug
