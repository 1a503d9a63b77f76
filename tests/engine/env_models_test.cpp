#include "env/env_models.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <numeric>

#include "mesh/mesh_loader.h"
#include "mesh/triangle_bvh.h"
#include "mesh_test_util.h"

namespace ug {
namespace {

TriangleMesh make(const std::string& name, uint64_t seed = kEnvStarterSeed) {
    TriangleMesh m;
    EXPECT_TRUE(makeEnvStarterModel(name, seed, &m)) << name;
    return m;
}

glm::vec3 corner(const TriangleMesh& m, size_t t, int k) {
    return m.positions[m.indices[3 * t + size_t(k)]];
}

glm::vec3 faceNormal(const TriangleMesh& m, size_t t) {
    return glm::normalize(glm::cross(corner(m, t, 1) - corner(m, t, 0), corner(m, t, 2) - corner(m, t, 0)));
}

glm::vec3 centroid(const TriangleMesh& m, size_t t) {
    return (corner(m, t, 0) + corner(m, t, 1) + corner(m, t, 2)) / 3.0f;
}

// Vertex ids with bit-identical positions merged (the models duplicate vertices per face group).
std::vector<uint32_t> weldedIds(const TriangleMesh& m) {
    std::map<std::tuple<float, float, float>, uint32_t> ids;
    std::vector<uint32_t> out;
    for (const glm::vec3& p : m.positions)
        out.push_back(ids.emplace(std::make_tuple(p.x, p.y, p.z), uint32_t(ids.size())).first->second);
    return out;
}

// Size ranges of the bounding box (x, y, z extents), from each model's description.
struct Extents {
    float lo[3], hi[3];
};
const std::map<std::string, Extents>& expectedExtents() {
    static const std::map<std::string, Extents> e = {
        {"bench", {{1.5f, 0.5f, 0.8f}, {1.7f, 0.8f, 1.0f}}},
        {"lamppost", {{0.4f, 0.8f, 3.9f}, {0.8f, 1.4f, 4.5f}}},
        {"trash_can", {{0.6f, 0.6f, 0.85f}, {0.7f, 0.7f, 0.95f}}},
        {"bus_shelter", {{3.1f, 1.5f, 2.4f}, {3.3f, 1.7f, 2.6f}}},
        {"fence_segment", {{1.9f, 0.05f, 1.0f}, {2.1f, 0.2f, 1.3f}}},
        {"pavement_slab", {{1.95f, 1.95f, 0.14f}, {2.05f, 2.05f, 0.16f}}},
        {"road_segment", {{3.95f, 3.95f, 0.099f}, {4.05f, 4.05f, 0.101f}}},
        {"tree", {{1.0f, 1.0f, 4.5f}, {6.0f, 6.0f, 5.5f}}},
        {"fountain", {{2.0f, 2.0f, 1.2f}, {2.2f, 2.2f, 2.0f}}},
        {"facade", {{3.95f, 0.4f, 5.95f}, {4.05f, 1.2f, 6.05f}}},
        {"steps", {{1.45f, 0.9f, 0.45f}, {1.55f, 1.6f, 0.7f}}},
        {"fountain_water", {{1.7f, 1.7f, 0.37f}, {1.75f, 1.75f, 0.39f}}}};
    return e;
}

}  // namespace

TEST(EnvModels, NamesInTheDocumentedOrderAndUnknownNamesRefused) {
    const std::vector<std::string> expected = {
        "bench",        "lamppost", "trash_can", "bus_shelter", "fence_segment", "pavement_slab",
        "road_segment", "tree",     "fountain",  "facade",      "steps",         "fountain_water"};
    EXPECT_EQ(envStarterNames(), expected);
    TriangleMesh m;
    m.base_color = {0.1f, 0.2f, 0.3f};
    EXPECT_FALSE(makeEnvStarterModel("gazebo", kEnvStarterSeed, &m));
    EXPECT_TRUE(m.positions.empty());
    EXPECT_EQ(m.base_color, glm::vec3(0.1f, 0.2f, 0.3f));
}

TEST(EnvModels, ValidModestSizedAndStandingOnTheGround) {
    for (const std::string& name : envStarterNames()) {
        SCOPED_TRACE(name);
        const TriangleMesh m = make(name);
        std::string error;
        ASSERT_TRUE(validateMesh(m, &error)) << error;
        EXPECT_GE(m.triangleCount(), name == "tree" ? 1000u : 100u);
        EXPECT_LE(m.triangleCount(), name == "tree" ? 20000u : 30000u);
        const Bounds3 b = meshBounds(m);
        EXPECT_NEAR(b.min.z, 0.0f, 1e-3f);
        EXPECT_GE(b.min.z, -1e-6f);
        const Extents& e = expectedExtents().at(name);
        for (int k = 0; k < 3; ++k) {
            EXPECT_GE(b.max[k] - b.min[k], e.lo[k]) << "axis " << k;
            EXPECT_LE(b.max[k] - b.min[k], e.hi[k]) << "axis " << k;
        }
        // The footprint centre is the origin, within the overhangs' asymmetry (lamp arm, balcony); the
        // tree's origin is its trunk, whatever its crown does.
        if (name == "tree") continue;
        EXPECT_LT(std::abs(b.min.x + b.max.x), 0.05f);
        EXPECT_LT(std::abs(b.min.y + b.max.y), name == "lamppost" || name == "facade" ? 1.2f : 0.05f);
    }
}

TEST(EnvModels, DeterministicAndOnlyTheTreeDependsOnTheSeed) {
    for (const std::string& name : envStarterNames()) {
        SCOPED_TRACE(name);
        const TriangleMesh a = make(name), b = make(name), other = make(name, 7);
        ASSERT_EQ(a.positions.size(), b.positions.size());
        ASSERT_EQ(a.indices, b.indices);
        EXPECT_EQ(
            0, std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(glm::vec3)));
        EXPECT_EQ(0, std::memcmp(a.normals.data(), b.normals.data(), a.normals.size() * sizeof(glm::vec3)));
        EXPECT_EQ(a.base_color, b.base_color);
        const bool same = a.positions.size() == other.positions.size() &&
                          std::memcmp(a.positions.data(), other.positions.data(),
                                      a.positions.size() * sizeof(glm::vec3)) == 0;
        EXPECT_EQ(same, name != "tree");
    }
}

