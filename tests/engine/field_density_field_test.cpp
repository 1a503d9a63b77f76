// BlobTree density fields: operator values and gradients, tile lists bit-identical to full evaluation,
// batch == scalar, positive-support bounds, solids, polylines, validation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "core/hash.h"
#include "field/density_field.h"

namespace ug {
namespace {

constexpr float kHalfRadius = 0.421875f;  // K(R/2, R)

float rnd(uint64_t seed, uint64_t i, uint64_t axis, float lo, float hi) {
    return lo + (hi - lo) * unitFloat(hashWords(seed, i, axis));
}

glm::vec3 rndPoint(uint64_t seed, uint64_t i, float lo, float hi) {
    return glm::vec3(rnd(seed, i, 0, lo, hi), rnd(seed, i, 1, lo, hi), rnd(seed, i, 2, lo, hi));
}

std::shared_ptr<const HeightField> hillyField() {
    auto hf = std::make_shared<HeightField>();
    std::string error;
    ProceduralTerrainDesc desc;
    desc.origin_m = glm::vec2(-8.0f);
    desc.width = desc.height = 17;
    desc.amplitude_m = 1.0f;
    desc.feature_size_m = 6.0f;
    EXPECT_TRUE(makeProceduralHeightField(desc, hf.get(), &error)) << error;
    return hf;
}

// Two balls, A = (w 1, centre 0, R 2) and B = (w b_weight, centre (1, 0, 0), R 2), under one operator.
// At the origin A = 1 and B = b_weight · K(1, 2) = b_weight · 0.421875.
DensityField twoBalls(FieldOp op, float b_weight) {
    DensityField f;
    const uint32_t refs[2] = {primitiveChild(addPrimitive(&f, makePoint({0, 0, 0}, 2.0f, 1.0f))),
                              primitiveChild(addPrimitive(&f, makePoint({1, 0, 0}, 2.0f, b_weight)))};
    f.root = addNode(&f, op, refs);
    return f;
}

TEST(DensityField, OperatorValuesAreExact) {
    const glm::vec3 o(0.0f);
    EXPECT_EQ(evaluate(twoBalls(FieldOp::Blend, 0.5f), o), 1.0f + 0.5f * kHalfRadius);
    EXPECT_EQ(evaluate(twoBalls(FieldOp::Union, 0.5f), o), 1.0f);
    EXPECT_EQ(evaluate(twoBalls(FieldOp::Intersection, 0.5f), o), 0.5f * kHalfRadius);
    EXPECT_EQ(evaluate(twoBalls(FieldOp::Difference, 0.5f), o), 1.0f - 0.5f * kHalfRadius);
    // a - max(b, 0): a negative b removes nothing.
    EXPECT_EQ(evaluate(twoBalls(FieldOp::Difference, -0.5f), o), 1.0f);
    EXPECT_EQ(evaluate(twoBalls(FieldOp::Blend, -0.5f), o), 1.0f - 0.5f * kHalfRadius);
    // Where only B reaches (x = 2.5: A is 0, B at d = 1.5).
    const glm::vec3 right(2.5f, 0, 0);
    const float b = 0.5f * std::pow(1.0f - 1.5f * 1.5f / 4.0f, 3.0f);
    EXPECT_FLOAT_EQ(evaluate(twoBalls(FieldOp::Union, 0.5f), right), b);
    EXPECT_EQ(evaluate(twoBalls(FieldOp::Intersection, 0.5f), right), 0.0f);
    // Where a <= 0 the difference keeps a (there is nothing to carve): 0 here, not -b.
    EXPECT_EQ(evaluate(twoBalls(FieldOp::Difference, 0.5f), right), 0.0f);
    // Where both reach, a - b (x = 1.5: A at d = 1.5, B at d = 0.5).
    const glm::vec3 mid(1.5f, 0, 0);
    const float a_mid = std::pow(1.0f - 1.5f * 1.5f / 4.0f, 3.0f), b_mid = 0.5f * std::pow(1.0f - 0.25f / 4.0f, 3.0f);
    EXPECT_FLOAT_EQ(evaluate(twoBalls(FieldOp::Difference, 0.5f), mid), a_mid - b_mid);
    // Outside both supports every operator is exactly 0.
    for (FieldOp op : {FieldOp::Blend, FieldOp::Union, FieldOp::Intersection, FieldOp::Difference})
        EXPECT_EQ(evaluate(twoBalls(op, 0.5f), glm::vec3(10, 0, 0)), 0.0f) << fieldOpName(op);
}

TEST(DensityField, EmptyFieldsAndOperatorsWithoutChildrenAreZero) {
    DensityField none;
    EXPECT_EQ(evaluate(none, glm::vec3(0)), 0.0f);
    EXPECT_TRUE(positiveBounds(none).empty());
    for (FieldOp op : {FieldOp::Blend, FieldOp::Union, FieldOp::Intersection, FieldOp::Difference}) {
        DensityField f;
        f.root = addNode(&f, op, {});
        EXPECT_EQ(evaluate(f, glm::vec3(0)), 0.0f);
        EXPECT_TRUE(buildTileList(f, Bounds{glm::vec3(-1), glm::vec3(1)}).empty());
    }
}

TEST(DensityField, UnionAndIntersectionGradientsFollowTheWinningChild) {
    const glm::vec3 p(0.25f, 0.5f, 0.0f);
    DensityField pair = twoBalls(FieldOp::Blend, 0.5f);
    const glm::vec4 a = primitiveValueAndGradient(pair.primitives[0], nullptr, p);
    const glm::vec4 b = primitiveValueAndGradient(pair.primitives[1], nullptr, p);
    ASSERT_GT(a.w, b.w);
    const glm::vec4 u = evaluateWithGradient(twoBalls(FieldOp::Union, 0.5f), p);
    const glm::vec4 i = evaluateWithGradient(twoBalls(FieldOp::Intersection, 0.5f), p);
    EXPECT_EQ(std::memcmp(&u, &a, sizeof(u)), 0);
    EXPECT_EQ(std::memcmp(&i, &b, sizeof(i)), 0);
}

// A random field: primitives of every kind, weights of both signs, a random tree over all operators,
// a polyline and a terrain solid subtracted.
DensityField randomField(uint64_t seed, std::shared_ptr<const HeightField> ground) {
    DensityField f;
    const uint32_t hf = addHeightField(&f, ground);
    std::vector<uint32_t> pool;
    const int count = 24;
    for (int i = 0; i < count; ++i) {
        auto r = [&](uint64_t axis, float lo, float hi) { return rnd(seed, uint64_t(i), axis, lo, hi); };
        const glm::vec3 c(r(0, -5, 5), r(1, -5, 5), r(2, -2, 2));
        const float radius = r(3, 0.5f, 2.0f);
        const float weight = r(4, -1.0f, 2.0f);
        Primitive p;
        switch (i % 8) {
            case 0: p = makePoint(c, radius, weight); break;
            case 1: p = makeCone(c, radius, c + glm::vec3(r(5, -3, 3), r(6, -3, 3), r(7, -1, 1)), r(8, 0.3f, 2.0f), weight); break;
            case 2: p = makeDisc(c, glm::vec3(r(5, -1, 1), r(6, -1, 1), r(7, 0.2f, 1)), r(8, 0, 1.5f), radius, weight); break;
            case 3: p = makeBox(c, glm::vec3(r(5, 0, 1), r(6, 0, 1), r(7, 0, 1)), radius, weight); break;
            case 4: p = makeHalfSpace(c, i % 16 == 4 ? glm::vec3(0, 0, 1) : glm::vec3(r(5, -1, 1), r(6, -1, 1), 1), radius, weight); break;
            case 5: p = makeTerrainLayer(hf, r(5, 0, 0.5f), radius, weight); break;
            case 6: p = makeSegment(c, c + glm::vec3(r(5, -2, 2), r(6, -2, 2), 0), radius, weight); break;
            default: p = makePoint(c, radius, -weight); break;
        }
        pool.push_back(primitiveChild(addPrimitive(&f, p)));
    }
    const glm::vec4 river[4] = {{-5, -5, 0, 0.5f}, {-1, -2, 0.2f, 1.0f}, {2, 0, 0, 0.7f}, {5, 4, 0.5f, 1.2f}};
    uint32_t polyline = 0;
    std::string error;
    EXPECT_TRUE(addPolyline(&f, river, seed % 2 ? 1.0f : -0.5f, &polyline, &error)) << error;
    pool.push_back(polyline);
    // Combine random groups of 1-4 until one node is left.
    uint64_t step = 0;
    while (pool.size() > 1) {
        const uint64_t h = hashWords(seed, 1000 + step++);
        const size_t take = std::min(pool.size(), size_t(1 + h % 4));
        const size_t at = size_t((h >> 8) % (pool.size() - take + 1));
        const FieldOp op = FieldOp((h >> 20) % 4);
        std::vector<uint32_t> group(pool.begin() + long(at), pool.begin() + long(at + take));
        pool.erase(pool.begin() + long(at), pool.begin() + long(at + take));
        pool.insert(pool.begin() + long(at), nodeChild(addNode(&f, op, group)));
    }
    f.root = pool[0];
    subtractSolids(&f, {makeTerrainSolid(hf, 0.3f)});
    return f;
}

TEST(DensityField, RandomFieldsAreValid) {
    auto ground = hillyField();
    for (uint64_t seed = 1; seed <= 20; ++seed) {
        std::string error;
        EXPECT_TRUE(validate(randomField(seed, ground), &error)) << seed << ": " << error;
    }
}

TEST(DensityField, TileListEvaluationIsBitIdenticalToFullEvaluation) {
    auto ground = hillyField();
    size_t pruned = 0, total = 0, empty_tiles = 0;
    std::vector<glm::vec3> points;
    std::vector<float> full(256), tiled(256), refined(256);
    std::vector<glm::vec4> full_g(256), tiled_g(256);
    TileFieldList region, tile;
    for (uint64_t seed = 1; seed <= 20; ++seed) {
        const DensityField f = randomField(seed, ground);
        // A 4 m region and 1 m tiles inside it (hierarchical refinement must agree too).
        const glm::vec3 region_lo = rndPoint(seed, 77, -7, 3);
        buildTileList(f, Bounds{region_lo, region_lo + 4.0f}, &region);
        for (uint64_t t = 0; t < 8; ++t) {
            const glm::vec3 lo = region_lo + glm::floor(rndPoint(seed * 31 + t, 5, 0, 3.999f));
            const Bounds box{lo, lo + 1.0f};
            buildTileList(f, box, &tile);
            total += f.primitives.size();
            pruned += f.primitives.size() - tile.primitives.size();
            empty_tiles += tile.empty();
            points.clear();
            for (uint64_t i = 0; i < 256; ++i) {
                glm::vec3 p = lo + rndPoint(seed * 131 + t, i, 0, 1);
                if (i % 16 == 0) p.x = lo.x;  // on the faces too
                if (i % 16 == 1) p.z = lo.z + 1.0f;
                points.push_back(p);
            }
            evaluateBatch(f, nullptr, points.data(), points.size(), full.data());
            evaluateBatch(f, &tile, points.data(), points.size(), tiled.data());
            ASSERT_EQ(std::memcmp(full.data(), tiled.data(), full.size() * sizeof(float)), 0)
                << "seed " << seed << " tile " << t;
            evaluateBatchWithGradient(f, nullptr, points.data(), points.size(), full_g.data());
            evaluateBatchWithGradient(f, &tile, points.data(), points.size(), tiled_g.data());
            ASSERT_EQ(std::memcmp(full_g.data(), tiled_g.data(), full_g.size() * sizeof(glm::vec4)), 0)
                << "seed " << seed << " tile " << t;
            TileFieldList child;
            buildTileList(f, box, &child, &region);
            EXPECT_EQ(child.primitives, tile.primitives);
            evaluateBatch(f, &child, points.data(), points.size(), refined.data());
            ASSERT_EQ(std::memcmp(full.data(), refined.data(), full.size() * sizeof(float)), 0);
            for (size_t i = 0; i < points.size(); ++i) {
                // Value-only and with-gradient paths agree on the value, and batch == scalar.
                ASSERT_EQ(std::memcmp(&full[i], &full_g[i].w, sizeof(float)), 0);
                const float scalar = evaluate(f, points[i]);
                const glm::vec4 scalar_g = evaluateWithGradient(f, points[i]);
                ASSERT_EQ(std::memcmp(&scalar, &full[i], sizeof(float)), 0);
                ASSERT_EQ(std::memcmp(&scalar_g, &full_g[i], sizeof(glm::vec4)), 0);
            }
        }
    }
    EXPECT_GT(pruned, total / 3) << "tile lists should leave most far primitives out";
    (void)empty_tiles;
}

TEST(DensityField, TileFarFromEveryPrimitiveIsEmpty) {
    const DensityField f = makeBlendField({makePoint({0, 0, 0}, 1.0f), makeBox({5, 0, 0}, {1, 1, 1}, 0.5f)});
    EXPECT_TRUE(buildTileList(f, Bounds{glm::vec3(20), glm::vec3(21)}).empty());
    const TileFieldList near = buildTileList(f, Bounds{glm::vec3(5.8f, 0, 0), glm::vec3(6.8f, 1, 1)});
    EXPECT_FALSE(near.empty());
    EXPECT_EQ(near.primitives, std::vector<uint32_t>{1});
}

// Gradient vs central differences through every operator (h = 1e-3 m; tolerance 3e-3 absolute plus
// 3e-3 relative to |∇f|, see field_primitive_test.cpp). Points near a non-smooth locus of max/min or of
// a clamped cone are skipped by checking that the one-sided differences agree, and so are points inside
// the terrain solid (|f| ~ 1e4).
TEST(DensityField, GradientsMatchFiniteDifferencesThroughEveryOperator) {
    auto ground = hillyField();
    const float h = 1e-3f;
    int checked = 0;
    for (uint64_t seed = 1; seed <= 10; ++seed) {
        const DensityField f = randomField(seed, ground);
        for (uint64_t i = 0; i < 300; ++i) {
            const glm::vec3 p = rndPoint(seed * 17, i, -5, 5);
            const glm::vec4 g = evaluateWithGradient(f, p);
            const double f0 = evaluate(f, p);
            // Below the ground the solid's 1e4 weight leaves float differences no resolution at h = 1e-3.
            if (std::abs(f0) > 100.0) continue;
            bool smooth = true;
            glm::dvec3 fd;
            for (int axis = 0; axis < 3 && smooth; ++axis) {
                glm::vec3 a = p, b = p;
                a[axis] -= h;
                b[axis] += h;
                const double fa = evaluate(f, a), fb = evaluate(f, b);
                const double back = (f0 - fa) / h, fwd = (fb - f0) / h;
                if (std::abs(back - fwd) > 0.05 * (1.0 + std::abs(back))) smooth = false;
                fd[axis] = (fb - fa) / (2.0 * h);
            }
            if (!smooth) continue;
            const double tol = 3e-3 + 3e-3 * glm::length(glm::vec3(g));
            for (int axis = 0; axis < 3; ++axis)
                ASSERT_NEAR(g[axis], fd[axis], tol) << "seed " << seed << " point " << i << " axis " << axis;
            if (g.w != 0.0f) ++checked;
        }
    }
    EXPECT_GT(checked, 300);
}

TEST(DensityField, PositiveBoundsContainEveryPointWithAPositiveValue) {
    auto ground = hillyField();
    for (uint64_t seed = 1; seed <= 20; ++seed) {
        const DensityField f = randomField(seed, ground);
        const Bounds b = positiveBounds(f);
        for (uint64_t i = 0; i < 2000; ++i) {
            const glm::vec3 p = rndPoint(seed * 7, i, -8, 8);
            if (evaluate(f, p) > 0.0f) {
                ASSERT_TRUE(contains(b, p)) << "seed " << seed;
            }
        }
    }
    // Finite for finite primitives, and only the positive ones count.
    const DensityField f = makeBlendField({makePoint({0, 0, 0}, 1.0f), makePoint({10, 0, 0}, 3.0f, -1.0f)});
    const Bounds b = positiveBounds(f);
    EXPECT_NEAR(b.lo.x, -1.0f, 1e-4f);
    EXPECT_NEAR(b.hi.x, 1.0f, 1e-4f);
}

TEST(DensityField, TerrainSolidSubtractionKeepsDetailsAboveTheGround) {
    auto ground = hillyField();
    DensityField f = makeBlendField({makeBox({0, 0, 0}, {4, 4, 4}, 1.0f)});  // density 1 in a big box
    const uint32_t hf = addHeightField(&f, ground);
    subtractSolids(&f, {makeTerrainSolid(hf, 0.05f)});
    std::string error;
    ASSERT_TRUE(validate(f, &error)) << error;
    for (uint64_t i = 0; i < 500; ++i) {
        const glm::vec3 p = rndPoint(3, i, -3, 3);
        const float surface = ground->sample(p.x, p.y);
        if (p.z >= surface) {
            EXPECT_EQ(evaluate(f, p), 1.0f);
        } else if (p.z < surface - 0.01f) {
            EXPECT_LT(evaluate(f, p), 0.0f);
        }
    }
}

TEST(DensityField, PolylineIsAGeneralizedCylinderWithoutBulgesAtJoints) {
    DensityField f;
    const glm::vec4 v[3] = {{0, 0, 0, 1.0f}, {2, 0, 0, 2.0f}, {2, 4, 0, 2.0f}};
    uint32_t ref = 0;
    std::string error;
    ASSERT_TRUE(addPolyline(&f, v, 1.0f, &ref, &error)) << error;
    f.root = ref;
    EXPECT_EQ(f.primitives.size(), 2u);
    EXPECT_EQ(evaluate(f, {2, 0, 0}), 1.0f);           // at the joint: max, not a sum
    EXPECT_EQ(evaluate(f, {1, 0.75f, 0}), kHalfRadius);  // R = 1.5 half way along the first edge
    EXPECT_EQ(evaluate(f, {3, 2, 0}), kHalfRadius);      // R = 2 along the second edge
    EXPECT_EQ(evaluate(f, {0, 3, 0}), 0.0f);  // exactly R = 2 from the second edge
    // Negative weight: an eraser along the same path.
    DensityField g;
    ASSERT_TRUE(addPolyline(&g, v, -0.5f, &ref, &error)) << error;
    g.root = ref;
    EXPECT_EQ(evaluate(g, {2, 0, 0}), -0.5f);
    EXPECT_EQ(evaluate(g, {3, 2, 0}), -0.5f * kHalfRadius);
    // Bad input.
    EXPECT_FALSE(addPolyline(&g, std::span<const glm::vec4>(v, 1), 1.0f, &ref, &error));
    EXPECT_NE(error.find("at least 2 vertices"), std::string::npos) << error;
    const glm::vec4 bad[2] = {{0, 0, 0, 1.0f}, {1, 0, 0, -1.0f}};
    EXPECT_FALSE(addPolyline(&g, bad, 1.0f, &ref, &error));
    EXPECT_NE(error.find("vertex 1 radius"), std::string::npos) << error;
    const glm::vec4 nan[2] = {{0, NAN, 0, 1.0f}, {1, 0, 0, 1.0f}};
    EXPECT_FALSE(addPolyline(&g, nan, 1.0f, &ref, &error));
    EXPECT_NE(error.find("vertex 0 position"), std::string::npos) << error;
}

TEST(DensityField, ValidationNamesTheBrokenPrimitiveOrNode) {
    std::string error;
    DensityField f = makeBlendField({makePoint({0, 0, 0}, 1.0f), makePoint({0, 0, 0}, -2.0f)});
    EXPECT_FALSE(validate(f, &error));
    EXPECT_NE(error.find("primitive 1 (point): radius_m"), std::string::npos) << error;

    f = makeBlendField({makePoint({0, 0, 0}, 1.0f)});
    f.children.push_back(nodeChild(5));
    f.nodes.push_back(FieldNode{FieldOp::Union, uint32_t(f.children.size() - 1), 1});
    EXPECT_FALSE(validate(f, &error));
    EXPECT_NE(error.find("node 1 (union): child 0 refers to node 5"), std::string::npos) << error;

    f = makeBlendField({makePoint({0, 0, 0}, 1.0f)});
    f.children[0] = primitiveChild(3);
    EXPECT_FALSE(validate(f, &error));
    EXPECT_NE(error.find("primitive 3"), std::string::npos) << error;

    f = makeBlendField({makePoint({0, 0, 0}, 1.0f)});
    f.root = 4;
    EXPECT_FALSE(validate(f, &error));
    EXPECT_NE(error.find("root 4"), std::string::npos) << error;

    f = makeBlendField({makeTerrainLayer(0, 1.0f, 1.0f)});
    EXPECT_FALSE(validate(f, &error));
    EXPECT_NE(error.find("height_field 0 is out of range"), std::string::npos) << error;
}

}  // namespace
}  // namespace ug
