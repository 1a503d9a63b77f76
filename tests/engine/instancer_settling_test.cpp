// Settling (instancer/settling.h): exact drops on hand-built stacks, an independent brute-force reference
// of the same definition, no new overlaps, and the exactness properties the selection has (any thread
// count, incremental = full, region = whole).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>

#include <glm/gtc/constants.hpp>

#include "analysis/placed_instances.h"
#include "analysis/rest_metrics.h"
#include "instancer/settling.h"
#include "instancer_test_util.h"

namespace ug {
namespace {

using test::InstancerFixture;

// A one-type Ghost Tile whose candidates are exactly `positions` (tile space), unrotated, scale 1.
GhostTile handTile(const std::vector<glm::vec3>& positions) {
    GhostTile t;
    t.settings.tile_size_m = 0.5f;
    CandidateSet& c = t.candidates;
    c.type_begin = {0, uint32_t(positions.size())};
    for (const glm::vec3& p : positions) {
        c.type.push_back(0);
        c.position.push_back(p);
        c.rotation.push_back(glm::quat(1.0f, 0.0f, 0.0f, 0.0f));
        c.scale.push_back(1.0f);
    }
    return t;
}

// Settling a one-type hand tile on the ground plane z = 0 (the input keeps pointers to tile and model).
SettleInput onGroundPlane(const GhostTile& tile, const DetailModel& model, int passes, float max_drop_m) {
    SettleInput in;
    in.tile = &tile;
    in.models = {&model};
    in.support.ground_z = 0.0f;
    in.settings = {.enabled = true, .passes = passes, .max_drop_m = max_drop_m};
    return in;
}

// Settles the instances `ids` of tile (0, 0, 0) alone, one thread; *store receives them.
std::vector<uint16_t> settleTileZero(const SettleInput& in, const std::vector<uint32_t>& ids, InstanceStore* store) {
    store->appendTile(packTile(glm::ivec3(0)), ids);
    SettledDrops drops;
    settleAll(in, *store, 1, &drops);
    const std::span<const uint16_t> d = drops.tile(packTile(glm::ivec3(0)));
    return {d.begin(), d.end()};
}

TEST(Settling, AStackComesToRestOnTheGroundBallByBall) {
    const DetailModel ball = test::sphereModel("ball", {{glm::vec3(0.0f), 0.05f}});
    // In tile (0,0,0): a ball 15 cm above the ground, one 5 cm above it, and one to the side in the air.
    const GhostTile tile = handTile({{0.2f, 0.2f, 0.2f}, {0.2f, 0.2f, 0.35f}, {0.4f, 0.2f, 0.3f}});
    InstanceStore store;
    const std::vector<uint32_t> ids = {0, 1, 2};
    store.appendTile(packTile(glm::ivec3(0)), ids);
    SettleInput in = onGroundPlane(tile, ball, 8, 1.0f);
    std::string error;
    ASSERT_TRUE(validateSettleInput(in, &error)) << error;
    SettledDrops drops;
    settleAll(in, store, 1, &drops);
    const std::span<const uint16_t> d = drops.tile(packTile(glm::ivec3(0)));
    ASSERT_EQ(d.size(), 3u);
    EXPECT_NEAR(dropMetres(d[0]), 0.15f, 2e-4f);  // onto the ground
    EXPECT_NEAR(dropMetres(d[1]), 0.20f, 2e-4f);  // onto the first, once it has fallen (two passes)
    EXPECT_NEAR(dropMetres(d[2]), 0.25f, 2e-4f);  // 20 cm to the side of the stack: the ground
    // Rounded down: never below the contact.
    EXPECT_LE(dropMetres(d[0]), 0.15f + 1e-6f);

    // One pass lets the upper ball fall only onto where the lower one was.
    in.settings.passes = 1;
    settleAll(in, store, 1, &drops);
    EXPECT_NEAR(dropMetres(drops.tile(packTile(glm::ivec3(0)))[1]), 0.05f, 2e-4f);
    // With nothing to land on within max_drop, an instance is held where it is; the one above it still
    // lands on it (5 cm), and the one to the side is held too.
    in.settings = {.enabled = true, .passes = 8, .max_drop_m = 0.1f};
    settleAll(in, store, 1, &drops);
    EXPECT_EQ(dropMetres(drops.tile(packTile(glm::ivec3(0)))[0]), 0.0f);
    EXPECT_NEAR(dropMetres(drops.tile(packTile(glm::ivec3(0)))[1]), 0.05f, 2e-4f);
    EXPECT_EQ(dropMetres(drops.tile(packTile(glm::ivec3(0)))[2]), 0.0f);
}

// The definition, evaluated directly: every sphere pair of every instance pair, no grid, no pruning.
std::vector<float> bruteForceDrops(const SettleInput& in, const std::vector<test::InstanceKey>& keys) {
    struct Item {
        uint64_t tile;
        uint32_t j;
        std::vector<Sphere> spheres;
    };
    std::vector<Item> items;
    for (const auto& [t, j] : keys)
        items.push_back({t, j, test::worldSpheres(*in.tile, *in.models[in.tile->candidates.type[j]], t, j)});
    const size_t n = items.size();
    const float gap = std::max(0.0f, in.tile->settings.delta_m);
    // Each instance's bounding sphere: around the box of its spheres.
    std::vector<glm::vec3> bc(n);
    std::vector<float> br(n);
    for (size_t i = 0; i < n; ++i) {
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        for (const Sphere& a : items[i].spheres) {
            lo = glm::min(lo, a.center - a.radius);
            hi = glm::max(hi, a.center + a.radius);
        }
        bc[i] = 0.5f * (lo + hi);
        br[i] = 0.5f * glm::length(hi - lo);
    }
    std::vector<float> limit(n, in.settings.max_drop_m);
    for (size_t i = 0; i < n; ++i)
        for (const Sphere& a : items[i].spheres)
            limit[i] = std::min(limit[i], std::max(0.0f, supportClearance(in.support, a.center, a.radius)));
    for (size_t i = 0; i < n; ++i) {  // held: nothing within max_drop below, unsettled
        bool any = limit[i] < in.settings.max_drop_m;
        for (size_t o = 0; o < n && !any; ++o)
            for (const Sphere& a : items[i].spheres)
                for (const Sphere& e : items[o].spheres) {
                    const bool lower = e.center.z < a.center.z ||
                                       (e.center.z == a.center.z &&
                                        std::make_pair(items[o].tile, items[o].j) < std::make_pair(items[i].tile, items[i].j));
                    if (o == i || !lower) continue;
                    const float reach = a.radius + e.radius + gap;
                    const float h2 = (a.center.x - e.center.x) * (a.center.x - e.center.x) +
                                     (a.center.y - e.center.y) * (a.center.y - e.center.y);
                    if (h2 < reach * reach && a.center.z - e.center.z - std::sqrt(reach * reach - h2) <= in.settings.max_drop_m)
                        any = true;
                }
        if (!any) limit[i] = -1.0f;
    }
    // A held instance follows the instances beside it: bounding spheres within the gap, centre not higher,
    // origins within one pass reach (twice the farthest any candidate's sphere reaches from its origin, + gap).
    float bound = 0.0f;
    for (uint32_t j = 0; j < in.tile->candidates.position.size(); ++j)
        for (const Sphere& s : in.models[in.tile->candidates.type[j]]->spheres)
            bound = std::max(bound, in.tile->candidates.scale[j] * (glm::length(s.center) + s.radius));
    const float pass_reach = 2.0f * bound + gap;
    auto originOf = [&](size_t i) {
        return tileOrigin(unpackTile(items[i].tile), in.tile->settings.tile_size_m) + in.tile->candidates.position[items[i].j];
    };
    std::vector<std::vector<size_t>> beside(n);
    for (size_t i = 0; i < n; ++i)
        for (size_t o = 0; o < n && limit[i] < 0.0f; ++o) {
            const glm::vec3 od = originOf(i) - originOf(o);
            const bool within = glm::length(glm::vec2(od)) < pass_reach && std::abs(od.z) < pass_reach + in.settings.max_drop_m;
            if (o != i && bc[o].z <= bc[i].z && glm::length(bc[i] - bc[o]) < br[i] + br[o] + gap && within)
                beside[i].push_back(o);
        }
    std::vector<float> drop(n, 0.0f), next(n);
    for (int pass = 0; pass < in.settings.passes; ++pass) {
        for (size_t i = 0; i < n; ++i) {
            if (limit[i] < 0.0f) {
                // The cap, rounded down as every drop is; then the least drop beside.
                next[i] = beside[i].empty() ? 0.0f : dropMetres(uint16_t(std::floor(in.settings.max_drop_m / kSettleQuantumM)));
                for (size_t o : beside[i]) next[i] = std::min(next[i], drop[o]);
                continue;
            }
            float d = limit[i];
            for (size_t o = 0; o < n; ++o) {
                if (o == i) continue;
                for (const Sphere& a : items[i].spheres)
                    for (const Sphere& e : items[o].spheres) {
                        const bool lower = e.center.z < a.center.z ||
                                           (e.center.z == a.center.z &&
                                            std::make_pair(items[o].tile, items[o].j) < std::make_pair(items[i].tile, items[i].j));
                        if (!lower) continue;
                        const float reach = a.radius + e.radius + gap;
                        const float h2 = (a.center.x - e.center.x) * (a.center.x - e.center.x) +
                                         (a.center.y - e.center.y) * (a.center.y - e.center.y);
                        if (h2 >= reach * reach) continue;
                        const float offset = a.center.z - e.center.z - std::sqrt(reach * reach - h2);
                        if (offset > in.settings.max_drop_m) continue;
                        d = std::min(d, std::max(0.0f, offset + drop[o]));
                    }
            }
            next[i] = dropMetres(uint16_t(std::min(65535.0f, std::max(0.0f, std::floor(d / kSettleQuantumM)))));
        }
        drop = next;
    }
    return drop;
}

// A stone held over the open (nothing within max_drop below it) moves down with the stone beside it; the
// stone resting on it follows; a stone held with nothing beside it stays where it was.
TEST(Settling, AHeldStoneMovesDownWithTheWallBesideIt) {
    // Two spheres side by side along x: collision spheres 6 cm wide, a bounding sphere of radius 8.2 cm.
    const DetailModel stone = test::sphereModel("stone", {{glm::vec3(-0.04f, 0.0f, 0.0f), 0.03f}, {glm::vec3(0.04f, 0.0f, 0.0f), 0.03f}});
    const GhostTile tile = handTile({{0.25f, 0.20f, 0.13f},    // 0: 10 cm above the ground
                                     {0.25f, 0.30f, 0.20f},    // 1: beside 0 (10 cm along y: no pair), 17 cm up
                                     {0.25f, 0.30f, 0.27f},    // 2: resting 1 cm above 1
                                     {0.25f, 0.45f, 0.40f}});  // 3: alone in the air
    SettleInput in = onGroundPlane(tile, stone, 8, 0.15f);
    InstanceStore store;
    const std::vector<uint16_t> d = settleTileZero(in, {0, 1, 2, 3}, &store);
    ASSERT_EQ(d.size(), 4u);
    EXPECT_NEAR(dropMetres(d[0]), 0.10f, 2e-4f);  // onto the ground
    EXPECT_EQ(d[1], d[0]);                         // held, in step with the stone beside it
    EXPECT_NEAR(dropMetres(d[2]), 0.11f, 3e-4f);  // onto the held stone, wherever it went
    EXPECT_EQ(d[3], 0u);                           // held, nothing beside it
    const std::vector<float> reference = bruteForceDrops(in, test::instancesOf(store));
    for (size_t i = 0; i < 4; ++i) EXPECT_EQ(dropMetres(d[i]), reference[i]) << "stone " << i;
}

// Boxes around rotated sphere sets touch while their origins lie farther apart than one pass reach: such a
// neighbour does not hold a stone (an update reads only one pass halo around what it recomputes).
TEST(Settling, AHeldStoneFollowsOnlyNeighboursWithinOnePassReach) {
    // One sphere of 4 cm, 10 cm off the origin: a pass reaches 2 x 14 cm. Bounding boxes of two stones
    // touch within 2 x 6.9 cm of their centres.
    const DetailModel stone = test::sphereModel("stone", {{glm::vec3(0.10f, 0.0f, 0.0f), 0.04f}});
    GhostTile tile = handTile({{0.05f, 0.25f, 0.10f},    // 0: its sphere at (0.15, 0.25), 6 cm above the ground
                               {0.34f, 0.25f, 0.20f},    // 1: turned half round, its sphere at (0.24, 0.25)
                               {0.05f, 0.34f, 0.20f}});  // 2: its sphere at (0.15, 0.34)
    tile.candidates.rotation[1] = glm::angleAxis(glm::pi<float>(), glm::vec3(0.0f, 0.0f, 1.0f));
    SettleInput in = onGroundPlane(tile, stone, 4, 0.15f);
    InstanceStore store;
    const std::vector<uint16_t> d = settleTileZero(in, {0, 1, 2}, &store);
    ASSERT_EQ(d.size(), 3u);
    EXPECT_NEAR(dropMetres(d[0]), 0.06f, 2e-4f);  // onto the ground
    // Stones 1 and 2 sit 10 cm higher, 9 cm to the side of stone 0 (no sphere pair), 16 cm over the ground:
    // held. Stone 2's origin is 13 cm from stone 0's: it moves down with it.
    EXPECT_EQ(d[2], d[0]);
    // Stone 1's box touches stone 0's and stone 2's, but its origin is 29 and 30 cm from theirs, past the
    // reach: nothing beside it holds it, and it stays where it was.
    EXPECT_EQ(d[1], 0u);
    const std::vector<float> reference = bruteForceDrops(in, test::instancesOf(store));
    for (size_t i = 0; i < 3; ++i) EXPECT_EQ(dropMetres(d[i]), reference[i]) << "stone " << i;
}

// Round stones' boxes touch from 1.7 times the pair reach apart (a ball's box has half-diagonal 1.7 r): a
// row of held stones, each following the one before it, would carry a drop farther in K passes than the K pass
// halos an update recomputes. Taking the one stone that fell away must leave the row as settling the new
// store in full does; before the origins were required within one pass reach, the stones beyond the
// window kept the drop they had followed.
TEST(Settling, AnUpdateAgreesWithTheWholeAlongARowOfHeldStones) {
    const DetailModel ball = test::sphereModel("ball", {{glm::vec3(0.0f), 0.04f}});
    // Tiles of 10 cm; a pass reaches 8 cm, one tile. Stone 0 stands 8 cm over the ground; stones 1-18 in a
    // row 12 cm apart (no sphere pair), each a millimetre higher than the last from 12 cm over the ground:
    // held, each beside only the one before it.
    std::vector<glm::vec3> local;
    std::map<uint64_t, std::vector<uint32_t>> tiles;
    uint64_t first_tile = 0;
    for (uint32_t k = 0; k < 19; ++k) {
        const glm::vec3 p(0.05f + 0.12f * float(k), 0.05f, k == 0 ? 0.12f : 0.16f + 0.001f * float(k));
        const glm::ivec3 t(glm::floor(p / 0.1f));
        local.push_back(p - 0.1f * glm::vec3(t));
        tiles[packTile(t)].push_back(k);
        if (k == 0) first_tile = packTile(t);
    }
    GhostTile tile = handTile(local);
    tile.settings.tile_size_m = 0.1f;
    InstanceStore row, without_first;
    for (const auto& [key, ids] : tiles) {
        row.appendTile(key, ids);
        if (key != first_tile) without_first.appendTile(key, ids);
    }
    SettleInput in = onGroundPlane(tile, ball, 16, 0.10f);
    SettledDrops drops;
    settleAll(in, row, 1, &drops);
    EXPECT_NEAR(dropMetres(drops.tile(first_tile)[0]), 0.08f, 2e-4f);  // onto the ground
    const std::vector<uint64_t> changed = {first_tile};
    settleUpdate(in, without_first, changed, 1, &drops, nullptr);
    SettledDrops full;
    settleAll(in, without_first, 1, &full);
    EXPECT_TRUE(drops == full);
    for (const auto& [key, ids] : tiles) {
        if (key == first_tile) continue;
        EXPECT_EQ(full.tile(key)[0], 0u) << "stone " << ids.front() << ": held, nothing beside it";
    }
}

struct PileScene {
    InstancerFixture fx{-0.002f, 220, 60};
    SettleInput settle;
    PileScene() {
        fx.input.types[0].field = InstancerFixture::field({makePoint({0.0f, 0.0f, 0.0f}, 0.9f, 4.0f)});
        fx.input.types[0].strategy = PriorityStrategy::Elevation;
        fx.input.types[0].layer_m = 0.03f;
        fx.input.types[1].field = InstancerFixture::field({makeSegment({-0.8f, -0.3f, 0.0f}, {0.6f, 0.5f, 0.1f}, 0.4f, 2.0f)});
        fx.input.types[1].strategy = PriorityStrategy::Elevation;
        fx.input.types[1].layer_m = 0.03f;
        fx.input.extent = Bounds{glm::vec3(-1.5f, -1.5f, 0.0f), glm::vec3(1.5f, 1.5f, 1.0f)};
        settle.tile = &fx.tile;
        settle.models = {&fx.models[0], &fx.models[1]};
        settle.support.ground_z = 0.0f;
        settle.settings = {.enabled = true, .passes = 6, .max_drop_m = 0.4f};
    }
    InstanceStore instantiate(int threads = 2) {
        Instantiator inst;
        std::string error;
        EXPECT_TRUE(inst.setInput(fx.input, &error)) << error;
        EXPECT_TRUE(inst.instantiateAll({.threads = threads}, nullptr, &error)) << error;
        return inst.store();
    }
};

TEST(Settling, MatchesTheDefinitionEvaluatedByBruteForceForAnyThreadCount) {
    PileScene scene;
    const InstanceStore store = scene.instantiate();
    ASSERT_GT(store.instanceCount(), 100u);
    SettledDrops one, two;
    settleAll(scene.settle, store, 1, &one);
    settleAll(scene.settle, store, 2, &two);
    EXPECT_TRUE(one == two);
    const std::vector<float> reference = bruteForceDrops(scene.settle, test::instancesOf(store));
    size_t k = 0, moved = 0;
    forEachSettled(store, &one, [&](uint64_t, uint32_t, float drop) {
        EXPECT_EQ(drop, reference[k]) << "instance " << k;
        moved += drop > 0.0f;
        ++k;
    });
    EXPECT_EQ(k, reference.size());
    EXPECT_GT(moved, k / 4);  // the pile really settled
}

TEST(Settling, CreatesNoOverlapAndLeavesNothingHovering) {
    PileScene scene;
    const InstanceStore store = scene.instantiate();
    SettledDrops drops;
    scene.settle.settings.passes = 32;  // enough for the whole pile to come down layer by layer
    settleAll(scene.settle, store, 2, &drops);
    const std::vector<PlacedInstance> before = placeInstances(store, scene.fx.tile);
    const std::vector<PlacedInstance> after = placeInstances(store, scene.fx.tile, &drops);
    const std::vector<const DetailModel*> models = {&scene.fx.models[0], &scene.fx.models[1]};
    // Pairwise: settled spheres are no closer than the instances were allowed to be before (contact, or
    // the interpenetration δ let them have already), up to the float rounding of the sums.
    std::vector<std::vector<Sphere>> sb(before.size()), sa(after.size());
    for (size_t i = 0; i < before.size(); ++i) {
        placedSpheres(before[i], *models[before[i].type], &sb[i]);
        placedSpheres(after[i], *models[after[i].type], &sa[i]);
    }
    auto gap = [](const std::vector<Sphere>& x, const std::vector<Sphere>& y) {
        float g = std::numeric_limits<float>::infinity();
        for (const Sphere& a : x)
            for (const Sphere& b : y) g = std::min(g, glm::length(a.center - b.center) - a.radius - b.radius);
        return g;
    };
    size_t checked = 0;
    for (size_t i = 0; i < before.size(); ++i)
        for (size_t o = i + 1; o < before.size(); ++o) {
            if (glm::length(glm::vec2(before[i].position - before[o].position)) > 0.5f) continue;
            const float g0 = gap(sb[i], sb[o]), g1 = gap(sa[i], sa[o]);
            EXPECT_GE(g1, std::min(g0, 0.0f) - 1e-5f) << "instances " << i << " and " << o;
            ++checked;
        }
    EXPECT_GT(checked, 1000u);
    const RestReport rest_before = measureRest(before, models, scene.settle.support, 0.02f, 2);
    const RestReport rest_after = measureRest(after, models, scene.settle.support, 0.02f, 2);
    EXPECT_GT(rest_before.hovering_fraction, 0.2);
    EXPECT_LE(rest_after.hovering_fraction, 0.02);
}

// Without a terrain, the ground plane keeps candidates from sinking into it (SinkConstraint::ground_z), as
// a terrain does: the rock pile's bottom rocks reached up to 5 cm into its floor. Settling never pushes
// anything under it, so what is instantiated on the plane stays above it.
TEST(Settling, TheGroundPlaneRefusesCandidatesThatWouldSinkIntoIt) {
    PileScene scene;
    const std::vector<const DetailModel*> models = {&scene.fx.models[0], &scene.fx.models[1]};
    const InstanceStore loose = scene.instantiate();
    const RestReport without = measureRest(placeInstances(loose, scene.fx.tile), models, scene.settle.support, 0.02f, 2);
    ASSERT_GT(without.sunk, 0u) << "the fixture should reach into its floor without the constraint";
    for (InstanceTypeSettings& t : scene.fx.input.types) t.sink.ground_z = 0.0f;
    const InstanceStore kept = scene.instantiate();
    EXPECT_GT(kept.instanceCount(), loose.instanceCount() / 2);
    EXPECT_TRUE(kept == scene.instantiate(1)) << "one thread and two differ";
    SettledDrops drops;
    settleAll(scene.settle, kept, 2, &drops);
    for (const SettledDrops* d : std::initializer_list<const SettledDrops*>{nullptr, &drops}) {
        const RestReport r = measureRest(placeInstances(kept, scene.fx.tile, d), models, scene.settle.support, 0.02f, 2);
        EXPECT_EQ(r.sunk, 0u) << (d ? "settled" : "as instantiated");
        EXPECT_LE(r.max_sunk_m, 0.02 + 1e-6);
    }
    // A non-finite limit with the plane on is refused, naming the type.
    scene.fx.input.types[1].sink.max_sink_m = std::numeric_limits<float>::quiet_NaN();
    Instantiator inst;
    std::string error;
    EXPECT_FALSE(inst.setInput(scene.fx.input, &error));
    EXPECT_NE(error.find("max_sink_m"), std::string::npos) << error;
}

TEST(Settling, UpdateAfterAnEditEqualsSettlingTheNewStore) {
    PileScene scene;
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(scene.fx.input, &error)) << error;
    ASSERT_TRUE(inst.instantiateAll({.threads = 2}, nullptr, &error)) << error;
    SettledDrops live;
    settleAll(scene.settle, inst.store(), 2, &live);
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> uni(-0.8f, 0.8f);
    std::vector<Primitive> prims = {makePoint({0.0f, 0.0f, 0.0f}, 0.9f, 4.0f)};
    for (int edit = 0; edit < 12; ++edit) {
        const Primitive added = makePoint({uni(rng), uni(rng), 0.0f}, 0.35f, 3.0f);
        prims.push_back(added);
        std::vector<InstanceTypeSettings> types = inst.input().types;
        types[0].field = InstancerFixture::field(prims);
        const Bounds dirty = primitiveBounds(added, nullptr);
        std::vector<uint64_t> changed;
        ASSERT_TRUE(inst.update(types, std::span<const Bounds>(&dirty, 1), {.threads = 2}, nullptr, &changed, &error))
            << error;
        std::vector<uint64_t> touched;
        settleUpdate(scene.settle, inst.store(), changed, 2, &live, &touched);
        SettledDrops full;
        settleAll(scene.settle, inst.store(), 1, &full);
        ASSERT_TRUE(live == full) << "after edit " << edit;
        EXPECT_FALSE(touched.empty());
    }
}

// The history (the drops after each pass) is what settling with fewer passes gives, also past the pass
// where nothing moves any more.
TEST(Settling, TheHistoryHoldsTheDropsOfEveryShorterRun) {
    PileScene scene;
    const InstanceStore store = scene.instantiate();
    for (const int passes : {1, 6, 24}) {
        SettleInput in = scene.settle;
        in.settings.passes = passes;
        SettledDrops drops;
        SettleHistory history;
        settleAll(in, store, 2, &drops, &history);
        EXPECT_EQ(history.passes, passes);
        ASSERT_EQ(history.after_pass.size(), size_t(passes - 1));
        bool moved_late = false;
        for (int k = 1; k < passes; ++k) {
            SettleInput shorter = in;
            shorter.settings.passes = k;
            SettledDrops expected;
            settleAll(shorter, store, 1, &expected);
            EXPECT_TRUE(history.after_pass[size_t(k - 1)] == expected) << passes << " passes, after pass " << k;
            if (k + 1 == passes) moved_late = !(expected == drops);
        }
        // 24 passes are more than this pile needs: the last ones repeat the drops.
        if (passes == 24) {
            EXPECT_FALSE(moved_late);
        }
    }
}

// Fewer passes than the pile is wide (a pass's halo is a tile here): the update computes a part of it and
// reads the ring around that part from the history.
class SettlingWithHistory : public ::testing::TestWithParam<int> {};

TEST_P(SettlingWithHistory, AnUpdateReadingTheHistoryEqualsSettlingTheNewStore) {
    PileScene scene;
    scene.settle.settings.passes = GetParam();
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(scene.fx.input, &error)) << error;
    ASSERT_TRUE(inst.instantiateAll({.threads = 2}, nullptr, &error)) << error;
    SettledDrops live, without_history;
    SettleHistory history;
    settleAll(scene.settle, inst.store(), 2, &live, &history);
    without_history = live;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uni(-0.8f, 0.8f);
    std::vector<Primitive> prims = {makePoint({0.0f, 0.0f, 0.0f}, 0.9f, 4.0f)};
    for (int edit = 0; edit < 12; ++edit) {
        // Add a ball, or take the last one away (an edit that lets the pile above it fall further).
        Bounds dirty;
        if (edit % 3 == 2) {
            dirty = primitiveBounds(prims.back(), nullptr);
            prims.pop_back();
        } else {
            prims.push_back(makePoint({uni(rng), uni(rng), 0.0f}, 0.35f, 3.0f));
            dirty = primitiveBounds(prims.back(), nullptr);
        }
        std::vector<InstanceTypeSettings> types = inst.input().types;
        types[0].field = InstancerFixture::field(prims);
        std::vector<uint64_t> changed;
        ASSERT_TRUE(inst.update(types, std::span<const Bounds>(&dirty, 1), {.threads = 2}, nullptr, &changed, &error))
            << error;
        std::vector<uint64_t> touched, touched_without;
        settleUpdate(scene.settle, inst.store(), changed, 2, &live, &touched, &history);
        settleUpdate(scene.settle, inst.store(), changed, 1, &without_history, &touched_without);
        SettledDrops full;
        SettleHistory full_history;
        settleAll(scene.settle, inst.store(), 1, &full, &full_history);
        ASSERT_TRUE(live == full) << "after edit " << edit;
        ASSERT_EQ(history.passes, scene.settle.settings.passes);
        ASSERT_TRUE(history.after_pass == full_history.after_pass) << "after edit " << edit;
        EXPECT_TRUE(without_history == full) << "after edit " << edit;
        EXPECT_EQ(touched, touched_without);
    }
    // A history of another pass count is not read: cleared, and the update is still exact.
    SettleInput more = scene.settle;
    more.settings.passes = scene.settle.settings.passes + 2;
    SettledDrops drops;
    settleAll(more, inst.store(), 2, &drops);
    std::vector<uint64_t> all_tiles;
    for (size_t t = 0; t < inst.store().tileCount(); ++t) all_tiles.push_back(inst.store().tileKey(t));
    settleUpdate(more, inst.store(), std::span<const uint64_t>(all_tiles.data(), 1), 2, &drops, nullptr, &history);
    EXPECT_EQ(history.passes, 0);
    SettledDrops full;
    settleAll(more, inst.store(), 1, &full);
    EXPECT_TRUE(drops == full);
}

