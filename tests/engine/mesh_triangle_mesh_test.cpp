#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "mesh_test_util.h"
#include "mesh/triangle_mesh.h"

namespace ug {

TEST(TriangleMesh, CubeNormalsAreUnitAndPointOutward) {
    TriangleMesh cube = test::unitCube();
    ASSERT_EQ(cube.normals.size(), 8u);
    for (size_t i = 0; i < 8; ++i) {
        EXPECT_NEAR(glm::length(cube.normals[i]), 1.0f, 1e-5f);
        EXPECT_GT(glm::dot(cube.normals[i], cube.positions[i]), 0.0f);  // corners: outward
    }
}

TEST(TriangleMesh, DegenerateTrianglesContributeNothing) {
    TriangleMesh m = test::flatQuad();
    m.positions.push_back({5, 5, 5});
    m.indices.insert(m.indices.end(), {0, 0, 4});  // zero area
    computeNormals(&m);
    EXPECT_NEAR(m.normals[0].z, 1.0f, 1e-6f);
}

TEST(TriangleMesh, BoundsOfEmptyAndCube) {
    EXPECT_EQ(meshBounds(TriangleMesh{}).max, glm::vec3(0.0f));
    const Bounds3 b = meshBounds(test::unitCube());
    EXPECT_EQ(b.min, glm::vec3(-0.5f));
    EXPECT_EQ(b.max, glm::vec3(0.5f));
}

TEST(TriangleMesh, ValidateNamesTheBadIndex) {
    TriangleMesh m = test::flatQuad();
    std::string error;
    EXPECT_TRUE(validateMesh(m, &error));
    m.indices[4] = 900;
    EXPECT_FALSE(validateMesh(m, &error));
    EXPECT_EQ(error, "triangle 1 references vertex 900 of 4");
}

TEST(TriangleMesh, ValidateRejectsNaNAndEmpty) {
    TriangleMesh m = test::flatQuad();
    m.positions[2].y = std::numeric_limits<float>::quiet_NaN();
    std::string error;
    EXPECT_FALSE(validateMesh(m, &error));
    EXPECT_NE(error.find("vertex 2"), std::string::npos);
    EXPECT_FALSE(validateMesh(TriangleMesh{}, &error));
    EXPECT_NE(error.find("no triangles"), std::string::npos);
}

TEST(TriangleMesh, AxisConversionsAreInverse) {
    TriangleMesh m = test::unitCube();
    m.positions[0] = {1, 2, 3};
    convertZUpToYUp(&m);
    EXPECT_EQ(m.positions[0], glm::vec3(1, 3, -2));
    convertYUpToZUp(&m);
    EXPECT_EQ(m.positions[0], glm::vec3(1, 2, 3));
}

}  // namespace ug
