// The snow cover effect (engine/env/snow.h): the paper's profile and displacement, geometry-controlled
// snow (extraction, refinement, border, shelter), procedural snow and terrain snow.
#include <gtest/gtest.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <utility>

#include "env/snow.h"
#include "env/snow_detail.h"
#include "mesh_test_util.h"

namespace ug {
namespace {

// The same sample everywhere; counts the batches it is asked for.
struct ConstantEnv {
    EnvSample e;
    int* calls;
    void operator()(const glm::vec3*, size_t n, EnvSample* out) const {
        ++*calls;
        std::fill(out, out + n, e);
    }
};

EnvSample snowOf(float s) {
    EnvSample e;
    e.snow = s;
    return e;
}

double signedAreaZ(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::dvec3 A(a), B(b), C(c);
    return 0.5 * glm::cross(B - A, C - A).z;
}

double maxEdge(const std::vector<glm::vec3>& p, const std::vector<uint32_t>& idx) {
    double m = 0.0;
    for (size_t t = 0; t < idx.size(); t += 3)
        for (int k = 0; k < 3; ++k)
            m = std::max(m, double(glm::length(p[idx[t + k]] - p[idx[t + (k + 1) % 3]])));
    return m;
}

// Edges used by exactly one triangle (the mesh's boundary), as vertex pairs.
std::vector<std::pair<uint32_t, uint32_t>> boundaryEdges(const std::vector<uint32_t>& idx) {
    std::map<std::pair<uint32_t, uint32_t>, int> count;
    for (size_t t = 0; t < idx.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = idx[t + k], b = idx[t + (k + 1) % 3];
            ++count[{std::min(a, b), std::max(a, b)}];
        }
    std::vector<std::pair<uint32_t, uint32_t>> out;
    for (const auto& [e, c] : count) {
        EXPECT_LE(c, 2) << "edge used by more than two triangles";
        if (c == 1) out.push_back(e);
    }
    return out;
}

SnowSettings fineSettings() {
    SnowSettings s;
    s.target_edge_m = 0.05f;
    s.d0_m = 0.05f;
    return s;
}

// A regular grid of quads (2 triangles each) over [x0, x1] x [y0, y1] at height z, wound towards +Z.
TriangleMesh gridQuad(float x0, float x1, float y0, float y1, float z, int n, TriangleMesh* into = nullptr) {
    TriangleMesh m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            m.positions.emplace_back(x0 + (x1 - x0) * float(i) / float(n),
                                     y0 + (y1 - y0) * float(j) / float(n), z);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1) + 1,
                           d = a + uint32_t(n + 1);
            m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
        }
    if (into) {
        appendMesh(into, m);
        return *into;
    }
    return m;
}

// ---------------------------------------------------------------------------------------------------
// Profile and displacement

TEST(SnowProfile, HandComputedValues) {
    EXPECT_EQ(snowEdgeProfile(0.0f, 0.05f), 0.0f);
    EXPECT_EQ(snowEdgeProfile(0.05f, 0.05f), 1.0f);
    EXPECT_EQ(snowEdgeProfile(0.025f, 0.05f), 0.31640625f);  // (1 - 0.5²)⁴ = 0.75⁴, exact in float
    EXPECT_EQ(snowEdgeProfile(1.0f, 0.05f), 1.0f);
    EXPECT_EQ(snowEdgeProfile(INFINITY, 0.05f), 1.0f);
    // d = 0.75 d0: (1 - 0.25²)⁴ = 0.9375⁴
    EXPECT_FLOAT_EQ(snowEdgeProfile(0.75f, 1.0f), 0.9375f * 0.9375f * 0.9375f * 0.9375f);
    // Increasing on [0, d0].
    float prev = 0.0f;
    for (int i = 1; i <= 100; ++i) {
        const float g = snowEdgeProfile(float(i) / 100.0f, 1.0f);
        EXPECT_GE(g, prev);
        prev = g;
    }
}

TEST(SnowProfile, DisplacementIsClampedPaperFormula) {
    EnvSample e;
    e.snow = 0.2f;
    e.occlusion = 0.5f;
    e.shelter = 0.8f;
    e.temperature = 0.5f;  // half a degree above freezing melts 0.01 m
    EXPECT_FLOAT_EQ(snowDisplacement(e, 1.0f, 0.05f), 0.5f * 0.8f * 0.2f - 0.01f);  // g = 1
    EXPECT_FLOAT_EQ(snowDisplacement(e, 0.025f, 0.05f), 0.5f * 0.8f * 0.2f * 0.31640625f - 0.01f);
    e.temperature = -6.0f;  // frost adds no snow
    EXPECT_FLOAT_EQ(snowDisplacement(e, 1.0f, 0.05f), 0.5f * 0.8f * 0.2f);
    e.temperature = 5.0f;  // melts 0.1 m > α s g = 0.08: clamped to 0 (not negative)
    EXPECT_EQ(snowDisplacement(e, 1.0f, 0.05f), 0.0f);
    e.temperature = 0.0f;
    e.shelter = 0.0f;  // under a roof
    EXPECT_EQ(snowDisplacement(e, 1.0f, 0.05f), 0.0f);
    e.shelter = 1.0f;
    EXPECT_EQ(snowDisplacement(e, 0.0f, 0.05f), 0.0f);  // the border
    e.snow = NAN;                                       // a broken environment is not hidden by the clamp
    EXPECT_TRUE(std::isnan(snowDisplacement(e, 1.0f, 0.05f)));
}