INSTANTIATE_TEST_SUITE_P(Passes, SettlingWithHistory, ::testing::Values(1, 2, 3, 6));

// A leaning chain of balls, each 9 cm beside and 1 cm above contact with the one before it: every ball
// rests (after enough passes) on the one below, so a change at the foot reaches the top, 3.5 m away.
struct Chain {
    static constexpr int kBalls = 40;
    DetailModel ball = test::sphereModel("ball", {{glm::vec3(0.0f), 0.05f}});
    GhostTile tile;
    std::vector<test::InstanceKey> keys;  // ball k = (tile of ball k, candidate k)
    SettleInput settle;
    Chain() {
        std::vector<glm::vec3> world;
        const float rise = std::sqrt(0.1f * 0.1f - 0.09f * 0.09f) + 0.01f;
        for (int k = 0; k < kBalls; ++k) world.push_back({0.09f * float(k) + 0.01f, 0.2f, 0.06f + rise * float(k)});
        std::vector<glm::vec3> local;
        for (const glm::vec3& p : world) {
            const glm::ivec3 t = tileOf(p, 0.5f);
            local.push_back(p - tileOrigin(t, 0.5f));
            keys.push_back({packTile(t), uint32_t(keys.size())});
        }
        tile = handTile(local);
        settle.tile = &tile;
        settle.models = {&ball};
        settle.support.ground_z = 0.0f;
        settle.settings = {.enabled = true, .passes = kBalls + 2, .max_drop_m = 1.0f};
    }
    InstanceStore store(int first) const {  // balls first.. (ids ascending per tile, tiles ascending)
        std::map<uint64_t, std::vector<uint32_t>> per_tile;
        for (int k = first; k < kBalls; ++k) per_tile[keys[size_t(k)].first].push_back(keys[size_t(k)].second);
        InstanceStore s;
        for (auto& [t, ids] : per_tile) s.appendTile(t, ids);
        return s;
    }
};

