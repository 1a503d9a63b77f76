// Resident per-tile instances and indirect draw commands (app/editor/render_data.h), without GL: the
// mirrors are what the GPU buffers hold, the commands what the multi-draws run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "editor/render_data.h"
#include "instancer/instance_store.h"
#include "instancer/tile_coord.h"

namespace ug::editor {
namespace {

// Two types: candidates 0..2 are type 0, 3..4 type 1.
CandidateSet twoTypeCandidates() {
    CandidateSet c;
    c.type_begin = {0, 3, 5};
    c.type = {0, 0, 0, 1, 1};
    for (uint32_t j = 0; j < 5; ++j) {
        c.position.push_back(glm::vec3(0.1f * float(j), 0.25f, 0.0f));
        c.rotation.push_back(glm::quat(1.0f, 0.0f, 0.0f, 0.0f));
        c.scale.push_back(1.0f);
    }
    return c;
}

using TileMap = std::map<glm::ivec3, std::vector<uint32_t>, bool (*)(const glm::ivec3&, const glm::ivec3&)>;
bool lessTile(const glm::ivec3& a, const glm::ivec3& b) { return packTile(a) < packTile(b); }

InstanceStore makeStore(const TileMap& tiles) {
    std::vector<std::pair<uint64_t, std::vector<uint32_t>>> sorted;
    for (const auto& [t, ids] : tiles) sorted.push_back({packTile(t), ids});
    std::sort(sorted.begin(), sorted.end());
    InstanceStore s;
    for (const auto& [key, ids] : sorted) s.appendTile(key, ids);
    return s;
}

// What the GPU would hold, read back through the slots: key -> ids (ascending), checking every packed
// instance names its own tile.
std::map<uint64_t, std::vector<uint32_t>> residentContent(const ResidentTiles& r) {
    std::map<uint64_t, std::vector<uint32_t>> out;
    for (size_t t = 0; t < r.tileCount(); ++t) {
        std::vector<uint32_t>& ids = out[r.tile_key[t]];
        EXPECT_EQ(r.tile_index.at(r.tile_key[t]), t);
        for (uint32_t type = 0; type < r.type_count; ++type) {
            const TileSlot s = r.slot[t * r.type_count + type];
            const uint32_t n = r.count[t * r.type_count + type];
            EXPECT_LE(n, s.capacity);
            EXPECT_LE(s.offset + s.capacity, r.types[type].mirror.size());
            for (uint32_t i = 0; i < n; ++i) {
                glm::ivec3 tile;
                uint32_t j = 0;
                unpackInstance(r.types[type].mirror[s.offset + i], &tile, &j);
                EXPECT_EQ(tile, r.tile_coord[t]);
                ids.push_back(j);
            }
        }
    }
    return out;
}

std::map<uint64_t, std::vector<uint32_t>> storeContent(const InstanceStore& s) {
    std::map<uint64_t, std::vector<uint32_t>> out;
    for (size_t t = 0; t < s.tileCount(); ++t) s.tileIds(t, &out[s.tileKey(t)]);
    return out;
}

// Keys whose id lists differ between two stores (what LiveResult::changed_tiles lists).
std::vector<uint64_t> changedKeys(const InstanceStore& a, const InstanceStore& b) {
    auto ca = storeContent(a), cb = storeContent(b);
    std::set<uint64_t> keys;
    for (const auto& [k, ids] : ca)
        if (!cb.count(k) || cb[k] != ids) keys.insert(k);
    for (const auto& [k, ids] : cb)
        if (!ca.count(k)) keys.insert(k);
    return {keys.begin(), keys.end()};
}

TEST(ResidentTiles, RebuildHoldsEveryInstanceOfTheStore) {
    const CandidateSet c = twoTypeCandidates();
    TileMap m(lessTile);
    m[{0, 0, 0}] = {0, 1, 3};
    m[{1, 0, 0}] = {2, 4};
    m[{-3, 2, 1}] = {0};
    const InstanceStore store = makeStore(m);
    ResidentTiles r;
    TileUploads up;
    std::string error;
    ASSERT_TRUE(rebuildResidentTiles(store, nullptr, c, 0.5f, 0.0f, &r, &up, &error)) << error;
    EXPECT_EQ(residentContent(r), storeContent(store));
    EXPECT_EQ(r.instances_per_type, (std::vector<uint64_t>{4, 2}));
    EXPECT_TRUE(up.full);
    EXPECT_EQ(up.tiles_uploaded, 3u);
    EXPECT_TRUE(up.types[0].whole && up.types[1].whole);
}

// One tile changes ids without changing its counts: exactly its two slots are rewritten in place, no other
// tile's slot moves, nothing else is uploaded.
TEST(ResidentTiles, UpdateRewritesOnlyTheChangedTileInPlace) {
    const CandidateSet c = twoTypeCandidates();
    TileMap m(lessTile);
    m[{0, 0, 0}] = {0, 1, 3};
    m[{1, 0, 0}] = {2, 4};
    m[{0, 1, 0}] = {1, 3, 4};
    const InstanceStore a = makeStore(m);
    ResidentTiles r;
    TileUploads up;
    std::string error;
    ASSERT_TRUE(rebuildResidentTiles(a, nullptr, c, 0.5f, 0.0f, &r, &up, &error)) << error;
    const std::vector<TileSlot> slots_before = r.slot;
    m[{1, 0, 0}] = {0, 3};
    const InstanceStore b = makeStore(m);
    const std::vector<uint64_t> changed = changedKeys(a, b);
    ASSERT_EQ(changed, std::vector<uint64_t>{packTile({1, 0, 0})});
    ASSERT_TRUE(updateResidentTiles(b, nullptr, c, changed, &r, &up, &error)) << error;
    EXPECT_EQ(residentContent(r), storeContent(b));
    EXPECT_EQ(r.slot.size(), slots_before.size());
    for (size_t i = 0; i < r.slot.size(); ++i) {
        EXPECT_EQ(r.slot[i].offset, slots_before[i].offset);
        EXPECT_EQ(r.slot[i].capacity, slots_before[i].capacity);
    }
    EXPECT_FALSE(up.full);
    EXPECT_EQ(up.tiles_uploaded, 1u);
    ASSERT_EQ(up.tiles, std::vector<glm::ivec3>{glm::ivec3(1, 0, 0)});
    const uint32_t t = r.tile_index.at(packTile({1, 0, 0}));
    for (uint32_t type = 0; type < 2; ++type) {
        EXPECT_FALSE(up.types[type].whole);
        ASSERT_EQ(up.types[type].ranges.size(), 1u);
        EXPECT_EQ(up.types[type].ranges[0].offset, r.slot[t * 2 + type].offset);
        EXPECT_EQ(up.types[type].ranges[0].count, 1u);
    }
    EXPECT_EQ(up.bytes_uploaded, 2 * sizeof(PackedInstance));
}

// Random edits: after every update the resident content equals the store, live slots never overlap, and
// the uploads touch only the changed tiles' slots.
TEST(ResidentTiles, RandomUpdatesEqualRebuild) {
    const CandidateSet c = twoTypeCandidates();
    std::mt19937 rng(3);
    auto randomIds = [&] {
        std::vector<uint32_t> ids;
        for (uint32_t j = 0; j < 5; ++j)
            if (rng() % 2) ids.push_back(j);
        return ids;
    };
    TileMap m(lessTile);
    for (int x = 0; x < 6; ++x)
        for (int y = 0; y < 6; ++y)
            if (auto ids = randomIds(); !ids.empty()) m[{x, y, 0}] = ids;
    InstanceStore store = makeStore(m);
    ResidentTiles r;
    TileUploads up;
    std::string error;
    ASSERT_TRUE(rebuildResidentTiles(store, nullptr, c, 0.5f, 0.0f, &r, &up, &error)) << error;
    for (int step = 0; step < 60; ++step) {
        // Edit a 2 x 2 patch: new ids, emptied tiles, new tiles outside the start area.
        const int x0 = int(rng() % 8) - 1, y0 = int(rng() % 8) - 1;
        for (int x = x0; x < x0 + 2; ++x)
            for (int y = y0; y < y0 + 2; ++y) {
                auto ids = randomIds();
                if (ids.empty())
                    m.erase({x, y, 0});
                else
                    m[{x, y, 0}] = ids;
            }
        const InstanceStore next = makeStore(m);
        const std::vector<uint64_t> changed = changedKeys(store, next);
        std::map<uint64_t, std::vector<TileSlot>> old_slots;
        for (size_t t = 0; t < r.tileCount(); ++t)
            old_slots[r.tile_key[t]].assign(r.slot.begin() + long(t * 2), r.slot.begin() + long(t * 2 + 2));
        ASSERT_TRUE(updateResidentTiles(next, nullptr, c, changed, &r, &up, &error)) << error;
        store = next;
        ASSERT_EQ(residentContent(r), storeContent(store)) << "step " << step;
        EXPECT_EQ(up.tiles_uploaded, changed.size());
        const std::set<uint64_t> changed_set(changed.begin(), changed.end());
        for (size_t t = 0; t < r.tileCount(); ++t)
            if (!changed_set.count(r.tile_key[t])) {  // unchanged tiles keep their slots
                for (uint32_t type = 0; type < 2; ++type)
                    EXPECT_EQ(r.slot[t * 2 + type].offset, old_slots.at(r.tile_key[t])[type].offset);
            }
        for (uint32_t type = 0; type < 2; ++type) {
            // Live slots of a type never overlap.
            std::vector<TileSlot> live;
            for (size_t t = 0; t < r.tileCount(); ++t)
                if (r.slot[t * 2 + type].capacity) live.push_back(r.slot[t * 2 + type]);
            std::sort(live.begin(), live.end(), [](TileSlot x, TileSlot y) { return x.offset < y.offset; });
            for (size_t i = 1; i < live.size(); ++i) ASSERT_LE(live[i - 1].offset + live[i - 1].capacity, live[i].offset);
            if (up.types[type].whole) continue;
            // Every upload range is inside a changed tile's slot.
            for (const TileUploads::Range& range : up.types[type].ranges) {
                bool inside = false;
                for (uint64_t key : changed) {
                    const auto it = r.tile_index.find(key);
                    if (it == r.tile_index.end()) continue;
                    const TileSlot s = r.slot[it->second * 2 + type];
                    inside |= range.offset >= s.offset && range.offset + range.count <= s.offset + s.capacity;
                }
                EXPECT_TRUE(inside) << "step " << step << ": range at " << range.offset;
            }
        }
    }
}

TEST(ResidentTiles, RefusesTilesOutsideThePackedRange) {
    const CandidateSet c = twoTypeCandidates();
    TileMap m(lessTile);
    m[{kPackedTileLimit + 1, 0, 0}] = {0};
    ResidentTiles r;
    TileUploads up;
    std::string error;
    EXPECT_FALSE(rebuildResidentTiles(makeStore(m), nullptr, c, 0.5f, 0.0f, &r, &up, &error));
    EXPECT_NE(error.find("32768"), std::string::npos) << error;
}

// A mesh per type with recognisable LOD index ranges.
std::vector<DetailLodMesh> testMeshes() {
    std::vector<DetailLodMesh> meshes(2);
    for (size_t i = 0; i < 2; ++i) {
        meshes[i].index_first = {0, 300, 360};
        meshes[i].index_count = {300, 60, 12};
        meshes[i].radius_m = 0.1f;
        meshes[i].scale_max = 1.0f;
    }
    return meshes;
}

uint32_t c_type(uint32_t candidate) { return candidate < 3 ? 0 : 1; }

// The view a draw is judged from: the vertex shaders drop the instances of a command that belong to the
// other representation (render_data.h drawnAsMesh); this is that rule, from the instance's own origin.
struct ShaderView {
    const CandidateSet* candidates = nullptr;
    glm::vec3 eye{0.0f};
    float pixels_per_radian = 0.0f;
    float impostor_px = 0.0f;
};

// What a set of commands draws, read through the mirror as the GPU would: (type, key, candidate) -> times.
// With a ShaderView, each instance counts only in the representation the shaders give it.
std::map<std::tuple<uint32_t, uint64_t, uint32_t>, int> drawn(const ResidentTiles& r, const IndirectDraws& d,
                                                             const std::vector<DetailLodMesh>& meshes,
                                                             const ShaderView* shader = nullptr) {
    std::map<std::tuple<uint32_t, uint64_t, uint32_t>, int> out;
    for (uint32_t type = 0; type < r.type_count; ++type)
        for (int level = 0; level < kLodCount; ++level) {
            const IndirectDraws::Group& g = d.groups[type][size_t(level)];
            uint64_t instances = 0;
            for (uint32_t k = g.first; k < g.first + g.count; ++k) {
                uint32_t first = 0, n = 0, stride = 1;
                if (level == kImpostorLod) {
                    // detail_impostor.vert: the i-th point is instance run.offset + i * run.stride.
                    const DrawArraysIndirectCommand& cmd = d.points[k];
                    EXPECT_EQ(cmd.instance_count, 1u);
                    EXPECT_EQ(cmd.first, 0u);
                    EXPECT_EQ(cmd.base_instance, k) << "a command reads the run beside it";
                    const PointRun& run = d.point_runs.at(cmd.base_instance);
                    EXPECT_EQ(cmd.count, (run.span + run.stride - 1) / run.stride);
                    first = run.offset;
                    stride = run.stride;
                    n = cmd.count;
                } else {
                    const DrawElementsIndirectCommand& cmd = d.elements[k];
                    EXPECT_EQ(cmd.count, meshes[type].index_count[size_t(level)]);
                    EXPECT_EQ(cmd.first_index, meshes[type].index_first[size_t(level)]);
                    first = cmd.base_instance;
                    n = cmd.instance_count;
                }
                EXPECT_GT(n, 0u);
                instances += n;
                for (uint32_t i = first; i < first + n * stride; i += stride) {
                    glm::ivec3 tile;
                    uint32_t j = 0;
                    unpackInstance(r.types[type].mirror[i], &tile, &j);
                    EXPECT_EQ(c_type(j), type);
                    if (shader) {
                        const glm::vec3 origin = glm::vec3(tile) * r.tile_size_m + shader->candidates->position[j];
                        const float px = 2.0f * meshes[type].radius_m * meshes[type].scale_max *
                                         shader->pixels_per_radian / glm::length(origin - shader->eye);
                        const float u = float((instanceHash(r.types[type].mirror[i])) & 1023u) / 1024.0f;
                        const bool mesh = px >= shader->impostor_px * (1.0f + kImpostorBand * u);
                        if (mesh != (level != kImpostorLod)) continue;
                    }
                    ++out[{type, packTile(tile), j}];
                }
            }
            EXPECT_EQ(instances, g.instances);
        }
    return out;
}

// The tiles (-half..half-1)² at z = 0, each of the five candidates in one with probability 1/one_in
// (empty tiles left out).
TileMap randomField(int half, uint32_t one_in, std::mt19937* rng) {
    TileMap m(lessTile);
    for (int x = -half; x < half; ++x)
        for (int y = -half; y < half; ++y) {
            std::vector<uint32_t> ids;
            for (uint32_t j = 0; j < 5; ++j)
                if ((*rng)() % one_in == 0) ids.push_back(j);
            if (!ids.empty()) m[{x, y, 0}] = ids;
        }
    return m;
}

TEST(IndirectDraws, EveryVisibleInstanceOnceAndCulledTilesAbsent) {
    const CandidateSet c = twoTypeCandidates();
    const std::vector<DetailLodMesh> meshes = testMeshes();
    std::mt19937 rng(9);
    // A 40 x 40 tile field (20 m) around the origin; the camera stands at its south edge looking north.
    TileMap m = randomField(20, 3, &rng);
    m[{0, 8, 0}] = {0, 3};  // at the look-at point
    InstanceStore store = makeStore(m);
    ResidentTiles r;
    TileUploads up;
    std::string error;
    ASSERT_TRUE(rebuildResidentTiles(store, nullptr, c, 0.5f, 0.0f, &r, &up, &error)) << error;
    // Then some edits, so slots are no longer in tile order (commands must not merge across gaps).
    for (int k = 0; k < 30; ++k) m[{int(rng() % 40) - 20, int(rng() % 40) - 20, 0}] = {0, 1, 2, 3, 4};
    const InstanceStore edited = makeStore(m);
    ASSERT_TRUE(updateResidentTiles(edited, nullptr, c, changedKeys(store, edited), &r, &up, &error)) << error;

    ViewParams view;
    view.eye = glm::vec3(0.0f, -3.0f, 1.5f);
    const glm::mat4 proj = glm::perspective(glm::radians(50.0f), 16.0f / 9.0f, 0.05f, 200.0f);
    view.view_proj = proj * glm::lookAt(view.eye, glm::vec3(0.0f, 4.0f, 0.0f), glm::vec3(0, 0, 1));
    view.pixels_per_radian = 720.0f / glm::radians(50.0f);
    IndirectDraws d;
    // A 0.2 m object covers 165 px at 1 m: LOD 0 within 1.8 m, impostors beyond 8.3 m.
    buildIndirectDraws(r, meshes, view, LodSettings{.lod1_px = 90.0f, .lod2_px = 30.0f, .impostor_px = 20.0f}, &d);
    EXPECT_EQ(d.tiles_visible + d.tiles_culled, r.tileCount());
    ASSERT_GT(d.tiles_culled, 0u);
    ASSERT_GT(d.tiles_visible, 0u);

    const ShaderView shader{&c, view.eye, view.pixels_per_radian, 20.0f};
    const auto counts = drawn(r, d, meshes, &shader);
    std::set<uint64_t> drawn_tiles;
    for (const auto& [key, times] : counts) {
        EXPECT_EQ(times, 1) << "an instance drawn " << times << " times";
        drawn_tiles.insert(std::get<1>(key));
    }
    uint64_t visible_instances = 0;
    for (size_t t = 0; t < r.tileCount(); ++t) {
        const glm::ivec3 tile = r.tile_coord[t];
        // Tiles well behind the eye (south of y = -4 m, i.e. tile y < -8) can never be visible.
        if (tile.y < -8) {
            EXPECT_LT(d.tile_distance[t], 0.0f) << tile.x << "," << tile.y;
        }
        if (d.tile_distance[t] < 0.0f) {
            EXPECT_FALSE(drawn_tiles.count(r.tile_key[t])) << "a culled tile is drawn";
            continue;
        }
        visible_instances += r.count[t * 2] + r.count[t * 2 + 1];
        EXPECT_TRUE(drawn_tiles.count(r.tile_key[t])) << "a visible tile is missing";
    }
    EXPECT_EQ(counts.size(), visible_instances);
    // The tile at the look-at point is in view; near tiles use the full mesh, the far rows impostors.
    EXPECT_GE(d.tile_distance[r.tile_index.at(packTile({0, 8, 0}))], 0.0f);
    for (uint32_t type = 0; type < 2; ++type) {
        EXPECT_GT(d.groups[type][0].instances, 0u);
        EXPECT_GT(d.groups[type][kImpostorLod].instances, 0u);
    }
    // Merging works: fewer commands than visible (tile, type) ranges.
    EXPECT_LT(d.commandCount(), visible_instances);
    // The switch is per instance across a band, not per tile: the commands of some tiles run in both
    // representations (each instance kept by one of them, as checked above).
    size_t in_both = 0;
    for (const auto& [key, times] : drawn(r, d, meshes)) in_both += times == 2 ? 1 : 0;
    EXPECT_GT(in_both, 0u) << "no tile is drawn in both representations: the band is missing";
}

// Whether any of a grid of points on the box, swept along `sweep`, projects inside the view (clip space).
bool sweptBoxSeen(const glm::mat4& view_proj, const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& sweep) {
    const int n = 4, steps = 24;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j)
            for (int k = 0; k <= n; ++k)
                for (int t = 0; t <= steps; ++t) {
                    const glm::vec3 f(float(i) / n, float(j) / n, float(k) / n);
                    const glm::vec3 p = lo + f * (hi - lo) + sweep * (float(t) / steps);
                    const glm::vec4 c = view_proj * glm::vec4(p, 1.0f);
                    if (c.w > 0.0f && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w && std::abs(c.z) <= c.w)
                        return true;
                }
    return false;
}

TEST(IndirectDraws, ShadowCastersAreDroppedOnlyWhereTheirShadowCannotReachTheView) {
    const CandidateSet c = twoTypeCandidates();
    const std::vector<DetailLodMesh> meshes = testMeshes();
    std::mt19937 rng(21);
    const TileMap m = randomField(20, 2, &rng);
    const InstanceStore store = makeStore(m);
    ResidentTiles r;
    TileUploads up;
    std::string error;
    ASSERT_TRUE(rebuildResidentTiles(store, nullptr, c, 0.5f, 0.0f, &r, &up, &error)) << error;

    // The sun's square over the whole 20 m field; the camera near its south edge, looking north-east.
    const glm::vec3 sun = glm::normalize(glm::vec3(0.45f, -0.50f, 0.74f));
    ViewParams caster;
    caster.view_proj = glm::ortho(-20.0f, 20.0f, -20.0f, 20.0f, 0.0f, 100.0f) *
                       glm::lookAt(sun * 50.0f, glm::vec3(0.0f), glm::vec3(0, 0, 1));
    caster.eye = glm::vec3(-2.0f, -6.0f, 1.5f);
    caster.pixels_per_radian = 720.0f / glm::radians(50.0f);
    caster.receiver_view_proj = glm::perspective(glm::radians(50.0f), 16.0f / 9.0f, 0.05f, 200.0f) *
                                glm::lookAt(caster.eye, glm::vec3(3.0f, 2.0f, 0.0f), glm::vec3(0, 0, 1));
    caster.cull_by_receiver = true;
    caster.shadow_sweep = -sun * (2.0f / sun.z);  // casters up to 2 m above the ground
    const LodSettings lod{.lod1_px = 90.0f, .lod2_px = 30.0f, .impostor_px = 20.0f};
    IndirectDraws culled, all;
    buildIndirectDraws(r, meshes, caster, lod, &culled);
    ViewParams whole = caster;
    whole.cull_by_receiver = false;
    buildIndirectDraws(r, meshes, whole, lod, &all);
    ASSERT_EQ(all.tiles_culled, 0u) << "the sun's square holds the whole field";

    // Each object sticks out of its cell by its radius (0.1 m); the cell's casters reach 2 m down the rays.
    const float reach = 0.1f;
    size_t dropped = 0, kept = 0;
    for (size_t t = 0; t < r.tileCount(); ++t) {
        const glm::vec3 lo = glm::vec3(r.tile_coord[t]) * 0.5f;
        const bool seen = sweptBoxSeen(caster.receiver_view_proj, lo - reach, lo + 0.5f + reach, caster.shadow_sweep);
        const bool drawn = culled.tile_distance[t] >= 0.0f;
        if (seen) {
            EXPECT_TRUE(drawn) << "a caster whose shadow reaches the view is dropped: tile " << r.tile_coord[t].x << ","
                               << r.tile_coord[t].y;
        }
        dropped += !drawn;
        kept += drawn;
        // What is drawn is drawn as without the receiver test: same distance, hence the same LOD.
        if (drawn) {
            EXPECT_EQ(culled.tile_distance[t], all.tile_distance[t]);
        }
    }
    // Behind the camera and beside the view, shadows cannot reach it: a good part of the square is dropped.
    EXPECT_GT(dropped, r.tileCount() / 4);
    EXPECT_GT(kept, r.tileCount() / 8);
}

TEST(PointStride, ThinsOnlyOnePixelPointsAndNeverPastOnePixelOfArea) {
    DetailLodMesh m;
    m.scale_max = 1.0f;
    m.silhouettes.radius = 0.1f;
    m.silhouettes.extent = 1.0f;
    m.coverage_m2 = {0.004f, 0.01f, 0.006f, 0.002f};
    // 2 px per metre: a 0.4 px sprite whose largest area is 0.04 px: 16 of them make 0.64 px, 32 would
    // make 1.28.
    EXPECT_EQ(pointStride(m, 2.0f), 16u);
    // 0.2 px per metre: 0.0004 px, thinned as far as allowed.
    EXPECT_EQ(pointStride(m, 0.2f), kMaxPointStride);
    // 10 px per metre: a 2 px sprite shows its silhouette; 9.9: one pixel of 0.98 px area, alone.
    EXPECT_EQ(pointStride(m, 10.0f), 1u);
    EXPECT_EQ(pointStride(m, 9.9f), 1u);
    EXPECT_EQ(pointStride(m, std::nanf("")), 1u);
    // A larger scale counts: at scale 2 the 2 px per metre point has 0.16 px, stride 4 (0.64).
    m.scale_max = 2.0f;
    EXPECT_EQ(pointStride(m, 2.0f), 4u);
}

TEST(IndirectDraws, FarPointsAreThinnedOnlyWhereEveryDrawnOneIsAPixelOfAtMostOnePixelOfArea) {
    const CandidateSet c = twoTypeCandidates();
    std::vector<DetailLodMesh> meshes = testMeshes();
    for (DetailLodMesh& m : meshes) {
        m.silhouettes.radius = 0.1f;
        m.silhouettes.extent = 1.0f;
        m.coverage_m2 = {0.001f, 0.002f, 0.002f, 0.001f};  // thin, as grass: a fraction of its square
    }
    std::mt19937 rng(4);
    const TileMap tiles = randomField(40, 2, &rng);
    ResidentTiles r;
    TileUploads up;
    std::string error;
    ASSERT_TRUE(rebuildResidentTiles(makeStore(tiles), nullptr, c, 0.5f, 0.0f, &r, &up, &error)) << error;

    // A 40 m field seen from 30 m up, 40 m south of it: its near rows are sprites (3 px), its far ones
    // pixels.
    ViewParams view;
    view.eye = glm::vec3(0.0f, -60.0f, 30.0f);
    const float fov = glm::radians(50.0f), height_px = 720.0f;
    view.view_proj = glm::perspective(fov, 16.0f / 9.0f, 0.05f, 400.0f) *
                     glm::lookAt(view.eye, glm::vec3(0.0f, 0.0f, 0.0f), glm::vec3(0, 0, 1));
    view.pixels_per_radian = height_px / fov;
    const LodSettings lod{.lod1_px = 90.0f, .lod2_px = 30.0f, .impostor_px = 20.0f};
    IndirectDraws all, thinned;
    buildIndirectDraws(r, meshes, view, lod, &all);
    view.point_scale = 0.5f * height_px / std::tan(0.5f * fov);
    buildIndirectDraws(r, meshes, view, lod, &thinned);

    // The runs cover the instances the unthinned commands draw, each once.
    auto covered = [&](const IndirectDraws& d, uint32_t type) {
        std::multiset<uint32_t> out;
        const IndirectDraws::Group& g = d.groups[type][kImpostorLod];
        for (uint32_t k = g.first; k < g.first + g.count; ++k)
            for (uint32_t i = 0; i < d.point_runs[k].span; ++i) out.insert(d.point_runs[k].offset + i);
        return out;
    };
    uint32_t thinned_runs = 0, whole_runs = 0;
    for (uint32_t type = 0; type < 2; ++type) {
        EXPECT_EQ(covered(thinned, type), covered(all, type));
        EXPECT_EQ(all.groups[type][kImpostorLod].instances, covered(all, type).size());
        EXPECT_LT(thinned.groups[type][kImpostorLod].instances, all.groups[type][kImpostorLod].instances);
        // Every point a thinned run draws is one pixel in the shader, and its stride times its largest
        // area is at most one pixel: kept with stride times its probability, it keeps the expected
        // coverage of the points it stands for.
        const IndirectDraws::Group& g = thinned.groups[type][kImpostorLod];
        const DetailLodMesh& m = meshes[type];
        const float most_m2 = *std::max_element(m.coverage_m2.begin(), m.coverage_m2.end());
        for (uint32_t k = g.first; k < g.first + g.count; ++k) {
            const PointRun& run = thinned.point_runs[k];
            ASSERT_TRUE(run.stride >= 1 && run.stride <= kMaxPointStride && (run.stride & (run.stride - 1)) == 0);
            if (run.stride == 1) {
                ++whole_runs;
                continue;
            }
            ++thinned_runs;
            for (uint32_t i = run.offset; i < run.offset + run.span; i += run.stride) {
                glm::ivec3 tile;
                uint32_t j = 0;
                unpackInstance(r.types[type].mirror[i], &tile, &j);
                const glm::vec3 world = glm::vec3(tile) * r.tile_size_m + c.position[j];
                const float w = (view.view_proj * glm::vec4(world, 1.0f)).w;
                const float px_per_m = view.point_scale / w;
                EXPECT_LT(2.0f * m.silhouettes.radius * m.silhouettes.extent * m.scale_max * px_per_m, 2.0f);
                EXPECT_LE(float(run.stride) * most_m2 * m.scale_max * m.scale_max * px_per_m * px_per_m, 1.0f);
            }
        }
    }
    EXPECT_GT(thinned_runs, 0u) << "nothing thinned: the view is too close for the test";
    EXPECT_GT(whole_runs, 0u) << "everything thinned: the view is too far for the test";
    // Without point_scale nothing is thinned.
    for (const PointRun& run : all.point_runs) EXPECT_EQ(run.stride, 1u);
}

}  // namespace
}  // namespace ug::editor