TEST(SnowSettingsCheck, RefusesNonFiniteAndOutOfRange) {
    auto refused = [](SnowSettings s, const char* field) {
        std::string error;
        EXPECT_FALSE(validateSnowSettings(s, &error)) << field;
        EXPECT_NE(error.find(field), std::string::npos) << error;
    };
    SnowSettings s;
    std::string error;
    EXPECT_TRUE(validateSnowSettings(s, &error)) << error;
    s = {};
    s.target_edge_m = NAN;
    refused(s, "target_edge_m");
    s = {};
    s.target_edge_m = 0.0f;
    refused(s, "target_edge_m");
    s = {};
    s.d0_m = NAN;
    refused(s, "d0_m");
    s = {};
    s.d0_m = -1.0f;
    refused(s, "d0_m");
    s = {};
    s.up = glm::vec3(NAN, 0, 1);
    refused(s, "up");
    s = {};
    s.up = glm::vec3(0, 0, 2);
    refused(s, "up");
    s = {};
    s.max_face_angle_deg = NAN;
    refused(s, "max_face_angle_deg");
    s = {};
    s.max_face_angle_deg = 120.0f;
    refused(s, "max_face_angle_deg");
    s = {};
    s.min_open = NAN;
    refused(s, "min_open");

    // And every builder refuses them.
    int calls = 0;
    const EnvQuery env = ConstantEnv{snowOf(0.1f), &calls};
    SnowSettings bad;
    bad.target_edge_m = NAN;
    SnowCover cover;
    EXPECT_FALSE(buildGeometrySnow(test::unitCube(), bad, env, &cover, &error));
    EXPECT_FALSE(buildBoxSnow({0, 0, 0}, {1, 1, 1}, bad, env, &cover, &error));
    EXPECT_FALSE(buildCylinderSnow({0, 0, 0}, 1, 1, bad, env, &cover, &error));
    EXPECT_FALSE(buildSphereSnow({0, 0, 0}, 1, bad, env, &cover, &error));
    EXPECT_EQ(calls, 0);
}

// ---------------------------------------------------------------------------------------------------
// Geometry-controlled snow

TEST(SnowGeometry, UnitCubeTopOnlyNoCrack) {
    const SnowSettings s = fineSettings();
    int calls = 0;
    const EnvQuery env = ConstantEnv{snowOf(0.1f), &calls};
    SnowCover cover;
    std::string error;
    ASSERT_TRUE(buildGeometrySnow(test::unitCube(), s, env, &cover, &error)) << error;
    EXPECT_EQ(calls, 2);  // the centroids, then every vertex: batches, not one call per point
    EXPECT_EQ(cover.base_faces_used, 2u);
    EXPECT_EQ(cover.patch_count, 1u);
    ASSERT_TRUE(validateMesh(cover.mesh, &error)) << error;
    EXPECT_EQ(cover.mesh.base_color, glm::vec3(0.9f, 0.92f, 0.95f));
    ASSERT_EQ(cover.surface_positions.size(), cover.mesh.positions.size());
    ASSERT_EQ(cover.mesh.normals.size(), cover.mesh.positions.size());

    size_t interior = 0, border = 0;
    for (size_t v = 0; v < cover.mesh.positions.size(); ++v) {
        const glm::vec3 p = cover.surface_positions[v];
        EXPECT_EQ(p.z, 0.5f);  // the top face only
        EXPECT_LE(std::fabs(p.x), 0.5f);
        EXPECT_LE(std::fabs(p.y), 0.5f);
        const float to_rim = std::min(0.5f - std::fabs(p.x), 0.5f - std::fabs(p.y));
        if (to_rim == 0.0f) {
            // On the base's top-face boundary: pinned, no crack.
            ++border;
            EXPECT_EQ(cover.border_distance_m[v], 0.0f);
            EXPECT_EQ(cover.displacement_m[v], 0.0f);
            EXPECT_EQ(cover.mesh.positions[v], p);
        } else {
            EXPECT_GT(cover.border_distance_m[v], 0.0f);
        }
        // d(p) against the analytic distance to the square's rim (infinite at or beyond d0).
        if (to_rim < 0.0499f) {
            EXPECT_NEAR(cover.border_distance_m[v], to_rim, 1e-6f);
        } else if (to_rim > 0.0501f) {
            EXPECT_EQ(cover.border_distance_m[v], INFINITY);
        }
        if (to_rim > 0.051f) {
            ++interior;
            EXPECT_EQ(cover.displacement_m[v], 0.1f);
            EXPECT_EQ(cover.mesh.positions[v].z, 0.5f + 0.1f);
        }
        EXPECT_NEAR(glm::length(cover.mesh.normals[v]), 1.0f, 1e-4f);
    }
    EXPECT_GT(border, 0u);
    EXPECT_GT(interior, 100u);
    // Both triangles want n = ceil(√2 / 0.05) = 29: every edge split 29 times, 2 · 29² triangles, every
    // edge (before displacement) within the target.
    EXPECT_EQ(cover.triangles_before_drop, 2u * 29u * 29u);
    EXPECT_LE(maxEdge(cover.surface_positions, cover.mesh.indices), s.target_edge_m + 1e-6);
    // The snow's open boundary is pinned to the base surface.
    for (const auto& [a, b] : boundaryEdges(cover.mesh.indices)) {
        EXPECT_EQ(cover.displacement_m[a], 0.0f);
        EXPECT_EQ(cover.displacement_m[b], 0.0f);
    }
    // Far from the border the surface is flat: normals point straight up.
    for (size_t v = 0; v < cover.mesh.positions.size(); ++v)
        if (cover.border_distance_m[v] == INFINITY && std::fabs(cover.surface_positions[v].x) < 0.3f &&
            std::fabs(cover.surface_positions[v].y) < 0.3f) {
            EXPECT_NEAR(cover.mesh.normals[v].z, 1.0f, 1e-5f);
        }
}

