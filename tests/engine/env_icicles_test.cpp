#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <gtest/gtest.h>

#include "env/icicles.h"
#include "mesh_test_util.h"

namespace ug {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// An axis-aligned box with split (per-face) vertices, as glTF flat-shaded meshes come: 24 vertices.
TriangleMesh splitBox(glm::vec3 lo, glm::vec3 hi) {
    TriangleMesh m;
    const auto corner = [&](int i) {
        return glm::vec3((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
    };
    // Outward quads (counter-clockwise seen from outside).
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        const uint32_t base = uint32_t(m.positions.size());
        for (int k = 0; k < 4; ++k) m.positions.push_back(corner(q[k]));
        m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    computeNormals(&m);
    return m;
}

TriangleMesh uvSphere(float radius, int slices, int stacks) {
    TriangleMesh m;
    m.positions.push_back({0, 0, radius});
    for (int i = 1; i < stacks; ++i)
        for (int j = 0; j < slices; ++j) {
            const float th = float(M_PI) * float(i) / float(stacks), ph = 2.0f * float(M_PI) * float(j) / float(slices);
            m.positions.push_back(radius * glm::vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)));
        }
    m.positions.push_back({0, 0, -radius});
    const auto v = [&](int i, int j) { return uint32_t(1 + (i - 1) * slices + (j % slices)); };
    const uint32_t south = uint32_t(m.positions.size() - 1);
    for (int j = 0; j < slices; ++j) {
        m.indices.insert(m.indices.end(), {0, v(1, j), v(1, j + 1)});
        for (int i = 1; i + 1 < stacks; ++i)
            m.indices.insert(m.indices.end(), {v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j), v(i + 1, j + 1), v(i, j + 1)});
        m.indices.insert(m.indices.end(), {south, v(stacks - 1, j + 1), v(stacks - 1, j)});
    }
    computeNormals(&m);
    return m;
}

// A closed cylinder about z (radius r, z in [0, height]), `sides` flat sides, welded, outward.
TriangleMesh cylinder(float r, float height, int sides) {
    TriangleMesh m;
    for (int k = 0; k < sides; ++k) {
        const float a = 2.0f * float(M_PI) * float(k) / float(sides);
        m.positions.push_back({r * std::cos(a), r * std::sin(a), 0.0f});
        m.positions.push_back({r * std::cos(a), r * std::sin(a), height});
    }
    const uint32_t bottom = uint32_t(m.positions.size()), top = bottom + 1;
    m.positions.push_back({0, 0, 0});
    m.positions.push_back({0, 0, height});
    for (int k = 0; k < sides; ++k) {
        const uint32_t b0 = uint32_t(2 * k), t0 = b0 + 1, b1 = uint32_t(2 * ((k + 1) % sides)), t1 = b1 + 1;
        m.indices.insert(m.indices.end(), {b0, b1, t1, b0, t1, t0, bottom, b1, b0, top, t0, t1});
    }
    computeNormals(&m);
    return m;
}

EnvSample freezing(float theta, float ice = 1.0f, float humidity = 0.0f) {
    EnvSample e;
    e.temperature = theta;
    e.icicles = ice;
    e.humidity = humidity;
    return e;
}

}  // namespace

// h(θ, η) = min(cap, k_θ (-θ) w(η)), w = 1 + η (η >= 0), 1 / (1 - η) (η < 0), defaults k_θ = 0.03, cap 0.35.
TEST(Icicles, LengthModelHandValues) {
    const IcicleSettings s;
    EXPECT_EQ(icicleLength(0.0f, 0.0f, s), 0.0f);
    EXPECT_EQ(icicleLength(3.0f, 2.0f, s), 0.0f);
    EXPECT_EQ(icicleLength(NAN, 0.0f, s), 0.0f);
    EXPECT_NEAR(icicleLength(-5.0f, 0.0f, s), 0.15f, 1e-6f);   // 0.03 * 5
    EXPECT_NEAR(icicleLength(-4.0f, 0.5f, s), 0.18f, 1e-6f);   // 0.03 * 4 * 1.5
    EXPECT_NEAR(icicleLength(-4.0f, -1.0f, s), 0.06f, 1e-6f);  // 0.03 * 4 / 2
    EXPECT_EQ(icicleLength(-1000.0f, 0.0f, s), 0.35f);
    EXPECT_EQ(icicleLength(-1000.0f, 50.0f, s), 0.35f);
    IcicleSettings dry_blind = s;
    dry_blind.humidity_gain = 0.0f;
    EXPECT_NEAR(icicleLength(-4.0f, -1.0f, dry_blind), 0.12f, 1e-6f);
}