namespace ug::editor {
namespace {

TEST(PackedInstance, RoundTripsTheCornersOfItsRangeAndTheDropCode) {
    const glm::ivec3 tiles[] = {{0, 0, 0},
                                {kPackedTileLimit, -kPackedTileLimit, kPackedTileZMax},
                                {-kPackedTileLimit, kPackedTileLimit, kPackedTileZMin},
                                {-1, -1, -1}};
    for (const glm::ivec3& t : tiles)
        for (uint32_t j : {0u, 1u, kPackedCandidateLimit - 1})
            for (uint32_t code : {0u, 1u, kPackedDropSteps}) {
                glm::ivec3 t2;
                uint32_t j2 = 0, code2 = 0;
                unpackInstance(packInstance(t, j, code), &t2, &j2, &code2);
                EXPECT_EQ(t2, t);
                EXPECT_EQ(j2, j);
                EXPECT_EQ(code2, code);
            }
}

TEST(PackedInstance, DropCodesRoundDownToTheStepAndSaturate) {
    const float unit = packedDropUnit(true, 0.5f);
    EXPECT_FLOAT_EQ(unit, 0.5f / 127.0f);
    EXPECT_EQ(packedDropUnit(false, 0.5f), 0.0f);
    EXPECT_EQ(packedDropCode(0.0f, unit), 0u);
    EXPECT_EQ(packedDropCode(unit * 0.99f, unit), 0u);  // never drawn lower than the engine settled it
    EXPECT_EQ(packedDropCode(unit * 3.5f, unit), 3u);
    EXPECT_EQ(packedDropCode(10.0f, unit), kPackedDropSteps);
    EXPECT_EQ(packedDropCode(0.3f, 0.0f), 0u);  // settling off
}

TEST(ResidentTiles, RebuildPacksEachInstancesSettledDrop) {
    CandidateSet c;
    c.type_begin = {0, 4};
    for (int j = 0; j < 4; ++j) {
        c.type.push_back(0);
        c.position.push_back(glm::vec3(0.1f * float(j)));
        c.rotation.push_back(glm::quat(1, 0, 0, 0));
        c.scale.push_back(1.0f);
    }
    InstanceStore store;
    const std::vector<uint32_t> ids = {0, 2, 3};
    store.appendTile(packTile({1, 2, -3}), ids);
    SettledDrops drops;
    const std::vector<uint16_t> units = {0, 1200, 5000};  // 0, 0.12 m, 0.5 m
    drops.append(packTile({1, 2, -3}), units);
    const float unit = packedDropUnit(true, 0.5f);
    ResidentTiles r;
    TileUploads up;
    std::string error;
    ASSERT_TRUE(rebuildResidentTiles(store, &drops, c, 0.5f, unit, &r, &up, &error)) << error;
    EXPECT_EQ(r.drop_unit_m, unit);
    const TileSlot slot = r.slot[0];
    std::vector<uint32_t> codes;
    for (uint32_t i = 0; i < 3; ++i) {
        glm::ivec3 t;
        uint32_t j = 0, code = 0;
        unpackInstance(r.types[0].mirror[slot.offset + i], &t, &j, &code);
        EXPECT_EQ(t, glm::ivec3(1, 2, -3));
        EXPECT_EQ(j, ids[i]);
        codes.push_back(code);
    }
    EXPECT_EQ(codes, (std::vector<uint32_t>{0u, uint32_t(std::floor(0.12f / unit)), kPackedDropSteps}));
    // A tile above the packed height is refused with the reason.
    InstanceStore high;
    high.appendTile(packTile({0, 0, kPackedTileZMax + 1}), ids);
    EXPECT_FALSE(rebuildResidentTiles(high, nullptr, c, 0.5f, 0.0f, &r, &up, &error));
    EXPECT_NE(error.find("packed range"), std::string::npos) << error;
}

}  // namespace
}  // namespace ug::editor