TEST(SnowGeometry, RefinementTilesEachFaceConformingly) {
    // An irregular patch: faces of very different sizes share edges with different segment counts.
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1.3f, 0.9f, 0}, {0.1f, 1, 0}, {0.55f, 0.4f, 0}, {0.5f, 0.05f, 0}};
    m.indices = {0, 5, 4, 5, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
    const SnowSettings s = fineSettings();
    int calls = 0;
    snow_detail::SnowLayout layout;
    size_t faces = 0, patches = 0;
    std::string error;
    ASSERT_TRUE(snow_detail::layOutGeometrySnow(m, s, ConstantEnv{snowOf(0.1f), &calls}, &layout, &faces,
                                                &patches, &error))
        << error;
    EXPECT_EQ(faces, 5u);
    EXPECT_EQ(patches, 1u);
    ASSERT_EQ(layout.tri_face.size() * 3, layout.indices.size());
    // Per face: every sub-triangle counter-clockwise, and together they cover exactly its area.
    std::vector<double> area(5, 0.0);
    for (size_t t = 0; t < layout.indices.size(); t += 3) {
        const double a = signedAreaZ(layout.surface[layout.indices[t]], layout.surface[layout.indices[t + 1]],
                                     layout.surface[layout.indices[t + 2]]);
        EXPECT_GT(a, 0.0);
        area[layout.tri_face[t / 3]] += a;
    }
    for (size_t f = 0; f < 5; ++f) {
        const uint32_t* t = &m.indices[3 * f];
        EXPECT_NEAR(area[f], signedAreaZ(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]), 1e-6) << f;
    }
    // Conforming: the only edges used once are on the patch's outer border (no T-junction inside), and
    // they are exactly the vertices with d = 0.
    for (const auto& [a, b] : boundaryEdges(layout.indices)) {
        EXPECT_EQ(layout.border_distance[a], 0.0f);
        EXPECT_EQ(layout.border_distance[b], 0.0f);
    }
    // Edge lengths: <= target, except transition strips (<= 1.5 target).
    EXPECT_LE(maxEdge(layout.surface, layout.indices), 1.5 * s.target_edge_m);
}

// d(p) of every refined vertex against a brute-force distance to the patch's outer polygon.
void expectBorderDistances(const TriangleMesh& m, const std::vector<glm::vec3>& polygon, float d0,
                           float target = 0.1f) {
    SnowSettings s = fineSettings();
    s.d0_m = d0;
    s.target_edge_m = target;
    int calls = 0;
    snow_detail::SnowLayout layout;
    size_t faces = 0, patches = 0;
    std::string error;
    ASSERT_TRUE(snow_detail::layOutGeometrySnow(m, s, ConstantEnv{snowOf(0.1f), &calls}, &layout, &faces,
                                                &patches, &error))
        << error;
    ASSERT_EQ(patches, 1u);
    size_t near = 0;
    for (size_t v = 0; v < layout.surface.size(); ++v) {
        const glm::vec3 p = layout.surface[v];
        float ref = INFINITY;
        for (size_t i = 0; i < polygon.size(); ++i) {
            const glm::vec3 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
            const float t = std::clamp(glm::dot(p - a, b - a) / glm::dot(b - a, b - a), 0.0f, 1.0f);
            ref = std::min(ref, glm::length(p - (a + (b - a) * t)));
        }
        const float d = layout.border_distance[v];
        if (d == 0.0f) {
            EXPECT_LT(ref, 1e-5f);  // a border vertex lies on the polygon
        } else if (ref < d0 * 0.999f) {
            ++near;
            EXPECT_NEAR(d, ref, 1e-5f);
        } else if (ref > d0 * 1.001f) {
            EXPECT_EQ(d, INFINITY);
        }
    }
    EXPECT_GT(near, 10u);
}

TEST(SnowGeometry, BorderDistanceMatchesBruteForce) {
    // The irregular patch of the test above.
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1.3f, 0.9f, 0}, {0.1f, 1, 0}, {0.55f, 0.4f, 0}, {0.5f, 0.05f, 0}};
    m.indices = {0, 5, 4, 5, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
    expectBorderDistances(m, {m.positions[0], m.positions[5], m.positions[1], m.positions[2], m.positions[3]},
                          0.2f);
    // A fan of large faces whose border edges are short (the search grid's fallback to the whole patch).
    TriangleMesh fan;
    fan.positions.push_back({0, 0, 0});
    std::vector<glm::vec3> rim;
    for (int i = 0; i < 96; ++i) {
        const float a = 2.0f * 3.14159265f * float(i) / 96.0f;
        rim.emplace_back(0.8f * std::cos(a), 0.8f * std::sin(a), 0.0f);
        fan.positions.push_back(rim.back());
    }
    for (uint32_t i = 0; i < 96; ++i) fan.indices.insert(fan.indices.end(), {0u, 1 + i, 1 + (i + 1) % 96});
    expectBorderDistances(fan, rim, 0.3f);
    expectBorderDistances(fan, rim, 0.05f, 0.04f);
}