TEST(Icicles, LengthIsMonotoneAndCapped) {
    const IcicleSettings s;
    for (float eta = -3.0f; eta <= 3.0f; eta += 0.25f) {
        float previous = 0.0f;
        for (float theta = 2.0f; theta >= -40.0f; theta -= 0.25f) {
            const float h = icicleLength(theta, eta, s);
            EXPECT_GE(h, previous) << theta << " " << eta;  // colder: never shorter
            EXPECT_LE(h, s.max_length_m);
            EXPECT_GE(h, icicleLength(theta, eta - 0.25f, s));  // wetter: never shorter
            if (theta < 0.0f && h < s.max_length_m) {
                EXPECT_GT(h, icicleLength(theta, eta - 0.25f, s));
            }
            previous = h;
        }
    }
}

TEST(Icicles, SettingsAreValidated) {
    EXPECT_EQ(validateIcicleSettings(IcicleSettings{}), "");
    IcicleSettings s;
    s.spacing_m = 0.0f;
    EXPECT_NE(validateIcicleSettings(s).find("spacing_m"), std::string::npos);
    s = {};
    s.up = {0, 0, 2};
    EXPECT_NE(validateIcicleSettings(s).find("up"), std::string::npos);
    s = {};
    s.max_length_m = NAN;
    EXPECT_NE(validateIcicleSettings(s).find("max_length_m"), std::string::npos);
    s = {};
    s.anchors = {{0, 0, NAN}};
    EXPECT_NE(validateIcicleSettings(s).find("anchors[0]"), std::string::npos);
    std::string error;
    EXPECT_TRUE(findIcicleAnchors(test::unitCube(), s, &error).empty());
    EXPECT_NE(error.find("anchors[0]"), std::string::npos);
}

// A 1 m x 0.5 m x 0.1 m slab: drips only from its bottom rim, 17 anchors along the 1 m edges
// (floor(1 / 0.06 + 0.5), centred: the first 0.02 m from the corner) and 8 along the 0.5 m ones.
TEST(IcicleAnchors, SlabDripsFromItsBottomRimEverySpacing) {
    const TriangleMesh slab = splitBox({-0.5f, -0.25f, 1.0f}, {0.5f, 0.25f, 1.1f});
    const IcicleSettings s;
    std::string error;
    const std::vector<IcicleAnchor> anchors = findIcicleAnchors(slab, s, &error);
    ASSERT_EQ(error, "");
    ASSERT_EQ(anchors.size(), 2u * 17u + 2u * 8u);
    std::map<float, std::vector<float>> along_x;  // y of the long edges -> x of their anchors
    for (const IcicleAnchor& a : anchors) {
        EXPECT_FLOAT_EQ(a.position.z, 1.0f);  // the bottom, never the top face
        const bool on_long = std::abs(std::abs(a.position.y) - 0.25f) < 1e-6f;
        const bool on_short = std::abs(std::abs(a.position.x) - 0.5f) < 1e-6f;
        EXPECT_TRUE(on_long != on_short);
        EXPECT_NEAR(glm::length(a.edge_dir), 1.0f, 1e-6f);
        EXPECT_NEAR(std::abs(a.edge_dir.x), on_long ? 1.0f : 0.0f, 1e-6f);
        if (on_long) along_x[a.position.y].push_back(a.position.x);
    }
    ASSERT_EQ(along_x.size(), 2u);
    for (auto& [y, xs] : along_x) {
        std::sort(xs.begin(), xs.end());
        ASSERT_EQ(xs.size(), 17u);
        for (size_t k = 0; k < xs.size(); ++k) EXPECT_NEAR(xs[k], -0.5f + 0.02f + 0.06f * float(k), 1e-5f);
    }
}

