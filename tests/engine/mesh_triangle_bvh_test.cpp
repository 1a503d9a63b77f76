#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "mesh_test_util.h"
#include "core/hash.h"
#include "mesh/procedural_models.h"
#include "mesh/triangle_bvh.h"

namespace ug {
namespace {

glm::vec3 unitVector(uint64_t seed, uint64_t i) {
    // Uniform on the sphere (z uniform, angle uniform).
    const float z = 2.0f * unitFloat(hashWords(seed, i, 0)) - 1.0f;
    const float a = 6.2831853f * unitFloat(hashWords(seed, i, 1));
    const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return {s * std::cos(a), s * std::sin(a), z};
}

// The BVH must return the brute force's float exactly: the same value, or +inf for both.
void expectSameHits(const TriangleMesh& mesh, const std::string& what) {
    SCOPED_TRACE(what);
    const TriangleBvh bvh(mesh, 2);
    EXPECT_EQ(bvh.triangleCount(), mesh.triangleCount());
    const Bounds3 box = meshBounds(mesh);
    const glm::vec3 centre = 0.5f * (box.min + box.max), half = 0.5f * (box.max - box.min);
    const float size = glm::length(box.max - box.min);
    int hits = 0, misses = 0, mismatches = 0;
    auto check = [&](const glm::vec3& o, const glm::vec3& d) {
        const float want = rayHitBruteForce(mesh, o, d), got = bvh.rayHit(o, d);
        if (std::isinf(want))
            ++misses;
        else
            ++hits;
        if (!(got == want)) {
            if (++mismatches <= 5)
                ADD_FAILURE() << "ray o=(" << o.x << "," << o.y << "," << o.z << ") d=(" << d.x << "," << d.y
                              << "," << d.z << "): bvh " << got << ", brute force " << want;
        }
    };
    for (uint64_t i = 0; i < 300; ++i) {
        // Random origins in and around the box, random directions: hits from inside and outside, and
        // misses (rays leaving the model or passing by it).
        const glm::vec3 o =
            centre + 1.5f * half *
                         (2.0f * glm::vec3(unitFloat(hashWords(7, i, 2)), unitFloat(hashWords(7, i, 3)),
                                           unitFloat(hashWords(7, i, 4))) -
                          1.0f);
        check(o, unitVector(11, i));
        // Rays aimed exactly at a vertex and at an edge's midpoint (shared by two triangles), from far out.
        const size_t t = size_t(hashWords(13, i) % mesh.triangleCount());
        const glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]];
        const glm::vec3 from = centre + 2.0f * size * unitVector(17, i);
        check(from, glm::normalize(a - from));
        check(from, glm::normalize(0.5f * (a + b) - from));
        // Surely missing: away from the box.
        const glm::vec3 out = centre + 2.0f * size * unitVector(19, i);
        check(out, glm::normalize(out - centre));
    }
    // Axis-aligned rays (zero direction components) through vertices: grazing edges and faces.
    for (size_t v = 0; v < std::min<size_t>(mesh.positions.size(), 40); ++v) {
        const glm::vec3 p =
            mesh.positions[v * (mesh.positions.size() / std::min<size_t>(mesh.positions.size(), 40))];
        for (int axis = 0; axis < 3; ++axis)
            for (float sign : {-1.0f, 1.0f}) {
                glm::vec3 d(0.0f);
                d[axis] = sign;
                glm::vec3 o = p;
                o[axis] -= sign * 2.0f * size;
                check(o, d);
            }
    }
    EXPECT_GT(hits, 100);
    EXPECT_GT(misses, 100);
    EXPECT_EQ(mismatches, 0);
}

}  // namespace

TEST(TriangleBvh, RayHitsEqualBruteForceExactly) {
    expectSameHits(test::unitCube(), "cube");
    expectSameHits(test::flatQuad(), "quad");
    expectSameHits(makeRock(3), "rock");
    expectSameHits(makeOakLeaf(3), "oak leaf (thin)");
    expectSameHits(makeTwig(3), "twig");
    expectSameHits(makeScannedRock(20000, 3), "scanned rock");
}

TEST(TriangleBvh, CubeEdgesAndCornersAreHit) {
    // Rays along the cube's edges, through the diagonal two triangles share, and through corners.
    const TriangleMesh cube = test::unitCube();
    const TriangleBvh bvh(cube);
    for (const glm::vec3& o :
         {glm::vec3(-0.5f, -0.5f, -3.0f), glm::vec3(0.0f, 0.0f, -3.0f), glm::vec3(0.5f, 0.0f, -3.0f)}) {
        const float got = bvh.rayHit(o, {0, 0, 1});
        EXPECT_EQ(got, rayHitBruteForce(cube, o, {0, 0, 1}));
        EXPECT_TRUE(std::isfinite(got));
    }
    EXPECT_EQ(bvh.rayHit({0.0f, 0.0f, 0.0f}, {1, 0, 0}), 0.5f);  // from inside
    const glm::vec3 d = glm::normalize(glm::vec3(1.0f));
    EXPECT_EQ(bvh.rayHit(glm::vec3(-2.0f), d), rayHitBruteForce(cube, glm::vec3(-2.0f), d));
    EXPECT_TRUE(std::isinf(bvh.rayHit({0.0f, 0.0f, 3.0f}, {0, 0, 1})));
    EXPECT_TRUE(std::isinf(bvh.rayHit({2.0f, 2.0f, 0.0f}, {0, 0, 1})));
}

TEST(TriangleBvh, IsTheSameForAnyThreadCountAndEmptyMisses) {
    const TriangleMesh rock = makeScannedRock(50000, 4);
    const TriangleBvh one(rock, 1), two(rock, 2), three(rock, 3);
    EXPECT_EQ(one.nodeCount(), two.nodeCount());
    EXPECT_EQ(one.nodeCount(), three.nodeCount());
    EXPECT_EQ(one.depth(), two.depth());
    EXPECT_LT(one.depth(), 64);
    for (uint64_t i = 0; i < 200; ++i) {
        const glm::vec3 d = unitVector(23, i);
        EXPECT_EQ(one.rayHit(glm::vec3(0.0f), d), two.rayHit(glm::vec3(0.0f), d));
        EXPECT_EQ(one.rayHit(glm::vec3(0.0f), d), three.rayHit(glm::vec3(0.0f), d));
    }
    const TriangleBvh empty(TriangleMesh{});
    EXPECT_EQ(empty.nodeCount(), 0u);
    EXPECT_TRUE(std::isinf(empty.rayHit(glm::vec3(0.0f), {0, 0, 1})));
}

}  // namespace ug