TEST(SnowGeometry, PatchesAndBordersMatchOpenMesh) {
    // A 12 x 12 grid of 0.25 m quads with three 2 x 2 holes of shelter and one 4 x 4 hole enclosing an
    // island: several patches, outer and inner borders. OpenMesh's half-edge structure is the reference.
    const int n = 12;
    const TriangleMesh m = gridQuad(0, 3, 0, 3, 0, n);
    auto sheltered = [](glm::vec3 p) {
        const int i = int(p.x / 0.25f), j = int(p.y / 0.25f);
        const bool hole = (i >= 1 && i < 3 && j >= 1 && j < 3) || (i >= 8 && i < 10 && j >= 1 && j < 3) ||
                          (i >= 1 && i < 3 && j >= 8 && j < 10);
        const bool ring = i >= 5 && i < 11 && j >= 5 && j < 11 && !(i >= 7 && i < 9 && j >= 7 && j < 9);
        return hole || ring;
    };
    const EnvQuery env = [&](const glm::vec3* p, size_t k, EnvSample* out) {
        for (size_t i = 0; i < k; ++i) {
            out[i] = snowOf(0.1f);
            out[i].shelter = sheltered(p[i]) ? 0.0f : 1.0f;
        }
    };
    OpenMesh::TriMesh_ArrayKernelT<> om;
    std::vector<OpenMesh::VertexHandle> vh;
    for (const glm::vec3& p : m.positions) vh.push_back(om.add_vertex({p.x, p.y, p.z}));
    for (size_t f = 0; f < m.triangleCount(); ++f) {
        const uint32_t* t = &m.indices[3 * f];
        const glm::vec3 c = (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) / 3.0f;
        if (!sheltered(c)) {
            ASSERT_TRUE(om.add_face(vh[t[0]], vh[t[1]], vh[t[2]]).is_valid());
        }
    }
    // Components by flood fill over face-face adjacency; boundary vertices from boundary half-edges.
    size_t components = 0;
    std::vector<int> seen(om.n_faces(), 0);
    for (auto f : om.faces()) {
        if (seen[f.idx()]) continue;
        ++components;
        std::vector<OpenMesh::FaceHandle> stack{f};
        seen[f.idx()] = 1;
        while (!stack.empty()) {
            const auto g = stack.back();
            stack.pop_back();
            for (auto h : om.ff_range(g))
                if (!seen[h.idx()]) {
                    seen[h.idx()] = 1;
                    stack.push_back(h);
                }
        }
    }
    std::vector<std::pair<float, float>> om_border;
    for (auto v : om.vertices())
        if (!om.is_isolated(v) && om.is_boundary(v)) om_border.emplace_back(om.point(v)[0], om.point(v)[1]);
    std::sort(om_border.begin(), om_border.end());

    snow_detail::SnowLayout layout;
    size_t faces = 0, patches = 0;
    std::string error;
    ASSERT_TRUE(snow_detail::layOutGeometrySnow(m, fineSettings(), env, &layout, &faces, &patches, &error))
        << error;
    EXPECT_EQ(faces, om.n_faces());
    EXPECT_EQ(patches, components);
    EXPECT_EQ(patches, 2u);  // the outer region (with its holes) and the island
    // Our border vertices that are base grid nodes: exactly OpenMesh's boundary vertices.
    std::vector<std::pair<float, float>> ours;
    for (size_t v = 0; v < layout.surface.size(); ++v) {
        const glm::vec3 p = layout.surface[v];
        const bool node = std::fmod(p.x, 0.25f) == 0.0f && std::fmod(p.y, 0.25f) == 0.0f;
        if (node && layout.border_distance[v] == 0.0f) ours.emplace_back(p.x, p.y);
    }
    std::sort(ours.begin(), ours.end());
    EXPECT_EQ(ours, om_border);
    EXPECT_GT(ours.size(), 40u);
}

// Two 0.5 m slabs side by side along x, the second `gap` m beyond the first and `step` m higher: the snow
// layout's points along the middle of their facing edges (y = 0.25, x from 0.5 to 0.5 + gap), as (x, d).
std::vector<std::pair<float, float>> facingEdgePoints(float gap, float step) {
    TriangleMesh m = gridQuad(0.0f, 0.5f, 0.0f, 0.5f, 0.0f, 4);
    gridQuad(0.5f + gap, 1.0f + gap, 0.0f, 0.5f, step, 4, &m);
    const EnvQuery env = [](const glm::vec3*, size_t k, EnvSample* out) {
        for (size_t i = 0; i < k; ++i) out[i] = snowOf(0.1f);
    };
    snow_detail::SnowLayout layout;
    size_t faces = 0, patches = 0;
    std::string error;
    EXPECT_TRUE(snow_detail::layOutGeometrySnow(m, fineSettings(), env, &layout, &faces, &patches, &error)) << error;
    EXPECT_EQ(patches, 2u);
    std::vector<std::pair<float, float>> out;
    for (size_t v = 0; v < layout.surface.size(); ++v) {
        const glm::vec3 p = layout.surface[v];
        if (std::fabs(p.y - 0.25f) <= 1e-6f && p.x >= 0.5f - 1e-6f && p.x <= 0.5f + gap + 1e-6f)
            out.emplace_back(p.x, layout.border_distance[v]);
    }
    std::sort(out.begin(), out.end());
    return out;
}

TEST(SnowGeometry, SnowBridgesANarrowJointBetweenSlabs) {
    // 8 mm apart at the same height (a paving slab's joint): the facing edges are no border, the snow keeps
    // its depth there (the outer borders are 0.25 m away, beyond d0 = 5 cm: d is infinite), and both
    // covers reach the middle of the joint, so no groove shows between them.
    const auto joint = facingEdgePoints(0.008f, 0.0f);
    ASSERT_EQ(joint.size(), 2u);
    for (const auto& [x, d] : joint) {
        EXPECT_NEAR(x, 0.504f, 1e-6f);
        EXPECT_EQ(d, INFINITY);
    }
    // 5 cm apart, or 1 cm higher: two borders, pinned to the slabs' edges (d = 0).
    for (const auto& [gap, step] : {std::pair{0.05f, 0.0f}, std::pair{0.008f, 0.01f}}) {
        const auto apart = facingEdgePoints(gap, step);
        ASSERT_EQ(apart.size(), 2u) << gap << " " << step;
        EXPECT_EQ(apart[0], std::make_pair(0.5f, 0.0f)) << gap << " " << step;
        EXPECT_EQ(apart[1], std::make_pair(0.5f + gap, 0.0f)) << gap << " " << step;
    }
}

