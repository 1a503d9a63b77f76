// The instantiator against independent references: brute-force sphere distances, a sequential greedy
// selection, full vs incremental vs region vs thread counts, and the field / constraint contracts.
#include <cmath>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "core/hash.h"
#include "instancer_test_util.h"

namespace ug {
namespace {

using test::InstancerFixture;
using test::instancesOf;

InstanceStats run(Instantiator& inst, int threads = 2, uint64_t order_seed = 0) {
    InstanceStats stats;
    std::string error;
    EXPECT_TRUE(inst.instantiateAll({.threads = threads, .tile_order_seed = order_seed}, &stats, &error)) << error;
    return stats;
}

// A pile and a patch: a blob field and a rod field overlapping around the origin.
void setPileFields(InstancerFixture& fx) {
    fx.input.types[0].field = InstancerFixture::field(
        {makePoint({0.0f, 0.0f, 0.0f}, 1.2f, 3.0f), makePoint({0.9f, 0.4f, 0.1f}, 0.6f, 2.0f)});
    fx.input.types[1].field = InstancerFixture::field({makeSegment({-1.2f, -0.8f, 0.0f}, {0.8f, 0.9f, 0.2f}, 0.5f, 2.5f)});
}

TEST(Instancer, MatchesTheSequentialGreedyReference) {
    InstancerFixture fx;
    setPileFields(fx);
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    const InstanceStats st = run(inst);
    ASSERT_GT(st.instances, 100u);
    EXPECT_EQ(instancesOf(inst.store()), test::greedyReference(inst));
    EXPECT_EQ(st.instances, st.instances_per_type[0] + st.instances_per_type[1]);
    EXPECT_GT(st.instances_per_type[0], 0u);
    EXPECT_GT(st.instances_per_type[1], 0u);
    EXPECT_EQ(st.candidates_tested, st.culled + st.density_rejected + st.constraint_rejected + st.alive);
}

// The alive set against a direct test of every candidate of every tile: origin in the extent, the density
// positive at each anchor, and the acceptance draw below the anchors' mean (DESIGN.md, "exact
// instantiation"). Thin slabs crossing tile borders in z are what the z-ordered culling skips most of.
TEST(Instancer, AliveCandidatesMatchADirectTestOnThinLayers) {
    InstancerFixture fx;
    fx.input.types[0].field = InstancerFixture::field({makeBox({0.0f, 0.0f, 0.02f}, {1.6f, 1.4f, 0.0f}, 0.05f, 1.5f)});
    fx.input.types[1].field = InstancerFixture::field({makeBox({0.2f, -0.1f, -0.49f}, {1.2f, 1.5f, 0.0f}, 0.04f, 2.0f)});
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    run(inst);
    std::set<test::InstanceKey> expected;
    const float s = fx.tile.settings.tile_size_m;
    const CandidateSet& c = fx.tile.candidates;
    const Bounds& e = fx.input.extent;
    const glm::ivec3 lo = tileOf(e.lo, s) - 1, hi = tileOf(e.hi, s) + 1;
    for (int x = lo.x; x <= hi.x; ++x)
        for (int y = lo.y; y <= hi.y; ++y)
            for (int z = lo.z; z <= hi.z; ++z) {
                const glm::ivec3 t(x, y, z);
                const uint64_t key = packTile(t);
                const glm::vec3 origin = tileOrigin(t, s);
                for (uint32_t j = 0; j < c.size(); ++j) {
                    const glm::vec3 o = origin + c.position[j];
                    if (!(e.lo.x <= o.x && o.x < e.hi.x && e.lo.y <= o.y && o.y < e.hi.y && e.lo.z <= o.z && o.z < e.hi.z))
                        continue;
                    const DensityField& f = *fx.input.types[c.type[j]].field;
                    const DetailModel& m = fx.models[c.type[j]];
                    bool positive = true;
                    float sum = 0.0f;
                    for (const glm::vec3& a : m.anchors) {
                        const float v = evaluate(f, origin + (c.position[j] + c.rotation[j] * (c.scale[j] * a)));
                        positive = positive && v > 0.0f;
                        sum += v;
                    }
                    const float mean = sum / float(m.anchors.size());
                    if (positive && unitFloat(hashWords(fx.input.seed, key, j, 1)) < std::min(1.0f, mean))
                        expected.insert({key, j});
                }
            }
    std::set<test::InstanceKey> alive;
    for (const auto& a : inst.aliveCandidates()) alive.insert({a.tile_key, a.candidate});
    EXPECT_GT(expected.size(), 100u);
    EXPECT_EQ(alive, expected);
}

// No two selected instances closer than δ, across tile borders too, measured on world-space sphere sets
// built from the candidate frames (not from the collision graph). Also maximality: every alive candidate
// left out does collide with a selected one.
void checkSeparation(float delta_m) {
    InstancerFixture fx(delta_m);
    setPileFields(fx);
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    run(inst);
    const auto inst_keys = instancesOf(inst.store());
    std::vector<std::vector<Sphere>> spheres;
    std::vector<glm::vec4> bound;  // centre, radius of each sphere set
    for (const auto& [t, j] : inst_keys) {
        spheres.push_back(test::worldSpheres(fx.tile, fx.models[fx.tile.candidates.type[j]], t, j));
        glm::vec3 lo(1e9f), hi(-1e9f);
        for (const Sphere& s : spheres.back()) {
            lo = glm::min(lo, s.center - s.radius);
            hi = glm::max(hi, s.center + s.radius);
        }
        bound.push_back(glm::vec4((lo + hi) * 0.5f, glm::length(hi - lo) * 0.5f));
    }
    auto distance = [](const std::vector<Sphere>& a, const std::vector<Sphere>& b) {
        float d = 1e9f;
        for (const Sphere& x : a)
            for (const Sphere& y : b) d = std::min(d, glm::length(x.center - y.center) - (x.radius + y.radius));
        return d;
    };
    size_t cross_tile_pairs_checked = 0;
    for (size_t a = 0; a < spheres.size(); ++a)
        for (size_t b = a + 1; b < spheres.size(); ++b) {
            if (glm::length(glm::vec3(bound[a]) - glm::vec3(bound[b])) - bound[a].w - bound[b].w > delta_m + 1e-3f) continue;
            if (inst_keys[a].first != inst_keys[b].first) ++cross_tile_pairs_checked;
            ASSERT_GT(distance(spheres[a], spheres[b]), delta_m - 1e-5f)
                << "instances " << a << " and " << b << " overlap beyond delta";
        }
    EXPECT_GT(cross_tile_pairs_checked, 50u);
}

TEST(Instancer, NoTwoInstancesCloserThanDeltaZero) { checkSeparation(0.0f); }
TEST(Instancer, NoTwoInstancesCloserThanNegativeDelta) { checkSeparation(-0.01f); }
TEST(Instancer, NoTwoInstancesCloserThanPositiveDelta) { checkSeparation(0.02f); }

TEST(Instancer, SameResultForAnyThreadCountAndTileOrder) {
    InstancerFixture fx;
    setPileFields(fx);
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    run(inst, 1);
    const InstanceStore reference = inst.store();
    for (int threads : {2, 3, 8})
        for (uint64_t order : {0ull, 1ull, 99ull}) {
            run(inst, threads, order);
            EXPECT_TRUE(inst.store() == reference) << threads << " threads, order " << order;
        }
}

TEST(Instancer, DifferentSeedGivesDifferentResult) {
    InstancerFixture fx;
    setPileFields(fx);
    Instantiator a, b;
    std::string error;
    ASSERT_TRUE(a.setInput(fx.input, &error)) << error;
    fx.input.seed = 6;
    ASSERT_TRUE(b.setInput(fx.input, &error)) << error;
    run(a);
    run(b);
    EXPECT_FALSE(a.store() == b.store());
}

TEST(Instancer, NothingWhereTheFieldIsNotPositive) {
    InstancerFixture fx;
    setPileFields(fx);
    // A hole: subtract a ball from the blob field.
    DensityField blob = makeBlendField({makePoint({0.0f, 0.0f, 0.0f}, 1.2f, 3.0f)});
    subtractSolids(&blob, {makePoint({0.3f, 0.0f, 0.0f}, 0.5f, 50.0f)});
    fx.input.types[0].field = std::make_shared<DensityField>(blob);
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    run(inst);
    size_t checked = 0;
    inst.store().forEach([&](uint64_t t, uint32_t j) {
        const uint16_t type = fx.tile.candidates.type[j];
        const glm::vec3 origin = tileOrigin(unpackTile(t), 0.5f);
        for (const glm::vec3& a : fx.models[type].anchors) {
            const glm::vec3 p = origin + fx.tile.candidates.position[j] +
                                fx.tile.candidates.rotation[j] * (fx.tile.candidates.scale[j] * a);
            ASSERT_GT(evaluate(*fx.input.types[type].field, p), 0.0f) << "anchor in a zero region";
            ++checked;
        }
        ASSERT_TRUE(contains(fx.input.extent, origin + fx.tile.candidates.position[j]));
    });
    EXPECT_GT(checked, 500u);
}

// With δ > 0 objects keep a gap, so a changed decision reaches candidates farther than the dirty tiles
// and must ripple on through tiles nobody edited: the key-order propagation is exercised for real.
class IncrementalEqualsFull : public ::testing::TestWithParam<float> {};

TEST_P(IncrementalEqualsFull, AfterHundredsOfRandomEdits) {
    InstancerFixture fx(GetParam(), 90, 60);
    // Each type's field is a blend of primitives we edit; we keep the primitive lists to rebuild them.
    std::vector<std::vector<Primitive>> prims(2);
    // Dense (saturated) fields, so decisions chain across tiles and edits ripple past the dirty tiles.
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

    std::mt19937 rng(1234);
    auto uni = [&](float a, float b) { return std::uniform_real_distribution<float>(a, b)(rng); };
    auto randomPrim = [&]() {
        const glm::vec3 c(uni(-1.6f, 1.6f), uni(-1.6f, 1.6f), uni(-0.6f, 0.6f));
        return uni(0, 1) < 0.7f ? makePoint(c, uni(0.3f, 0.9f), uni(-1.0f, 5.0f))
                                : makeSegment(c, c + glm::vec3(uni(-0.5f, 0.5f), uni(-0.5f, 0.5f), 0.0f), uni(0.2f, 0.5f),
                                              uni(0.5f, 4.0f));
    };
    const DensityField empty;
    size_t compared = 0;
    for (int edit = 0; edit < 300; ++edit) {
        const size_t type = size_t(rng() % 2);
        std::vector<Primitive>& list = prims[type];
        std::vector<Bounds> dirty;
        const int op = list.empty() ? 0 : int(rng() % 5);
        const size_t k = list.empty() ? 0 : rng() % list.size();
        auto bounds = [&](const Primitive& p) { return primitiveBounds(p, nullptr); };
        if (op == 0) {  // add
            list.push_back(randomPrim());
            dirty.push_back(bounds(list.back()));
        } else if (op == 1) {  // move
            dirty.push_back(bounds(list[k]));
            const glm::vec3 d(uni(-0.3f, 0.3f), uni(-0.3f, 0.3f), uni(-0.1f, 0.1f));
            list[k].center_m += d;
            list[k].end_m += d;
            dirty.push_back(bounds(list[k]));
        } else if (op == 2) {  // resize
            dirty.push_back(bounds(list[k]));
            list[k].radius_m = std::max(0.1f, list[k].radius_m * uni(0.7f, 1.4f));
            list[k].end_radius_m = std::max(0.1f, list[k].end_radius_m * uni(0.7f, 1.4f));
            dirty.push_back(bounds(list[k]));
        } else if (op == 3) {  // delete
            dirty.push_back(bounds(list[k]));
            list.erase(list.begin() + long(k));
        } else {  // change weight
            list[k].weight = uni(-1.0f, 5.0f);
            dirty.push_back(bounds(list[k]));
        }
        std::vector<InstanceTypeSettings> types = live.input().types;
        types[type].field = InstancerFixture::field(list);
        InstanceStats st;
        std::vector<uint64_t> changed;
        ASSERT_TRUE(live.update(types, dirty, {.threads = 2}, &st, &changed, &error)) << error;
        if (edit % 3 == 2 || edit == 299) {
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
    EXPECT_EQ(compared, 100u);
}

INSTANTIATE_TEST_SUITE_P(Instancer, IncrementalEqualsFull, ::testing::Values(0.0f, 0.15f));

TEST(Instancer, DeletingAPrimitiveReleasesNeighboursBeyondTheDirtyTiles) {
    // Blobs fill x in [0, 0.88] and win every contest (weight 50); rods live from x = 1.0 on. With a gap
    // δ = 0.15 the border blobs reject rods in tiles x >= 1.0, which the blob field's dirty tiles (x < 1.0)
    // do not include. Deleting the blob box kills every candidate of the dirty tiles, so only the old
    // selected blobs can tell those rods to look again.
    InstancerFixture fx(0.15f);
    const Primitive blob_box = makeBox({0.44f, 0.0f, 0.0f}, glm::vec3(0.44f, 1.5f, 0.5f), 0.001f, 50.0f);
    fx.input.types[0].field = InstancerFixture::field({blob_box});
    fx.input.types[1].field = InstancerFixture::field({makeBox({1.5f, 0.0f, 0.0f}, glm::vec3(0.5f, 1.5f, 0.5f), 0.001f, 1.0f)});
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    run(inst);
    auto rodsOf = [&](const InstanceStore& store) {
        std::vector<test::InstanceKey> rods;
        store.forEach([&](uint64_t t, uint32_t j) {
            if (fx.tile.candidates.type[j] == 1) rods.push_back({t, j});
        });
        return rods;
    };
    const auto rods_before = rodsOf(inst.store());
    std::vector<InstanceTypeSettings> types = inst.input().types;
    types[0].field = InstancerFixture::field({});
    const Bounds dirty = primitiveBounds(blob_box, nullptr);
    InstanceStats after;
    ASSERT_TRUE(inst.update(types, std::span<const Bounds>(&dirty, 1), {}, &after, nullptr, &error)) << error;
    EXPECT_EQ(after.instances_per_type[0], 0u);
    EXPECT_NE(rodsOf(inst.store()), rods_before) << "no rod was released";
    InstancerInput fresh_input = fx.input;
    fresh_input.types = types;
    Instantiator fresh;
    ASSERT_TRUE(fresh.setInput(fresh_input, &error)) << error;
    run(fresh);
    EXPECT_TRUE(inst.store() == fresh.store());
}

TEST(Instancer, UpdateReportsChangedTilesOnlyNearTheEdit) {
    InstancerFixture fx;
    fx.input.types[0].field = InstancerFixture::field({makePoint({-1.0f, 0.0f, 0.0f}, 0.8f, 2.0f),
                                                       makePoint({1.2f, 1.2f, 0.0f}, 0.6f, 2.0f)});
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    run(inst);
    const InstanceStore before = inst.store();
    std::vector<InstanceTypeSettings> types = inst.input().types;
    const Primitive added = makePoint({1.2f, -1.2f, 0.0f}, 0.4f, 2.0f);
    types[0].field = InstancerFixture::field({makePoint({-1.0f, 0.0f, 0.0f}, 0.8f, 2.0f),
                                              makePoint({1.2f, 1.2f, 0.0f}, 0.6f, 2.0f), added});
    InstanceStats st;
    std::vector<uint64_t> changed;
    const Bounds dirty = primitiveBounds(added, nullptr);
    ASSERT_TRUE(inst.update(types, std::span<const Bounds>(&dirty, 1), {}, &st, &changed, &error)) << error;
    ASSERT_FALSE(changed.empty());
    EXPECT_GT(inst.store().instanceCount(), before.instanceCount());
    for (uint64_t key : changed) {
        const glm::vec3 o = tileOrigin(unpackTile(key), 0.5f);
        EXPECT_TRUE(overlaps(Bounds{o - 0.5f, o + 1.0f}, dirty)) << "a far tile changed";
    }
    // Tiles away from the edit kept their instances.
    for (size_t t = 0; t < before.tileCount(); ++t) {
        const uint64_t key = before.tileKey(t);
        if (std::binary_search(changed.begin(), changed.end(), key)) continue;
        std::vector<uint32_t> a, b;
        before.tileIds(t, &a);
        const int64_t u = inst.store().findTile(key);
        ASSERT_GE(u, 0);
        inst.store().tileIds(size_t(u), &b);
        EXPECT_EQ(a, b);
    }
}

TEST(Instancer, UnionOfRegionsEqualsTheWhole) {
    InstancerFixture fx;
    setPileFields(fx);
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    run(inst);
    const auto whole = instancesOf(inst.store());
    // Cuts that do not fall on tile borders (0.5 m grid), so tiles are shared between regions.
    const float xs[] = {-2.0f, -0.37f, 0.61f, 2.0f};
    const float ys[] = {-2.0f, 0.13f, 2.0f};
    std::vector<test::InstanceKey> joined;
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 2; ++k) {
            const Bounds region{glm::vec3(xs[i], ys[k], -1.0f), glm::vec3(xs[i + 1], ys[k + 1], 1.0f)};
            InstanceStore part;
            InstanceStats st;
            ASSERT_TRUE(instantiateRegion(fx.input, region, {.threads = 2}, &part, &st, &error)) << error;
            const auto keys = instancesOf(part);
            joined.insert(joined.end(), keys.begin(), keys.end());
        }
    std::sort(joined.begin(), joined.end());
    EXPECT_EQ(joined, whole);
}

TEST(Instancer, RegionRejectsEmptyInvertedOrNonFiniteBoxes) {
    InstancerFixture fx;
    setPileFields(fx);
    std::string error;
    InstanceStore out;
    for (const Bounds& bad : {Bounds{glm::vec3(1.0f), glm::vec3(1.0f)}, Bounds{glm::vec3(1.0f), glm::vec3(0.0f)},
                              Bounds{glm::vec3(0.0f), glm::vec3(NAN, 1.0f, 1.0f)}}) {
        EXPECT_FALSE(instantiateRegion(fx.input, bad, {}, &out, nullptr, &error));
        EXPECT_NE(error.find("region"), std::string::npos) << error;
    }
}

TEST(Instancer, RelativeDensitiesFollowTheFieldsWithoutCollisions) {
    // δ = -0.45 m, far below the models' size: nothing collides, so each type's count is candidates x acceptance. Fields 0.4 and
    // 0.2 over the same volume: the ratio must be 2 within 10 % (counts are in the thousands).
    InstancerFixture fx(-0.45f, 150, 150);
    fx.input.types[0].field = InstancerFixture::field({makeBox({0, 0, 0}, glm::vec3(3.0f), 0.1f, 0.4f)});
    fx.input.types[1].field = InstancerFixture::field({makeBox({0, 0, 0}, glm::vec3(3.0f), 0.1f, 0.2f)});
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    const InstanceStats st = run(inst);
    ASSERT_GT(st.instances_per_type[1], 1000u);
    const double ratio = double(st.instances_per_type[0]) / double(st.instances_per_type[1]);
    EXPECT_NEAR(ratio, 2.0, 0.2);
    // And the absolute acceptance: 0.4 of the blob candidates whose origin is in the extent.
    const double expected_blobs = 0.4 * 150 * (4.0 / 0.5) * (4.0 / 0.5) * (2.0 / 0.5);
    EXPECT_NEAR(double(st.instances_per_type[0]) / expected_blobs, 1.0, 0.05);
}

TEST(Instancer, WeightedKeysMixCollidingTypesInProportion) {
    // Same sphere model for both types, saturated fields (acceptance 1), weights 2 : 1. With δ = 0 the
    // selection competes; Efraimidis–Spirakis keys make the heavier type win about twice as often.
    InstancerFixture fx(0.0f, 150, 150);
    fx.models[1] = fx.models[0];
    fx.models[1].name = "blob2";
    GhostTileInput gi;
    gi.settings = fx.tile.settings;
    gi.types.push_back({.name = "a", .candidate_count = 150, .scale_min = 0.8f, .scale_max = 1.2f});
    gi.types.push_back({.name = "b", .candidate_count = 150, .scale_min = 0.8f, .scale_max = 1.2f});
    gi.models = {&fx.models[0], &fx.models[1]};
    std::string error;
    ASSERT_TRUE(buildGhostTile(gi, {.threads = 2}, &fx.tile, &error)) << error;
    fx.input.types[0].field = InstancerFixture::field({makeBox({0, 0, 0}, glm::vec3(3.0f), 0.1f, 2.0f)});
    fx.input.types[1].field = InstancerFixture::field({makeBox({0, 0, 0}, glm::vec3(3.0f), 0.1f, 1.0f)});
    Instantiator inst;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    const InstanceStats st = run(inst);
    const double ratio = double(st.instances_per_type[0]) / double(st.instances_per_type[1]);
    // Stated tolerance: within 25 % of 2 (packing effects bias the exact proportion).
    EXPECT_GT(ratio, 1.5);
    EXPECT_LT(ratio, 2.5);
    std::printf("weighted mix: %llu : %llu = %.3f\n", (unsigned long long)st.instances_per_type[0],
                (unsigned long long)st.instances_per_type[1], ratio);
}

TEST(Instancer, OrientationAndSizeConstraintsAreRespected) {
    InstancerFixture fx;
    setPileFields(fx);
    fx.input.types[1].orientation.enabled = true;
    fx.input.types[1].orientation.min_cos = std::cos(glm::radians(40.0f));
    fx.input.types[1].orientation.direction.direction = glm::normalize(glm::vec3(1.0f, 0.0f, 1.0f));
    fx.input.types[0].size.enabled = true;
    fx.input.types[0].size.tolerance = 0.05f;
    fx.input.types[0].size.target = SizeField{.kind = SizeFieldKind::Ramp,
                                              .field = std::make_shared<DensityField>(
                                                  makeBlendField({makePoint({0, 0, 0}, 1.5f, 1.0f)})),
                                              .value_lo = 0.0f, .value_hi = 1.0f, .scale_lo = 1.15f, .scale_hi = 0.85f};
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    const InstanceStats st = run(inst);
    ASSERT_GT(st.instances_per_type[0], 20u);
    ASSERT_GT(st.instances_per_type[1], 20u);
    EXPECT_GT(st.constraint_rejected, 0u);
    const CandidateSet& c = fx.tile.candidates;
    inst.store().forEach([&](uint64_t t, uint32_t j) {
        const glm::vec3 o = tileOrigin(unpackTile(t), 0.5f) + c.position[j];
        if (c.type[j] == 1) {
            const glm::vec3 z = c.rotation[j] * glm::vec3(0, 0, 1);
            EXPECT_GE(glm::dot(z, fx.input.types[1].orientation.direction.direction), std::cos(glm::radians(40.0f)) - 1e-5f);
        } else {
            const float target = evaluateSize(fx.input.types[0].size.target, nullptr, o);
            EXPECT_LE(std::fabs(c.scale[j] / target - 1.0f), 0.05f + 1e-5f);
        }
    });
}

TEST(Instancer, GradientOrientationFollowsTheFieldNormal) {
    // Fig. 17 right: u = ∇f of a ball field; kept rods point away from the centre.
    InstancerFixture fx;
    auto ball = InstancerFixture::field({makePoint({0, 0, 0}, 1.5f, 3.0f)});
    fx.input.types[1].field = ball;
    fx.input.types[1].orientation = {.enabled = true,
                                     .direction = {.kind = DirectionFieldKind::Gradient, .field = ball},
                                     .min_cos = 0.9f};
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
    const InstanceStats st = run(inst);
    ASSERT_GT(st.instances_per_type[1], 20u);
    const CandidateSet& c = fx.tile.candidates;
    inst.store().forEach([&](uint64_t t, uint32_t j) {
        const glm::vec3 o = tileOrigin(unpackTile(t), 0.5f) + c.position[j];
        const glm::vec3 z = c.rotation[j] * glm::vec3(0, 0, 1);
        if (glm::length(o) > 0.05f) {
            EXPECT_GE(glm::dot(z, -glm::normalize(o)), 0.9f - 1e-4f);
        }
    });
}

TEST(Instancer, ElevationFillsFromTheBottom) {
    // In a tall box, elevation priority fills the lowest layers first: with the same field, its instances
    // sit lower on average than random priority's, and its lowest layer is denser.
    InstancerFixture fx;
    fx.input.types[0].field = InstancerFixture::field({makeBox({0, 0, 0}, glm::vec3(1.5f, 1.5f, 0.8f), 0.1f, 0.5f)});
    auto meanZ = [&](PriorityStrategy s) {
        fx.input.types[0].strategy = s;
        Instantiator inst;
        std::string error;
        EXPECT_TRUE(inst.setInput(fx.input, &error)) << error;
        run(inst);
        double z = 0;
        inst.store().forEach([&](uint64_t t, uint32_t j) { z += tileOrigin(unpackTile(t), 0.5f).z + fx.tile.candidates.position[j].z; });
        return z / double(inst.store().instanceCount());
    };
    const double random_z = meanZ(PriorityStrategy::Random);
    const double elevation_z = meanZ(PriorityStrategy::Elevation);
    EXPECT_LT(elevation_z, random_z - 0.01);
}

TEST(Instancer, RejectsBadInputWithReasons) {
    InstancerFixture fx;
    setPileFields(fx);
    Instantiator inst;
    std::string error;
    InstancerInput bad = fx.input;
    bad.extent = Bounds{glm::vec3(1.0f), glm::vec3(0.0f)};
    EXPECT_FALSE(inst.setInput(bad, &error));
    EXPECT_NE(error.find("extent"), std::string::npos) << error;
    bad = fx.input;
    bad.types[0].layer_m = NAN;
    EXPECT_FALSE(inst.setInput(bad, &error));
    EXPECT_NE(error.find("layer_m"), std::string::npos) << error;
    bad = fx.input;
    bad.types.pop_back();
    EXPECT_FALSE(inst.setInput(bad, &error));
    bad = fx.input;
    bad.types[1].size.enabled = true;
    bad.types[1].size.tolerance = -1.0f;
    EXPECT_FALSE(inst.setInput(bad, &error));
    EXPECT_NE(error.find("tolerance"), std::string::npos) << error;
    // A scene whose state could exhaust memory is refused before it is allocated.
    InstancerInput huge = fx.input;
    huge.extent = Bounds{glm::vec3(-20000.0f, -20000.0f, -1.0f), glm::vec3(20000.0f, 20000.0f, 1.0f)};
    huge.types[0].field = InstancerFixture::field({makeBox({0, 0, 0}, glm::vec3(19000.0f, 19000.0f, 0.5f), 0.1f, 1.0f)});
    ASSERT_TRUE(inst.setInput(huge, &error)) << error;
    InstanceStats st;
    EXPECT_FALSE(inst.instantiateAll({.threads = 2}, &st, &error));
    EXPECT_NE(error.find("refusing"), std::string::npos) << error;
    // Within the tile-count limit but too dense for the memory budget (8 km x 8 km, a field everywhere):
    // refused while planning, before any per-tile state exists (it used to end in bad_alloc at 8 GB).
    InstancerInput dense = fx.input;
    dense.extent = Bounds{glm::vec3(-4000.0f, -4000.0f, 0.0f), glm::vec3(4000.0f, 4000.0f, 0.5f)};
    dense.types[0].field = InstancerFixture::field({makeBox({0, 0, 0.25f}, glm::vec3(4000.0f, 4000.0f, 0.25f), 0.1f, 1.0f)});
    ASSERT_TRUE(inst.setInput(dense, &error)) << error;
    EXPECT_FALSE(inst.instantiateAll({.threads = 2}, &st, &error));
    EXPECT_NE(error.find("more than the allowed 8192 MiB"), std::string::npos) << error;
    EXPECT_NE(error.find("--region"), std::string::npos) << error;
}

TEST(InstanceStore, RoundTripsTilesAndIdsCompactly) {
    InstanceStore store;
    std::vector<uint32_t> a = {0, 3, 4, 200, 1000, 70000};
    std::vector<uint32_t> b = {5};
    store.appendTile(packTile({-3, 4, 0}), a);
    store.appendTile(packTile({-3, 4, 1}), {});
    store.appendTile(packTile({7, -1, 2}), b);
    EXPECT_EQ(store.tileCount(), 2u);
    EXPECT_EQ(store.instanceCount(), 7u);
    std::vector<uint32_t> out;
    store.tileIds(0, &out);
    EXPECT_EQ(out, a);
    store.tileIds(1, &out);
    EXPECT_EQ(out, b);
    EXPECT_EQ(unpackTile(store.tileKey(0)), glm::ivec3(-3, 4, 0));
    EXPECT_EQ(store.findTile(packTile({7, -1, 2})), 1);
    EXPECT_EQ(store.findTile(packTile({7, -1, 3})), -1);
    EXPECT_EQ(store.byteSize(), 2 * 8 + 3 * 4 + (1 + 1 + 1 + 2 + 2 + 3) + 1);
}

TEST(TileCoord, PacksAndOrdersTiles) {
    for (glm::ivec3 t : {glm::ivec3(0), glm::ivec3(-1, 2, -3), glm::ivec3(kTileCoordLimit, -kTileCoordLimit, 5)})
        EXPECT_EQ(unpackTile(packTile(t)), t);
    EXPECT_EQ(tileOf(glm::vec3(-0.01f, 0.0f, 0.49f), 0.5f), glm::ivec3(-1, 0, 0));
}

}  // namespace
}  // namespace ug
