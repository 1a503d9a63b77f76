// The sun's shadow view (shadow_frame.h): what the camera sees of the extent, up to the shadow distance,
// lies inside the map; along the sun's rays the map keeps the order of depth; a view that misses the
// scene has no map.
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "editor/orbit_camera.h"
#include "editor/shadow_frame.h"

namespace ug::editor {
namespace {

const glm::vec3 kSun = glm::normalize(glm::vec3(0.45f, -0.50f, 0.74f));

OrbitCamera closeCamera() {
    OrbitCamera c;
    c.target = glm::vec3(2.0f, -1.0f, 0.0f);
    c.distance_m = 4.0f;
    c.aspect = 16.0f / 9.0f;
    return c;
}

TEST(ShadowFrame, EverythingSeenWithinTheShadowDistanceIsInsideTheMap) {
    const Bounds extent{glm::vec3(-10.0f, -10.0f, -0.5f), glm::vec3(10.0f, 10.0f, 1.5f)};
    const OrbitCamera cam = closeCamera();
    const ShadowFrame f = fitShadowFrame(cam, extent, kSun, 2048);
    ASSERT_TRUE(f.valid);
    const glm::mat4 vp = cam.viewProjection();
    const glm::vec3 eye = cam.eye();
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int seen = 0;
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 p = extent.lo + glm::vec3(u(rng), u(rng), u(rng)) * (extent.hi - extent.lo);
        const glm::vec4 c = vp * glm::vec4(p, 1.0f);
        const bool in_view = c.w > 0.0f && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w;
        const glm::vec3 forward = glm::normalize(cam.target - eye);
        if (!in_view || glm::dot(p - eye, forward) > f.distance_m) continue;
        ++seen;
        const glm::vec4 t = f.texture * glm::vec4(p, 1.0f);
        EXPECT_GE(t.x, 0.0f);
        EXPECT_LE(t.x, 1.0f);
        EXPECT_GE(t.y, 0.0f);
        EXPECT_LE(t.y, 1.0f);
        EXPECT_GE(t.z, 0.0f);
        EXPECT_LE(t.z, 1.0f);
    }
    EXPECT_GT(seen, 500);
    // Close up, the map covers far less than the 20 m extent: texels of a few millimetres, not 1 cm.
    EXPECT_LT(f.texel_m, 20.0f / 2048.0f);
}

TEST(ShadowFrame, CastersOutsideTheViewButTowardTheSunAreInTheMapsDepthRange) {
    // A point the camera sees, and one higher along the ray toward the sun (a caster above it), anywhere
    // in the extent: same place in the map, the caster nearer the light.
    const Bounds extent{glm::vec3(-10.0f, -10.0f, 0.0f), glm::vec3(10.0f, 10.0f, 8.0f)};
    const OrbitCamera cam = closeCamera();
    const ShadowFrame f = fitShadowFrame(cam, extent, kSun, 1024);
    ASSERT_TRUE(f.valid);
    const glm::vec3 ground = cam.target;
    const glm::vec3 caster = ground + kSun * 6.0f;
    ASSERT_LE(caster.z, extent.hi.z);
    const glm::vec4 a = f.texture * glm::vec4(ground, 1.0f);
    const glm::vec4 b = f.texture * glm::vec4(caster, 1.0f);
    EXPECT_NEAR(a.x, b.x, 1e-4f);
    EXPECT_NEAR(a.y, b.y, 1e-4f);
    EXPECT_LT(b.z, a.z);
    EXPECT_GE(b.z, 0.0f);
    EXPECT_LE(a.z, 1.0f);
}

TEST(ShadowFrame, AViewThatMissesTheSceneHasNoMap) {
    const Bounds extent{glm::vec3(-1.0f), glm::vec3(1.0f)};
    OrbitCamera cam;
    cam.target = glm::vec3(500.0f, 500.0f, 0.0f);
    cam.distance_m = 2.0f;
    EXPECT_FALSE(fitShadowFrame(cam, extent, kSun, 1024).valid);
}

TEST(ShadowFrame, SlidingTheCameraMovesTheMapByWholeTexels) {
    // The same view size, moved: a fixed world point keeps its position within a texel (no shimmer).
    const Bounds extent{glm::vec3(-50.0f, -50.0f, 0.0f), glm::vec3(50.0f, 50.0f, 2.0f)};
    OrbitCamera a = closeCamera(), b = a;
    b.target += glm::vec3(0.0123f, 0.0077f, 0.0f);
    const ShadowFrame fa = fitShadowFrame(a, extent, kSun, 2048), fb = fitShadowFrame(b, extent, kSun, 2048);
    ASSERT_TRUE(fa.valid && fb.valid);
    ASSERT_NEAR(fa.texel_m, fb.texel_m, 1e-7f);
    const glm::vec3 p(1.0f, 0.5f, 0.2f);
    const glm::vec2 ta = glm::vec2(fa.texture * glm::vec4(p, 1.0f)) * 2048.0f;
    const glm::vec2 tb = glm::vec2(fb.texture * glm::vec4(p, 1.0f)) * 2048.0f;
    const glm::vec2 d = ta - tb;
    EXPECT_NEAR(d.x, std::round(d.x), 0.02f);
    EXPECT_NEAR(d.y, std::round(d.y), 0.02f);
}

}  // namespace
}  // namespace ug::editor