TEST(SnowGeometry, UniformMeshEdgesWithinTarget) {
    // Equilateral faces: every edge of a face has the same count, no transition strip.
    TriangleMesh m;
    const float h = std::sqrt(3.0f) / 2.0f;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0.5f, h, 0}, {1.5f, h, 0}};
    m.indices = {0, 1, 2, 1, 3, 2};
    SnowSettings s = fineSettings();
    s.target_edge_m = 0.1f;
    int calls = 0;
    snow_detail::SnowLayout layout;
    size_t faces = 0, patches = 0;
    std::string error;
    ASSERT_TRUE(snow_detail::layOutGeometrySnow(m, s, ConstantEnv{snowOf(0.1f), &calls}, &layout, &faces,
                                                &patches, &error));
    EXPECT_EQ(layout.indices.size() / 3, 2u * 10u * 10u);  // n = ceil(1 / 0.1) = 10, n² per face
    EXPECT_LE(maxEdge(layout.surface, layout.indices), 0.1 + 1e-6);
    // Welded: 2 faces of a 10-grid sharing one edge: 66 + 66 - 11 vertices.
    EXPECT_EQ(layout.surface.size(), 121u);
}

TEST(SnowGeometry, NothingUnderTheRoof) {
    // Ground grid over [-1, 1]² at z = 0, a roof over [-0.5, 0.5]² at z = 2 (no walls).
    TriangleMesh m = gridQuad(-1, 1, -1, 1, 0, 4);
    gridQuad(-0.5f, 0.5f, -0.5f, 0.5f, 2, 2, &m);
    // The caller's shelter: 0 under the roof, 1 elsewhere.
    int calls = 0;
    const EnvQuery env = [&calls](const glm::vec3* p, size_t n, EnvSample* out) {
        ++calls;
        for (size_t i = 0; i < n; ++i) {
            out[i] = snowOf(0.1f);
            const bool under = p[i].z < 1.9f && std::fabs(p[i].x) < 0.5f && std::fabs(p[i].y) < 0.5f;
            out[i].shelter = under ? 0.0f : 1.0f;
        }
    };
    SnowCover cover;
    std::string error;
    ASSERT_TRUE(buildGeometrySnow(m, fineSettings(), env, &cover, &error)) << error;
    EXPECT_EQ(cover.base_faces_used,
              32u - 8u + 8u);          // ground minus the 2x2 quads under the roof, plus the roof
    EXPECT_EQ(cover.patch_count, 2u);  // the ground ring and the roof
    bool roof = false, ground = false;
    for (size_t t = 0; t < cover.mesh.indices.size(); t += 3) {
        const glm::vec3 c = (cover.surface_positions[cover.mesh.indices[t]] +
                             cover.surface_positions[cover.mesh.indices[t + 1]] +
                             cover.surface_positions[cover.mesh.indices[t + 2]]) /
                            3.0f;
        if (c.z > 1.0f)
            roof = true;
        else {
            ground = true;
            EXPECT_FALSE(std::fabs(c.x) < 0.5f && std::fabs(c.y) < 0.5f) << "snow under the roof";
        }
    }
    EXPECT_TRUE(roof);
    EXPECT_TRUE(ground);
    // The hole's rim is a border too: the ground snow is pinned along it.
    for (size_t v = 0; v < cover.surface_positions.size(); ++v) {
        const glm::vec3 p = cover.surface_positions[v];
        if (p.z == 0.0f && std::max(std::fabs(p.x), std::fabs(p.y)) == 0.5f) {
            EXPECT_EQ(cover.displacement_m[v], 0.0f);
        }
    }
}

TEST(SnowGeometry, SteepFacesTakeNoSnow) {
    auto tilted = [](float deg) {
        const float r = glm::radians(deg);
        TriangleMesh m;  // a face whose normal is `deg` from +Z (rotated about X)
        m.positions = {{0, 0, 0}, {1, 0, 0}, {0, std::cos(r), std::sin(r)}};
        m.indices = {0, 1, 2};
        return m;
    };
    int calls = 0;
    const EnvQuery env = ConstantEnv{snowOf(0.1f), &calls};
    SnowCover cover;
    std::string error;
    ASSERT_TRUE(buildGeometrySnow(tilted(70.0f), fineSettings(), env, &cover, &error)) << error;
    EXPECT_EQ(cover.mesh.triangleCount(), 0u);
    EXPECT_EQ(cover.base_faces_used, 0u);
    ASSERT_TRUE(buildGeometrySnow(tilted(50.0f), fineSettings(), env, &cover, &error)) << error;
    EXPECT_GT(cover.mesh.triangleCount(), 0u);
    EXPECT_EQ(cover.base_faces_used, 1u);
    // A face pointing down (reversed winding) takes none either.
    TriangleMesh down = test::flatQuad();
    std::swap(down.indices[1], down.indices[2]);
    std::swap(down.indices[4], down.indices[5]);
    ASSERT_TRUE(buildGeometrySnow(down, fineSettings(), env, &cover, &error)) << error;
    EXPECT_EQ(cover.mesh.triangleCount(), 0u);
}

