// Tile variants (docs/architecture.md "No period"): independent draws of each type's candidates, several per
// tile, with the collision graph between a tile's own variant (offset 0) and any variant of its neighbours.
#include <gtest/gtest.h>

#include <set>
#include <tuple>

#include "core/hash.h"
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

// The definition, by brute force: i and j (at offset v) are joined when some pair of their spheres
// collides, except at offset 0 between two variants (one tile holds one variant, so they never meet).
// The variant of a candidate is computed here from the layout, not with the header's helpers.
std::set<Edge> bruteForceEdges(const GhostTileInput& input, const CandidateSet& c) {
    const uint32_t variants = input.settings.variants;
    std::vector<uint32_t> variant(c.size());
    for (uint32_t t = 0; t + 1 < c.type_begin.size(); ++t) {
        const uint32_t count = input.types[t].candidate_count;
        for (uint32_t i = c.type_begin[t]; i < c.type_begin[t + 1]; ++i) variant[i] = (i - c.type_begin[t]) / count;
    }
    std::set<Edge> edges;
    const float s = input.settings.tile_size_m;
    std::vector<std::vector<Sphere>> spheres(c.size());
    for (uint32_t i = 0; i < c.size(); ++i) candidateSpheres(c, i, *input.models[c.type[i]], &spheres[i]);
    for (uint32_t i = 0; i < c.size(); ++i)
        for (uint32_t j = 0; j < c.size(); ++j)
            for (uint32_t v = 0; v < kOffsetCount; ++v) {
                if (v == kCenterOffset && (i == j || (variants > 1 && variant[i] != variant[j]))) continue;
                const glm::vec3 shift = glm::vec3(offsetVector(v)) * s;
                bool hit = false;
                for (const Sphere& a : spheres[i])
                    for (const Sphere& b : spheres[j])
                        hit = hit || spheresCollide(a.center, a.radius, b.center, b.radius, shift,
                                                    input.settings.delta_m);
                if (hit) edges.insert({i, j, v});
            }
    return edges;
}

// The graph test's fixture (twigs and rocks in a 0.4 m tile), with a variant count.
struct Fixture {
    DetailModel rod = test::rodModel(9, 0.12f, 0.012f);
    DetailModel blob = test::blobModel(6, 0.08f, 3);
    GhostTileInput input;
    explicit Fixture(uint32_t variants, float delta = 0.005f, uint32_t twigs_n = 70, uint32_t rocks_n = 50) {
        input.settings = {.tile_size_m = 0.4f, .delta_m = delta, .seed = 7, .variants = variants};
        DetailTypeSettings twigs{.name = "twig", .candidate_count = twigs_n, .scale_min = 0.8f, .scale_max = 1.3f};
        twigs.orientation.mode = OrientationMode::Tilt;
        twigs.orientation.tilt_ranges = {{80.0f, 100.0f, 1.0f}};
        DetailTypeSettings rocks{.name = "rock", .candidate_count = rocks_n, .position = PositionMode::Jittered};
        input.types = {twigs, rocks};
        input.models = {&rod, &blob};
    }
};

// A fingerprint of everything a tile holds, to compare against the builder before variants existed.
uint64_t fingerprint(const GhostTile& t) {
    Hasher h;
    h.add(t.key);
    const CandidateSet& c = t.candidates;
    h.addBytes(c.type_begin.data(), c.type_begin.size() * sizeof(uint32_t));
    h.addBytes(c.type.data(), c.type.size() * sizeof(uint16_t));
    h.addBytes(c.position.data(), c.position.size() * sizeof(glm::vec3));
    h.addBytes(c.rotation.data(), c.rotation.size() * sizeof(glm::quat));
    h.addBytes(c.scale.data(), c.scale.size() * sizeof(float));
    h.addBytes(t.graph.rowOffsets().data(), t.graph.rowOffsets().size() * sizeof(uint32_t));
    h.addBytes(t.graph.encodedBytes().data(), t.graph.encodedBytes().size());
    return h.value();
}