// A union of closed, outward parts: after welding, every directed edge is matched by its reverse, and
// every connected piece encloses a positive volume.
TEST(EnvModels, ClosedOutwardPartsWithoutDegenerateTriangles) {
    for (const std::string& name : envStarterNames()) {
        SCOPED_TRACE(name);
        const TriangleMesh m = make(name);
        const std::vector<uint32_t> id = weldedIds(m);
        std::map<std::pair<uint32_t, uint32_t>, int> edges;
        std::vector<uint32_t> parent(m.positions.size());
        std::iota(parent.begin(), parent.end(), 0u);
        auto root = [&](uint32_t v) {
            while (parent[v] != v) v = parent[v] = parent[parent[v]];
            return v;
        };
        size_t degenerate = 0;
        for (size_t t = 0; t < m.triangleCount(); ++t) {
            const glm::vec3 n =
                glm::cross(corner(m, t, 1) - corner(m, t, 0), corner(m, t, 2) - corner(m, t, 0));
            degenerate += 0.5f * glm::length(n) < 1e-7f;
            for (int k = 0; k < 3; ++k) {
                const uint32_t a = id[m.indices[3 * t + size_t(k)]],
                               b = id[m.indices[3 * t + size_t(k + 1) % 3]];
                edges[{a, b}]++;
                parent[root(a)] = root(b);
            }
        }
        EXPECT_EQ(degenerate, 0u);
        int unmatched = 0;
        for (const auto& [edge, n] : edges) {
            const auto rev = edges.find({edge.second, edge.first});
            unmatched += rev == edges.end() || rev->second != n;
        }
        EXPECT_EQ(unmatched, 0);
        std::map<uint32_t, double> volume;  // per welded piece
        for (size_t t = 0; t < m.triangleCount(); ++t) {
            const glm::dvec3 a = corner(m, t, 0), b = corner(m, t, 1), c = corner(m, t, 2);
            volume[root(id[m.indices[3 * t]])] += glm::dot(a, glm::cross(b, c)) / 6.0;
        }
        for (const auto& [piece, v] : volume) EXPECT_GT(v, 0.0) << "piece " << piece;
    }
}