TEST(IcicleAnchors, WeldedCubeAndRoundRimLoop) {
    // Shared-vertex unit cube: four 1 m bottom edges, 17 anchors each, at z = -0.5.
    const std::vector<IcicleAnchor> cube = findIcicleAnchors(test::unitCube(), IcicleSettings{});
    ASSERT_EQ(cube.size(), 4u * 17u);
    for (const IcicleAnchor& a : cube) EXPECT_FLOAT_EQ(a.position.z, -0.5f);
    // A 32-sided drum: its bottom rim turns 11.25° per vertex, one closed loop of perimeter
    // P = 64 r sin(π/32), n = floor(P / 0.06 + 0.5) = 31 anchors, P / 31 apart along the rim.
    const float r = 0.3f;
    const std::vector<IcicleAnchor> drum = findIcicleAnchors(cylinder(r, 0.4f, 32), IcicleSettings{});
    const float perimeter = 64.0f * r * std::sin(float(M_PI) / 32.0f);
    ASSERT_EQ(drum.size(), 31u);
    for (size_t k = 0; k < drum.size(); ++k) {
        EXPECT_EQ(drum[k].position.z, 0.0f);
        const float d = glm::length(glm::vec2(drum[k].position));
        EXPECT_GE(d, r * std::cos(float(M_PI) / 32.0f) - 1e-6f);
        EXPECT_LE(d, r + 1e-6f);
        // Neighbours along the loop (also across its start): a chord just under the arc step P / 31.
        const float chord = glm::distance(drum[k].position, drum[(k + 1) % drum.size()].position);
        EXPECT_LE(chord, perimeter / 31.0f + 1e-5f);
        EXPECT_GE(chord, 0.99f * perimeter / 31.0f);
    }
}

TEST(IcicleAnchors, DoNotDependOnVertexOrder) {
    TriangleMesh slab = splitBox({-0.5f, -0.25f, 1.0f}, {0.5f, 0.25f, 1.1f});
    const std::vector<IcicleAnchor> reference = findIcicleAnchors(slab, IcicleSettings{});
    // Reverse the vertex array (and remap), then reverse the triangle order.
    const uint32_t n = uint32_t(slab.positions.size());
    std::reverse(slab.positions.begin(), slab.positions.end());
    for (uint32_t& i : slab.indices) i = n - 1 - i;
    std::reverse(slab.indices.begin(), slab.indices.end());  // also flips each triangle's order: rewind it
    for (size_t t = 0; t < slab.indices.size(); t += 3) std::swap(slab.indices[t + 1], slab.indices[t + 2]);
    const std::vector<IcicleAnchor> shuffled = findIcicleAnchors(slab, IcicleSettings{});
    ASSERT_EQ(shuffled.size(), reference.size());
    for (size_t k = 0; k < reference.size(); ++k) {
        EXPECT_EQ(shuffled[k].position, reference[k].position);
        EXPECT_NEAR(std::abs(glm::dot(shuffled[k].edge_dir, reference[k].edge_dir)), 1.0f, 1e-6f);
    }
}

TEST(IcicleAnchors, SmoothClosedMeshAndRoomInteriorHaveNone) {
    EXPECT_TRUE(findIcicleAnchors(uvSphere(0.5f, 24, 12), IcicleSettings{}).empty());
    // Inside-out box: a room. Ceiling-to-wall corners are concave (water on the walls runs away from them).
    TriangleMesh room = splitBox({0, 0, 0}, {3, 4, 2.5f});
    for (size_t t = 0; t < room.indices.size(); t += 3) std::swap(room.indices[t + 1], room.indices[t + 2]);
    EXPECT_TRUE(findIcicleAnchors(room, IcicleSettings{}).empty());
}

// An open roof quad, 1 m wide, rising 0.5 m over 1 m in +y: only its low edge (the eave) drips, for
// either winding; a flat open quad drips from all four sides.
TEST(IcicleAnchors, OpenRoofDripsFromItsEave) {
    TriangleMesh roof;
    roof.positions = {{-0.5f, 0, 1}, {0.5f, 0, 1}, {0.5f, 1, 1.5f}, {-0.5f, 1, 1.5f}};
    roof.indices = {0, 1, 2, 0, 2, 3};
    for (int winding = 0; winding < 2; ++winding) {
        SCOPED_TRACE(winding);
        if (winding == 1) std::swap(roof.indices[1], roof.indices[2]), std::swap(roof.indices[4], roof.indices[5]);
        const std::vector<IcicleAnchor> anchors = findIcicleAnchors(roof, IcicleSettings{});
        ASSERT_EQ(anchors.size(), 17u);
        for (const IcicleAnchor& a : anchors) {
            EXPECT_EQ(a.position.y, 0.0f);
            EXPECT_EQ(a.position.z, 1.0f);
        }
    }
    EXPECT_EQ(findIcicleAnchors(test::flatQuad(), IcicleSettings{}).size(), 4u * 17u);
}