TEST(SnowGeometry, MeltedAndOccludedSnowIsDropped) {
    int calls = 0;
    EnvSample warm = snowOf(0.1f);
    warm.temperature = 10.0f;  // melts 0.2 m > α s: entirely
    SnowCover cover;
    std::string error;
    ASSERT_TRUE(
        buildGeometrySnow(test::flatQuad(), fineSettings(), ConstantEnv{warm, &calls}, &cover, &error));
    EXPECT_EQ(cover.mesh.triangleCount(), 0u);
    EXPECT_GT(cover.triangles_before_drop, 0u);
    EXPECT_EQ(cover.base_faces_used, 0u);
    EnvSample half = snowOf(0.1f);
    half.occlusion = 0.5f;
    ASSERT_TRUE(
        buildGeometrySnow(test::flatQuad(), fineSettings(), ConstantEnv{half, &calls}, &cover, &error));
    const float top = *std::max_element(cover.displacement_m.begin(), cover.displacement_m.end());
    EXPECT_FLOAT_EQ(top, 0.05f);
}

TEST(SnowGeometry, RefusesAbsurdSizesUpFront) {
    TriangleMesh plane = test::flatQuad();
    scaleMesh(&plane, 10.0f);  // 10 m x 10 m
    SnowSettings s = fineSettings();
    s.target_edge_m = 1e-6f;
    int calls = 0;
    SnowCover cover;
    std::string error;
    EXPECT_FALSE(buildGeometrySnow(plane, s, ConstantEnv{snowOf(0.1f), &calls}, &cover, &error));
    EXPECT_NE(error.find("triangles"), std::string::npos) << error;
    EXPECT_NE(error.find("target_edge_m"), std::string::npos) << error;

    // A sliver: small area (the area estimate passes) but a 1 km edge subdivides into n² = 10^10.
    TriangleMesh sliver;
    sliver.positions = {{0, 0, 0}, {1000, 0, 0}, {1000, 1e-4f, 0}};
    sliver.indices = {0, 1, 2};
    s.target_edge_m = 0.01f;
    error.clear();
    EXPECT_FALSE(buildGeometrySnow(sliver, s, ConstantEnv{snowOf(0.1f), &calls}, &cover, &error));
    EXPECT_NE(error.find("subdivision"), std::string::npos) << error;

    // And a broken base mesh.
    error.clear();
    EXPECT_FALSE(
        buildGeometrySnow(TriangleMesh{}, fineSettings(), ConstantEnv{snowOf(0.1f), &calls}, &cover, &error));
    EXPECT_NE(error.find("base mesh"), std::string::npos) << error;
}

TEST(SnowGeometry, NonFiniteEnvironmentIsReported) {
    int calls = 0;
    SnowCover cover;
    std::string error;
    EXPECT_FALSE(buildGeometrySnow(test::flatQuad(), fineSettings(), ConstantEnv{snowOf(INFINITY), &calls},
                                   &cover, &error));
    EXPECT_NE(error.find("non-finite"), std::string::npos) << error;
}

TEST(SnowGeometry, DeterministicAndWeldsSeams) {
    // The cube with every face's vertices duplicated (a flat-shaded export): welding gives one patch.
    TriangleMesh split;
    const TriangleMesh cube = test::unitCube();
    for (uint32_t i : cube.indices) {
        split.indices.push_back(uint32_t(split.positions.size()));
        split.positions.push_back(cube.positions[i]);
    }
    const EnvQuery env = [](const glm::vec3* p, size_t n, EnvSample* out) {
        for (size_t i = 0; i < n; ++i)
            out[i] = snowOf(0.1f + 0.05f * std::sin(7.0f * p[i].x + 3.0f * p[i].y));
    };
    SnowSettings s = fineSettings();
    s.up = glm::normalize(glm::vec3(0.2f, 0.1f, 1.0f));
    SnowCover a, b;
    std::string error;
    ASSERT_TRUE(buildGeometrySnow(split, s, env, &a, &error)) << error;
    ASSERT_TRUE(buildGeometrySnow(split, s, env, &b, &error)) << error;
    EXPECT_EQ(a.patch_count, 1u);
    EXPECT_EQ(a.base_faces_used, 2u);
    ASSERT_EQ(a.mesh.positions.size(), b.mesh.positions.size());
    ASSERT_GT(a.mesh.positions.size(), 0u);
    EXPECT_EQ(std::memcmp(a.mesh.positions.data(), b.mesh.positions.data(),
                          a.mesh.positions.size() * sizeof(glm::vec3)),
              0);
    EXPECT_EQ(
        std::memcmp(a.mesh.normals.data(), b.mesh.normals.data(), a.mesh.normals.size() * sizeof(glm::vec3)),
        0);
    EXPECT_EQ(a.mesh.indices, b.mesh.indices);
    // Displaced along the tilted `up`.
    for (size_t v = 0; v < a.mesh.positions.size(); ++v) {
        const glm::vec3 moved = a.mesh.positions[v] - a.surface_positions[v];
        EXPECT_NEAR(glm::length(moved - s.up * a.displacement_m[v]), 0.0f, 1e-6f);
    }
}

// ---------------------------------------------------------------------------------------------------
// Procedural snow

