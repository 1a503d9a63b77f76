// The Sculpt tool's pile math (scene/sculpt_pile.h): one vertical cone primitive per held spot, whose
// isosurface stands at the material's angle of repose, measured the way the editor's statistics do.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

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

// A bed sampled from a known surface: bed(xy) on (2 n + 1)² cells of `cell` around `centre`.
PileBed bedOf(glm::vec2 centre, float cell, int n, const std::function<float(glm::vec2)>& height) {
    PileBed bed;
    bed.centre_m = centre;
    bed.cell_m = cell;
    bed.half_cells = n;
    for (int j = -n; j <= n; ++j)
        for (int i = -n; i <= n; ++i) bed.height_m.push_back(height(centre + cell * glm::vec2(i, j)));
    return bed;
}

// Material poured onto a pile adds its volume above the pile at the angle of repose (pileConeOnBed): on
// nothing it is the lone cone; on a plateau it is the lone cone lifted by the plateau; poured on the top
// of a cone of the same angle it makes the cone of both volumes; on the flank of one it rises above it.
TEST(SculptPile, ConeOnABedAddsItsVolumeAboveTheBed) {
    const float deg = 35.0f, slope = std::tan(glm::radians(deg));
    const glm::vec3 base(1.0f, -2.0f, 0.5f);
    const float v = 0.16f;
    const PileCone lone = pileConeForVolume(base, v, deg);
    const PileCone on_nothing = pileConeOnBed(base, bedOf(glm::vec2(base), 0.05f, 20, [](glm::vec2) { return 0.0f; }), v, deg);
    EXPECT_EQ(on_nothing.height_m, lone.height_m);
    EXPECT_EQ(on_nothing.base_radius_m, lone.base_radius_m);

    const PileCone on_plateau =
        pileConeOnBed(base, bedOf(glm::vec2(base), 0.01f, 150, [](glm::vec2) { return 0.3f; }), v, deg);
    EXPECT_NEAR(on_plateau.height_m, 0.3f + lone.height_m, 0.02f * lone.height_m);
    EXPECT_NEAR(on_plateau.height_m / on_plateau.base_radius_m, slope, 1e-4f);
    EXPECT_EQ(on_plateau.base_m, base);

    const PileCone old = pileConeForVolume(base, 0.5f, deg);
    auto old_surface = [&](glm::vec2 xy) {
        return std::max(0.0f, old.height_m - slope * glm::length(xy - glm::vec2(base)));
    };
    const PileCone on_top = pileConeOnBed(base, bedOf(glm::vec2(base), 0.01f, 150, old_surface), v, deg);
    EXPECT_NEAR(on_top.height_m, pileConeForVolume(base, 0.5f + v, deg).height_m, 0.01f * on_top.height_m);

    // On the flank, 0.3 m from the old apex: higher than the flank there plus nothing, lower than the old
    // apex plus a lone cone.
    const glm::vec3 flank = base + glm::vec3(0.3f, 0.0f, 0.0f);
    const PileCone on_flank = pileConeOnBed(flank, bedOf(glm::vec2(flank), 0.01f, 150, old_surface), v, deg);
    EXPECT_GT(on_flank.height_m, old_surface(glm::vec2(flank)) + 0.2f * lone.height_m);
    EXPECT_LT(on_flank.height_m, old.height_m + lone.height_m);
    EXPECT_GT(on_flank.height_m, lone.height_m);
}

}  // namespace
}  // namespace ug
