// positiveBoundsIn() and HeightField::heightRange(): the instantiator skips candidates outside these
// bounds without evaluating the field, so they must never leave out a point where the field is positive.
#include <random>

#include <gtest/gtest.h>

#include "field/density_field.h"
#include "field/height_field.h"

namespace ug {
namespace {

std::shared_ptr<const HeightField> terrain() {
    auto hf = std::make_shared<HeightField>();
    std::string error;
    EXPECT_TRUE(makeProceduralHeightField({.origin_m = {-8, -8}, .cell_size_m = 0.5f, .width = 33, .height = 33,
                                           .seed = 3, .amplitude_m = 1.5f, .feature_size_m = 6.0f},
                                          hf.get(), &error))
        << error;
    return hf;
}

TEST(HeightRange, BoundsEveryBilinearHeightInTheRectangle) {
    auto hf = terrain();
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-10.0f, 10.0f), len(0.0f, 3.0f);
    for (int k = 0; k < 300; ++k) {
        const glm::vec2 lo(u(rng), u(rng));
        const glm::vec2 hi = lo + glm::vec2(len(rng), len(rng));
        const glm::vec2 r = hf->heightRange(lo, hi);
        ASSERT_LE(r.x, r.y);
        for (int s = 0; s < 49; ++s) {
            const float x = lo.x + (hi.x - lo.x) * float(s % 7) / 6.0f, y = lo.y + (hi.y - lo.y) * float(s / 7) / 6.0f;
            const float h = hf->sample(x, y);
            ASSERT_GE(h, r.x - 1e-5f);
            ASSERT_LE(h, r.y + 1e-5f);
        }
    }
    // The whole field: its global range; a tiny rectangle: a range far narrower.
    const glm::vec2 all = hf->heightRange({-100, -100}, {100, 100});
    EXPECT_EQ(all, glm::vec2(hf->minHeight(), hf->maxHeight()));
    const glm::vec2 small = hf->heightRange({0.1f, 0.1f}, {0.3f, 0.3f});
    EXPECT_LT(small.y - small.x, (all.y - all.x) * 0.5f);
}

TEST(PositiveBoundsIn, NeverLeavesOutAPositivePoint) {
    DensityField f;
    const uint32_t ground = addHeightField(&f, terrain());
    const uint32_t layer = addPrimitive(&f, makeTerrainLayer(ground, 0.1f, 0.2f, 0.8f));
    const uint32_t ball = addPrimitive(&f, makePoint({1, 2, 0.5f}, 1.5f, 2.0f));
    const uint32_t slab = addPrimitive(&f, makeBox({-3, 0, 0}, {1, 2, 0.5f}, 0.3f, 1.0f));
    const uint32_t hole = addPrimitive(&f, makePoint({1, 2, 0.5f}, 0.7f, 5.0f));
    const uint32_t neg = addPrimitive(&f, makePoint({-3, 1, 0}, 0.5f, -3.0f));
    const uint32_t blend_refs[] = {primitiveChild(layer), primitiveChild(ball), primitiveChild(neg)};
    const uint32_t blend = addNode(&f, FieldOp::Blend, blend_refs);
    const uint32_t inter_refs[] = {primitiveChild(slab), nodeChild(blend)};
    const uint32_t inter = addNode(&f, FieldOp::Intersection, inter_refs);
    const uint32_t uni_refs[] = {nodeChild(blend), nodeChild(inter)};
    const uint32_t uni = addNode(&f, FieldOp::Union, uni_refs);
    const uint32_t diff_refs[] = {nodeChild(uni), primitiveChild(hole)};
    f.root = addNode(&f, FieldOp::Difference, diff_refs);
    subtractSolids(&f, {makeTerrainSolid(ground, 0.05f)});
    std::string error;
    ASSERT_TRUE(validate(f, &error)) << error;

    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-6.0f, 6.0f), z(-2.0f, 2.5f), len(0.2f, 2.0f), t(0.0f, 1.0f);
    size_t positive_points = 0, skipped_boxes = 0;
    for (int k = 0; k < 400; ++k) {
        const glm::vec3 lo(u(rng), u(rng), z(rng));
        const Bounds box{lo, lo + glm::vec3(len(rng), len(rng), len(rng))};
        TileFieldList list;
        buildTileList(f, box, &list);
        const Bounds pos = positiveBoundsIn(f, list);
        if (pos.empty()) ++skipped_boxes;
        for (int s = 0; s < 200; ++s) {
            const glm::vec3 p = box.lo + (box.hi - box.lo) * glm::vec3(t(rng), t(rng), t(rng));
            if (evaluate(f, p) > 0.0f) {
                ++positive_points;
                ASSERT_TRUE(contains(pos, p)) << "positive point outside the local bounds";
            }
        }
    }
    EXPECT_GT(positive_points, 1000u);
    EXPECT_GT(skipped_boxes, 50u);  // and the bounds do prune
}

}  // namespace
}  // namespace ug