TEST(SnowProcedural, BoxTopAndRim) {
    const glm::vec3 c(1, 2, 3), h(1.0f, 0.5f, 0.25f);
    int calls = 0;
    SnowCover cover;
    std::string error;
    const SnowSettings s = fineSettings();
    ASSERT_TRUE(buildBoxSnow(c, h, s, ConstantEnv{snowOf(0.1f), &calls}, &cover, &error)) << error;
    EXPECT_EQ(calls, 1);
    ASSERT_TRUE(validateMesh(cover.mesh, &error)) << error;
    const float top = c.z + h.z;
    size_t rim = 0, inner = 0;
    double area = 0.0;
    for (size_t v = 0; v < cover.mesh.positions.size(); ++v) {
        const glm::vec3 p = cover.surface_positions[v];
        EXPECT_EQ(p.z, top);
        const float to_rim = std::min(std::min(p.x - (c.x - h.x), (c.x + h.x) - p.x),
                                      std::min(p.y - (c.y - h.y), (c.y + h.y) - p.y));
        EXPECT_GE(to_rim, 0.0f);
        if (to_rim == 0.0f) {
            ++rim;
            EXPECT_EQ(cover.mesh.positions[v].z, top);  // displacement 0 on the rim
        }
        if (to_rim > 0.051f) {
            ++inner;
            EXPECT_EQ(cover.mesh.positions[v].z, top + 0.1f);
        }
    }
    EXPECT_GT(rim, 0u);
    EXPECT_GT(inner, 0u);
    // Before the drop: 2 nx ny triangles, cells of side <= target / √2: nx = ceil(2 / 0.03536) = 57, ny = 29.
    EXPECT_EQ(cover.triangles_before_drop, 2u * 57u * 29u);
    EXPECT_LE(maxEdge(cover.surface_positions, cover.mesh.indices), s.target_edge_m + 1e-6);
    for (size_t t = 0; t < cover.mesh.indices.size(); t += 3)
        area += signedAreaZ(cover.surface_positions[cover.mesh.indices[t]],
                            cover.surface_positions[cover.mesh.indices[t + 1]],
                            cover.surface_positions[cover.mesh.indices[t + 2]]);
    EXPECT_LE(area, 2.0 * 1.0 + 1e-4);  // at most the top (corner cells all on the rim are dropped)
    EXPECT_GT(area, 2.0 * 1.0 - 0.01);

    // `up` too far from +Z: the top takes no snow, and that is not an error.
    SnowSettings sideways = s;
    sideways.up = glm::vec3(1, 0, 0);
    ASSERT_TRUE(buildBoxSnow(c, h, sideways, ConstantEnv{snowOf(0.1f), &calls}, &cover, &error));
    EXPECT_EQ(cover.mesh.triangleCount(), 0u);
    EXPECT_FALSE(buildBoxSnow(c, glm::vec3(1, -1, 1), s, ConstantEnv{snowOf(0.1f), &calls}, &cover, &error));
    SnowSettings tiny = s;
    tiny.target_edge_m = 1e-6f;
    EXPECT_FALSE(buildBoxSnow(c, h, tiny, ConstantEnv{snowOf(0.1f), &calls}, &cover, &error));
    EXPECT_NE(error.find("triangles"), std::string::npos) << error;
}

TEST(SnowProcedural, ShelterBelowMinOpenHasNoSnow) {
    int calls = 0;
    const EnvQuery env = [&calls](const glm::vec3* p, size_t n, EnvSample* out) {
        ++calls;
        for (size_t i = 0; i < n; ++i) {
            out[i] = snowOf(0.1f);
            out[i].shelter = p[i].x < 0.0f ? 0.3f : 1.0f;  // 0.3 < min_open = 0.5
        }
    };
    SnowCover cover;
    std::string error;
    ASSERT_TRUE(buildBoxSnow({0, 0, 0}, {1, 1, 1}, fineSettings(), env, &cover, &error)) << error;
    for (size_t v = 0; v < cover.surface_positions.size(); ++v) {
        if (cover.surface_positions[v].x < 0.0f) {
            EXPECT_EQ(cover.displacement_m[v], 0.0f);
        } else if (cover.border_distance_m[v] == INFINITY) {
            EXPECT_EQ(cover.displacement_m[v], 0.1f);
        }
    }
}

TEST(SnowProcedural, CylinderTopDisc) {
    const glm::vec3 base(0, 0, 1);
    const float r = 0.5f, height = 2.0f;
    int calls = 0;
    SnowCover cover;
    std::string error;
    const SnowSettings s = fineSettings();
    ASSERT_TRUE(buildCylinderSnow(base, r, height, s, ConstantEnv{snowOf(0.1f), &calls}, &cover, &error))
        << error;
    EXPECT_EQ(calls, 1);
    const size_t K = 15;  // ceil(1.46 · 0.5 / 0.05)
    EXPECT_EQ(cover.triangles_before_drop, 6 * K * K);
    ASSERT_TRUE(validateMesh(cover.mesh, &error)) << error;
    EXPECT_LE(maxEdge(cover.surface_positions, cover.mesh.indices), s.target_edge_m + 1e-6);
    bool centre = false;
    for (size_t v = 0; v < cover.mesh.positions.size(); ++v) {
        const glm::vec3 p = cover.surface_positions[v];
        EXPECT_EQ(p.z, 3.0f);
        const float rho = std::hypot(p.x, p.y);
        EXPECT_LE(rho, r + 1e-6f);
        if (cover.border_distance_m[v] == 0.0f) {
            EXPECT_NEAR(rho, r, 1e-6f);  // the rim
            EXPECT_EQ(cover.mesh.positions[v].z, 3.0f);
        } else {
            EXPECT_GT(r - rho, 1e-3f);
        }
        if (p.x == 0.0f && p.y == 0.0f) {
            centre = true;
            EXPECT_EQ(cover.mesh.positions[v].z, 3.0f + 0.1f);
            EXPECT_NEAR(cover.mesh.normals[v].z, 1.0f, 1e-5f);
        }
    }
    EXPECT_TRUE(centre);
    for (size_t t = 0; t < cover.mesh.indices.size(); t += 3)
        EXPECT_GT(signedAreaZ(cover.surface_positions[cover.mesh.indices[t]],
                              cover.surface_positions[cover.mesh.indices[t + 1]],
                              cover.surface_positions[cover.mesh.indices[t + 2]]),
                  0.0);
}

