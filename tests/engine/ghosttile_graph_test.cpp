// The collision graph against an independent brute force, and its storage.
#include <gtest/gtest.h>

#include <set>
#include <tuple>

#include "ghosttile/ghost_tile.h"
#include "ghosttile_test_util.h"

namespace ug {
namespace {

using Edge = std::tuple<uint32_t, uint32_t, uint32_t>;  // (i, j, offset index)

std::set<Edge> graphEdges(const GhostTile& tile) {
    std::set<Edge> edges;
    for (uint32_t i = 0; i < tile.graph.nodeCount(); ++i)
        tile.graph.forEachNeighbor(i, [&](uint32_t j, uint32_t v) { edges.insert({i, j, v}); });
    return edges;
}

// Every (i, j, v) over all 27 offsets and all sphere pairs: O(N^2 27 S^2), no grid, no early exit.
std::set<Edge> bruteForceEdges(const GhostTileInput& input, const CandidateSet& c) {
    std::set<Edge> edges;
    const float s = input.settings.tile_size_m;
    std::vector<std::vector<Sphere>> spheres(c.size());
    for (uint32_t i = 0; i < c.size(); ++i) candidateSpheres(c, i, *input.models[c.type[i]], &spheres[i]);
    for (uint32_t i = 0; i < c.size(); ++i)
        for (uint32_t j = 0; j < c.size(); ++j)
            for (uint32_t v = 0; v < kOffsetCount; ++v) {
                if (i == j && v == kCenterOffset) continue;
                glm::vec3 shift = glm::vec3(offsetVector(v)) * s;
                bool hit = false;
                for (const Sphere& a : spheres[i])
                    for (const Sphere& b : spheres[j])
                        hit = hit || spheresCollide(a.center, a.radius, b.center, b.radius, shift,
                                                    input.settings.delta_m);
                if (hit) edges.insert({i, j, v});
            }
    return edges;
}

struct Fixture {
    DetailModel rod = test::rodModel(9, 0.12f, 0.012f);
    DetailModel blob = test::blobModel(6, 0.08f, 3);
    GhostTileInput input;
    Fixture(float delta, uint64_t seed = 7) {
        input.settings = {.tile_size_m = 0.4f, .delta_m = delta, .seed = seed};
        DetailTypeSettings twigs{.name = "twig", .candidate_count = 70, .scale_min = 0.8f, .scale_max = 1.3f};
        twigs.orientation.mode = OrientationMode::Tilt;
        twigs.orientation.tilt_ranges = {{80.0f, 100.0f, 1.0f}};
        DetailTypeSettings rocks{.name = "rock", .candidate_count = 50, .position = PositionMode::Jittered};
        input.types = {twigs, rocks};
        input.models = {&rod, &blob};
    }
};

TEST(GhostTileGraph, EqualsBruteForceAcrossAllOffsetsForAnyDelta) {
    for (float delta : {-0.01f, 0.0f, 0.015f}) {
        Fixture f(delta);
        GhostTile tile;
        std::string error;
        ASSERT_TRUE(buildGhostTile(f.input, {.threads = 2}, &tile, &error)) << error;
        std::set<Edge> expected = bruteForceEdges(f.input, tile.candidates);
        std::set<Edge> got = graphEdges(tile);
        EXPECT_EQ(got, expected) << "delta " << delta;
        // The tile must actually exercise neighbour offsets, or the test proves little.
        size_t cross = 0;
        for (const Edge& e : expected) cross += std::get<2>(e) != kCenterOffset;
        EXPECT_GT(cross, 50u) << "delta " << delta;
        EXPECT_EQ(tile.stats.pair_count * 2, got.size());
    }
}

TEST(GhostTileGraph, EveryEdgeHasItsMirror) {
    Fixture f(0.005f);
    GhostTile tile;
    std::string error;
    ASSERT_TRUE(buildGhostTile(f.input, {}, &tile, &error)) << error;
    std::set<Edge> edges = graphEdges(tile);
    ASSERT_FALSE(edges.empty());
    for (const auto& [i, j, v] : edges) EXPECT_TRUE(edges.count({j, i, mirrorOffset(v)})) << i << " " << j << " " << v;
}

TEST(GhostTileGraph, LargerDeltaOnlyAddsEdges) {
    GhostTile tight, loose;
    std::string error;
    Fixture a(-0.005f), b(0.01f);
    ASSERT_TRUE(buildGhostTile(a.input, {}, &tight, &error)) << error;
    ASSERT_TRUE(buildGhostTile(b.input, {}, &loose, &error)) << error;
    std::set<Edge> e1 = graphEdges(tight), e2 = graphEdges(loose);
    EXPECT_LT(e1.size(), e2.size());
    for (const Edge& e : e1) EXPECT_TRUE(e2.count(e));
}

TEST(GhostTileGraph, SameInputsGiveTheSameTileForAnyThreadCount) {
    Fixture f(0.0f);
    GhostTile reference;
    std::string error;
    ASSERT_TRUE(buildGhostTile(f.input, {.threads = 1}, &reference, &error)) << error;
    for (int threads : {2, 3, 8}) {
        GhostTile tile;
        ASSERT_TRUE(buildGhostTile(f.input, {.threads = threads}, &tile, &error)) << error;
        EXPECT_EQ(tile.key, reference.key);
        EXPECT_EQ(tile.graph.rowOffsets(), reference.graph.rowOffsets()) << threads;
        EXPECT_EQ(tile.graph.encodedBytes(), reference.graph.encodedBytes()) << threads;
        ASSERT_EQ(tile.candidates.size(), reference.candidates.size());
        for (uint32_t i = 0; i < tile.candidates.size(); ++i) {
            EXPECT_EQ(tile.candidates.position[i], reference.candidates.position[i]);
            EXPECT_EQ(tile.candidates.rotation[i], reference.candidates.rotation[i]);
        }
    }
}

TEST(GhostTileGraph, DifferentSeedGivesDifferentTileAndKey) {
    Fixture a(0.0f, 7), b(0.0f, 8);
    GhostTile ta, tb;
    std::string error;
    ASSERT_TRUE(buildGhostTile(a.input, {}, &ta, &error));
    ASSERT_TRUE(buildGhostTile(b.input, {}, &tb, &error));
    EXPECT_NE(ta.key, tb.key);
    EXPECT_NE(ta.graph.encodedBytes(), tb.graph.encodedBytes());
}

TEST(GhostTileGraph, StoresEachPairInAtMostFourBytes) {
    Fixture f(0.01f);
    f.input.types[0].candidate_count = 600;
    GhostTile tile;
    std::string error;
    ASSERT_TRUE(buildGhostTile(f.input, {}, &tile, &error)) << error;
    ASSERT_GT(tile.stats.pair_count, 10000u);
    EXPECT_LE(tile.stats.bytes_per_pair, 4.0);
    EXPECT_DOUBLE_EQ(tile.stats.rho, double(tile.stats.pair_count) / tile.stats.candidate_count);
}

TEST(CollisionGraph, RowsRoundTripIncludingMultiByteDeltas) {
    // Row 0: keys with deltas needing 1, 2 and 3 varint bytes; row 1 empty; row 2 starts at key 0.
    const uint32_t n = 20000;
    std::vector<std::vector<uint32_t>> rows(3);
    rows.resize(n);
    rows[0] = {5, 6, 200, 20000, 539999};
    rows[2] = {0, 1, 2, 127, 128, 16511};
    CollisionGraph g;
    std::string error;
    ASSERT_TRUE(CollisionGraph::fromRows(n, rows, &g, &error)) << error;
    EXPECT_EQ(g.edgeCount(), 11u);
    for (uint32_t i : {0u, 1u, 2u}) {
        std::vector<uint32_t> back;
        g.forEachNeighbor(i, [&](uint32_t j, uint32_t v) { back.push_back(j * kOffsetCount + v); });
        EXPECT_EQ(back, rows[i]) << "row " << i;
    }
    EXPECT_EQ(g.degree(1), 0u);
    EXPECT_TRUE(g.hasEdge(0, 539999 / 27, 539999 % 27));
    EXPECT_FALSE(g.hasEdge(0, 1, 0));
}

TEST(CollisionGraph, RejectsUnsortedRowsAndOutOfRangeKeys) {
    CollisionGraph g;
    std::string error;
    EXPECT_FALSE(CollisionGraph::fromRows(2, {{3, 2}, {}}, &g, &error));
    EXPECT_FALSE(CollisionGraph::fromRows(2, {{54}, {}}, &g, &error));  // 2 nodes * 27 = 54 keys
    EXPECT_FALSE(CollisionGraph::fromRows(2, {{1, 1}, {}}, &g, &error));
    // A stream whose last byte promises a continuation that never comes.
    EXPECT_FALSE(CollisionGraph::fromEncoded(1, {0, 1}, {0x80}, &g, &error));
    EXPECT_NE(error.find("truncated"), std::string::npos) << error;
}

TEST(CollisionGraph, OffsetIndexAndMirror) {
    for (uint32_t v = 0; v < kOffsetCount; ++v) {
        EXPECT_EQ(offsetIndex(offsetVector(v)), v);
        EXPECT_EQ(offsetVector(mirrorOffset(v)), -offsetVector(v));
    }
    EXPECT_EQ(offsetIndex({0, 0, 0}), kCenterOffset);
}

}  // namespace
}  // namespace ug
