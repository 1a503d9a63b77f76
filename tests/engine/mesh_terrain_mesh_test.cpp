// Height field -> terrain mesh: exact samples at full resolution, decimation bound, clipping, errors.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "field/height_field.h"
#include "mesh/terrain_mesh.h"

namespace ug {
namespace {

HeightField proceduralField(int width, int height, glm::vec2 origin = glm::vec2(0.0f), float cell = 1.0f) {
    ProceduralTerrainDesc desc;
    desc.origin_m = origin;
    desc.cell_size_m = cell;
    desc.width = width;
    desc.height = height;
    desc.seed = 11;
    desc.amplitude_m = 3.0f;
    HeightField hf;
    std::string error;
    EXPECT_TRUE(makeProceduralHeightField(desc, &hf, &error)) << error;
    return hf;
}

Bounds xyExtent(float x0, float y0, float x1, float y1) {
    return Bounds{glm::vec3(x0, y0, -1.0f), glm::vec3(x1, y1, 1.0f)};
}

// Distinct X and Y coordinates of the grid, i.e. the grid lines.
std::set<float> distinct(const TriangleMesh& m, int axis) {
    std::set<float> values;
    for (const glm::vec3& p : m.positions) values.insert(p[axis]);
    return values;
}

void expectFacesUp(const TriangleMesh& m) {
    for (size_t t = 0; t < m.indices.size(); t += 3) {
        const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                        c = m.positions[m.indices[t + 2]];
        ASSERT_GT(glm::cross(b - a, c - a).z, 0.0f) << "triangle " << t / 3;
    }
}

}  // namespace

TEST(TerrainMesh, FullResolutionCarriesTheExactSamples) {
    const HeightField hf = proceduralField(33, 17, glm::vec2(-5.0f, 2.0f), 0.5f);
    TriangleMesh m;
    std::string error;
    ASSERT_TRUE(heightFieldMesh(hf, Bounds::everything(), 1000, &m, &error)) << error;
    ASSERT_TRUE(validateMesh(m, &error)) << error;
    ASSERT_EQ(m.positions.size(), 33u * 17u);
    EXPECT_EQ(m.triangleCount(), 32u * 16u * 2u);
    ASSERT_EQ(m.normals.size(), m.positions.size());
    for (int j = 0; j < 17; ++j) {
        for (int i = 0; i < 33; ++i) {
            const glm::vec3 p = m.positions[size_t(j) * 33 + size_t(i)];
            EXPECT_EQ(p.x, -5.0f + 0.5f * float(i));
            EXPECT_EQ(p.y, 2.0f + 0.5f * float(j));
            EXPECT_EQ(p.z, hf.at(i, j));
        }
    }
    for (const glm::vec3& n : m.normals) {
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
        EXPECT_GT(n.z, 0.0f);
    }
    expectFacesUp(m);
    EXPECT_EQ(m.base_color, kTerrainColor);
}

TEST(TerrainMesh, DecimationKeepsAtMostTheCellBudgetAndStaysOnTheField) {
    const HeightField hf = proceduralField(129, 65);
    for (int budget : {1, 2, 3, 7, 16, 64, 128, 500}) {
        SCOPED_TRACE(budget);
        TriangleMesh m;
        std::string error;
        ASSERT_TRUE(heightFieldMesh(hf, Bounds::everything(), budget, &m, &error)) << error;
        const std::set<float> xs = distinct(m, 0), ys = distinct(m, 1);
        EXPECT_LE(xs.size() - 1, size_t(budget));
        EXPECT_LE(ys.size() - 1, size_t(budget));
        EXPECT_EQ(m.positions.size(), xs.size() * ys.size());
        // The borders are the field's; a budget of at least half the cells cannot need a stride > 2.
        EXPECT_EQ(*xs.begin(), 0.0f);
        EXPECT_EQ(*xs.rbegin(), 128.0f);
        EXPECT_EQ(*ys.rbegin(), 64.0f);
        if (budget >= 64) {
            EXPECT_GE(ys.size() - 1, 32u);
        }
        for (const glm::vec3& p : m.positions) ASSERT_NEAR(p.z, hf.sample(p.x, p.y), 1e-5f);
        expectFacesUp(m);
    }
}

TEST(TerrainMesh, ClipsToTheExtentAndClampsAnExtentLargerThanTheField) {
    const HeightField hf =
        proceduralField(41, 41, glm::vec2(100.0f, 200.0f), 0.25f);  // [100, 110] x [200, 210]
    TriangleMesh m;
    std::string error;
    ASSERT_TRUE(heightFieldMesh(hf, xyExtent(102.1f, 203.3f, 107.6f, 209.05f), 1000, &m, &error)) << error;
    Bounds3 b = meshBounds(m);
    EXPECT_FLOAT_EQ(b.min.x, 102.1f);
    EXPECT_FLOAT_EQ(b.max.x, 107.6f);
    EXPECT_FLOAT_EQ(b.min.y, 203.3f);
    EXPECT_FLOAT_EQ(b.max.y, 209.05f);
    for (const glm::vec3& p : m.positions) ASSERT_NEAR(p.z, hf.sample(p.x, p.y), 1e-5f);
    // Interior lines are sample lines (every 0.25 m): 102.25 .. 107.5 plus the two borders.
    EXPECT_EQ(distinct(m, 0).size(), 22u + 2u);
    expectFacesUp(m);

    ASSERT_TRUE(heightFieldMesh(hf, xyExtent(-1e6f, 205.0f, 1e6f, 1e6f), 1000, &m, &error)) << error;
    b = meshBounds(m);
    EXPECT_EQ(b.min.x, 100.0f);
    EXPECT_EQ(b.max.x, 110.0f);
    EXPECT_EQ(b.min.y, 205.0f);
    EXPECT_EQ(b.max.y, 210.0f);
    EXPECT_EQ(m.positions.size(), 41u * 21u);
}

TEST(TerrainMesh, RejectsBadInputAndLeavesTheOutputAlone) {
    const HeightField hf = proceduralField(9, 9);  // [0, 8]^2
    TriangleMesh untouched;
    untouched.positions = {glm::vec3(1.0f)};
    const float nan = std::numeric_limits<float>::quiet_NaN();
    struct Case {
        const char* what;
        const HeightField* field;
        Bounds extent;
        int budget;
        const char* reason;
    };
    const HeightField empty;
    const HeightField thin(glm::vec2(0.0f), 1.0f, 1, 5, std::vector<float>(5, 0.0f));
    const Case cases[] = {
        {"empty field", &empty, Bounds::everything(), 10, "empty"},
        {"one sample wide", &thin, Bounds::everything(), 10, "2 x 2"},
        {"zero budget", &hf, Bounds::everything(), 0, "max_cells_per_side"},
        {"huge budget", &hf, Bounds::everything(), kMaxHeightFieldSide + 1, "max_cells_per_side"},
        {"empty extent", &hf, Bounds{}, 10, "empty"},
        {"NaN extent", &hf, xyExtent(nan, 0.0f, 4.0f, 4.0f), 10, "NaN"},
        {"no overlap", &hf, xyExtent(20.0f, 20.0f, 30.0f, 30.0f), 10, "does not overlap"},
        {"touches along a line", &hf, xyExtent(8.0f, 0.0f, 12.0f, 8.0f), 10, "line"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        TriangleMesh out = untouched;
        std::string error;
        EXPECT_FALSE(heightFieldMesh(*c.field, c.extent, c.budget, &out, &error));
        EXPECT_NE(error.find(c.reason), std::string::npos) << error;
        EXPECT_EQ(error.rfind("terrain mesh: ", 0), 0u) << error;
        EXPECT_EQ(out.positions.size(), 1u);
    }
}

}  // namespace ug
