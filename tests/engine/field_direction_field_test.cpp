// Direction and size control fields.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <string>

#include "field/direction_field.h"

namespace ug {
namespace {

std::shared_ptr<const DensityField> ball() {
    return std::make_shared<DensityField>(makeBlendField({makePoint({0, 0, 0}, 2.0f)}));
}

TEST(DirectionField, ConstantReturnsItsDirection) {
    DirectionField d;
    EXPECT_EQ(evaluateDirection(d, nullptr, {3, 4, 5}), glm::vec3(0, 0, 1));
    d.direction = glm::vec3(1, 0, 0);
    EXPECT_EQ(evaluateDirection(d, nullptr, {3, 4, 5}), glm::vec3(1, 0, 0));
}

TEST(DirectionField, GradientIsNormalizedAndFallsBackToUpWhereFlat) {
    DirectionField d{.kind = DirectionFieldKind::Gradient, .field = ball()};
    const glm::vec3 u = evaluateDirection(d, nullptr, {1, 0, 0});  // a ball's density grows inwards
    EXPECT_NEAR(u.x, -1.0f, 1e-6f);
    EXPECT_NEAR(glm::length(u), 1.0f, 1e-6f);
    EXPECT_EQ(evaluateDirection(d, nullptr, {0, 0, 0}), glm::vec3(0, 0, 1));   // centre: flat
    EXPECT_EQ(evaluateDirection(d, nullptr, {9, 0, 0}), glm::vec3(0, 0, 1));   // outside: flat
    const TileFieldList list = buildTileList(*d.field, Bounds{glm::vec3(0), glm::vec3(1)});
    const glm::vec3 p(0.5f, 0.25f, 0.75f);
    const glm::vec3 a = evaluateDirection(d, nullptr, p), b = evaluateDirection(d, &list, p);
    EXPECT_EQ(std::memcmp(&a, &b, sizeof(a)), 0);
}

TEST(SizeField, RampMapsFieldValuesLinearlyAndClamps) {
    SizeField s{.kind = SizeFieldKind::Ramp, .field = ball(), .value_lo = 0.0f, .value_hi = 1.0f,
                .scale_lo = 0.5f, .scale_hi = 1.5f};
    EXPECT_EQ(evaluateSize(s, nullptr, {0, 0, 0}), 1.5f);       // f = 1
    EXPECT_EQ(evaluateSize(s, nullptr, {9, 0, 0}), 0.5f);       // f = 0
    EXPECT_EQ(evaluateSize(s, nullptr, {1, 0, 0}), 0.921875f);  // f = 0.421875
    s.value_hi = 0.5f;
    EXPECT_EQ(evaluateSize(s, nullptr, {0, 0, 0}), 1.5f);  // clamped above
    EXPECT_EQ(evaluateSize(SizeField{.scale = 2.0f}, nullptr, {0, 0, 0}), 2.0f);
}

TEST(SizeField, ValidationRejectsBadSettings) {
    std::string error;
    EXPECT_TRUE(validate(SizeField{}, &error)) << error;
    EXPECT_FALSE(validate(SizeField{.scale = -1.0f}, &error));
    EXPECT_NE(error.find("scale"), std::string::npos) << error;
    EXPECT_FALSE(validate(SizeField{.kind = SizeFieldKind::Ramp}, &error));
    EXPECT_NE(error.find("needs a density field"), std::string::npos) << error;
    EXPECT_FALSE(validate(SizeField{.kind = SizeFieldKind::Ramp, .field = ball(), .value_lo = 1.0f, .value_hi = 1.0f},
                          &error));
    EXPECT_NE(error.find("value_lo < value_hi"), std::string::npos) << error;
    EXPECT_FALSE(validate(DirectionField{.direction = glm::vec3(0, 0, 2)}, &error));
    EXPECT_NE(error.find("unit"), std::string::npos) << error;
    EXPECT_FALSE(validate(DirectionField{.kind = DirectionFieldKind::Gradient}, &error));
    EXPECT_TRUE(validate(DirectionField{.kind = DirectionFieldKind::Gradient, .field = ball()}, &error)) << error;
}

}  // namespace
}  // namespace ug
