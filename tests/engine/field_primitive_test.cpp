// Skeletal primitives: exact kernel values, analytic gradients, support bounds, parameter validation.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/hash.h"
#include "field/height_field.h"
#include "field/primitive.h"

namespace ug {
namespace {

// K(R/2, R) = (1 - 1/4)³, exactly representable.
constexpr float kHalfRadius = 0.421875f;

HeightField flatField(float height_m) {
    return HeightField(glm::vec2(-10.0f), 1.0f, 21, 21, std::vector<float>(21 * 21, height_m));
}

HeightField hillyField() {
    HeightField hf;
    std::string error;
    ProceduralTerrainDesc desc;
    desc.origin_m = glm::vec2(-8.0f);
    desc.width = desc.height = 17;
    desc.amplitude_m = 1.0f;
    desc.feature_size_m = 6.0f;
    desc.seed = 3;
    EXPECT_TRUE(makeProceduralHeightField(desc, &hf, &error)) << error;
    return hf;
}

float rnd(uint64_t seed, uint64_t i, uint64_t axis, float lo, float hi) {
    return lo + (hi - lo) * unitFloat(hashWords(seed, i, axis));
}

TEST(Primitive, PointValuesAreExactAtCentreMidRadiusAndSupportBoundary) {
    // weight 2, R 2, centre (1, 2, 3):  value 2 at the centre, 2·K(1, 2) at d = 1, 0 from d = 2 on.
    const Primitive p = makePoint({1, 2, 3}, 2.0f, 2.0f);
    EXPECT_EQ(primitiveValue(p, nullptr, {1, 2, 3}), 2.0f);
    EXPECT_EQ(primitiveValue(p, nullptr, {2, 2, 3}), 2.0f * kHalfRadius);
    EXPECT_EQ(primitiveValue(p, nullptr, {1, 1, 3}), 2.0f * kHalfRadius);
    EXPECT_EQ(primitiveValue(p, nullptr, {3, 2, 3}), 0.0f);
    EXPECT_EQ(primitiveValue(p, nullptr, {9, 2, 3}), 0.0f);
    const Primitive brush = makePoint({0, 0, 0}, 2.0f, -1.0f);
    EXPECT_EQ(primitiveValue(brush, nullptr, {0, 1, 0}), -kHalfRadius);
}

TEST(Primitive, SegmentIsACapsuleAndAConeWithTwoRadii) {
    //   a=(0,0,0) ============ b=(4,0,0), R = 2
    const Primitive s = makeSegment({0, 0, 0}, {4, 0, 0}, 2.0f);
    EXPECT_EQ(primitiveValue(s, nullptr, {2, 0, 0}), 1.0f);
    EXPECT_EQ(primitiveValue(s, nullptr, {2, 1, 0}), kHalfRadius);
    EXPECT_EQ(primitiveValue(s, nullptr, {-1, 0, 0}), kHalfRadius);  // beyond the end cap
    EXPECT_EQ(primitiveValue(s, nullptr, {5, 0, 0}), kHalfRadius);
    EXPECT_EQ(primitiveValue(s, nullptr, {2, 0, 2}), 0.0f);
    EXPECT_EQ(primitiveValue(s, nullptr, {7, 0, 0}), 0.0f);
    // Cone: R = 1 at a, 3 at b, so R = 2 at the middle.
    const Primitive c = makeCone({0, 0, 0}, 1.0f, {4, 0, 0}, 3.0f);
    EXPECT_EQ(primitiveValue(c, nullptr, {2, 0, 0}), 1.0f);
    EXPECT_EQ(primitiveValue(c, nullptr, {2, 1, 0}), kHalfRadius);
    EXPECT_EQ(primitiveValue(c, nullptr, {2, 2, 0}), 0.0f);
    EXPECT_EQ(primitiveValue(c, nullptr, {-0.5f, 0, 0}), kHalfRadius);  // R = 1 at the a end
    EXPECT_EQ(primitiveValue(c, nullptr, {5.5f, 0, 0}), kHalfRadius);   // R = 3 at the b end
    EXPECT_EQ(primitiveValue(c, nullptr, {-1, 0, 0}), 0.0f);
}

TEST(Primitive, DiscDistanceIsToTheFlatDisc) {
    // Disc of radius 1 in the z = 0 plane, falloff R = 2.
    const Primitive d = makeDisc({0, 0, 0}, {0, 0, 3}, 1.0f, 2.0f);
    EXPECT_EQ(primitiveValue(d, nullptr, {0, 0, 0}), 1.0f);
    EXPECT_EQ(primitiveValue(d, nullptr, {0.5f, 0, 0}), 1.0f);
    EXPECT_EQ(primitiveValue(d, nullptr, {0.5f, 0, 1}), kHalfRadius);
    EXPECT_EQ(primitiveValue(d, nullptr, {2, 0, 0}), kHalfRadius);  // 1 from the rim
    EXPECT_EQ(primitiveValue(d, nullptr, {0, -2, 0}), kHalfRadius);
    EXPECT_EQ(primitiveValue(d, nullptr, {0, 0, 2}), 0.0f);
    EXPECT_EQ(primitiveValue(d, nullptr, {3, 0, 0}), 0.0f);
}

TEST(Primitive, BoxIsFullInsideAndFallsOffOutside) {
    const Primitive b = makeBox({0, 0, 0}, {1, 2, 3}, 2.0f, 0.5f);
    EXPECT_EQ(primitiveValue(b, nullptr, {0, 0, 0}), 0.5f);
    EXPECT_EQ(primitiveValue(b, nullptr, {1, -2, 3}), 0.5f);  // on the corner
    EXPECT_EQ(primitiveValue(b, nullptr, {2, 0, 0}), 0.5f * kHalfRadius);
    EXPECT_EQ(primitiveValue(b, nullptr, {0, 0, -4}), 0.5f * kHalfRadius);
    EXPECT_EQ(primitiveValue(b, nullptr, {3, 0, 0}), 0.0f);
    EXPECT_EQ(primitiveValue(b, nullptr, {0, 4, 0}), 0.0f);
    EXPECT_EQ(primitiveValue(b, nullptr, {2.5f, 3.5f, 0}), 0.0f);  // d² = 2.25 + 2.25 > 4
}

TEST(Primitive, HalfSpaceIsFullInsideAndFallsOffOutside) {
    const Primitive h = makeHalfSpace({0, 0, 1}, {0, 0, 1}, 2.0f);
    EXPECT_EQ(primitiveValue(h, nullptr, {5, 5, -100}), 1.0f);
    EXPECT_EQ(primitiveValue(h, nullptr, {0, 0, 1}), 1.0f);
    EXPECT_EQ(primitiveValue(h, nullptr, {0, 0, 2}), kHalfRadius);
    EXPECT_EQ(primitiveValue(h, nullptr, {0, 0, 3}), 0.0f);
    EXPECT_EQ(primitiveValue(h, nullptr, {0, 0, 30}), 0.0f);
}

TEST(Primitive, TerrainLayerIsFullBetweenGroundAndThickness) {
    const HeightField ground = flatField(1.0f);
    const Primitive l = makeTerrainLayer(0, 0.5f, 2.0f);
    EXPECT_EQ(primitiveValue(l, &ground, {0, 0, 1.0f}), 1.0f);
    EXPECT_EQ(primitiveValue(l, &ground, {3, 4, 1.25f}), 1.0f);
    EXPECT_EQ(primitiveValue(l, &ground, {0, 0, 1.5f}), 1.0f);
    EXPECT_EQ(primitiveValue(l, &ground, {0, 0, 0.0f}), kHalfRadius);  // 1 below the ground
    EXPECT_EQ(primitiveValue(l, &ground, {0, 0, 2.5f}), kHalfRadius);  // 1 above the layer
    EXPECT_EQ(primitiveValue(l, &ground, {0, 0, 3.5f}), 0.0f);
    EXPECT_EQ(primitiveValue(l, &ground, {0, 0, -1.0f}), 0.0f);
    EXPECT_EQ(primitiveValue(l, &ground, {500, 0, 1.25f}), 1.0f);  // clamped: extends past the grid
}

TEST(Primitive, TerrainSolidIsFullDeepBelowAndZeroFromTheSurfaceUp) {
    const HeightField ground = flatField(1.0f);
    const Primitive s = makeTerrainSolid(0, 2.0f, 10.0f);
    EXPECT_EQ(primitiveValue(s, &ground, {0, 0, -5.0f}), 10.0f);
    EXPECT_EQ(primitiveValue(s, &ground, {0, 0, -1.0f}), 10.0f);  // depth 2 = R
    EXPECT_EQ(primitiveValue(s, &ground, {0, 0, 0.0f}), 10.0f * kHalfRadius);
    EXPECT_EQ(primitiveValue(s, &ground, {0, 0, 1.0f}), 0.0f);
    EXPECT_EQ(primitiveValue(s, &ground, {0, 0, 1.5f}), 0.0f);
}

TEST(Primitive, ValueAndGradientReturnsTheSameValueBits) {
    const HeightField ground = hillyField();
    const std::vector<Primitive> prims = {
        makePoint({0, 0, 0}, 2.0f), makeCone({-1, 0, 0}, 0.5f, {2, 1, 0}, 1.5f), makeDisc({0, 0, 0}, {1, 1, 1}, 1.0f, 1.0f),
        makeBox({0, 0, 0}, {1, 0.5f, 0.2f}, 1.0f), makeHalfSpace({0, 0, 0}, {1, 2, 3}, 1.0f),
        makeTerrainLayer(0, 0.3f, 1.0f, -0.7f), makeTerrainSolid(0, 0.5f)};
    for (size_t k = 0; k < prims.size(); ++k)
        for (uint64_t i = 0; i < 200; ++i) {
            const glm::vec3 p(rnd(1, i, 0, -3, 3), rnd(1, i, 1, -3, 3), rnd(1, i, 2, -3, 3));
            const float v = primitiveValue(prims[k], &ground, p);
            const float w = primitiveValueAndGradient(prims[k], &ground, p).w;
            ASSERT_EQ(std::memcmp(&v, &w, sizeof(float)), 0) << "primitive " << k;
        }
}

// Central differences in double around float evaluations: step h = 1e-3 m, so the truncation error is
// O(h²·f''') ~ 1e-5 and the rounding error ~ 1e-7/h ~ 1e-4 for values of order 1. Tolerance 2e-3 abs +
// 2e-3 relative to |∇f|. Points where the gradient is not continuous are skipped (cone end planes,
// bilinear cell edges).
void expectGradientMatchesFiniteDifferences(const Primitive& prim, const HeightField* hf, uint64_t seed,
                                            const char* what) {
    const float h = 1e-3f;
    int checked = 0;
    for (uint64_t i = 0; i < 400; ++i) {
        const glm::vec3 p(rnd(seed, i, 0, -3, 3), rnd(seed, i, 1, -3, 3), rnd(seed, i, 2, -3, 3));
        if (prim.kind == PrimitiveKind::Segment) {
            const glm::vec3 ab = prim.end_m - prim.center_m;
            const float t = glm::dot(p - prim.center_m, ab) / glm::dot(ab, ab);
            if (std::abs(t) < 0.01f || std::abs(t - 1.0f) < 0.01f) continue;
        }
        if (hf) {
            const float u = (p.x - hf->origin().x) / hf->cellSize(), v = (p.y - hf->origin().y) / hf->cellSize();
            if (std::abs(u - std::round(u)) < 0.01f || std::abs(v - std::round(v)) < 0.01f) continue;
        }
        const glm::vec4 g = primitiveValueAndGradient(prim, hf, p);
        for (int axis = 0; axis < 3; ++axis) {
            glm::vec3 a = p, b = p;
            a[axis] -= h;
            b[axis] += h;
            const double fd = (double(primitiveValue(prim, hf, b)) - double(primitiveValue(prim, hf, a))) / (2.0 * h);
            const double tol = 2e-3 + 2e-3 * glm::length(glm::vec3(g));
            ASSERT_NEAR(g[axis], fd, tol) << what << " at (" << p.x << ", " << p.y << ", " << p.z << ") axis " << axis;
        }
        if (g.w != 0.0f) ++checked;
    }
    EXPECT_GT(checked, 20) << what << ": too few points inside the support";
}

TEST(Primitive, GradientsMatchFiniteDifferencesForEveryKind) {
    const HeightField ground = hillyField();
    expectGradientMatchesFiniteDifferences(makePoint({0.5f, 0, 0}, 2.5f, 1.5f), nullptr, 11, "point");
    expectGradientMatchesFiniteDifferences(makeSegment({-1, -1, 0}, {1, 2, 0.5f}, 2.0f), nullptr, 12, "capsule");
    expectGradientMatchesFiniteDifferences(makeCone({-2, 0, 0}, 0.5f, {2, 1, 0}, 2.5f, -1.0f), nullptr, 13, "cone");
    expectGradientMatchesFiniteDifferences(makeDisc({0, 0, 0}, {1, 1, 2}, 1.0f, 1.5f), nullptr, 14, "disc");
    expectGradientMatchesFiniteDifferences(makeBox({0, 0, 0}, {1, 0.5f, 0.7f}, 1.5f), nullptr, 15, "box");
    expectGradientMatchesFiniteDifferences(makeHalfSpace({0, 0, 0}, {1, -2, 3}, 2.0f), nullptr, 16, "half-space");
    expectGradientMatchesFiniteDifferences(makeTerrainLayer(0, 0.5f, 1.5f), &ground, 17, "terrain layer");
    expectGradientMatchesFiniteDifferences(makeTerrainSolid(0, 2.0f, 1.0f), &ground, 18, "terrain solid");
}

TEST(Primitive, BoundsContainEveryPointWithANonZeroValue) {
    const HeightField ground = hillyField();
    const std::vector<Primitive> prims = {
        makePoint({0.3f, 0, 0}, 1.7f), makeCone({-1, 0, 0}, 0.5f, {2, 1, 0}, 1.5f),
        makeDisc({0, 0, 0}, {1, 1, 1}, 1.0f, 1.0f), makeDisc({0, 0, 0}, {0, 0, 1}, 1.5f, 0.5f),
        makeBox({0, 0, 0}, {1, 0.5f, 0.2f}, 1.0f), makeHalfSpace({0, 0, 0.5f}, {0, 0, 1}, 1.0f),
        makeHalfSpace({0.5f, 0, 0}, {-1, 0, 0}, 1.0f), makeTerrainLayer(0, 0.3f, 1.0f),
        makeTerrainSolid(0, 0.5f)};
    for (size_t k = 0; k < prims.size(); ++k) {
        const Bounds b = primitiveBounds(prims[k], &ground);
        int non_zero = 0;
        for (uint64_t i = 0; i < 20000; ++i) {
            const glm::vec3 p(rnd(7, i, 0, -4, 4), rnd(7, i, 1, -4, 4), rnd(7, i, 2, -4, 4));
            if (primitiveValue(prims[k], &ground, p) == 0.0f) continue;
            ++non_zero;
            ASSERT_TRUE(contains(b, p)) << primitiveKindName(prims[k].kind) << " " << k;
        }
        EXPECT_GT(non_zero, 0) << k;
    }
    // A half-space along an axis is bounded on its outer side; a tilted one is not.
    EXPECT_NEAR(primitiveBounds(prims[5], nullptr).hi.z, 1.5f, 1e-4f);  // padded a little
    EXPECT_TRUE(std::isinf(primitiveBounds(makeHalfSpace({0, 0, 0}, {0, 1, 1}, 1.0f), nullptr).hi.z));
}

TEST(Primitive, ValidationNamesTheIndexTheFieldAndTheReason) {
    std::string error;
    EXPECT_TRUE(validatePrimitive(makePoint({0, 0, 0}, 1.0f), 0, 0, &error)) << error;

    EXPECT_FALSE(validatePrimitive(makePoint({0, 0, 0}, -1.0f), 3, 0, &error));
    EXPECT_NE(error.find("primitive 3 (point)"), std::string::npos) << error;
    EXPECT_NE(error.find("radius_m"), std::string::npos) << error;

    EXPECT_FALSE(validatePrimitive(makePoint({0, 0, 0}, 0.0f), 0, 0, &error));
    EXPECT_NE(error.find("radius_m"), std::string::npos) << error;

    EXPECT_FALSE(validatePrimitive(makePoint({0, NAN, 0}, 1.0f), 1, 0, &error));
    EXPECT_NE(error.find("center_m"), std::string::npos) << error;

    EXPECT_FALSE(validatePrimitive(makePoint({0, 0, 0}, 1.0f, NAN), 2, 0, &error));
    EXPECT_NE(error.find("weight"), std::string::npos) << error;

    EXPECT_FALSE(validatePrimitive(makePoint({0, 0, 0}, INFINITY), 2, 0, &error));
    EXPECT_NE(error.find("radius_m"), std::string::npos) << error;

    EXPECT_FALSE(validatePrimitive(makeCone({0, 0, 0}, 1.0f, {1, 0, 0}, -2.0f), 4, 0, &error));
    EXPECT_NE(error.find("end_radius_m"), std::string::npos) << error;

    EXPECT_FALSE(validatePrimitive(makeDisc({0, 0, 0}, {0, 0, 0}, 1.0f, 1.0f), 5, 0, &error));
    EXPECT_NE(error.find("primitive 5 (disc): normal is zero"), std::string::npos) << error;

    EXPECT_FALSE(validatePrimitive(makeHalfSpace({0, 0, 0}, {0, 0, 0}, 1.0f), 6, 0, &error));
    EXPECT_NE(error.find("normal is zero"), std::string::npos) << error;

    Primitive unnormalized = makeHalfSpace({0, 0, 0}, {0, 0, 1}, 1.0f);
    unnormalized.normal = {0, 0, 2};
    EXPECT_FALSE(validatePrimitive(unnormalized, 0, 0, &error));
    EXPECT_NE(error.find("unit"), std::string::npos) << error;

    EXPECT_FALSE(validatePrimitive(makeBox({0, 0, 0}, {1, -1, 1}, 1.0f), 7, 0, &error));
    EXPECT_NE(error.find("half_extents_m"), std::string::npos) << error;

    EXPECT_FALSE(validatePrimitive(makeTerrainLayer(2, 0.5f, 1.0f), 8, 2, &error));
    EXPECT_NE(error.find("height_field 2 is out of range"), std::string::npos) << error;

    EXPECT_FALSE(validatePrimitive(makeTerrainLayer(0, -0.5f, 1.0f), 8, 1, &error));
    EXPECT_NE(error.find("thickness_m"), std::string::npos) << error;
}

}  // namespace
}  // namespace ug