TEST(Settling, AChangeAtTheFootOfALongChainReachesItsTop) {
    Chain chain;
    const InstanceStore all = chain.store(0), without_foot = chain.store(1);
    SettledDrops drops, expected;
    settleAll(chain.settle, all, 1, &drops);
    // Every ball came down by 1 cm per ball below it: the top one by 40 cm... capped by nothing here.
    float top = 0.0f;
    forEachSettled(all, &drops, [&](uint64_t, uint32_t j, float d) {
        if (j == Chain::kBalls - 1) top = d;
    });
    EXPECT_NEAR(top, 0.06f - 0.05f + 0.01f * float(Chain::kBalls - 1), 0.01f);
    settleAll(chain.settle, without_foot, 1, &expected);
    const std::vector<uint64_t> changed = {chain.keys[0].first};
    std::vector<uint64_t> touched;
    SettledDrops drops_too = drops;
    SettleHistory history;
    settleAll(chain.settle, all, 2, &drops_too, &history);
    settleUpdate(chain.settle, without_foot, changed, 1, &drops, &touched);
    EXPECT_TRUE(drops == expected);
    // The same read from the history: every pass's drops of the chain's upper part change.
    settleUpdate(chain.settle, without_foot, changed, 2, &drops_too, nullptr, &history);
    EXPECT_TRUE(drops_too == expected);
    SettleHistory expected_history;
    settleAll(chain.settle, without_foot, 1, &expected, &expected_history);
    EXPECT_TRUE(history.after_pass == expected_history.after_pass);
    // A region job at the top of the chain needs the foot: its halo reaches it.
    const Bounds region{glm::vec3(3.0f, 0.0f, -1.0f), glm::vec3(4.0f, 0.5f, 4.0f)};
    const float halo = settleHaloMetres(chain.settle);
    InstanceStore wide;
    std::map<uint64_t, std::vector<uint32_t>> per_tile;
    for (int k = 0; k < Chain::kBalls; ++k) {
        const glm::vec3 p = tileOrigin(unpackTile(chain.keys[size_t(k)].first), 0.5f) +
                            chain.tile.candidates.position[size_t(k)];
        if (glm::all(glm::greaterThanEqual(p, region.lo - halo)) && glm::all(glm::lessThan(p, region.hi + halo)))
            per_tile[chain.keys[size_t(k)].first].push_back(uint32_t(k));
    }
    for (auto& [t, ids] : per_tile) wide.appendTile(t, ids);
    SettledDrops wide_drops, whole_drops;
    settleAll(chain.settle, wide, 1, &wide_drops);
    settleAll(chain.settle, all, 1, &whole_drops);
    InstanceStore own, expected_store;
    SettledDrops own_drops, expected_drops;
    cropToRegion(wide, wide_drops, chain.tile, region, &own, &own_drops);
    cropToRegion(all, whole_drops, chain.tile, region, &expected_store, &expected_drops);
    EXPECT_GT(own.instanceCount(), 5u);
    EXPECT_TRUE(own == expected_store);
    EXPECT_TRUE(own_drops == expected_drops);
}