TEST(GhostTileVariants, OneVariantIsBitIdenticalToTheBuilderBeforeVariants) {
    // Key and fingerprint printed by the builder at 8efccc5 (before variants) for this fixture, delta
    // 0.005 m: a variants = 1 tile, its key and its graph must not change, or every cache and bench moves.
    Fixture f(1);
    GhostTile tile;
    std::string error;
    ASSERT_TRUE(buildGhostTile(f.input, {.threads = 2}, &tile, &error)) << error;
    EXPECT_EQ(hex64(tile.key), "003f708f293009ea");
    EXPECT_EQ(hex64(fingerprint(tile)), "7d5466b551b1aafa");
    EXPECT_EQ(tile.candidates.variants, 1u);
}

TEST(GhostTileVariants, LayoutIsGroupedByTypeThenVariant) {
    Fixture f(4);
    CandidateSet c;
    std::string error;
    ASSERT_TRUE(generateCandidates(f.input, &c, &error)) << error;
    ASSERT_EQ(c.variants, 4u);
    ASSERT_EQ(c.size(), 4u * (70 + 50));
    EXPECT_EQ(c.type_begin, (std::vector<uint32_t>{0, 280, 480}));
    EXPECT_EQ(c.perVariantSize(), 120u);
    for (uint32_t t = 0; t < 2; ++t)
        for (uint32_t v = 0; v < 4; ++v) {
            const uint32_t count = t == 0 ? 70 : 50;
            EXPECT_EQ(c.variantBegin(t, v), c.type_begin[t] + v * count);
            EXPECT_EQ(c.variantEnd(t, v), c.type_begin[t] + (v + 1) * count);
            for (uint32_t i = c.variantBegin(t, v); i < c.variantEnd(t, v); ++i) {
                ASSERT_EQ(c.type[i], t);
                ASSERT_EQ(c.variantOf(i), v) << i;
            }
        }
}

TEST(GhostTileVariants, VariantZeroIsTodaysCandidatesAndOthersAreFreshDraws) {
    Fixture one(1), four(4);
    CandidateSet a, b;
    std::string error;
    ASSERT_TRUE(generateCandidates(one.input, &a, &error)) << error;
    ASSERT_TRUE(generateCandidates(four.input, &b, &error)) << error;
    for (uint32_t t = 0; t < 2; ++t) {
        const uint32_t count = a.type_begin[t + 1] - a.type_begin[t];
        for (uint32_t k = 0; k < count; ++k) {
            const uint32_t i = a.type_begin[t] + k, j = b.variantBegin(t, 0) + k;
            ASSERT_EQ(a.position[i], b.position[j]);
            ASSERT_EQ(a.rotation[i], b.rotation[j]);
            ASSERT_EQ(a.scale[i], b.scale[j]);
        }
        // Other variants are independent draws: no frame repeats variant 0's.
        for (uint32_t v = 1; v < 4; ++v) {
            uint32_t same = 0;
            for (uint32_t k = 0; k < count; ++k)
                same += b.position[b.variantBegin(t, v) + k] == b.position[b.variantBegin(t, 0) + k];
            EXPECT_EQ(same, 0u) << "type " << t << " variant " << v;
        }
    }
    // Jittered rocks stay one per cell in every variant (same distribution as variant 0).
    const float s = four.input.settings.tile_size_m;
    for (uint32_t v = 0; v < 4; ++v) {
        std::set<std::tuple<int, int, int>> cells;
        for (uint32_t i = b.variantBegin(1, v); i < b.variantEnd(1, v); ++i) {
            const glm::ivec3 cell = glm::ivec3(glm::floor(b.position[i] / (s / 4.0f)));  // 4^3 >= 50
            cells.insert({cell.x, cell.y, cell.z});
            ASSERT_TRUE(glm::all(glm::lessThan(b.position[i], glm::vec3(s))));
        }
        EXPECT_EQ(cells.size(), 50u) << "variant " << v;
    }
}

TEST(GhostTileVariants, GraphEqualsBruteForceWithTheVariantRule) {
    for (float delta : {-0.01f, 0.01f}) {
        Fixture f(3, delta, 40, 30);
        GhostTile tile;
        std::string error;
        ASSERT_TRUE(buildGhostTile(f.input, {.threads = 2}, &tile, &error)) << error;
        const std::set<Edge> got = graphEdges(tile);
        EXPECT_EQ(got, bruteForceEdges(f.input, tile.candidates)) << "delta " << delta;
        EXPECT_EQ(tile.stats.pair_count * 2, got.size());
    }
}

