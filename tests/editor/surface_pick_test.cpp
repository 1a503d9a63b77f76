// Click to place (app/editor/surface_pick.h, particle_tools.h addParticlePart) on a real document with a
// bench and a bus shelter: the pick is the nearest of the ground and the objects' base meshes along the
// ray, at the distance the engine's brute-force ray test finds on the mesh placed in the world (a separate
// routine from the pick's), with the face's normal towards the viewer; a part added there sits on it as
// documented, and the system stays valid.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <utility>

#include "editor/particle_tools.h"
#include "editor/surface_pick.h"
#include "editor_test_util.h"
#include "env/env_scene.h"
#include "mesh/triangle_bvh.h"
#include "particles/particle_json.h"

namespace ug::editor {
namespace {

// The object's base mesh moved into the world by its placement.
TriangleMesh worldMesh(const EnvScene& env, size_t object) {
    const EnvObject& o = env.objects()[object];
    TriangleMesh m = *env.types()[o.type].mesh;
    for (glm::vec3& p : m.positions) p = o.placement.toWorld(p);
    return m;
}

// By brute force, independently of the pick: the distance to the nearest of the ground and the world
// meshes along the ray, and which mesh (-1: the ground, or nothing).
std::pair<float, int64_t> nearestAlong(const Document& doc, const Ray& ray, const std::vector<TriangleMesh>& meshes) {
    const SurfaceHit ground = pickGround(doc, ray);
    float nearest = ground.hit ? glm::distance(ray.origin_m, ground.point_m) : INFINITY;
    int64_t which = -1;
    for (size_t k = 0; k < meshes.size(); ++k) {
        const float t = rayHitBruteForce(meshes[k], ray.origin_m, ray.direction);
        if (t < nearest) {
            nearest = t;
            which = int64_t(k);
        }
    }
    return {nearest, which};
}

TEST(SurfacePick, TheNearestOfTheGroundAndTheObjectsAlongTheRay) {
    test::OpenEnvDocument o;
    ASSERT_TRUE(o.doc);
    const Document& doc = *o.doc;
    const EnvScene& env = *doc.environment();
    ASSERT_EQ(env.objects().size(), 2u);
    std::vector<TriangleMesh> meshes = {worldMesh(env, 0), worldMesh(env, 1)};
    // Rays from around the bench and the shelter, down and sideways, in every direction the view has.
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    int on_objects = 0, on_ground = 0;
    for (int i = 0; i < 400; ++i) {
        const glm::vec3 target(i % 2 ? 1.0f : 2.6f, i % 2 ? 1.0f : 2.6f, 0.4f);
        const glm::vec3 aim = target + glm::vec3(unit(rng), unit(rng), unit(rng) * 0.4f) * 1.2f;
        const glm::vec3 eye = aim + glm::normalize(glm::vec3(unit(rng), unit(rng), 0.3f + std::abs(unit(rng)))) * 4.0f;
        const Ray ray{eye, glm::normalize(aim - eye)};
        const ScenePick pick = pickSceneSurface(doc, ray);
        const auto [nearest, object] = nearestAlong(doc, ray, meshes);
        ASSERT_EQ(pick.hit.hit, std::isfinite(nearest)) << i;
        if (!pick.hit.hit) continue;
        EXPECT_EQ(pick.object, object) << i;
        EXPECT_NEAR(glm::distance(eye, pick.hit.point_m), nearest, 1e-3f) << i;
        EXPECT_NEAR(glm::length(pick.hit.normal), 1.0f, 1e-4f) << i;
        if (object >= 0) {
            EXPECT_LT(glm::dot(pick.hit.normal, ray.direction), 0.0f) << "the face seen, ray " << i;
        }
        ++(object >= 0 ? on_objects : on_ground);
    }
    EXPECT_GT(on_objects, 100);
    EXPECT_GT(on_ground, 20);
}

TEST(SurfacePick, PartsPlacedOnASurfaceSitOnItAlongItsNormal) {
    test::OpenEnvDocument o;
    ASSERT_TRUE(o.doc);
    const Document& doc = *o.doc;
    // Straight down onto the bench (at 1, 1; its slats have gaps): the first upward face met.
    ScenePick seat;
    for (int k = 0; k < 64 && seat.object != 0; ++k)
        seat = pickSceneSurface(doc, rayDownOnto(doc, glm::vec2(1.0f) + 0.04f * glm::vec2(float(k % 8) - 4.0f, float(k / 8) - 4.0f)));
    ASSERT_EQ(seat.object, 0);
    EXPECT_GT(seat.hit.point_m.z, 0.2f);
    EXPECT_GT(seat.hit.normal.z, 0.95f);  // the seat leans back a little
    // Sideways into the shelter, from around it at head height until one meets a wall or a post: a
    // normal far from up.
    ScenePick wall;
    for (int k = 0; k < 16 && !(wall.object == 1 && wall.hit.normal.z < 0.5f); ++k) {
        const float a = float(k) * 0.3927f;
        const glm::vec3 eye = glm::vec3(2.6f, 2.6f, 1.2f) + 4.0f * glm::vec3(std::cos(a), std::sin(a), 0.0f);
        wall = pickSceneSurface(doc, Ray{eye, glm::normalize(glm::vec3(2.6f, 2.6f, 1.0f) - eye)});
    }
    ASSERT_EQ(wall.object, 1);
    ASSERT_LT(wall.hit.normal.z, 0.5f);

    for (const ScenePick* pick : {static_cast<const ScenePick*>(&seat), static_cast<const ScenePick*>(&wall)}) {
        const glm::vec3 at = pick->hit.point_m, n = pick->hit.normal;
        ParticleScene scene;
        ASSERT_EQ(addParticlePart(&scene, ParticlePart::Generator, at, n, false),
                  (ParticleHandle{ParticlePart::Generator, 0, false}));
        const ParticleGenerator& g = scene.generators[0];
        EXPECT_EQ(g.center_m, at);
        EXPECT_NEAR(glm::dot(g.axis_u_m, g.axis_v_m), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::length(g.axis_u_m), 0.1f, 1e-5f);
        EXPECT_NEAR(glm::length(g.axis_v_m), 0.1f, 1e-5f);
        EXPECT_GT(glm::dot(glm::normalize(glm::cross(g.axis_u_m, g.axis_v_m)), n), 0.9999f) << "strands leave the face";
        EXPECT_FALSE(g.on_terrain);
        ASSERT_EQ(addParticlePart(&scene, ParticlePart::Attractor, at, n, false),
                  (ParticleHandle{ParticlePart::Attractor, 0, false}));
        EXPECT_NEAR(glm::distance(scene.attractors[0].a_m, at + 0.3f * n), 0.0f, 1e-5f);
        ASSERT_EQ(addParticlePart(&scene, ParticlePart::Cutter, at, n, false),
                  (ParticleHandle{ParticlePart::Cutter, 0, false}));
        EXPECT_EQ(scene.cutters[0].normal, n);
        EXPECT_NEAR(cutterValue(scene.cutters[0], at), -0.2f, 1e-5f) << "the plane lies 20 cm out";
        std::string error;
        EXPECT_TRUE(validateParticleScene(scene, &error)) << error;
    }
    // On the terrain: the usual patch, dropped onto it.
    const ScenePick ground = pickSceneSurface(doc, rayDownOnto(doc, glm::vec2(0.3f, 3.5f)));
    ASSERT_EQ(ground.object, -1);
    ParticleScene scene;
    addParticlePart(&scene, ParticlePart::Generator, ground.hit.point_m, ground.hit.normal, true);
    EXPECT_TRUE(scene.generators[0].on_terrain);
    EXPECT_NEAR(glm::length(scene.generators[0].axis_u_m), 0.25f, 1e-6f);
}

// Click to place on a detail instance (the rocks of rock_pile_moss, settled as drawn): the pick is the
// nearest of the ground and the instances' models, at the distance the brute-force ray test finds on each
// model placed in the world; a generator placed there is a details generator on that type, and the project
// gathers the rocks around the click into it.
TEST(SurfacePick, DetailInstancesAreHitOnTheirModelsAndAGeneratorThereGrowsOnThem) {
    std::random_device rd;
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("ug_pick_details_" + std::to_string(rd()) + std::to_string(rd()));
    std::string error;
    std::unique_ptr<Document> doc =
        Document::open((std::filesystem::path(UG_SOURCE_DIR) / "assets/scenes/rock_pile_moss.json").string(),
                       DocumentOptions{.cache_dir = (dir / "cache").string(), .threads = 2}, &error);
    ASSERT_TRUE(doc) << error;
    doc->live().waitIdle();
    LiveResult r;
    ASSERT_TRUE(doc->live().poll(&r));
    const std::vector<PlacedInstance> placed = placeInstances(*r.store, doc->ghostTile(), r.drops.get());
    ASSERT_GT(placed.size(), 500u);
    std::vector<TriangleMesh> world(placed.size());
    for (size_t i = 0; i < placed.size(); ++i) {
        world[i] = doc->models()[placed[i].type].mesh;
        for (glm::vec3& p : world[i].positions) p = placed[i].position + placed[i].rotation * (placed[i].scale * p);
    }
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    int on_instances = 0;
    glm::vec3 rock_hit(0.0f);
    for (int k = 0; k < 30; ++k) {
        const glm::vec3 aim = placed[(k * 37) % placed.size()].position;
        const glm::vec3 eye = aim + glm::normalize(glm::vec3(unit(rng), unit(rng), 0.5f + std::abs(unit(rng)))) * 3.0f;
        const Ray ray{eye, glm::normalize(aim - eye)};
        const ScenePick pick = pickSceneSurface(*doc, ray, placed);
        const auto [nearest, instance] = nearestAlong(*doc, ray, world);
        ASSERT_TRUE(pick.hit.hit) << k;
        EXPECT_EQ(pick.instance, instance) << k;
        EXPECT_EQ(pick.object, -1) << k;
        EXPECT_NEAR(glm::distance(eye, pick.hit.point_m), nearest, 1e-3f) << k;
        EXPECT_LE(glm::dot(pick.hit.normal, ray.direction), 0.0f) << k << ": the face seen";
        if (instance >= 0) {
            EXPECT_EQ(pick.detail_type, placed[size_t(instance)].type) << k;
            if (doc->project().detail_types[pick.detail_type].model.name == "rock") rock_hit = pick.hit.point_m;
            ++on_instances;
        }
    }
    EXPECT_GT(on_instances, 20) << "rays aimed at instances' origins should mostly meet them";
    ASSERT_NE(rock_hit, glm::vec3(0.0f));
    // A generator placed on a rock: moss on the rocks around the click, gathered by the project.
    ParticleSystemFile system = (*doc->particles())[0];
    const size_t before = system.scene.generators.size();
    const ParticleHandle added = addDetailsGenerator(&system.scene, "rock", rock_hit);
    EXPECT_EQ(added, (ParticleHandle{ParticlePart::Generator, before, false}));
    ASSERT_TRUE(doc->setParticleSystem(0, system, &error)) << error;
    const ParticleGenerator& g = (*doc->particles())[0].scene.generators.at(before);
    EXPECT_EQ(g.kind, GeneratorKind::Details);
    ASSERT_TRUE(g.mesh);
    EXPECT_GT(g.mesh->triangleCount(), 100u) << "the rocks within half a metre of the click";
    doc.reset();
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
}

}  // namespace
}  // namespace ug::editor