TEST(IcicleAnchors, AuthoredAnchorsFollowAndAutomaticCanBeOff) {
    IcicleSettings s;
    s.anchors = {{1, 2, 3}, {4, 5, 6}};
    const TriangleMesh slab = splitBox({-0.5f, -0.25f, 1.0f}, {0.5f, 0.25f, 1.1f});
    const std::vector<IcicleAnchor> all = findIcicleAnchors(slab, s);
    ASSERT_EQ(all.size(), 50u + 2u);
    EXPECT_EQ(all[50].position, glm::vec3(1, 2, 3));
    EXPECT_EQ(all[51].position, glm::vec3(4, 5, 6));
    EXPECT_NEAR(glm::dot(all[51].edge_dir, s.up), 0.0f, 1e-6f);
    s.automatic_anchors = false;
    EXPECT_EQ(findIcicleAnchors(slab, s).size(), 2u);
}

TEST(IcicleAnchors, RefuseBadMeshesAndAbsurdCounts) {
    std::string error;
    TriangleMesh broken = test::unitCube();
    broken.indices[4] = 99;
    EXPECT_TRUE(findIcicleAnchors(broken, IcicleSettings{}, &error).empty());
    EXPECT_NE(error.find("base mesh"), std::string::npos);
    // 100 km of drip edge every millimetre: 4e8 anchors, refused before sampling.
    const TriangleMesh huge = splitBox({0, 0, 0}, {1e5f, 1e5f, 10.0f});
    IcicleSettings fine;
    fine.spacing_m = 0.001f;
    error.clear();
    EXPECT_TRUE(findIcicleAnchors(huge, fine, &error).empty());
    EXPECT_NE(error.find("exceed the limit"), std::string::npos);
    EXPECT_TRUE(findIcicleAnchors(TriangleMesh{}, IcicleSettings{}, &error).empty());  // nothing, no error
}

TEST(IcicleShapes, AreClosedFiniteOutwardAndTaper) {
    const std::vector<IcicleShape>& shapes = icicleShapes();
    ASSERT_EQ(shapes.size(), kIcicleShapeLengths * kIcicleShapeSeeds);
    for (size_t k = 0; k < shapes.size(); ++k) {
        SCOPED_TRACE(k);
        const IcicleShape& shape = shapes[k];
        const TriangleMesh& m = shape.mesh;
        std::string error;
        ASSERT_TRUE(validateMesh(m, &error)) << error;
        EXPECT_EQ(shape.seed, k % kIcicleShapeSeeds);
        EXPECT_GE(m.triangleCount(), 200u);
        EXPECT_LE(m.triangleCount(), 1000u);
        ASSERT_EQ(m.normals.size(), m.positions.size());
        std::map<std::pair<uint32_t, uint32_t>, int> edges;
        double volume = 0.0;
        for (size_t t = 0; t < m.indices.size(); t += 3) {
            const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]], c = m.positions[m.indices[t + 2]];
            volume += double(glm::dot(a, glm::cross(b, c))) / 6.0;
            for (int e = 0; e < 3; ++e) edges[{m.indices[t + e], m.indices[t + (e + 1) % 3]}]++;
        }
        for (const auto& [edge, n] : edges) {  // each edge used once each way: closed and consistently wound
            EXPECT_EQ(n, 1);
            EXPECT_EQ(edges.count({edge.second, edge.first}), 1u);
        }
        EXPECT_GT(volume, 0.0);
        const Bounds3 b = meshBounds(m);
        EXPECT_EQ(b.max.z, 0.0f);
        EXPECT_EQ(b.min.z, -shape.length_m);
        // Thinner below: the horizontal extent (distance from the z axis) of the bottom quarter is less
        // than the top quarter's, and the top disc is the chain's top sphere blend (a few mm to cm).
        float top = 0.0f, bottom = 0.0f;
        for (const glm::vec3& p : m.positions) {
            const float r = glm::length(glm::vec2(p));
            if (p.z > -0.25f * shape.length_m) top = std::max(top, r);
            if (p.z < -0.75f * shape.length_m) bottom = std::max(bottom, r);
        }
        EXPECT_LT(bottom, 0.75f * top);
        EXPECT_GT(shape.top_radius_m, 0.004f);
        EXPECT_LT(shape.top_radius_m, 0.25f * shape.length_m);
        if (k >= kIcicleShapeSeeds) {
            EXPECT_GT(shape.length_m, shapes[k - kIcicleShapeSeeds].length_m);
        }
    }
    EXPECT_NE(shapes[0].mesh.positions, shapes[1].mesh.positions);  // seeds differ
}