TEST(SnowProcedural, SphereCapDownToMaxAngle) {
    const glm::vec3 c(0, 0, 2);
    const float R = 0.4f;
    SnowSettings s = fineSettings();
    s.max_face_angle_deg = 60.0f;
    int calls = 0;
    SnowCover cover;
    std::string error;
    ASSERT_TRUE(buildSphereSnow(c, R, s, ConstantEnv{snowOf(0.1f), &calls}, &cover, &error)) << error;
    ASSERT_TRUE(validateMesh(cover.mesh, &error)) << error;
    EXPECT_LE(maxEdge(cover.surface_positions, cover.mesh.indices), s.target_edge_m + 1e-6);
    bool pole = false;
    for (size_t v = 0; v < cover.mesh.positions.size(); ++v) {
        const glm::vec3 p = cover.surface_positions[v];
        EXPECT_NEAR(glm::length(p - c), R, 1e-5f);
        const float cos_polar = (p.z - c.z) / R;
        EXPECT_GE(cos_polar, 0.5f - 1e-5f);  // within 60° of +Z
        if (cover.border_distance_m[v] == 0.0f) {
            EXPECT_NEAR(cos_polar, 0.5f, 1e-5f);
            EXPECT_EQ(cover.mesh.positions[v], p);
        }
        if (p.x == 0.0f && p.y == 0.0f) {
            pole = true;
            EXPECT_EQ(cover.displacement_m[v], 0.1f);  // geodesic 0.4 · π/3 > d0: full depth
        }
    }
    EXPECT_TRUE(pole);
    // A cap of no angle is empty, not an error.
    s.max_face_angle_deg = 0.0f;
    ASSERT_TRUE(buildSphereSnow(c, R, s, ConstantEnv{snowOf(0.1f), &calls}, &cover, &error));
    EXPECT_EQ(cover.mesh.triangleCount(), 0u);
    EXPECT_FALSE(
        buildSphereSnow(c, -1.0f, fineSettings(), ConstantEnv{snowOf(0.1f), &calls}, &cover, &error));
}

// ---------------------------------------------------------------------------------------------------
// Terrain snow

HeightField flatField(float z) {
    return HeightField({0, 0}, 1.0f, 11, 11, std::vector<float>(121, z));
}

TEST(SnowTerrain, FlatFieldRisesUniformly) {
    const HeightField hf = flatField(1.0f);
    int calls = 0;
    SnowCover cover;
    std::string error;
    const Bounds region{{2, 2, -100}, {8, 8, 100}};
    ASSERT_TRUE(
        buildTerrainSnow(hf, region, 0.5f, fineSettings(), ConstantEnv{snowOf(0.2f), &calls}, &cover, &error))
        << error;
    EXPECT_EQ(calls, 1);
    EXPECT_EQ(cover.mesh.positions.size(), 13u * 13u);
    EXPECT_EQ(cover.mesh.triangleCount(), 2u * 12u * 12u);
    float xmin = 1e9f, xmax = -1e9f;
    for (const glm::vec3& p : cover.mesh.positions) {
        EXPECT_EQ(p.z, 1.0f + 0.2f);
        xmin = std::min(xmin, p.x);
        xmax = std::max(xmax, p.x);
    }
    EXPECT_EQ(xmin, 2.0f);
    EXPECT_EQ(xmax, 8.0f);
    for (const glm::vec3& n : cover.mesh.normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);
}

TEST(SnowTerrain, RegionIsClippedOrRefused) {
    const HeightField hf = flatField(1.0f);
    int calls = 0;
    SnowCover cover;
    std::string error;
    const EnvQuery env = ConstantEnv{snowOf(0.2f), &calls};
    EXPECT_FALSE(
        buildTerrainSnow(hf, Bounds{{20, 20, 0}, {30, 30, 1}}, 0.5f, fineSettings(), env, &cover, &error));
    EXPECT_NE(error.find("does not overlap"), std::string::npos) << error;
    EXPECT_FALSE(buildTerrainSnow(hf, Bounds{}, 0.5f, fineSettings(), env, &cover, &error));  // the empty box
    EXPECT_FALSE(buildTerrainSnow(hf, Bounds::everything(), 1e-6f, fineSettings(), env, &cover, &error));
    EXPECT_NE(error.find("triangles"), std::string::npos) << error;
    EXPECT_FALSE(buildTerrainSnow(hf, Bounds::everything(), NAN, fineSettings(), env, &cover, &error));
    EXPECT_FALSE(
        buildTerrainSnow(HeightField{}, Bounds::everything(), 1.0f, fineSettings(), env, &cover, &error));
    EXPECT_EQ(calls, 0);
    // Half outside: clipped to the field's rectangle [0, 10]².
    ASSERT_TRUE(
        buildTerrainSnow(hf, Bounds{{5, -5, 0}, {15, 5, 1}}, 1.0f, fineSettings(), env, &cover, &error));
    for (const glm::vec3& p : cover.mesh.positions) {
        EXPECT_GE(p.x, 5.0f);
        EXPECT_LE(p.x, 10.0f);
        EXPECT_GE(p.y, 0.0f);
        EXPECT_LE(p.y, 5.0f);
    }
    EXPECT_EQ(cover.mesh.positions.size(), 6u * 6u);
}

}  // namespace
}  // namespace ug
