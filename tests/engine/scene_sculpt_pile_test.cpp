// The Sculpt tool's pile math (scene/sculpt_pile.h): one vertical cone primitive per held spot, whose
// isosurface stands at the material's angle of repose, measured the way the editor's statistics do.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/sculpt_pile.h"

namespace ug {
namespace {

constexpr float kIso = 0.5f;

TEST(SculptPile, IsoRadiusFactorIsWhereAPointReachesTheIso) {
    for (float w : {0.6f, 1.0f, 2.5f}) {
        const float f = isoRadiusFactor(w, kIso);
        ASSERT_GT(f, 0.0f);
        EXPECT_NEAR(primitiveValue(makePoint(glm::vec3(0.0f), 2.0f, w), nullptr, glm::vec3(2.0f * f, 0, 0)), kIso,
                    1e-4f);
    }
    EXPECT_EQ(isoRadiusFactor(0.5f, kIso), 0.0f);  // never reaches the isosurface
    EXPECT_EQ(isoRadiusFactor(-1.0f, kIso), 0.0f);
}

TEST(SculptPile, ConeForVolumeStandsAtTheAngleOfRepose) {
    for (float deg : {20.0f, 35.0f, 50.0f, 89.0f}) {
        const PileCone c = pileConeForVolume(glm::vec3(1, 2, 3), 5.0f, deg);
        EXPECT_NEAR(c.height_m / c.base_radius_m, std::tan(glm::radians(deg)), 1e-4f * std::tan(glm::radians(deg)));
        EXPECT_NEAR(3.14159265f * c.base_radius_m * c.base_radius_m * c.height_m / 3.0f, 5.0f, 1e-3f);
        EXPECT_EQ(c.base_m, glm::vec3(1, 2, 3));
    }
    // Twice the material: every length grows by the cube root of 2.
    const PileCone a = pileConeForVolume(glm::vec3(0), 1.0f, 35.0f), b = pileConeForVolume(glm::vec3(0), 2.0f, 35.0f);
    EXPECT_NEAR(b.base_radius_m / a.base_radius_m, std::cbrt(2.0f), 1e-4f);
}

// The primitive's isosurface, measured from vertical columns over the ground through its base, is the
// cone: centred on the base, tan(angle) high per metre of radius, whatever the angle.
TEST(SculptPile, ConePrimitiveIsosurfaceIsTheCone) {
    for (float deg : {25.0f, 35.0f, 50.0f}) {
        SCOPED_TRACE(deg);
        const glm::vec3 base(3.0f, -4.0f, 1.5f);
        const PileCone cone = pileConeForVolume(base, 2.0f, deg);
        const Primitive prim = pileConePrimitive(cone, 1.0f, kIso);
        EXPECT_EQ(prim.kind, PrimitiveKind::Segment);
        EXPECT_EQ(prim.center_m, base);
        EXPECT_EQ(prim.end_m.x, base.x);  // the axis is vertical
        EXPECT_EQ(prim.end_m.y, base.y);
        EXPECT_GT(prim.end_m.z, base.z);
        std::string error;
        ASSERT_TRUE(validatePrimitive(prim, 0, 0, &error)) << error;
        const DensityField field = makeBlendField({prim});
        const PileMeasure m = measurePile(
            [&](glm::vec2 xy) { return pileThicknessOverPlane(field, kIso, xy, base.z, base.z + 20.0f); },
            glm::vec2(base), 1.5f * cone.base_radius_m, 0.02f);
        ASSERT_TRUE(m.found);
        EXPECT_LT(glm::length(m.centroid_m - glm::vec2(base)), 0.01f);
        EXPECT_NEAR(m.height_m, cone.height_m, 0.02f * cone.height_m + 0.01f);
        EXPECT_NEAR(m.radius_m, cone.base_radius_m, 0.03f * cone.base_radius_m + 0.02f);
        const float ratio = m.height_m / m.radius_m;
        EXPECT_NEAR(ratio, std::tan(glm::radians(deg)), 0.1f * std::tan(glm::radians(deg)));
        // A cone holds a third of its cylinder; a column or a dome would hold more.
        EXPECT_NEAR(m.volume_m3 / (3.14159265f * m.radius_m * m.radius_m * m.height_m), 1.0f / 3.0f, 0.05f);
    }
}

TEST(SculptPile, ConesAreRecognisedOtherSegmentsNot) {
    EXPECT_TRUE(isPileCone(pileConePrimitive(pileConeForVolume(glm::vec3(1, 1, 0), 1.0f, 35.0f), 1.0f, kIso)));
    EXPECT_FALSE(isPileCone(makeSegment(glm::vec3(0), glm::vec3(0, 0, 1), 0.5f)));           // a capsule
    EXPECT_FALSE(isPileCone(makeCone(glm::vec3(0), 1.0f, glm::vec3(0.1f, 0, 1), 0.2f)));      // leaning
    EXPECT_FALSE(isPileCone(makePoint(glm::vec3(0), 1.0f)));
}

TEST(SculptPile, MeasureFindsNothingOnBareGround) {
    const PileMeasure m = measurePile([](glm::vec2) { return 0.0f; }, glm::vec2(0.0f), 2.0f, 0.1f);
    EXPECT_FALSE(m.found);
    EXPECT_EQ(m.columns, 0);
}

}  // namespace
}  // namespace ug
