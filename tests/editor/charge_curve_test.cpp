// The Particles window's a(t) curve editor without ImGui (app/editor/charge_curve.h): keys map to the plot
// and back, stay strictly ordered however they are dragged, are added on the curve and never all removed.
#include <gtest/gtest.h>

#include "editor/charge_curve.h"

namespace ug::editor {
namespace {

ChargeCurveFrame frame() {
    ChargeCurveFrame f;  // 200 x 100 px at (10, 20); steps 0..40 across, charges -2..2 up
    f.min_px = {10, 20};
    f.max_px = {210, 120};
    f.steps = 40;
    f.lo = -2.0f;
    f.hi = 2.0f;
    return f;
}

TEST(ChargeCurve, KeysMapToThePlotAndBack) {
    const ChargeCurveFrame f = frame();
    EXPECT_EQ(chargeKeyPixel(f, {0, -2.0f}), glm::vec2(10, 120));   // bottom left
    EXPECT_EQ(chargeKeyPixel(f, {40, 2.0f}), glm::vec2(210, 20));   // top right
    EXPECT_EQ(chargeKeyPixel(f, {20, 0.0f}), glm::vec2(110, 70));   // the middle
    EXPECT_EQ(chargeKeyAtPixel(f, {110, 70}), (ChargeKey{20, 0.0f}));
    EXPECT_EQ(chargeKeyAtPixel(f, {62, 45}), (ChargeKey{10, 1.0f}));  // 52/200 of 40 steps rounds to 10
    // Outside the plot: clamped to its steps and range.
    EXPECT_EQ(chargeKeyAtPixel(f, {-50, -50}), (ChargeKey{0, 2.0f}));
    EXPECT_EQ(chargeKeyAtPixel(f, {500, 500}), (ChargeKey{40, -2.0f}));
}

TEST(ChargeCurve, TheRangeHoldsEveryKeyAndZero) {
    float lo = 0, hi = 0;
    chargeCurveRange({{0, 0.0f}}, &lo, &hi);
    EXPECT_EQ(lo, -1.0f);
    EXPECT_EQ(hi, 1.0f);
    chargeCurveRange({{0, 0.5f}, {10, -3.0f}}, &lo, &hi);
    EXPECT_EQ(hi, 3.75f);  // the largest magnitude with a quarter to spare, symmetric
    EXPECT_EQ(lo, -3.75f);
    chargeCurveRange({{0, 1e6f}}, &lo, &hi);
    EXPECT_EQ(hi, kMaxChargeMagnitude);
}

TEST(ChargeCurve, PicksTheNearestKeyWithinReach) {
    const ChargeCurveFrame f = frame();
    const std::vector<ChargeKey> keys = {{0, 1.0f}, {20, 0.0f}, {24, 0.0f}};
    EXPECT_EQ(nearestChargeKey(keys, f, {111, 72}, 8.0f), 1u);
    EXPECT_EQ(nearestChargeKey(keys, f, {128, 70}, 8.0f), 2u);  // step 24 is at x = 130
    EXPECT_EQ(nearestChargeKey(keys, f, {160, 70}, 8.0f), kNoChargeKey);
}

TEST(ChargeCurve, ADraggedKeyStaysBetweenItsNeighbours) {
    std::vector<ChargeKey> keys = {{0, 1.0f}, {10, 0.0f}, {20, -1.0f}};
    EXPECT_TRUE(moveChargeKey(&keys, 1, {35, 0.5f}));
    EXPECT_EQ(keys[1], (ChargeKey{19, 0.5f}));  // not past step 20
    EXPECT_TRUE(moveChargeKey(&keys, 1, {0, 0.5f}));
    EXPECT_EQ(keys[1], (ChargeKey{1, 0.5f}));   // not onto step 0
    EXPECT_TRUE(moveChargeKey(&keys, 2, {500, 1e9f}));
    EXPECT_EQ(keys[2], (ChargeKey{500, kMaxChargeMagnitude}));  // the last key goes anywhere after step 1
    EXPECT_FALSE(moveChargeKey(&keys, 2, {500, 1e9f}));          // no move
    EXPECT_FALSE(moveChargeKey(&keys, 3, {5, 0.0f}));            // no such key
    ParticleScene s;
    s.attractors.push_back({});
    s.attractors[0].charge = keys;
    std::string error;
    EXPECT_TRUE(validateParticleScene(s, &error)) << error;      // still strictly increasing
}

TEST(ChargeCurve, KeysAreAddedInOrderAndNeverAllRemoved) {
    std::vector<ChargeKey> keys = {{0, 1.0f}, {20, -1.0f}};
    EXPECT_EQ(insertChargeKey(&keys, {10, chargeAt(keys, 10)}), 1u);
    EXPECT_EQ(keys[1], (ChargeKey{10, 0.0f}));  // on the curve: a(10) halfway between +1 and -1
    EXPECT_EQ(insertChargeKey(&keys, {30, 5.0f}), 3u);
    EXPECT_EQ(insertChargeKey(&keys, {10, 2.0f}), kNoChargeKey);  // step 10 is keyed already
    EXPECT_EQ(keys.size(), 4u);
    EXPECT_TRUE(removeChargeKey(&keys, 0));
    EXPECT_TRUE(removeChargeKey(&keys, 0));
    EXPECT_TRUE(removeChargeKey(&keys, 0));
    EXPECT_FALSE(removeChargeKey(&keys, 0));  // a charge needs one key
    EXPECT_FALSE(removeChargeKey(&keys, 7));
    EXPECT_EQ(keys, (std::vector<ChargeKey>{{30, 5.0f}}));
}

}  // namespace
}  // namespace ug::editor
