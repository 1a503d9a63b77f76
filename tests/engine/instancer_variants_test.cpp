// Instantiation with Ghost Tile variants: each tile holds the variant tileVariant() picks, the selection
// still equals the sequential greedy reference and the sphere-set distances, and every exactness property
// (incremental = full, threads, tile order, regions) holds when neighbours hold different variants.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "core/hash.h"
#include "instancer_test_util.h"

namespace ug {
namespace {

using test::InstancerFixture;
using test::instancesOf;

constexpr uint32_t kVariants = 4;

InstanceStats run(Instantiator& inst, int threads = 2, uint64_t order_seed = 0) {
    InstanceStats stats;
    std::string error;
    EXPECT_TRUE(inst.instantiateAll({.threads = threads, .tile_order_seed = order_seed}, &stats, &error)) << error;
    return stats;
}

// The instancer tests' pile and patch.
void setPileFields(InstancerFixture& fx) {
    fx.input.types[0].field = InstancerFixture::field(
        {makePoint({0.0f, 0.0f, 0.0f}, 1.2f, 3.0f), makePoint({0.9f, 0.4f, 0.1f}, 0.6f, 2.0f)});
    fx.input.types[1].field = InstancerFixture::field({makeSegment({-1.2f, -0.8f, 0.0f}, {0.8f, 0.9f, 0.2f}, 0.5f, 2.5f)});
}

// Fields saturated over the whole extent: every tile tests every type, and acceptance is 1.
void setSaturatedFields(InstancerFixture& fx) {
    fx.input.types[0].field = InstancerFixture::field({makeBox({0, 0, 0}, glm::vec3(3.0f), 0.1f, 3.0f)});
    fx.input.types[1].field = InstancerFixture::field({makeBox({0, 0, 0}, glm::vec3(3.0f), 0.1f, 2.0f)});
}

uint32_t variantOfTile(const InstancerFixture& fx, uint64_t tile_key) {
    return tileVariant(fx.input.seed, tile_key, fx.tile.settings.variants);
}

TEST(InstancerVariants, TileVariantIsAHashOfSeedAndTile) {
    EXPECT_EQ(tileVariant(5, packTile({3, -2, 1}), 1), 0u);
    std::vector<uint32_t> seen(kVariants, 0);
    for (int x = -10; x < 10; ++x)
        for (int y = -10; y < 10; ++y) {
            const uint32_t v = tileVariant(5, packTile({x, y, 0}), kVariants);
            ASSERT_LT(v, kVariants);
            ++seen[v];
            EXPECT_EQ(v, tileVariant(5, packTile({x, y, 0}), kVariants));
        }
    for (uint32_t v = 0; v < kVariants; ++v) EXPECT_GT(seen[v], 60u) << v;  // 400 tiles, ~100 each
    uint32_t differ = 0;
    for (int x = 0; x < 50; ++x) differ += tileVariant(5, packTile({x, 0, 0}), 8) != tileVariant(6, packTile({x, 0, 0}), 8);
    EXPECT_GT(differ, 30u);  // the seed matters
}

TEST(InstancerVariants, EachTileSelectsOnlyFromItsVariantAndNeighboursDiffer) {
    InstancerFixture fx(0.0f, 150, 100, kVariants);
    setPileFields(fx);
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    const InstanceStats st = run(inst);
    ASSERT_GT(st.instances, 100u);
    const CandidateSet& c = fx.tile.candidates;
    std::set<uint64_t> tiles;
    inst.store().forEach([&](uint64_t t, uint32_t j) {
        const uint32_t v = variantOfTile(fx, t);
        const uint32_t type = c.type[j];
        ASSERT_GE(j, c.variantBegin(type, v));
        ASSERT_LT(j, c.variantEnd(type, v));
        tiles.insert(t);
    });
    for (const auto& a : inst.aliveCandidates()) ASSERT_EQ(c.variantOf(a.candidate), variantOfTile(fx, a.tile_key));
    // Face neighbours with instances on both sides and different variants: the case the graph's
    // cross-variant edges exist for.
    size_t differing = 0;
    for (uint64_t t : tiles)
        for (const glm::ivec3 e : {glm::ivec3(1, 0, 0), glm::ivec3(0, 1, 0), glm::ivec3(0, 0, 1)}) {
            const uint64_t u = packTile(unpackTile(t) + e);
            if (tiles.count(u) && variantOfTile(fx, u) != variantOfTile(fx, t)) ++differing;
        }
    EXPECT_GT(differing, 20u);
}

TEST(InstancerVariants, CountsOnlyTheTestedVariant) {
    InstancerFixture fx(0.0f, 150, 100, kVariants);
    setSaturatedFields(fx);
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    const InstanceStats st = run(inst);
    ASSERT_GT(st.tiles_touched, 100u);
    EXPECT_EQ(st.candidates_tested, st.tiles_touched * (150 + 100));  // one variant per tile, not 4
    EXPECT_EQ(st.candidates_tested, st.culled + st.density_rejected + st.constraint_rejected + st.alive);
}

TEST(InstancerVariants, MemoryBudgetCountsOneVariantPerTile) {
    // A tile's state holds at most its variant's candidates: the budget's per-tile bound (named in the
    // refusal) uses 250, not the 1,000 the Ghost Tile stores.
    InstancerFixture fx(0.0f, 150, 100, kVariants);
    setSaturatedFields(fx);
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    InstanceStats st;
    EXPECT_FALSE(inst.instantiateAll({.threads = 2, .max_memory_bytes = 64 << 10}, &st, &error));
    EXPECT_NE(error.find("tiles of 250 candidates"), std::string::npos) << error;
}

TEST(InstancerVariants, MatchesTheSequentialGreedyReference) {
    for (float delta : {0.0f, 0.15f}) {
        InstancerFixture fx(delta, 150, 100, kVariants);
        setPileFields(fx);
        Instantiator inst;
        std::string error;
        ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
        const InstanceStats st = run(inst);
        ASSERT_GT(st.instances, 50u);
        EXPECT_EQ(instancesOf(inst.store()), test::greedyReference(inst)) << "delta " << delta;
    }
}

// Sphere-set distances between selected instances in world space (not through the collision graph):
// no pair closer than δ, counting the pairs across a border between tiles of different variants.
void checkSeparation(float delta_m) {
    InstancerFixture fx(delta_m, 150, 100, kVariants);
    setPileFields(fx);
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    run(inst);
    const auto keys = instancesOf(inst.store());
    std::vector<std::vector<Sphere>> spheres;
    std::vector<glm::vec4> bound;
    for (const auto& [t, j] : keys) {
        spheres.push_back(test::worldSpheres(fx.tile, fx.models[fx.tile.candidates.type[j]], t, j));
        glm::vec3 lo(1e9f), hi(-1e9f);
        for (const Sphere& s : spheres.back()) {
            lo = glm::min(lo, s.center - s.radius);
            hi = glm::max(hi, s.center + s.radius);
        }
        bound.push_back(glm::vec4((lo + hi) * 0.5f, glm::length(hi - lo) * 0.5f));
    }
    size_t cross_variant_pairs = 0;
    for (size_t a = 0; a < spheres.size(); ++a)
        for (size_t b = a + 1; b < spheres.size(); ++b) {
            if (glm::length(glm::vec3(bound[a]) - glm::vec3(bound[b])) - bound[a].w - bound[b].w > delta_m + 1e-3f)
                continue;
            if (variantOfTile(fx, keys[a].first) != variantOfTile(fx, keys[b].first)) ++cross_variant_pairs;
            float d = 1e9f;
            for (const Sphere& x : spheres[a])
                for (const Sphere& y : spheres[b]) d = std::min(d, glm::length(x.center - y.center) - (x.radius + y.radius));
            ASSERT_GT(d, delta_m - 1e-5f) << "instances " << a << " and " << b << " overlap beyond delta";
        }
    EXPECT_GT(cross_variant_pairs, 30u);
}

TEST(InstancerVariants, NoTwoInstancesCloserThanDeltaZero) { checkSeparation(0.0f); }
TEST(InstancerVariants, NoTwoInstancesCloserThanPositiveDelta) { checkSeparation(0.02f); }

TEST(InstancerVariants, SameResultForAnyThreadCountAndTileOrder) {
    InstancerFixture fx(0.0f, 150, 100, kVariants);
    setPileFields(fx);
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    run(inst, 1);
    const InstanceStore reference = inst.store();
    for (int threads : {2, 3, 8})
        for (uint64_t order : {0ull, 7ull}) {
            run(inst, threads, order);
            EXPECT_TRUE(inst.store() == reference) << threads << " threads, order " << order;
        }
}

TEST(InstancerVariants, UnionOfRegionsEqualsTheWhole) {
    InstancerFixture fx(0.15f, 150, 100, kVariants);
    setPileFields(fx);
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    run(inst);
    const auto whole = instancesOf(inst.store());
    const float xs[] = {-2.0f, -0.37f, 0.61f, 2.0f};
    const float ys[] = {-2.0f, 0.13f, 2.0f};
    std::vector<test::InstanceKey> joined;
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 2; ++k) {
            const Bounds region{glm::vec3(xs[i], ys[k], -1.0f), glm::vec3(xs[i + 1], ys[k + 1], 1.0f)};
            InstanceStore part;
            ASSERT_TRUE(instantiateRegion(fx.input, region, {.threads = 2}, &part, nullptr, &error)) << error;
            const auto keys = instancesOf(part);
            joined.insert(joined.end(), keys.begin(), keys.end());
        }
    std::sort(joined.begin(), joined.end());
    EXPECT_EQ(joined, whole);
}

class VariantsIncrementalEqualsFull : public ::testing::TestWithParam<float> {};

TEST_P(VariantsIncrementalEqualsFull, AfterRandomEdits) {
    InstancerFixture fx(GetParam(), 90, 60, kVariants);
    std::vector<std::vector<Primitive>> prims(2);
    prims[0] = {makeBox({0.0f, 0.0f, 0.0f}, glm::vec3(1.2f, 1.2f, 0.4f), 0.5f, 3.0f)};
    prims[1] = {makeBox({0.0f, 0.0f, 0.0f}, glm::vec3(1.2f, 1.2f, 0.4f), 0.5f, 2.0f)};
    auto apply = [&](InstancerInput* in) {
        for (int i = 0; i < 2; ++i) in->types[size_t(i)].field = InstancerFixture::field(prims[size_t(i)]);
    };
    apply(&fx.input);
    Instantiator live;
    std::string error;
    ASSERT_TRUE(live.setInput(fx.input, &error)) << error;
    run(live);
    std::mt19937 rng(4321);
    auto uni = [&](float a, float b) { return std::uniform_real_distribution<float>(a, b)(rng); };
    size_t compared = 0;
    for (int edit = 0; edit < 90; ++edit) {
        const size_t type = size_t(rng() % 2);
        std::vector<Primitive>& list = prims[type];
        std::vector<Bounds> dirty;
        auto bounds = [&](const Primitive& p) { return primitiveBounds(p, nullptr); };
        if (list.empty() || rng() % 3 == 0) {  // add
            const glm::vec3 c(uni(-1.6f, 1.6f), uni(-1.6f, 1.6f), uni(-0.6f, 0.6f));
            list.push_back(makePoint(c, uni(0.3f, 0.9f), uni(-1.0f, 5.0f)));
            dirty.push_back(bounds(list.back()));
        } else if (rng() % 2 == 0) {  // move
            const size_t k = rng() % list.size();
            dirty.push_back(bounds(list[k]));
            const glm::vec3 d(uni(-0.3f, 0.3f), uni(-0.3f, 0.3f), uni(-0.1f, 0.1f));
            list[k].center_m += d;
            list[k].end_m += d;
            dirty.push_back(bounds(list[k]));
        } else {  // delete
            const size_t k = rng() % list.size();
            dirty.push_back(bounds(list[k]));
            list.erase(list.begin() + long(k));
        }
        std::vector<InstanceTypeSettings> types = live.input().types;
        types[type].field = InstancerFixture::field(list);
        ASSERT_TRUE(live.update(types, dirty, {.threads = 2}, nullptr, nullptr, &error)) << error;
        if (edit % 3 == 2) {
            InstancerInput fresh_input = fx.input;
            apply(&fresh_input);
            Instantiator fresh;
            ASSERT_TRUE(fresh.setInput(fresh_input, &error)) << error;
            run(fresh, 1);
            ASSERT_TRUE(live.store() == fresh.store()) << "after edit " << edit;
            EXPECT_EQ(instancesOf(live.store()), test::greedyReference(live)) << "after edit " << edit;
            ++compared;
        }
    }
    EXPECT_EQ(compared, 30u);
}

INSTANTIATE_TEST_SUITE_P(InstancerVariants, VariantsIncrementalEqualsFull, ::testing::Values(0.0f, 0.15f));

// The measure: the share of instances with an exact twin (same candidate, so the same position
// modulo the tile) one tile away. Per offset (the tile's period vectors, averaged over the 26), and at any
// of the 26 offsets. Tiles of the same variant still meet (a neighbour holds the same one with
// probability 1 / variants), so the per-offset share falls about as 1 / variants, the any-offset share
// much less at 4 variants.
struct TwinShares {
    double per_offset = 0.0, any_offset = 0.0;
};

TwinShares twinShares(uint32_t variants) {
    InstancerFixture fx(0.0f, 150, 100, variants);
    setSaturatedFields(fx);
    Instantiator inst;
    std::string error;
    EXPECT_TRUE(inst.setInput(fx.input, &error)) << error;
    run(inst);
    const auto keys = instancesOf(inst.store());
    const std::set<test::InstanceKey> all(keys.begin(), keys.end());
    uint64_t per_offset = 0, any = 0;
    for (const auto& [t, j] : keys) {
        bool twin = false;
        for (uint32_t v = 0; v < kOffsetCount; ++v) {
            if (v == kCenterOffset || !all.count({packTile(unpackTile(t) + offsetVector(v)), j})) continue;
            ++per_offset;
            twin = true;
        }
        any += twin;
    }
    if (keys.empty()) return {};
    return {double(per_offset) / (26.0 * double(keys.size())), double(any) / double(keys.size())};
}

TEST(InstancerVariants, FewerExactTwinsOneTileAway) {
    const TwinShares one = twinShares(1), four = twinShares(kVariants), many = twinShares(16);
    std::printf("exact twin one tile away, per offset / at any of the 26: 1 variant %.1f %% / %.1f %%, "
                "4 variants %.1f %% / %.1f %%, 16 variants %.1f %% / %.1f %%\n",
                100.0 * one.per_offset, 100.0 * one.any_offset, 100.0 * four.per_offset, 100.0 * four.any_offset,
                100.0 * many.per_offset, 100.0 * many.any_offset);
    EXPECT_GT(one.per_offset, 0.08);
    EXPECT_LT(four.per_offset, 0.4 * one.per_offset);  // ~1/4 expected
    EXPECT_LT(many.per_offset, 0.15 * one.per_offset);  // ~1/16 expected
    EXPECT_LT(many.any_offset, 0.8 * one.any_offset);
}

}  // namespace
}  // namespace ug