TEST(IcicleShapes, AreDeterministic) {
    for (size_t c : {size_t(0), kIcicleShapeLengths - 1}) {
        const IcicleShape fresh = makeIcicleShape(c, 2);
        const IcicleShape& cached = icicleShapes()[c * kIcicleShapeSeeds + 2];
        EXPECT_EQ(fresh.mesh.positions, cached.mesh.positions);
        EXPECT_EQ(fresh.mesh.indices, cached.mesh.indices);
        EXPECT_EQ(fresh.top_radius_m, cached.top_radius_m);
    }
}

TEST(IciclePlacement, NeedsFrostAndIce) {
    const std::vector<IcicleAnchor> anchors(6, IcicleAnchor{{0, 0, 2}, {1, 0, 0}});
    const std::vector<EnvSample> env = {freezing(0.0f), freezing(2.0f),       freezing(-5.0f, 0.0f),
                                        freezing(-5.0f, -1.0f), freezing(NAN), freezing(-5.0f, NAN)};
    const std::vector<IcicleInstance> icicles = placeIcicles(anchors, env, std::vector<float>(6, kInf), IcicleSettings{});
    EXPECT_TRUE(icicles.empty());
}

// h = 0.15 m at θ = -5 (η = 0); free = 0.95 x clearance: kept when free >= h, shortened to free when
// free >= h / 2, dropped below.
TEST(IciclePlacement, ClearanceKeepsShortensOrDrops) {
    std::vector<IcicleAnchor> anchors;
    for (int k = 0; k < 5; ++k) anchors.push_back({{0.1f * float(k), 0, 2}, {1, 0, 0}});
    const std::vector<EnvSample> env(5, freezing(-5.0f));
    const std::vector<float> clearance = {kInf, 0.2f, 0.1f, 0.02f, NAN};  // 0.02: 2 cm above a floor
    std::string error;
    const std::vector<IcicleInstance> icicles = placeIcicles(anchors, env, clearance, IcicleSettings{}, &error);
    ASSERT_EQ(error, "");
    ASSERT_EQ(icicles.size(), 3u);
    EXPECT_EQ(icicles[0].anchor, anchors[0].position);
    EXPECT_NEAR(icicles[0].length_m, 0.15f, 1e-6f);
    EXPECT_NEAR(icicles[1].length_m, 0.15f, 1e-6f);   // free 0.19
    EXPECT_NEAR(icicles[2].length_m, 0.095f, 1e-6f);  // free 0.095 >= 0.075
    EXPECT_EQ(icicles[2].anchor, anchors[2].position);
    // 0.15 is nearer (in ratio) to the 0.12 m class than the 0.22 m one: scale 1.25.
    const std::vector<IcicleShape>& shapes = icicleShapes();
    EXPECT_EQ(icicles[0].shape / kIcicleShapeSeeds, 1u);
    EXPECT_NEAR(icicles[0].scale, 0.15f / shapes[icicles[0].shape].length_m, 1e-6f);
    for (const IcicleInstance& i : icicles) {
        EXPECT_GE(i.yaw_rad, 0.0f);
        EXPECT_LT(i.yaw_rad, 6.2832f);
    }
}

TEST(IciclePlacement, HangsBelowItsAnchorCappedForAnyUp) {
    for (const glm::vec3 up : {glm::vec3(0, 0, 1), glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f))}) {
        SCOPED_TRACE(up.y);
        IcicleSettings s;
        s.up = up;
        std::vector<IcicleAnchor> anchors;
        std::vector<EnvSample> env;
        for (int k = 0; k < 24; ++k) {
            anchors.push_back({{0.07f * float(k), 1.0f, 2.0f}, {1, 0, 0}});
            env.push_back(freezing(-0.5f - 1.5f * float(k), 1.0f, 0.1f * float(k % 5) - 0.2f));
        }
        const std::vector<IcicleInstance> icicles = placeIcicles(anchors, env, std::vector<float>(24, kInf), s);
        ASSERT_EQ(icicles.size(), 24u);
        for (const IcicleInstance& icicle : icicles) {
            EXPECT_LE(icicle.length_m, s.max_length_m);
            const TriangleMesh m = icicleMesh({icicle});
            float top = -kInf, bottom = kInf;
            for (const glm::vec3& p : m.positions) {
                top = std::max(top, glm::dot(p - icicle.anchor, up));
                bottom = std::min(bottom, glm::dot(p - icicle.anchor, up));
            }
            EXPECT_LE(top, 1e-5f);
            EXPECT_NEAR(bottom, -icicle.length_m, 1e-5f);
        }
        EXPECT_EQ(icicles.back().length_m, s.max_length_m);  // θ = -35: capped
        std::string error;
        const TriangleMesh all = icicleMesh(icicles, &error);
        ASSERT_EQ(error, "");
        size_t triangles = 0;
        for (const IcicleInstance& i : icicles) triangles += icicleShapes()[i.shape].mesh.triangleCount();
        EXPECT_EQ(all.triangleCount(), triangles);
        EXPECT_TRUE(validateMesh(all, &error)) << error;
        for (const glm::vec3& n : all.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-4f);
    }
}

