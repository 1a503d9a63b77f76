// Levels of detail of static meshes (static_lod.h): the level choice, the spatial split of large meshes drawn
// once, the simplified levels' bounds and locked borders, and the per-frame draws.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "editor/static_lod.h"

namespace ug::editor {
namespace {

// An open height field over [x0, x0 + n step] x [y0, y0 + n step], z a smooth bump (amplitude 0.1 m).
TriangleMesh gridMesh(int n, float step, float x0, float y0) {
    TriangleMesh mesh;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const float x = x0 + float(i) * step, y = y0 + float(j) * step;
            mesh.positions.push_back({x, y, 0.1f * std::sin(x) * std::cos(0.7f * y)});
        }
    auto at = [n](int i, int j) { return uint32_t(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return mesh;
}

// A closed latitude-longitude sphere of radius 1 about the origin.
TriangleMesh sphereMesh(int rings, int segments) {
    TriangleMesh mesh;
    const float pi = 3.14159265f;
    mesh.positions.push_back({0, 0, 1});
    for (int r = 1; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const float th = pi * float(r) / float(rings), ph = 2.0f * pi * float(s) / float(segments);
            mesh.positions.push_back({std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)});
        }
    mesh.positions.push_back({0, 0, -1});
    const uint32_t south = uint32_t(mesh.positions.size() - 1);
    auto ring = [segments](int r, int s) { return uint32_t(1 + (r - 1) * segments + (s % segments)); };
    for (int s = 0; s < segments; ++s) {
        mesh.indices.insert(mesh.indices.end(), {0u, ring(1, s), ring(1, s + 1)});
        mesh.indices.insert(mesh.indices.end(), {south, ring(rings - 1, s + 1), ring(rings - 1, s)});
    }
    for (int r = 1; r + 1 < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            mesh.indices.insert(mesh.indices.end(), {ring(r, s), ring(r + 1, s), ring(r + 1, s + 1)});
            mesh.indices.insert(mesh.indices.end(), {ring(r, s), ring(r + 1, s + 1), ring(r, s + 1)});
        }
    return mesh;
}

// The vertices on the mesh's open border: those of edges used by one triangle only.
std::set<uint32_t> borderVertices(const std::vector<uint32_t>& indices, uint32_t first, uint32_t count) {
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (uint32_t t = first; t < first + count; t += 3)
        for (uint32_t k = 0; k < 3; ++k) {
            const uint32_t a = indices[t + k], b = indices[t + (k + 1) % 3];
            ++edges[{std::min(a, b), std::max(a, b)}];
        }
    std::set<uint32_t> out;
    for (const auto& [e, uses] : edges)
        if (uses == 1) out.insert({e.first, e.second});
    return out;
}

Bounds levelBounds(const TriangleMesh& mesh, const std::vector<uint32_t>& indices, uint32_t first, uint32_t count) {
    Bounds b;
    for (uint32_t i = first; i < first + count; ++i) b = unite(b, Bounds{mesh.positions[indices[i]], mesh.positions[indices[i]]});
    return b;
}

StaticLodPiece levels(float e1, float e2, float e3) {
    StaticLodPiece p;
    p.level_count = 4;
    p.error_m = {0.0f, e1, e2, e3};
    return p;
}

}  // namespace

TEST(StaticLod, ChoosesTheCoarsestLevelUnderAPixel) {
    const StaticLodPiece p = levels(0.001f, 0.01f, 0.1f);
    const float ppr = 1000.0f, size = 1.0f;
    // At d metres one metre covers 1000 / d px: level k is allowed when error_k 1000 / d < 1.
    EXPECT_EQ(chooseStaticLevel(p, 1.0f, size, 0.5f, ppr), 0);    // 2 px for level 1
    EXPECT_EQ(chooseStaticLevel(p, 1.0f, size, 1.0f, ppr), 0);    // exactly 1 px: not below
    EXPECT_EQ(chooseStaticLevel(p, 1.0f, size, 2.0f, ppr), 1);    // 0.5 px, level 2: 5 px
    EXPECT_EQ(chooseStaticLevel(p, 1.0f, size, 20.0f, ppr), 2);   // 0.5 px, level 3: 5 px
    EXPECT_EQ(chooseStaticLevel(p, 1.0f, size, 200.0f, ppr), 3);
    EXPECT_EQ(chooseStaticLevel(p, 1.0f, size, 0.0f, ppr), 0);    // the eye inside the chunk
    // The instances' scale scales the error: twice as large, 20 m is exactly 1 px for level 2.
    EXPECT_EQ(chooseStaticLevel(p, 2.0f, size, 20.0f, ppr), 1);
    EXPECT_EQ(chooseStaticLevel(p, 2.0f, size, 40.1f, ppr), 2);
}

TEST(StaticLod, SkipsMeshesBelowHalfAPixel) {
    const StaticLodPiece p = levels(0.001f, 0.01f, 0.1f);
    // 5 cm covers 0.5 px at 100 m (1000 px per radian).
    EXPECT_EQ(chooseStaticLevel(p, 1.0f, 0.05f, 99.0f, 1000.0f), 2);  // level 3: 1.01 px
    EXPECT_EQ(chooseStaticLevel(p, 1.0f, 0.05f, 101.0f, 1000.0f), -1);
    StaticLodPiece single;  // no simplified level: level 0 until skipped
    EXPECT_EQ(chooseStaticLevel(single, 1.0f, 0.05f, 99.0f, 1000.0f), 0);
    EXPECT_EQ(chooseStaticLevel(single, 1.0f, 0.05f, 101.0f, 1000.0f), -1);
}

TEST(StaticLod, LevelsAMeshBringsAreOnePieceWithErrorsThatNeverShrink) {
    const TriangleMesh mesh = gridMesh(4, 0.5f, 0.0f, 0.0f);
    std::vector<MeshLodLevel> brought(4);
    for (size_t k = 0; k < brought.size(); ++k) {
        brought[k].indices.assign(mesh.indices.begin(), mesh.indices.begin() + 3 * (8 >> k));
        brought[k].error_m = k == 1 ? 0.001f : 0.01f * float(k + 1);  // level 2 claims less than level 1
    }
    const StaticLodMesh lods = authoredStaticLod(mesh, brought);
    ASSERT_EQ(lods.pieces.size(), 1u);
    EXPECT_FALSE(lods.split);
    const StaticLodPiece& p = lods.pieces[0];
    ASSERT_EQ(p.level_count, uint32_t(kStaticLodLevels));  // the mesh and the first three brought
    EXPECT_EQ(p.count[0], mesh.indices.size());
    for (int k = 1; k < kStaticLodLevels; ++k) {
        EXPECT_EQ(p.count[size_t(k)], brought[size_t(k - 1)].indices.size());
        EXPECT_TRUE(std::equal(brought[size_t(k - 1)].indices.begin(), brought[size_t(k - 1)].indices.end(),
                               lods.indices.begin() + p.first[size_t(k)]));
    }
    EXPECT_EQ(p.error_m[1], 0.01f);
    EXPECT_EQ(p.error_m[2], 0.01f);  // raised to level 1's
    EXPECT_EQ(p.error_m[3], 0.03f);
    EXPECT_EQ(p.bounds.lo.x, 0.0f);
    EXPECT_EQ(p.bounds.hi.x, 2.0f);
}

TEST(StaticLod, DistanceToBox) {
    const Bounds box{{0, 0, 0}, {1, 2, 3}};
    EXPECT_FLOAT_EQ(distanceToBox({0.5f, 1.0f, 1.0f}, box), 0.0f);
    EXPECT_FLOAT_EQ(distanceToBox({4.0f, 1.0f, 1.0f}, box), 3.0f);
    EXPECT_FLOAT_EQ(distanceToBox({4.0f, 6.0f, 1.0f}, box), 5.0f);
}

TEST(StaticLod, SplitPutsEveryTriangleInExactlyOneCell) {
    const TriangleMesh mesh = gridMesh(20, 0.5f, -3.0f, -3.0f);  // [-3, 7]^2
    const auto cells = splitTrianglesIntoCells(mesh, 2.0f);
    std::vector<int> seen(mesh.indices.size() / 3, 0);
    std::set<std::pair<int64_t, int64_t>> keys;
    std::pair<int64_t, int64_t> previous{INT64_MIN, INT64_MIN};
    for (const auto& cell : cells) {
        ASSERT_FALSE(cell.empty());
        std::set<std::pair<int64_t, int64_t>> cell_keys;
        for (uint32_t t : cell) {
            ++seen[t];
            const glm::vec3 c = (mesh.positions[mesh.indices[t * 3]] + mesh.positions[mesh.indices[t * 3 + 1]] +
                                 mesh.positions[mesh.indices[t * 3 + 2]]) /
                                3.0f;
            cell_keys.insert({int64_t(std::floor(c.x / 2.0f)), int64_t(std::floor(c.y / 2.0f))});
        }
        ASSERT_EQ(cell_keys.size(), 1u);  // one cell's triangles share the centroid's cell
        EXPECT_LT(previous, *cell_keys.begin());  // sorted by (ix, iy), each cell once
        previous = *cell_keys.begin();
        keys.insert(previous);
    }
    for (int n : seen) EXPECT_EQ(n, 1);
    EXPECT_EQ(cells.size(), 36u);  // cells -2..3 on each axis: [-4, 8) holds the centroids in (-3, 7)
    EXPECT_TRUE(splitTrianglesIntoCells(TriangleMesh{}, 2.0f).empty());
}

TEST(StaticLod, SparseMeshesSplitIntoLargerCells) {
    // 100 x 100 m in 1 m quads: 20,000 triangles; cells of 16,384 on average: sqrt(1e4 16384 / 2e4) m.
    EXPECT_NEAR(splitCellSize(gridMesh(100, 1.0f, 0.0f, 0.0f)), std::sqrt(1e4f * 16384.0f / 2e4f), 1e-3f);
    EXPECT_EQ(splitCellSize(TriangleMesh{}), kStaticCellM);
}

TEST(StaticLod, SplitPiecesHaveTheirTrianglesBoundsAndMeetAtTheirBorders) {
    const TriangleMesh mesh = gridMesh(184, 4.0f / 184.0f, 0.0f, 0.0f);  // 4 x 4 m, 67,712 triangles: 2 m cells
    ASSERT_EQ(splitCellSize(mesh), kStaticCellM);
    const std::vector<StaticLodMesh> lods = buildStaticLodMeshes({&mesh}, {true}, 2);
    ASSERT_EQ(lods.size(), 1u);
    const StaticLodMesh& l = lods[0];
    ASSERT_TRUE(l.split);
    ASSERT_EQ(l.pieces.size(), 4u);
    size_t level0 = 0;
    for (const StaticLodPiece& p : l.pieces) {
        level0 += p.count[0];
        const Bounds b = levelBounds(mesh, l.indices, p.first[0], p.count[0]);
        EXPECT_EQ(b.lo, p.bounds.lo);
        EXPECT_EQ(b.hi, p.bounds.hi);
        EXPECT_GE(p.bounds.lo.x, -1e-6f);
        EXPECT_LE(p.bounds.hi.x - p.bounds.lo.x, 2.0f + 4.0f / 184.0f + 1e-4f);  // one cell and a quad
        EXPECT_GT(p.level_count, 1u);
        // Every vertex of the piece's own border (the grid's rim and the cell seams) stays at every level.
        const std::set<uint32_t> border = borderVertices(l.indices, p.first[0], p.count[0]);
        for (uint32_t k = 1; k < p.level_count; ++k) {
            std::set<uint32_t> used(l.indices.begin() + p.first[k], l.indices.begin() + p.first[k] + p.count[k]);
            for (uint32_t v : border) ASSERT_TRUE(used.count(v)) << "level " << k << " lost border vertex " << v;
        }
    }
    EXPECT_EQ(level0, mesh.indices.size());
    EXPECT_EQ(l.bounds.lo, levelBounds(mesh, mesh.indices, 0, uint32_t(mesh.indices.size())).lo);
}

TEST(StaticLod, LevelsShrinkAndKeepTheBoundsWithinTheirError) {
    for (const TriangleMesh& mesh : {sphereMesh(48, 96), gridMesh(64, 1.0f / 16.0f, 0.0f, 0.0f)}) {
        std::vector<uint32_t> indices;
        const StaticLodPiece p = buildStaticLodPiece(mesh, nullptr, &indices);
        ASSERT_GT(p.level_count, 2u);
        EXPECT_EQ(p.count[0], mesh.indices.size());
        EXPECT_EQ(p.error_m[0], 0.0f);
        const Bounds b0 = levelBounds(mesh, indices, p.first[0], p.count[0]);
        for (uint32_t k = 1; k < p.level_count; ++k) {
            EXPECT_LE(double(p.triangles(int(k))), kStaticLevelShrink * double(p.triangles(int(k - 1))));
            EXPECT_GE(p.error_m[k], p.error_m[k - 1]);
            const Bounds bk = levelBounds(mesh, indices, p.first[k], p.count[k]);
            const float tol = p.error_m[k] + 1e-5f;
            for (int a = 0; a < 3; ++a) {
                EXPECT_LE(bk.lo[a] - b0.lo[a], tol) << "level " << k << " axis " << a;
                EXPECT_LE(b0.hi[a] - bk.hi[a], tol) << "level " << k << " axis " << a;
            }
        }
    }
}

TEST(StaticLod, NormalsThatBendAcrossWideTrianglesCountAsError) {
    // A flat plate (z = 0: no geometric error at any level) whose rim normals lean 45 degrees outward, as on
    // a bevelled cap: a level whose triangles reach from the rim far inward spreads the lean over the top.
    const int n = 32;
    const float step = 1.0f / 16.0f;
    TriangleMesh flat = gridMesh(n, step, 0.0f, 0.0f);
    for (glm::vec3& p : flat.positions) p.z = 0.0f;
    flat.normals.assign(flat.positions.size(), glm::vec3(0, 0, 1));
    TriangleMesh bevel = flat;
    const float edge = float(n) * step;
    for (size_t v = 0; v < bevel.positions.size(); ++v) {
        const glm::vec3 p = bevel.positions[v];
        glm::vec3 out(0.0f);
        if (p.x == 0.0f) out.x = -1.0f;
        if (p.x == edge) out.x = 1.0f;
        if (p.y == 0.0f) out.y = -1.0f;
        if (p.y == edge) out.y = 1.0f;
        if (out != glm::vec3(0.0f)) bevel.normals[v] = glm::normalize(glm::normalize(out) + glm::vec3(0, 0, 1));
    }
    std::vector<uint32_t> indices;
    const StaticLodPiece a = buildStaticLodPiece(flat, nullptr, &indices);
    const StaticLodPiece b = buildStaticLodPiece(bevel, nullptr, &indices);
    ASSERT_GT(a.level_count, 1u);
    ASSERT_EQ(a.level_count, b.level_count);  // the same geometry simplifies alike
    EXPECT_LT(a.error_m[1], 1e-6f);
    // Level 0's own worst: a cell triangle (width step / sqrt 2) from the rim (chord 2 sin 22.5 deg) inward.
    const float level0 = step / std::sqrt(2.0f) * 2.0f * std::sin(0.3927f);
    EXPECT_GT(b.error_m[1], 2.0f * level0);
}

TEST(StaticLod, LockedBorderKeepsEveryBorderVertex) {
    const TriangleMesh mesh = gridMesh(64, 1.0f / 16.0f, 0.0f, 0.0f);
    std::vector<uint32_t> indices;
    const StaticLodPiece p = buildStaticLodPiece(mesh, nullptr, &indices);
    ASSERT_GT(p.level_count, 1u);
    const std::set<uint32_t> border = borderVertices(mesh.indices, 0, uint32_t(mesh.indices.size()));
    EXPECT_EQ(border.size(), 4u * 64u);
    for (uint32_t k = 1; k < p.level_count; ++k) {
        const std::set<uint32_t> used(indices.begin() + p.first[k], indices.begin() + p.first[k] + p.count[k]);
        for (uint32_t v : border) ASSERT_TRUE(used.count(v)) << "level " << k << " lost border vertex " << v;
        // And the rim is still the rim: the level's own open border is the same vertices.
        EXPECT_EQ(borderVertices(indices, p.first[k], p.count[k]), border);
    }
}

TEST(StaticLod, SameLevelsForAnyThreadCount) {
    const TriangleMesh a = gridMesh(184, 4.0f / 184.0f, 0.0f, 0.0f), b = sphereMesh(24, 48);
    const auto one = buildStaticLodMeshes({&a, &b, nullptr}, {true, false, false}, 1);
    const auto four = buildStaticLodMeshes({&a, &b, nullptr}, {true, false, false}, 4);
    ASSERT_EQ(one.size(), 3u);
    for (size_t m = 0; m < 3; ++m) {
        EXPECT_EQ(one[m].indices, four[m].indices);
        ASSERT_EQ(one[m].pieces.size(), four[m].pieces.size());
        for (size_t p = 0; p < one[m].pieces.size(); ++p) EXPECT_EQ(one[m].pieces[p].error_m, four[m].pieces[p].error_m);
    }
    EXPECT_TRUE(one[2].pieces.empty());
}

TEST(StaticLod, TheCacheBuildsOnlyNewMeshesAndGivesWhatABuildGives) {
    auto a = std::make_shared<const TriangleMesh>(gridMesh(60, 0.05f, 0.0f, 0.0f));
    auto b = std::make_shared<const TriangleMesh>(sphereMesh(16, 32));
    auto c = std::make_shared<const TriangleMesh>(sphereMesh(12, 24));
    StaticLodCache cache;
    size_t built = 0;
    auto expectBuilt = [&](const std::vector<std::shared_ptr<const TriangleMesh>>& meshes, const std::vector<bool>& split) {
        const std::vector<std::shared_ptr<const StaticLodMesh>> got = cache.levels(meshes, split, 2, &built);
        std::vector<const TriangleMesh*> raw;
        for (const auto& m : meshes) raw.push_back(m.get());
        const std::vector<StaticLodMesh> want = buildStaticLodMeshes(raw, split, 1);
        ASSERT_EQ(got.size(), want.size());
        for (size_t m = 0; m < got.size(); ++m) {
            EXPECT_EQ(got[m]->indices, want[m].indices) << m;
            EXPECT_EQ(got[m]->split, want[m].split) << m;
            ASSERT_EQ(got[m]->pieces.size(), want[m].pieces.size()) << m;
        }
    };
    expectBuilt({a, b}, {false, false});
    EXPECT_EQ(built, 2u);
    expectBuilt({b, a}, {false, false});  // the same objects, in another order
    EXPECT_EQ(built, 0u);
    expectBuilt({a, c}, {false, false});  // b's replacement (a class's new snow)
    EXPECT_EQ(built, 1u);
    expectBuilt({a, c}, {true, false});   // split now: levels of other pieces
    EXPECT_EQ(built, 1u);
    expectBuilt({b}, {false});            // b was forgotten when a call did not name it
    EXPECT_EQ(built, 1u);
}

TEST(StaticLod, TheSunsCastersChangeWithWhatCastsAndNotWithTheTerrainsSnow) {
    auto bench = std::make_shared<const TriangleMesh>(sphereMesh(8, 16));
    auto bench_snow = std::make_shared<const TriangleMesh>(gridMesh(4, 0.1f, 0.0f, 0.0f));
    auto terrain_snow = std::make_shared<const TriangleMesh>(gridMesh(8, 0.1f, 0.0f, 0.0f));
    auto scene = [&](std::shared_ptr<const TriangleMesh> ground, glm::vec3 bench_at,
                     std::shared_ptr<const TriangleMesh> on_bench) {
        std::vector<MeshInstances> meshes(3);
        meshes[0].name = "env/bench";
        meshes[0].mesh = bench;
        meshes[0].instances = {InstanceTransform{.position = bench_at}};
        meshes[1].name = "snow/bench/0";
        meshes[1].mesh = on_bench;
        meshes[1].instances = meshes[0].instances;
        meshes[2].name = "snow/terrain/0_0";
        meshes[2].mesh = ground;
        meshes[2].ground_layer = true;
        return meshes;
    };
    const std::vector<MeshInstances> before = scene(terrain_snow, {1.0f, 2.0f, 0.0f}, bench_snow);
    const std::vector<SunCaster> casters = sunCasters(&before);
    ASSERT_EQ(casters.size(), 2u);  // the bench and its snow; the terrain's snow casts nothing
    EXPECT_EQ(casters[0].mesh, bench);
    EXPECT_EQ(casters[1].mesh, bench_snow);
    // A footprint: the terrain's snow is a new mesh, the casters are the same.
    const auto trodden = std::make_shared<const TriangleMesh>(*terrain_snow);
    const std::vector<MeshInstances> footprint = scene(trodden, {1.0f, 2.0f, 0.0f}, bench_snow);
    EXPECT_EQ(sunCasters(&footprint), casters);
    // The bench moved by a millimetre, or its snow recomputed as a new mesh (equal triangles, new object):
    // the map is drawn again.
    const std::vector<MeshInstances> moved = scene(terrain_snow, {1.001f, 2.0f, 0.0f}, bench_snow);
    EXPECT_NE(sunCasters(&moved), casters);
    const auto recomputed = std::make_shared<const TriangleMesh>(*bench_snow);
    const std::vector<MeshInstances> resnowed = scene(terrain_snow, {1.0f, 2.0f, 0.0f}, recomputed);
    EXPECT_NE(sunCasters(&resnowed), casters);
    // No meshes, and meshes without triangles, cast nothing.
    EXPECT_TRUE(sunCasters(nullptr).empty());
    std::vector<MeshInstances> empty = before;
    empty[0].mesh = std::make_shared<const TriangleMesh>();
    EXPECT_EQ(sunCasters(&empty).size(), 1u);
}

TEST(StaticLod, ChunksKnowTheirLargestScaleAndPiecesTheirEngineBoxes) {
    MeshInstances entry;
    auto mesh = std::make_shared<TriangleMesh>(gridMesh(4, 0.25f, 0.0f, 0.0f));  // [0, 1]^2, |z| <= 0.1
    entry.mesh = mesh;
    for (auto [x, s] : {std::pair{1.0f, 0.5f}, {2.0f, 2.0f}, {20.0f, 1.0f}}) {
        InstanceTransform t;
        t.position = {x, 0.0f, 0.0f};
        t.scale = s;
        entry.instances.push_back(t);
    }
    const StaticInstanceChunks chunks = chunkStaticInstances(entry);
    ASSERT_EQ(chunks.chunks.size(), 2u);  // x = 1 and 2 share the 8 m chunk 0; x = 20 is chunk 2
    EXPECT_EQ(chunks.chunks[0].scale_max, 2.0f);
    EXPECT_EQ(chunks.chunks[1].scale_max, 1.0f);
    // A piece box through an instance: moved and scaled (no rotation: exact).
    GpuStaticInstance g;
    g.position_scale = {10.0f, 0.0f, 1.0f, 2.0f};
    const Bounds box = staticInstanceBox(g, Bounds{{0, 0, 0}, {1, 2, 3}});
    EXPECT_EQ(box.lo, glm::vec3(10, 0, 1));
    EXPECT_EQ(box.hi, glm::vec3(12, 4, 7));
    EXPECT_TRUE(staticInstanceBox(g, Bounds{}).empty());
}

TEST(StaticLod, DrawsMergeRunsAtOneLevelAndSkipTheFarthest) {
    // One mesh 0.1 m across with levels of {0, 1 mm, 1 cm, 10 cm} error; chunks of 10 instances at 1, 2, 3,
    // 30 and 300 m along +x from the eye.
    StaticEntryLods e;
    StaticLodPiece p = levels(0.001f, 0.01f, 0.1f);
    p.first = {0, 300, 400, 430};
    p.count = {300, 90, 30, 6};
    p.bounds = Bounds{{0, 0, 0}, {0.1f, 0, 0}};
    e.lods.pieces = {p};
    e.lods.bounds = p.bounds;
    for (float x : {1.0f, 2.0f, 3.0f, 30.0f, 300.0f}) {
        StaticInstanceChunks::Chunk chunk;
        chunk.first = uint32_t(e.chunks.size()) * 10;
        chunk.count = 10;
        chunk.scale_max = 1.0f;
        chunk.bounds = Bounds{{x, -0.05f, -0.05f}, {x + 0.1f, 0.05f, 0.05f}};
        e.chunks.push_back(chunk);
    }
    const glm::mat4 everything = glm::ortho(-1000.0f, 1000.0f, -1000.0f, 1000.0f, -1000.0f, 1000.0f);
    std::vector<StaticDrawRange> draws;
    // 1000 px per radian: at 1 m level 1 is exactly 1 px (not below: level 0); at 2 and 3 m level 1 (one
    // run); at 30 m level 2; at 300 m the mesh covers 0.33 px: skipped.
    uint64_t triangles = buildStaticDraws(e, everything, glm::vec3(0.0f), 1000.0f, 0, &draws);
    ASSERT_EQ(draws.size(), 3u);
    auto expectDraw = [](const StaticDrawRange& d, uint32_t first, uint32_t count, uint32_t inst, uint32_t n) {
        EXPECT_EQ(d.first_index, first);
        EXPECT_EQ(d.index_count, count);
        EXPECT_EQ(d.first_instance, inst);
        EXPECT_EQ(d.instance_count, n);
    };
    expectDraw(draws[0], 0, 300, 0, 10);
    expectDraw(draws[1], 300, 90, 10, 20);
    expectDraw(draws[2], 400, 30, 30, 10);
    EXPECT_EQ(triangles, 100u * 10 + 30u * 20 + 10u * 10);
    // The shadow pass one level coarser, clamped to the coarsest: 1 m at level 1, 2 and 3 m at 2, 30 m at 3.
    triangles = buildStaticDraws(e, everything, glm::vec3(0.0f), 1000.0f, 1, &draws);
    ASSERT_EQ(draws.size(), 3u);
    expectDraw(draws[0], 300, 90, 0, 10);
    expectDraw(draws[1], 400, 30, 10, 20);
    expectDraw(draws[2], 430, 6, 30, 10);
    EXPECT_EQ(triangles, 30u * 10 + 10u * 20 + 2u * 10);
    // A frustum without the 2 m chunk (x in [1.5, 2.5] outside): the 3 m chunk starts a run of its own.
    const glm::mat4 gap = glm::ortho(2.5f, 1000.0f, -1000.0f, 1000.0f, -1000.0f, 1000.0f);
    buildStaticDraws(e, gap, glm::vec3(0.0f), 1000.0f, 0, &draws);
    ASSERT_EQ(draws.size(), 2u);
    expectDraw(draws[0], 300, 90, 20, 10);
    expectDraw(draws[1], 400, 30, 30, 10);
}

}  // namespace ug::editor
