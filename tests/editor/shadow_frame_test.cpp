// The sun's shadow view (shadow_frame.h): what the camera sees of the extent, up to the shadow distance,
// lies inside the map; along the sun's rays the map keeps the order of depth; a view that misses the
// scene has no map; a map fit while moving serves the next frames of a slow orbit, and only while it
// covers everything they see.
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

// How many of `samples` random extent points `cam` sees within `frame`'s shadow distance, and how many of
// those lie outside `map` (a map drawn for an earlier frame).
struct Coverage {
    int seen = 0, outside = 0;
};
Coverage seenOutside(const OrbitCamera& cam, const ShadowFrame& frame, const ShadowFrame& map, const Bounds& extent,
                     int samples) {
    const glm::mat4 vp = cam.viewProjection();
    const glm::vec3 eye = cam.eye(), forward = glm::normalize(cam.target - eye);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Coverage c;
    for (int i = 0; i < samples; ++i) {
        const glm::vec3 p = extent.lo + glm::vec3(u(rng), u(rng), u(rng)) * (extent.hi - extent.lo);
        const glm::vec4 q = vp * glm::vec4(p, 1.0f);
        if (!(q.w > 0.0f && std::abs(q.x) <= q.w && std::abs(q.y) <= q.w)) continue;
        if (glm::dot(p - eye, forward) > frame.distance_m) continue;
        ++c.seen;
        const glm::vec4 t = map.texture * glm::vec4(p, 1.0f);
        if (t.x < 0.0f || t.x > 1.0f || t.y < 0.0f || t.y > 1.0f) ++c.outside;
    }
    return c;
}

TEST(ShadowFrame, AMapFitWhileMovingServesTheNextFramesOfASlowOrbitWhileItCoversThem) {
    const Bounds extent{glm::vec3(-20.0f, -20.0f, -0.5f), glm::vec3(20.0f, 20.0f, 1.5f)};
    const OrbitCamera start = closeCamera();
    const ShadowFrame tight = fitShadowFrame(start, extent, kSun, 2048);
    const ShadowFrame held = fitShadowFrame(start, extent, kSun, 2048, kMovingShadowMargin);
    ASSERT_TRUE(tight.valid && held.valid);
    // The margin costs texels as wide as it widens the square, and the wider map holds the tight one.
    EXPECT_NEAR(held.texel_m / tight.texel_m, 1.0f + 2.0f * kMovingShadowMargin, 0.01f);
    EXPECT_TRUE(shadowFrameHolds(held, tight));
    EXPECT_FALSE(shadowFrameHolds(tight, held));
    int held_steps = 0;
    for (int deg = 1; deg <= 90; ++deg) {
        OrbitCamera cam = start;
        cam.yaw_rad += glm::radians(float(deg));
        const ShadowFrame wanted = fitShadowFrame(cam, extent, kSun, 2048);
        ASSERT_TRUE(wanted.valid);
        if (!shadowFrameHolds(held, wanted)) continue;
        ++held_steps;
        // Held means covered: nothing this frame sees lies outside the earlier map.
        const Coverage c = seenOutside(cam, wanted, held, extent, 4000);
        EXPECT_GT(c.seen, 100) << deg << " deg";
        EXPECT_EQ(c.outside, 0) << deg << " deg";
    }
    // A drag of a degree or two a frame redraws every few frames, not every frame; a quarter turn redraws.
    OrbitCamera one = start, quarter = start;
    one.yaw_rad += glm::radians(1.0f);
    quarter.yaw_rad += glm::radians(90.0f);
    EXPECT_TRUE(shadowFrameHolds(held, fitShadowFrame(one, extent, kSun, 2048)));
    EXPECT_FALSE(shadowFrameHolds(held, fitShadowFrame(quarter, extent, kSun, 2048)));
    EXPECT_GE(held_steps, 3);
    EXPECT_LT(held_steps, 90);
}

TEST(ShadowFrame, AHeldMapDoesNotServeAZoomThatWouldBlurItsShadows) {
    const Bounds extent{glm::vec3(-20.0f, -20.0f, -0.5f), glm::vec3(20.0f, 20.0f, 1.5f)};
    const OrbitCamera start = closeCamera();
    const ShadowFrame held = fitShadowFrame(start, extent, kSun, 2048, kMovingShadowMargin);
    OrbitCamera closer = start;
    closer.distance_m *= 0.5f;
    const ShadowFrame wanted = fitShadowFrame(closer, extent, kSun, 2048);
    ASSERT_TRUE(wanted.valid);
    // Covered, but with texels more than kHeldTexelRatio times as wide as the close view's own.
    EXPECT_EQ(seenOutside(closer, wanted, held, extent, 4000).outside, 0);
    EXPECT_GT(held.texel_m, kHeldTexelRatio * wanted.texel_m);
    EXPECT_FALSE(shadowFrameHolds(held, wanted));
    // An invalid frame neither holds nor is held.
    EXPECT_FALSE(shadowFrameHolds(ShadowFrame{}, wanted));
    EXPECT_FALSE(shadowFrameHolds(held, ShadowFrame{}));
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
