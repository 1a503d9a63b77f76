// The Particles window's overlay (markers.h addParticleMarkers): where the skeletons are drawn.
#include <gtest/gtest.h>

#include "editor/markers.h"

namespace ug::editor {
namespace {

TEST(ParticleMarkers, AttractorsGeneratorsAndCuttersAreDrawnWhereTheyAct) {
    ParticleSystemFile system;
    ParticleGenerator g;
    g.center_m = {0.0f, 0.0f, 0.0f};
    g.axis_u_m = {0.5f, 0.0f, 0.0f};
    g.axis_v_m = {0.0f, 0.25f, 0.0f};
    system.scene.generators.push_back(g);
    Attractor repel;
    repel.a_m = {1.0f, 2.0f, 3.0f};
    repel.influence_m = 0.5f;
    repel.charge = {ChargeKey{0, -1.0f}, ChargeKey{10, 2.0f}};
    system.scene.attractors.push_back(repel);
    Cutter cut;
    cut.center_m = {0.0f, 0.0f, 0.1f};
    cut.threshold_m = 0.2f;
    system.scene.cutters.push_back(cut);
    MarkerGeometry m;
    addParticleMarkers(system, ParticleHandle{ParticlePart::Cutter, 0}, &m);

    // The attractor: a dot at its place, red (repelling at step 0), and its reach as three circles.
    ASSERT_FALSE(m.points.empty());
    EXPECT_EQ(m.points[0].position, repel.a_m);
    EXPECT_EQ(m.points[0].color, kRepelColor);
    size_t reach = 0, outline = 0, cutter = 0;
    for (const MarkerVertex& v : m.lines) {
        if (v.color == kRepelColor * 0.7f) {
            EXPECT_NEAR(glm::length(v.position - repel.a_m), 0.5f, 1e-5f);
            ++reach;
        } else if (v.color == kGeneratorColor) {
            EXPECT_NEAR(std::abs(v.position.x), 0.5f, 1e-6f);
            EXPECT_NEAR(std::abs(v.position.y), 0.25f, 1e-6f);
            EXPECT_EQ(v.position.z, 0.0f);
            ++outline;
        } else if (v.color == kCutterColor) {
            EXPECT_GE(v.position.z, 0.3f - 1e-6f);  // the plane where it triggers: centre + threshold
            ++cutter;
        }
    }
    EXPECT_EQ(reach, 3u * 2u * 32u);
    EXPECT_EQ(outline, 8u);
    EXPECT_EQ(cutter, 10u);  // the square and the normal's tick
    // Every handle's dot where the Select tool picks it: the generator's centre in blue, the cutter's
    // point on its plane in the selection's colour (it is the one selected), then their tilt dots at the
    // tips of their normals.
    ASSERT_EQ(m.points.size(), 5u);
    EXPECT_EQ(m.points[3].color, kGeneratorColor);
    EXPECT_EQ(m.points[4].position, glm::vec3(0.0f, 0.0f, 0.4f));
    EXPECT_EQ(m.points[4].color, kCutterColor);
    EXPECT_EQ(m.points[1].position, g.center_m);
    EXPECT_EQ(m.points[1].color, kGeneratorColor);
    EXPECT_EQ(m.points[2].position, glm::vec3(0.0f, 0.0f, 0.3f));
    EXPECT_EQ(m.points[2].color, kSelectedColor);
}

}  // namespace
}  // namespace ug::editor