TEST(IciclePlacement, IsAPureFunctionOfTheAnchor) {
    std::vector<IcicleAnchor> anchors;
    for (int k = 0; k < 12; ++k) anchors.push_back({{0.06f * float(k), 0, 1}, {1, 0, 0}});
    const std::vector<EnvSample> env(12, freezing(-6.0f));
    const std::vector<IcicleInstance> all = placeIcicles(anchors, env, std::vector<float>(12, kInf), IcicleSettings{});
    // Dropping the first half changes nothing for the rest.
    const std::vector<IcicleAnchor> tail(anchors.begin() + 6, anchors.end());
    const std::vector<IcicleInstance> part =
        placeIcicles(tail, std::vector<EnvSample>(6, freezing(-6.0f)), std::vector<float>(6, kInf), IcicleSettings{});
    ASSERT_EQ(all.size(), 12u);
    ASSERT_EQ(part.size(), 6u);
    bool yaws_differ = false;
    for (size_t k = 0; k < 6; ++k) {
        EXPECT_EQ(part[k].shape, all[6 + k].shape);
        EXPECT_EQ(part[k].yaw_rad, all[6 + k].yaw_rad);
        yaws_differ |= part[k].yaw_rad != part[0].yaw_rad;
    }
    EXPECT_TRUE(yaws_differ);
}

// With length_variation v, every icicle keeps a length in ((1 - v) h, h], not all the same, and the
// variation is a function of the anchor (the same anchor, the same length).
TEST(IciclePlacement, LengthVariationShortensWithinItsFraction) {
    IcicleSettings s;
    s.length_variation = 0.4f;
    std::vector<IcicleAnchor> anchors;
    for (int k = 0; k < 40; ++k) anchors.push_back({{0.06f * float(k), 0, 1}, {1, 0, 0}});
    const std::vector<EnvSample> env(40, freezing(-5.0f));  // h = 0.15
    const std::vector<IcicleInstance> icicles = placeIcicles(anchors, env, std::vector<float>(40, kInf), s);
    ASSERT_EQ(icicles.size(), 40u);
    float lo = kInf, hi = 0.0f;
    for (const IcicleInstance& i : icicles) {
        EXPECT_GT(i.length_m, 0.6f * 0.15f);
        EXPECT_LE(i.length_m, 0.15f + 1e-6f);
        lo = std::min(lo, i.length_m), hi = std::max(hi, i.length_m);
    }
    EXPECT_GT(hi - lo, 0.03f);  // 40 draws spread over most of the 0.06 m range
    const std::vector<IcicleInstance> again = placeIcicles({anchors[7]}, {env[7]}, {kInf}, s);
    ASSERT_EQ(again.size(), 1u);
    EXPECT_EQ(again[0].length_m, icicles[7].length_m);
    s.length_variation = 1.0f;
    EXPECT_NE(validateIcicleSettings(s).find("length_variation"), std::string::npos);
}

TEST(IciclePlacement, RefusesMismatchedInputs) {
    std::string error;
    const std::vector<IcicleAnchor> anchors(3, IcicleAnchor{{0, 0, 1}, {1, 0, 0}});
    EXPECT_TRUE(placeIcicles(anchors, std::vector<EnvSample>(2), std::vector<float>(3, kInf), IcicleSettings{}, &error).empty());
    EXPECT_NE(error.find("3 anchors, 2 samples, 3 clearances"), std::string::npos);
    IcicleInstance bad{};
    bad.shape = 999;
    bad.scale = 1.0f;
    error.clear();
    EXPECT_EQ(icicleMesh({bad}, &error).triangleCount(), 0u);
    EXPECT_NE(error.find("shape 999"), std::string::npos);
    bad.shape = 0;
    bad.scale = 0.0f;
    error.clear();
    EXPECT_EQ(icicleMesh({bad}, &error).triangleCount(), 0u);
    EXPECT_NE(error.find("scale"), std::string::npos);
}

}  // namespace ug
