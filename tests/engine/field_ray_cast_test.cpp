// Rays against a height field and a density isosurface (the editor's brushes aim with these): exact
// answers on hand-built planes and balls, and the edge cases (starting below the ground, missing rays).
#include <gtest/gtest.h>

#include <cmath>

#include "field/density_field.h"
#include "field/ray_cast.h"
#include "instancer/instance_query.h"
#include "instancer/tile_coord.h"

namespace ug {
namespace {

// A 5 x 5-sample plane tilted along X: h = 0.5 x over [0, 4]^2 (cells of 1 m), flat beyond the border.
HeightField tiltedPlane() {
    std::vector<float> h(25);
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) h[size_t(j * 5 + i)] = 0.5f * float(i);
    return HeightField(glm::vec2(0.0f), 1.0f, 5, 5, h);
}

TEST(RayCast, VerticalRayHitsTheBilinearHeight) {
    const HeightField hf = tiltedPlane();
    for (float x : {0.0f, 0.3f, 1.7f, 3.99f}) {
        const Ray ray{glm::vec3(x, 2.2f, 50.0f), glm::vec3(0.0f, 0.0f, -1.0f)};
        float t = 0.0f;
        ASSERT_TRUE(rayHeightField(hf, ray, 100.0f, &t)) << x;
        EXPECT_NEAR(ray.at(t).z, 0.5f * x, 1e-3f) << x;
    }
}

TEST(RayCast, SlantedRayHitsTheFirstCrossing) {
    // A ray from (-10, 2, 5) going +X and down at 45 degrees: z = 5 - (x + 10) meets the flat border
    // (h = 0 for x <= 0) at x = -5.
    const HeightField hf = tiltedPlane();
    const Ray ray{glm::vec3(-10.0f, 2.0f, 5.0f), glm::normalize(glm::vec3(1.0f, 0.0f, -1.0f))};
    float t = 0.0f;
    ASSERT_TRUE(rayHeightField(hf, ray, 100.0f, &t));
    EXPECT_NEAR(ray.at(t).x, -5.0f, 1e-3f);
    EXPECT_NEAR(ray.at(t).z, 0.0f, 1e-3f);
}

TEST(RayCast, FlatGroundIsHitFromEveryAngle) {
    // A flat field has a slab of no thickness: the rays the editor cast at the flat street (the one that
    // failed: from (4.98, 0.93, 7.71) along (-0.26, 0.33, -0.91)) and a fan of others must all meet it.
    const HeightField flat(glm::vec2(0.0f), 0.25f, 41, 41, std::vector<float>(41 * 41, 0.0f));
    std::vector<Ray> rays{{glm::vec3(4.98f, 0.93f, 7.71f), glm::normalize(glm::vec3(-0.26f, 0.33f, -0.91f))}};
    for (int i = 0; i < 200; ++i) {
        const float a = 0.031f * float(i), pitch = 0.2f + 0.0065f * float(i);
        rays.push_back({glm::vec3(5.0f, 5.0f, 3.0f + 0.01f * float(i)),
                        glm::normalize(glm::vec3(std::cos(a) * std::cos(pitch), std::sin(a) * std::cos(pitch),
                                                 -std::sin(pitch)))});
    }
    for (size_t k = 0; k < rays.size(); ++k) {
        const Ray& ray = rays[k];
        const float t_plane = -ray.origin_m.z / ray.direction.z;
        const glm::vec3 p = ray.at(t_plane);
        if (p.x < 0.0f || p.y < 0.0f || p.x > 10.0f || p.y > 10.0f) continue;  // beyond the samples: clamped, flat too
        float t = 0.0f;
        ASSERT_TRUE(rayHeightField(flat, ray, 100.0f, &t)) << "ray " << k;
        EXPECT_NEAR(t, t_plane, 1e-3f) << "ray " << k;
    }
}

TEST(RayCast, MissesAndStartsBelow) {
    const HeightField hf = tiltedPlane();
    float t = 0.0f;
    // Upward: never meets the ground.
    EXPECT_FALSE(
        rayHeightField(hf, Ray{glm::vec3(1.0f, 1.0f, 5.0f), glm::vec3(0.0f, 0.0f, 1.0f)}, 100.0f, &t));
    // Too short.
    EXPECT_FALSE(
        rayHeightField(hf, Ray{glm::vec3(1.0f, 1.0f, 5.0f), glm::vec3(0.0f, 0.0f, -1.0f)}, 2.0f, &t));
    // Starts under the ground.
    EXPECT_FALSE(
        rayHeightField(hf, Ray{glm::vec3(4.0f, 1.0f, 1.0f), glm::vec3(0.0f, 0.0f, -1.0f)}, 100.0f, &t));
}

TEST(RayCast, IsosurfaceOfABall) {
    // A ball of radius R = 2 and weight 1: f = (1 - d²/4)³ = 0.5 at d² = 4 (1 - 0.5^(1/3)).
    const DensityField ball = makeBlendField({makePoint(glm::vec3(1.0f, 2.0f, 3.0f), 2.0f)});
    const float d_iso = 2.0f * std::sqrt(1.0f - std::cbrt(0.5f));
    const Ray down{glm::vec3(1.0f, 2.0f, 20.0f), glm::vec3(0.0f, 0.0f, -1.0f)};
    float t = 0.0f;
    ASSERT_TRUE(rayDensityIsosurface(ball, down, 0.5f, 100.0f, 0.02f, &t));
    EXPECT_NEAR(down.at(t).z, 3.0f + d_iso, 1e-4f);
    // A ray that passes 1.5 m from the centre stays below 0.5 (d_iso < 1.5): no hit.
    const Ray beside{glm::vec3(2.5f, 2.0f, 20.0f), glm::vec3(0.0f, 0.0f, -1.0f)};
    EXPECT_FALSE(rayDensityIsosurface(ball, beside, 0.5f, 100.0f, 0.02f, &t));
    // Starting inside: the next entry, none here.
    const Ray inside{glm::vec3(1.0f, 2.0f, 3.0f), glm::vec3(0.0f, 0.0f, -1.0f)};
    EXPECT_FALSE(rayDensityIsosurface(ball, inside, 0.5f, 100.0f, 0.02f, &t));
    // An empty field has no surface.
    EXPECT_FALSE(rayDensityIsosurface(DensityField{}, down, 0.5f, 100.0f, 0.02f, &t));
}

TEST(RayCast, IsosurfaceTakesTheNearerOfTwoBalls) {
    const DensityField two = makeBlendField(
        {makePoint(glm::vec3(0.0f, 0.0f, 0.0f), 1.0f), makePoint(glm::vec3(0.0f, 0.0f, 5.0f), 1.0f)});
    const float d_iso = std::sqrt(1.0f - std::cbrt(0.5f));
    const Ray down{glm::vec3(0.0f, 0.0f, 20.0f), glm::vec3(0.0f, 0.0f, -1.0f)};
    float t = 0.0f;
    ASSERT_TRUE(rayDensityIsosurface(two, down, 0.5f, 100.0f, 0.01f, &t));
    EXPECT_NEAR(down.at(t).z, 5.0f + d_iso, 1e-4f);
}

TEST(InstanceQuery, CountsInsideAndOutsideAndHashes) {
    // Two types, one candidate each, at (0.1, 0.1, 0.1) and (0.4, 0.4, 0.4) of a 0.5 m tile.
    CandidateSet c;
    c.type_begin = {0, 1, 2};
    c.type = {0, 1};
    c.position = {glm::vec3(0.1f), glm::vec3(0.4f)};
    c.rotation = {glm::quat(1, 0, 0, 0), glm::quat(1, 0, 0, 0)};
    c.scale = {1.0f, 1.0f};
    InstanceStore store;
    const uint32_t both[] = {0, 1};
    const uint32_t first[] = {0};
    store.appendTile(packTile(glm::ivec3(0, 0, 0)), both);   // origins (0.1..) and (0.4..)
    store.appendTile(packTile(glm::ivec3(2, 0, 0)), first);  // origin (1.1, 0.1, 0.1)
    const Bounds box{glm::vec3(0.0f), glm::vec3(0.3f)};
    const BoxCounts counts = countInstancesInBox(store, c, 0.5f, box);
    EXPECT_EQ(counts.inside, (std::vector<uint64_t>{1, 0}));
    EXPECT_EQ(counts.outside, (std::vector<uint64_t>{1, 1}));
    const BoxCounts none = countInstancesInBox(store, c, 0.5f, Bounds{});
    EXPECT_EQ(none.outside, (std::vector<uint64_t>{2, 1}));

    InstanceStore same;
    same.appendTile(packTile(glm::ivec3(0, 0, 0)), both);
    same.appendTile(packTile(glm::ivec3(2, 0, 0)), first);
    EXPECT_EQ(instanceStoreHash(store), instanceStoreHash(same));
    InstanceStore other;
    other.appendTile(packTile(glm::ivec3(0, 0, 0)), both);
    other.appendTile(packTile(glm::ivec3(2, 0, 0)), std::span<const uint32_t>(both + 1, 1));
    EXPECT_NE(instanceStoreHash(store), instanceStoreHash(other));
    EXPECT_NE(instanceStoreHash(store), instanceStoreHash(InstanceStore{}));
}

}  // namespace
}  // namespace ug
