// Click to place (app/editor/surface_pick.h, particle_tools.h addParticlePart) on a real document with a
// bench and a bus shelter: the pick is the nearest of the ground and the objects' base meshes along the
// ray, at the distance the engine's brute-force ray test finds on the mesh placed in the world (a separate
// routine from the pick's), with the face's normal towards the viewer; a part added there sits on it as
// documented, and the system stays valid.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "editor/particle_tools.h"
#include "editor/surface_pick.h"
#include "editor_test_util.h"
#include "env/env_scene.h"
#include "mesh/triangle_bvh.h"

namespace ug::editor {
namespace {

// The object's base mesh moved into the world by its placement.
TriangleMesh worldMesh(const EnvScene& env, size_t object) {
    const EnvObject& o = env.objects()[object];
    TriangleMesh m = *env.types()[o.type].mesh;
    for (glm::vec3& p : m.positions) p = o.placement.toWorld(p);
    return m;
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
        const SurfaceHit ground = pickGround(doc, ray);
        float nearest = ground.hit ? glm::distance(eye, ground.point_m) : INFINITY;
        int64_t object = -1;
        for (size_t k = 0; k < meshes.size(); ++k) {
            const float t = rayHitBruteForce(meshes[k], eye, ray.direction);
            if (t < nearest) {
                nearest = t;
                object = int64_t(k);
            }
        }
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

}  // namespace
}  // namespace ug::editor
