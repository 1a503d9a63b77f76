#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "mesh/procedural_models.h"

namespace ug {

// Closed (every directed edge has its reverse exactly once) and outward (positive signed volume).
TEST(ProceduralModels, AreClosedOutwardCentredAndModest) {
    const std::map<std::string, std::pair<float, float>> size_range_m = {
        {"rock", {0.10f, 0.15f}},     {"flat_stone", {0.12f, 0.18f}}, {"pebble", {0.03f, 0.05f}},
        {"leaf_oak", {0.08f, 0.13f}}, {"leaf_birch", {0.07f, 0.12f}}, {"twig", {0.25f, 0.35f}},
        {"grass_tuft", {0.07f, 0.13f}}, {"mushroom", {0.08f, 0.15f}}, {"pine_needles", {0.06f, 0.10f}},
        {"hay_wisp", {0.15f, 0.25f}},   {"leaf_oak_dry", {0.06f, 0.12f}}, {"leaf_birch_dry", {0.06f, 0.11f}},
        {"leaf_oak_wet", {0.08f, 0.13f}}, {"leaf_birch_wet", {0.07f, 0.12f}}, {"petal", {0.03f, 0.045f}},
        {"trash_can", {0.10f, 0.14f}}, {"trash_paper", {0.055f, 0.085f}}, {"trash_cup", {0.08f, 0.10f}},
        {"trash_bottle", {0.17f, 0.23f}}, {"grass_tuft_dried", {0.07f, 0.18f}}};
    for (const std::string& name : starterAssetNames()) {
        SCOPED_TRACE(name);
        TriangleMesh m;
        ASSERT_TRUE(makeStarterAsset(name, kStarterAssetSeed, &m));
        std::string error;
        ASSERT_TRUE(validateMesh(m, &error)) << error;
        EXPECT_GE(m.triangleCount(), 200u);
        EXPECT_LE(m.triangleCount(), 3000u);
        const Bounds3 b = meshBounds(m);
        EXPECT_LT(glm::length(b.min + b.max), 1e-5f);  // centred on the box
        const glm::vec3 e = b.max - b.min;
        const float size = std::max(e.x, std::max(e.y, e.z));
        EXPECT_GE(size, size_range_m.at(name).first);
        EXPECT_LE(size, size_range_m.at(name).second);
        std::map<std::pair<uint32_t, uint32_t>, int> edges;
        double volume = 0.0;
        for (size_t t = 0; t < m.indices.size(); t += 3) {
            const glm::vec3 a = m.positions[m.indices[t]], p = m.positions[m.indices[t + 1]], c = m.positions[m.indices[t + 2]];
            volume += double(glm::dot(a, glm::cross(p, c))) / 6.0;
            for (int k = 0; k < 3; ++k) edges[{m.indices[t + k], m.indices[t + (k + 1) % 3]}]++;
        }
        int open = 0;
        for (const auto& [edge, n] : edges) open += (n != 1 || !edges.count({edge.second, edge.first}));
        EXPECT_EQ(open, 0);
        EXPECT_GT(volume, 0.0);
    }
}

TEST(ProceduralModels, AreDeterministicInTheSeed) {
    EXPECT_EQ(makeOakLeaf(4).positions, makeOakLeaf(4).positions);
    EXPECT_NE(makeRock(4).positions, makeRock(5).positions);
    TriangleMesh unused;
    EXPECT_FALSE(makeStarterAsset("unicorn", 1, &unused));
}

}  // namespace ug

namespace ug {

TEST(ProceduralModels, ScannedRockIsClosedOutwardAndSized) {
    for (uint32_t target : {20u, 5000u, 100000u}) {
        SCOPED_TRACE(target);
        const TriangleMesh m = makeScannedRock(target, 3);
        std::string error;
        ASSERT_TRUE(validateMesh(m, &error)) << error;
        // 20 k^2 triangles, k rounded: off by at most sqrt(20 target) + 5.
        EXPECT_NEAR(double(m.triangleCount()), double(target), std::sqrt(20.0 * target) + 5.0);
        EXPECT_EQ(m.normals.size(), m.positions.size());
        EXPECT_EQ(m.positions.size(), m.triangleCount() / 2 + 2);  // a closed genus-0 triangle mesh
        const Bounds3 b = meshBounds(m);
        EXPECT_LT(glm::length(b.min + b.max), 1e-5f);
        const glm::vec3 e = b.max - b.min;
        EXPECT_GE(std::max(e.x, std::max(e.y, e.z)), 0.6f);
        EXPECT_LE(std::max(e.x, std::max(e.y, e.z)), 1.4f);
        if (target > 5000) continue;  // the edge check is for the small ones (a map of every edge)
        std::map<std::pair<uint32_t, uint32_t>, int> edges;
        double volume = 0.0;
        for (size_t t = 0; t < m.indices.size(); t += 3) {
            const glm::vec3 a = m.positions[m.indices[t]], p = m.positions[m.indices[t + 1]],
                            c = m.positions[m.indices[t + 2]];
            volume += double(glm::dot(a, glm::cross(p, c))) / 6.0;
            for (int k = 0; k < 3; ++k) edges[{m.indices[t + k], m.indices[t + (k + 1) % 3]}]++;
        }
        int open = 0;
        for (const auto& [edge, n] : edges) open += (n != 1 || !edges.count({edge.second, edge.first}));
        EXPECT_EQ(open, 0);
        EXPECT_GT(volume, 0.0);
    }
    EXPECT_EQ(makeScannedRock(3000, 8).positions, makeScannedRock(3000, 8).positions);
    EXPECT_NE(makeScannedRock(3000, 8).positions, makeScannedRock(3000, 9).positions);
}

}  // namespace ug
