// Silhouette areas (coverage.h) of shapes whose projections are known exactly.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "editor/coverage.h"

namespace ug::editor {
namespace {

struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
};

// An axis-aligned box of sides (a, b, c), closed, 12 triangles.
Mesh box(float a, float b, float c) {
    Mesh m;
    for (int k = 0; k < 8; ++k)
        m.positions.push_back(glm::vec3((k & 1) ? a : 0.0f, (k & 2) ? b : 0.0f, (k & 4) ? c : 0.0f));
    const uint32_t faces[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    for (const auto& f : faces) m.indices.insert(m.indices.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
    return m;
}

CoverageProfile cover(const Mesh& m) { return measureCoverage(m.positions, m.indices.data(), m.indices.size(), 256); }

TEST(Coverage, ACubeFromAboveIsItsFaceAndFromTheSideItsProjectedWidth) {
    const CoverageProfile c = cover(box(1.0f, 1.0f, 1.0f));
    EXPECT_NEAR(c.area_m2[3], 1.0f, 0.03f);  // straight down: one face
    // Horizontal views at azimuths (k + 1/2) 45 degrees: the width |cos| + |sin| times the height 1.
    const float w = std::cos(0.3926991f) + std::sin(0.3926991f);
    EXPECT_NEAR(c.area_m2[0], w, 0.03f);
}

TEST(Coverage, AFlatSheetVanishesEdgeOnAndOverlapsCountOnce) {
    // A 1 x 1 sheet 1 mm thick: from the side almost nothing, from above its area.
    const CoverageProfile one = cover(box(1.0f, 1.0f, 0.001f));
    EXPECT_NEAR(one.area_m2[3], 1.0f, 0.03f);
    EXPECT_LT(one.area_m2[0], 0.02f);
    EXPECT_NEAR(one.area_m2[1], std::sin(0.5235988f), 0.04f);  // 30 degrees up: the sheet foreshortened
    // Two coincident sheets cover what one does (a union, not a sum of triangle areas).
    Mesh two = box(1.0f, 1.0f, 0.001f);
    const Mesh other = box(1.0f, 1.0f, 0.001f);
    const uint32_t base = uint32_t(two.positions.size());
    two.positions.insert(two.positions.end(), other.positions.begin(), other.positions.end());
    for (uint32_t i : other.indices) two.indices.push_back(base + i);
    EXPECT_NEAR(cover(two).area_m2[3], one.area_m2[3], 1e-6f);
}

TEST(Coverage, NothingCoversNothing) {
    const std::vector<glm::vec3> none;
    const CoverageProfile c = measureCoverage(none, nullptr, 0);
    for (float a : c.area_m2) EXPECT_EQ(a, 0.0f);
}

}  // namespace
}  // namespace ug::editor