// Flat shading: unit normals, and no vertex shared across a sharp edge. Two triangles sharing an edge's
// vertices (not just its positions) never meet at more than 70 degrees (a 6-sided twig's ring: 60); and
// outside the tree's bent tubes a vertex normal never leans more than 40 degrees from a face using it
// (a box corner shared by two faces would lean 45).
TEST(EnvModels, UnitNormalsAndSharpEdgesStaySharp) {
    for (const std::string& name : envStarterNames()) {
        SCOPED_TRACE(name);
        const TriangleMesh m = make(name);
        ASSERT_EQ(m.normals.size(), m.positions.size());
        for (const glm::vec3& n : m.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
        std::map<std::pair<uint32_t, uint32_t>, std::vector<size_t>> shared;
        size_t leaning = 0;
        for (size_t t = 0; t < m.triangleCount(); ++t) {
            const glm::vec3 f = faceNormal(m, t);
            for (int k = 0; k < 3; ++k) {
                const uint32_t a = m.indices[3 * t + size_t(k)], b = m.indices[3 * t + size_t(k + 1) % 3];
                shared[{std::min(a, b), std::max(a, b)}].push_back(t);
                leaning += glm::dot(f, m.normals[a]) < std::cos(glm::radians(40.0f));
            }
        }
        if (name != "tree") {
            EXPECT_EQ(leaning, 0u);
        }
        size_t sharp = 0;
        for (const auto& [edge, tris] : shared)
            for (size_t i = 1; i < tris.size(); ++i)
                sharp +=
                    glm::dot(faceNormal(m, tris[0]), faceNormal(m, tris[i])) < std::cos(glm::radians(70.0f));
        EXPECT_EQ(sharp, 0u);
    }
}

// Parts overlap but never touch face on face: a horizontal face lying on another (a post's top under a
// roof, a baluster's foot on a slab) would be an up-facing face with no sky above it, and flickers in a
// viewer. Checked for horizontal faces, where snow and drip edges are read: no horizontal triangle's
// centroid lies inside another horizontal triangle at the same height.
TEST(EnvModels, NoHorizontalFaceLiesOnAnother) {
    for (const std::string& name : envStarterNames()) {
        SCOPED_TRACE(name);
        const TriangleMesh m = make(name);
        std::vector<size_t> flat;
        for (size_t t = 0; t < m.triangleCount(); ++t)
            if (std::abs(faceNormal(m, t).z) > 0.999f) flat.push_back(t);
        auto inside = [&](const glm::vec3& p, size_t t) {  // strictly, in the XY projection
            float sign = 0.0f;
            for (int k = 0; k < 3; ++k) {
                const glm::vec3 a = corner(m, t, k), b = corner(m, t, (k + 1) % 3);
                const float c = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
                if (std::abs(c) < 1e-7f) return false;
                if (sign == 0.0f) sign = c;
                if (c * sign < 0.0f) return false;
            }
            return true;
        };
        size_t lying = 0;
        for (const size_t u : flat) {
            const glm::vec3 c = centroid(m, u);
            for (const size_t d : flat)
                lying += d != u && std::abs(corner(m, d, 0).z - c.z) < 1e-4f && inside(c, d);
        }
        EXPECT_EQ(lying, 0u);
    }
}

TEST(EnvModels, BusShelterRoofCoversTheWholeBenchSeat) {
    const TriangleMesh m = make("bus_shelter");
    const TriangleBvh bvh(m, 1);
    size_t seat = 0;
    for (size_t t = 0; t < m.triangleCount(); ++t) {
        const glm::vec3 c = centroid(m, t);
        if (faceNormal(m, t).z < 0.99f || std::abs(c.z - 0.45f) > 0.005f) continue;
        ++seat;
        for (const glm::vec3 o : {c, corner(m, t, 0), corner(m, t, 1), corner(m, t, 2)}) {
            const float d = bvh.rayHit(o + glm::vec3(0, 0, 1e-3f), {0, 0, 1});
            ASSERT_TRUE(std::isfinite(d)) << c.x << " " << c.y;
            EXPECT_NEAR(o.z + 1e-3f + d, 2.4f, 1e-3f);  // the first thing above is the roof's underside
        }
    }
    EXPECT_GE(seat, 4u * 16u);  // four slats, each an 8 x 1 grid on top
}

TEST(EnvModels, FacadeWindowsAreRecessedWithDripEdgesUnderTheirSills) {
    const TriangleMesh m = make("facade");
    const TriangleBvh bvh(m, 1);
    for (const float x : {-1.0f, 1.0f})
        for (const float bottom : {1.0f, 3.9f}) {
            SCOPED_TRACE(testing::Message() << "window " << x << ", " << bottom);
            // Straight up from below the sill, just in front of the wall: the sill's underside, 6 cm
            // under the opening.
            const glm::vec3 o(x, 0.235f, bottom - 0.3f);
            EXPECT_NEAR(o.z + bvh.rayHit(o, {0, 0, 1}), bottom - 0.06f, 1e-4f);
            size_t drip = 0;
            for (size_t t = 0; t < m.triangleCount(); ++t) {
                const glm::vec3 c = centroid(m, t);
                drip += faceNormal(m, t).z < -0.99f && std::abs(c.x - x) < 0.6f && c.y > 0.2f && c.y < 0.3f &&
                        std::abs(c.z - (bottom - 0.06f)) < 1e-3f;
            }
            EXPECT_GE(drip, 2u);
        }
    // The lower openings' panes (beside the mullion at x = +-1) are recessed 0.2 m behind the wall face
    // at y = 0.2.
    for (const float x : {-1.2f, -0.8f, 0.8f, 1.2f})
        EXPECT_NEAR(bvh.rayHit({x, 2.0f, 1.7f}, {0, -1, 0}), 2.0f, 1e-4f);
    EXPECT_NEAR(bvh.rayHit({0.0f, 2.0f, 1.7f}, {0, -1, 0}), 1.8f, 1e-4f);  // the pier between them
}

TEST(EnvModels, WrittenFilesReloadWithTheSameTrianglesAndBounds) {
    const std::string dir = test::tempPath("env_models");
    std::string error;
    ASSERT_TRUE(writeEnvStarterModels(dir, &error)) << error;
    for (const std::string& name : envStarterNames()) {
        SCOPED_TRACE(name);
        const TriangleMesh m = make(name);
        TriangleMesh back;
        ASSERT_TRUE(loadMeshFile(dir + "/" + name + ".glb", &back, &error)) << error;
        convertYUpToZUp(&back);
        EXPECT_EQ(back.triangleCount(), m.triangleCount());
        const Bounds3 a = meshBounds(m), b = meshBounds(back);
        EXPECT_LT(glm::length(a.min - b.min) + glm::length(a.max - b.max), 1e-5f);
        EXPECT_LT(glm::length(back.base_color - m.base_color), 1e-6f);
    }
}

// The committed assets/env_models/*.glb are what the generators make now (regenerate them with
// `undergrowth make-assets` after changing a model). A tolerance, not bits: another compiler may round
// the trigonometry differently.
TEST(EnvModels, CommittedAssetsMatchTheGenerators) {
    for (const std::string& name : envStarterNames()) {
        SCOPED_TRACE(name);
        TriangleMesh committed;
        std::string error;
        ASSERT_TRUE(loadMeshFile(std::string(UG_SOURCE_DIR) + "/assets/env_models/" + name + ".glb",
                                 &committed, &error))
            << error;
        convertYUpToZUp(&committed);
        const TriangleMesh m = make(name);
        ASSERT_EQ(committed.triangleCount(), m.triangleCount());
        ASSERT_EQ(committed.positions.size(), m.positions.size());
        float worst = 0.0f;
        for (size_t i = 0; i < m.positions.size(); ++i)
            worst = std::max(worst, glm::length(committed.positions[i] - m.positions[i]));
        EXPECT_LT(worst, 1e-4f);
    }
}

}  // namespace ug