TEST(Settling, RegionJobsGrownByTheHaloMatchTheWhole) {
    PileScene scene;
    const InstanceStore whole = scene.instantiate();
    SettledDrops whole_drops;
    settleAll(scene.settle, whole, 2, &whole_drops);
    const float halo = settleHaloMetres(scene.settle);
    EXPECT_GT(halo, 0.0f);
    const Bounds regions[] = {{glm::vec3(-1.5f, -1.5f, 0.0f), glm::vec3(0.1f, 0.2f, 1.0f)},
                              {glm::vec3(0.1f, -1.5f, 0.0f), glm::vec3(1.5f, 0.2f, 1.0f)},
                              {glm::vec3(-1.5f, 0.2f, 0.0f), glm::vec3(1.5f, 1.5f, 1.0f)}};
    uint64_t total = 0;
    for (const Bounds& r : regions) {
        InstanceStore wide;
        std::string error;
        ASSERT_TRUE(instantiateRegion(scene.fx.input, Bounds{r.lo - halo, r.hi + halo}, {.threads = 2}, &wide, nullptr,
                                      &error))
            << error;
        SettledDrops wide_drops;
        settleAll(scene.settle, wide, 2, &wide_drops);
        InstanceStore own, expected;
        SettledDrops own_drops, expected_drops;
        cropToRegion(wide, wide_drops, scene.fx.tile, r, &own, &own_drops);
        cropToRegion(whole, whole_drops, scene.fx.tile, r, &expected, &expected_drops);
        EXPECT_TRUE(own == expected);
        EXPECT_TRUE(own_drops == expected_drops);
        total += own.instanceCount();
    }
    EXPECT_EQ(total, whole.instanceCount());
}

}  // namespace
}  // namespace ug