TEST(GhostTileVariants, MirrorsSameVariantAtOffsetZeroAndCrossVariantNeighbours) {
    Fixture f(4);
    GhostTile tile;
    std::string error;
    ASSERT_TRUE(buildGhostTile(f.input, {}, &tile, &error)) << error;
    const CandidateSet& c = tile.candidates;
    const std::set<Edge> edges = graphEdges(tile);
    ASSERT_FALSE(edges.empty());
    size_t same_tile = 0, cross_variant = 0;
    for (const auto& [i, j, v] : edges) {
        EXPECT_TRUE(edges.count({j, i, mirrorOffset(v)})) << i << " " << j << " " << v;
        if (v == kCenterOffset) {
            EXPECT_EQ(c.variantOf(i), c.variantOf(j)) << "offset-0 edge between variants: " << i << " " << j;
            ++same_tile;
        } else if (c.variantOf(i) != c.variantOf(j)) {
            ++cross_variant;
        }
    }
    EXPECT_GT(same_tile, 100u);
    EXPECT_GT(cross_variant, 500u);  // a neighbour may hold any variant
}

TEST(GhostTileVariants, VariantZeroSubgraphIsTheOneVariantGraph) {
    // Restricted to variant 0, a variants = 4 tile is today's tile: same candidates, same edges at every
    // offset (the builder's variant rule only removes offset-0 edges between different variants).
    Fixture one(1), four(4);
    GhostTile a, b;
    std::string error;
    ASSERT_TRUE(buildGhostTile(one.input, {.threads = 1}, &a, &error)) << error;
    ASSERT_TRUE(buildGhostTile(four.input, {.threads = 3}, &b, &error)) << error;
    auto toOne = [&](uint32_t id) {  // a variant-0 id of b as an id of a
        const uint32_t t = b.candidates.type[id];
        return a.candidates.type_begin[t] + (id - b.candidates.type_begin[t]);
    };
    std::set<Edge> restricted;
    for (const auto& [i, j, v] : graphEdges(b))
        if (b.candidates.variantOf(i) == 0 && b.candidates.variantOf(j) == 0) restricted.insert({toOne(i), toOne(j), v});
    EXPECT_EQ(restricted, graphEdges(a));
}

TEST(GhostTileVariants, SameTileForAnyThreadCount) {
    Fixture f(4);
    GhostTile reference;
    std::string error;
    ASSERT_TRUE(buildGhostTile(f.input, {.threads = 1}, &reference, &error)) << error;
    for (int threads : {2, 5}) {
        GhostTile tile;
        ASSERT_TRUE(buildGhostTile(f.input, {.threads = threads}, &tile, &error)) << error;
        EXPECT_EQ(fingerprint(tile), fingerprint(reference)) << threads;
    }
}

TEST(GhostTileVariants, KeyDependsOnTheVariantCountAndOneKeepsTodaysKey) {
    Fixture f(1);
    const uint64_t one = ghostTileKey(f.input);
    f.input.settings.variants = 2;
    const uint64_t two = ghostTileKey(f.input);
    f.input.settings.variants = 3;
    EXPECT_NE(one, two);
    EXPECT_NE(ghostTileKey(f.input), two);
}

TEST(GhostTileVariants, ValidationRefusesBadVariantCounts) {
    std::string error;
    for (uint32_t bad : {0u, 65u}) {
        Fixture f(bad);
        EXPECT_FALSE(validateGhostTileInput(f.input, &error)) << bad;
        EXPECT_NE(error.find("variants"), std::string::npos) << error;
        EXPECT_NE(error.find("[1, 64]"), std::string::npos) << error;
    }
    Fixture ok(64);
    EXPECT_TRUE(validateGhostTileInput(ok.input, &error)) << error;
    // 40,000 candidates in all are fine once, not 64 times (2.56 M > kMaxCandidatesPerTile).
    Fixture big(64, 0.0f, 20000, 20000);
    EXPECT_FALSE(validateGhostTileInput(big.input, &error));
    EXPECT_NE(error.find("64 variants"), std::string::npos) << error;
    EXPECT_NE(error.find(std::to_string(kMaxCandidatesPerTile)), std::string::npos) << error;
    big.input.settings.variants = 26;  // 26 x 40,000 = 1,040,000 <= 1,048,576
    EXPECT_TRUE(validateGhostTileInput(big.input, &error)) << error;
}

}  // namespace
}  // namespace ug
