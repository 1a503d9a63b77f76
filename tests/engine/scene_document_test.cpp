// The editor's document layer: editable densities (stable ids, no unbounded growth, wrapping a non-blend
// root), commands with undo and redo that give back the exact instance sets, strokes as one step, the
// live instancer (coalescing, accumulated changed tiles, cancelled resets) against fresh full runs, saving
// (round trip, rebased paths, failures that lose nothing), autosave and recovery, recent files.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/atomic_file.h"
#include "instancer/instantiator.h"
#include "particles/particle_json.h"
#include "scene/document.h"
#include "scene/edit_commands.h"
#include "scene/live_instancer.h"
#include "scene/project.h"
#include "scene_test_util.h"

namespace ug {
namespace {

namespace fs = std::filesystem;
using test::samePrimitive;
using test::sameValues;

// Every test's own folder.
class TempDir : public test::TempDir {
public:
    TempDir() : test::TempDir("ug_document_test_") {}
};

// Two types: rocks with a Blend root (one editable point) and pebbles whose root is an intersection
// (wrapped on the first edit). `models_dir` is how the file names the models folder (absolute or relative).
std::string projectJson(const std::string& models_dir, bool with_extent = true) {
    std::string j = R"({"format": "undergrowth-project", "format_version": 2, "name": "doc_test",
 "ghost_tile": {"tile_size_m": 0.5, "delta_m": -0.002, "seed": 7},
 "terrain": {"procedural": {"origin": [-2, -2], "cell_size_m": 0.25, "width": 17, "height": 17, "seed": 3,
                            "octaves": 2, "amplitude_m": 0.15, "feature_size_m": 2}},
)";
    if (with_extent) j += R"( "extent": {"min": [-2, -2, -0.5], "max": [2, 2, 0.8]},
)";
    j += R"( "instantiation": {"seed": 1, "chunk_size_m": 8},
 "detail_types": [
  {"name": "rock", "model": {"mesh": ")" +
         models_dir + R"(/rock.glb"}, "candidates": {"count": 100, "scale": [0.8, 1.2]},
   "density": {"blend": [{"point": {"center": [0.5, 0.5, 0], "radius": 0.8, "weight": 0.8}}]},
   "instancing": {"strategy": "elevation"}},
  {"name": "pebble", "model": {"mesh": ")" +
         models_dir + R"(/pebble.glb"}, "candidates": {"count": 160, "scale": [0.8, 1.2]},
   "density": {"intersection": [{"terrain_layer": {"thickness": 0.05, "radius": 0.1}},
                                {"point": {"center": [-0.5, -0.5, 0], "radius": 1.0, "weight": 0.7}}]}}]})";
    return j;
}

std::string modelsDir() { return (fs::path(UG_SOURCE_DIR) / "assets" / "models").string(); }

std::string writeProject(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
    return path.string();
}

DocumentOptions optionsFor(const TempDir& dir) {
    return DocumentOptions{.cache_dir = (dir.path() / "cache").string(),
                           .config_dir = (dir.path() / "config").string(),
                           .threads = 2,
                           .autosave_interval_s = 10.0};
}

std::unique_ptr<Document> openDoc(const std::string& path, const DocumentOptions& options) {
    std::string error;
    std::unique_ptr<Document> doc = Document::open(path, options, &error);
    EXPECT_TRUE(doc) << error;
    return doc;
}

// A fresh, independent full run of what the document holds now.
InstanceStore fullRun(const Document& doc) {
    InstancerInput in = doc.instancerInput();
    if (in.extent.empty()) return InstanceStore();
    Instantiator inst;
    std::string error;
    EXPECT_TRUE(inst.setInput(in, &error)) << error;
    EXPECT_TRUE(inst.instantiateAll({.threads = 2}, nullptr, &error)) << error;
    return inst.store();
}

InstanceStore liveStore(Document& doc) {
    const LiveResult r = doc.waitForResult();
    EXPECT_TRUE(r.ok) << r.error;
    return *r.store;
}

// The live result is the same as a fresh full run, and returns it.
InstanceStore settled(Document& doc) {
    const InstanceStore live = liveStore(doc);
    EXPECT_TRUE(live == fullRun(doc)) << "live result differs from a full run";
    return live;
}

Bounds sceneBox() { return Bounds{glm::vec3(-2.0f, -2.0f, -0.5f), glm::vec3(2.0f, 2.0f, 0.8f)}; }

// ---- editable density ----------------------------------------------------------------------------------------

TEST(DocumentCommand, AddMoveRemoveDuplicateEditTheField) {
    TempDir dir;
    auto doc = openDoc(writeProject(dir.path() / "scene.json", projectJson(modelsDir())), optionsFor(dir));
    ASSERT_TRUE(doc);
    std::string error;
    ASSERT_EQ(doc->primitiveIds(0).size(), 1u);  // the file's point is editable
    EXPECT_TRUE(doc->primitiveIds(1).empty());   // an intersection root: nothing editable yet
    const uint64_t file_point = doc->primitiveIds(0)[0];
    Primitive p;
    size_t type = 9;
    ASSERT_TRUE(doc->findPrimitive(file_point, &type, &p));
    EXPECT_EQ(type, 0u);
    EXPECT_TRUE(samePrimitive(p, makePoint({0.5f, 0.5f, 0.0f}, 0.8f, 0.8f)));

    const Primitive a = makePoint({-1.0f, 1.0f, 0.0f}, 0.5f, 0.9f);
    const uint64_t id_a = doc->addPrimitive(0, a, &error);
    ASSERT_NE(id_a, 0u) << error;
    const Primitive b = makeSegment({1.0f, -1.0f, 0.0f}, {1.5f, -0.5f, 0.1f}, 0.3f, 0.7f);
    const uint64_t id_b = doc->addPrimitive(0, b, &error);
    ASSERT_NE(id_b, 0u) << error;
    EXPECT_EQ(doc->primitiveIds(0), (std::vector<uint64_t>{file_point, id_a, id_b}));
    EXPECT_TRUE(sameValues(doc->project().detail_types[0].density,
                           makeBlendField({makePoint({0.5f, 0.5f, 0.0f}, 0.8f, 0.8f), a, b}), sceneBox(), 100));

    // Move and resize a: same id, same place in the blend.
    const Primitive a2 = makePoint({-0.8f, 1.2f, 0.05f}, 0.6f, 1.1f);
    ASSERT_TRUE(doc->setPrimitive(id_a, a2, &error)) << error;
    EXPECT_EQ(doc->primitiveIds(0), (std::vector<uint64_t>{file_point, id_a, id_b}));
    ASSERT_TRUE(doc->findPrimitive(id_a, &type, &p));
    EXPECT_TRUE(samePrimitive(p, a2));

    // Duplicate b, moved: a new id at the end, moved skeleton.
    const uint64_t id_c = doc->duplicatePrimitive(id_b, {0.0f, 0.5f, 0.0f}, &error);
    ASSERT_NE(id_c, 0u) << error;
    ASSERT_TRUE(doc->findPrimitive(id_c, &type, &p));
    Primitive c = b;
    c.center_m += glm::vec3(0.0f, 0.5f, 0.0f);
    c.end_m += glm::vec3(0.0f, 0.5f, 0.0f);
    EXPECT_TRUE(samePrimitive(p, c));

    ASSERT_TRUE(doc->removePrimitive(id_b, &error)) << error;
    EXPECT_EQ(doc->primitiveIds(0), (std::vector<uint64_t>{file_point, id_a, id_c}));
    EXPECT_FALSE(doc->findPrimitive(id_b, nullptr, nullptr));
    EXPECT_TRUE(sameValues(doc->project().detail_types[0].density,
                           makeBlendField({makePoint({0.5f, 0.5f, 0.0f}, 0.8f, 0.8f), a2, c}), sceneBox(), 100));

    // The intersection root is wrapped: Blend(old tree, new primitive), the old tree locked.
    const DensityField old_pebble = doc->project().detail_types[1].density;
    const Primitive d = makePoint({-0.5f, 0.5f, 0.0f}, 0.4f, 0.5f);
    const uint64_t id_d = doc->addPrimitive(1, d, &error);
    ASSERT_NE(id_d, 0u) << error;
    EXPECT_EQ(doc->primitiveIds(1), std::vector<uint64_t>{id_d});
    const DensityField& pebble = doc->project().detail_types[1].density;
    ASSERT_EQ(pebble.nodes[pebble.root].op, FieldOp::Blend);
    EXPECT_EQ(pebble.nodes[pebble.root].child_count, 2u);
    // Terrain primitives need the terrain attached to evaluate: compare the compiled fields instead.
    DensityField wrapped_ref = old_pebble;
    const uint32_t old_root = wrapped_ref.root;
    const uint32_t prim_ref = primitiveChild(addPrimitive(&wrapped_ref, d));
    const uint32_t kids[2] = {nodeChild(old_root), prim_ref};
    wrapped_ref.root = addNode(&wrapped_ref, FieldOp::Blend, kids);
    Project ref_project = doc->project();
    ref_project.detail_types[1].density = wrapped_ref;
    InstanceTypeSettings ref_settings;
    ASSERT_TRUE(compileDetailType(ref_project, 1, doc->terrain(), &ref_settings, &error)) << error;
    EXPECT_TRUE(sameValues(*doc->compiled().types[1].field, *ref_settings.field, sceneBox(), 20));

    // Errors name the reason and change nothing.
    EXPECT_FALSE(doc->setPrimitive(id_b, a, &error));
    EXPECT_NE(error.find("no primitive with id " + std::to_string(id_b)), std::string::npos) << error;
    EXPECT_EQ(doc->addPrimitive(0, makePoint({0, 0, 0}, -1.0f), &error), 0u);
    EXPECT_NE(error.find("detail type 'rock': primitive 0 (point): radius_m"), std::string::npos) << error;
    EXPECT_EQ(doc->addPrimitive(5, a, &error), 0u);
    EXPECT_NE(error.find("no detail type 5"), std::string::npos) << error;
    EXPECT_EQ(doc->primitiveIds(0), (std::vector<uint64_t>{file_point, id_a, id_c}));
    settled(*doc);
}

TEST(DocumentCommand, RemovingNeverGrowsTheFieldAndUndoGivesTheSameValues) {
    TempDir dir;
    auto doc = openDoc(writeProject(dir.path() / "scene.json", projectJson(modelsDir())), optionsFor(dir));
    ASSERT_TRUE(doc);
    std::string error;
    std::vector<uint64_t> ids;
    doc->beginStroke("Paint");
    for (int k = 0; k < 150; ++k)
        ids.push_back(doc->addPrimitive(0, makePoint({-1.5f + 0.02f * k, 0.3f * std::sin(k * 0.3f), 0.0f}, 0.2f, 0.5f),
                                        &error));
    doc->endStroke();
    const DensityField full = doc->project().detail_types[0].density;
    // Remove them in a scattered order, many more than the compaction threshold.
    doc->beginStroke("Erase");
    for (int k = 0; k < 150; k += 2) ASSERT_TRUE(doc->removePrimitive(ids[size_t(k)], &error)) << error;
    for (int k = 149; k > 0; k -= 2) ASSERT_TRUE(doc->removePrimitive(ids[size_t(k)], &error)) << error;
    doc->endStroke();
    const DensityField& erased = doc->project().detail_types[0].density;
    EXPECT_LE(erased.primitives.size(), 1u + kMinOrphansBeforeCompaction + 1u) << "removed primitives pile up";
    EXPECT_EQ(doc->primitiveIds(0).size(), 1u);
    // Undo the erase: the same values at every point, bit for bit (the order in the blend came back).
    ASSERT_TRUE(doc->undo());
    EXPECT_TRUE(sameValues(doc->project().detail_types[0].density, full, sceneBox(), 100));
    for (size_t k = 0; k < ids.size(); ++k) EXPECT_EQ(doc->primitiveIds(0)[k + 1], ids[k]);
    settled(*doc);
}

// ---- undo / redo -----------------------------------------------------------------------------------------------

TEST(DocumentCommand, UndoAndRedoGiveBackTheExactInstanceSets) {
    TempDir dir;
    auto doc = openDoc(writeProject(dir.path() / "scene.json", projectJson(modelsDir())), optionsFor(dir));
    ASSERT_TRUE(doc);
    std::string error;
    std::vector<InstanceStore> states{settled(*doc)};
    EXPECT_GT(states[0].instanceCount(), 20u);
    EXPECT_FALSE(doc->isDirty());
    const uint64_t id = doc->addPrimitive(0, makePoint({-1.0f, -1.0f, 0.1f}, 0.6f, 1.0f), &error);
    ASSERT_NE(id, 0u) << error;
    states.push_back(settled(*doc));
    ASSERT_TRUE(doc->setPrimitive(id, makePoint({-0.7f, -0.9f, 0.1f}, 0.7f, 1.2f), &error)) << error;
    states.push_back(settled(*doc));
    const uint64_t file_point = doc->primitiveIds(0)[0];
    ASSERT_TRUE(doc->removePrimitive(file_point, &error)) << error;  // the file's own primitive
    states.push_back(settled(*doc));
    ASSERT_NE(doc->duplicatePrimitive(id, {1.5f, 1.5f, 0.0f}, &error), 0u) << error;
    states.push_back(settled(*doc));
    ASSERT_NE(doc->addPrimitive(1, makePoint({0.8f, -0.8f, 0.0f}, 0.7f, 0.9f), &error), 0u) << error;  // wraps
    states.push_back(settled(*doc));
    for (size_t k = 1; k < states.size(); ++k) EXPECT_FALSE(states[k] == states[k - 1]) << "edit " << k << " changed nothing";
    EXPECT_TRUE(doc->isDirty());

    for (size_t k = states.size() - 1; k-- > 0;) {
        ASSERT_TRUE(doc->undo());
        EXPECT_TRUE(settled(*doc) == states[k]) << "undo to state " << k;
    }
    EXPECT_FALSE(doc->canUndo());
    EXPECT_FALSE(doc->isDirty()) << "undoing back to the opened state is clean";
    for (size_t k = 1; k < states.size(); ++k) {
        ASSERT_TRUE(doc->redo());
        EXPECT_TRUE(settled(*doc) == states[k]) << "redo to state " << k;
    }
    EXPECT_FALSE(doc->canRedo());
    // A new edit after an undo drops the redo steps.
    ASSERT_TRUE(doc->undo());
    ASSERT_TRUE(doc->setSeed(3, &error)) << error;
    EXPECT_FALSE(doc->canRedo());
}

// A brush stroke is one unit (issue 9): its primitives share a tag (Primitive::stroke), and moving,
// re-weighting, duplicating and deleting them together is one undo step each, exact, and saved.
TEST(DocumentCommand, AStrokesPrimitivesAreMovedDuplicatedAndDeletedAsOneUndoStepAndKeepTheirTagSaved) {
    TempDir dir;
    const fs::path path = dir.path() / "scene.json";
    auto doc = openDoc(writeProject(path, projectJson(modelsDir())), optionsFor(dir));
    ASSERT_TRUE(doc);
    std::string error;
    const uint64_t file_point = doc->primitiveIds(0)[0];
    EXPECT_EQ(doc->strokeMembers(file_point), std::vector<uint64_t>{file_point});  // untagged: alone
    EXPECT_TRUE(doc->strokeMembers(987654).empty());
    const uint32_t tag = doc->newStrokeTag();
    EXPECT_EQ(tag, 1u);
    // A stroke over two types (a paint stroke mixing rock and pebble), and a lone primitive.
    std::vector<Primitive> prims;
    for (int k = 0; k < 4; ++k) {
        Primitive p = makeCone({-1.2f + 0.6f * k, -0.5f, 0.0f}, 0.5f, {-1.2f + 0.6f * k, -0.5f, 0.4f}, 0.2f, 2.0f);
        p.stroke = tag;
        prims.push_back(p);
    }
    doc->beginStroke("Sculpt");
    std::vector<uint64_t> ids;
    for (size_t k = 0; k < prims.size(); ++k) ids.push_back(doc->addPrimitive(k < 3 ? 0 : 1, prims[k], &error));
    doc->endStroke();
    for (uint64_t id : ids) ASSERT_NE(id, 0u) << error;
    const uint64_t lone = doc->addPrimitive(0, makePoint({1.0f, 1.0f, 0.0f}, 0.4f, 1.0f), &error);
    ASSERT_NE(lone, 0u) << error;
    EXPECT_EQ(doc->newStrokeTag(), tag + 1);
    EXPECT_EQ(doc->strokeMembers(ids[2]), ids);  // any member names the whole stroke, across types
    EXPECT_EQ(doc->strokeMembers(lone), std::vector<uint64_t>{lone});
    const InstanceStore made = settled(*doc);

    // Moved together: one undo step.
    std::vector<std::pair<uint64_t, Primitive>> moved;
    for (size_t k = 0; k < ids.size(); ++k) moved.emplace_back(ids[k], translatedPrimitive(prims[k], {0.3f, 0.2f, 0.0f}));
    ASSERT_TRUE(doc->setPrimitives(moved, "Move stroke", &error)) << error;
    EXPECT_EQ(doc->undoName(), "Move stroke");
    for (size_t k = 0; k < ids.size(); ++k) {
        Primitive p;
        ASSERT_TRUE(doc->findPrimitive(ids[k], nullptr, &p));
        EXPECT_TRUE(samePrimitive(p, moved[k].second)) << k;
    }
    const InstanceStore after_move = settled(*doc);
    EXPECT_FALSE(after_move == made);
    // All or nothing: an unknown id among the edits refuses the whole batch.
    std::vector<std::pair<uint64_t, Primitive>> bad = moved;
    bad[0].second = translatedPrimitive(prims[0], {5.0f, 0.0f, 0.0f});
    bad.emplace_back(987654, prims[0]);
    EXPECT_FALSE(doc->setPrimitives(bad, "Move stroke", &error));
    EXPECT_NE(error.find("987654"), std::string::npos) << error;
    Primitive still;
    ASSERT_TRUE(doc->findPrimitive(ids[0], nullptr, &still));
    EXPECT_TRUE(samePrimitive(still, moved[0].second));

    // Duplicated: the copies are a new stroke of their own, the original untouched.
    const std::vector<uint64_t> copies = doc->duplicatePrimitives(ids, {0.0f, 1.0f, 0.0f}, &error);
    ASSERT_EQ(copies.size(), ids.size()) << error;
    EXPECT_EQ(doc->strokeMembers(copies[1]), copies);
    EXPECT_EQ(doc->strokeMembers(ids[1]), ids);
    Primitive copy;
    ASSERT_TRUE(doc->findPrimitive(copies[0], nullptr, &copy));
    EXPECT_EQ(copy.stroke, tag + 1);
    // A lone duplicate of a member joins no stroke.
    const uint64_t single = doc->duplicatePrimitive(ids[0], {0.0f, -1.0f, 0.0f}, &error);
    ASSERT_NE(single, 0u) << error;
    EXPECT_EQ(doc->strokeMembers(single), std::vector<uint64_t>{single});

    // Saved and reopened: the tags come back with the primitives, so the strokes are units again.
    ASSERT_TRUE(doc->save(&error)) << error;
    {
        auto reopened = openDoc(path.string(), optionsFor(dir));
        ASSERT_TRUE(reopened);
        size_t tagged = 0;
        for (size_t t = 0; t < 2; ++t)
            for (uint64_t id : reopened->primitiveIds(t)) {
                Primitive p;
                ASSERT_TRUE(reopened->findPrimitive(id, nullptr, &p));
                if (p.stroke == tag) {
                    ++tagged;
                    EXPECT_EQ(reopened->strokeMembers(id).size(), ids.size());
                }
            }
        EXPECT_EQ(tagged, ids.size());
        EXPECT_TRUE(liveStore(*reopened) == settled(*doc));
    }

    // Deleted together: one undo step, which gives back the exact set.
    const InstanceStore before_delete = settled(*doc);
    ASSERT_TRUE(doc->removePrimitives(doc->strokeMembers(ids[3]), "Delete stroke", &error)) << error;
    for (uint64_t id : ids) EXPECT_FALSE(doc->findPrimitive(id, nullptr, nullptr));
    EXPECT_TRUE(doc->findPrimitive(lone, nullptr, nullptr));
    EXPECT_FALSE(settled(*doc) == before_delete);
    ASSERT_TRUE(doc->undo());
    EXPECT_TRUE(settled(*doc) == before_delete);
    EXPECT_EQ(doc->strokeMembers(ids[0]), ids);
}

TEST(DocumentCommand, AStrokeOfTwentyStampsIsOneUndoStep) {
    TempDir dir;
    auto doc = openDoc(writeProject(dir.path() / "scene.json", projectJson(modelsDir())), optionsFor(dir));
    ASSERT_TRUE(doc);
    std::string error;
    const InstanceStore before = settled(*doc);
    doc->beginStroke("Paint");
    for (int k = 0; k < 20; ++k) {
        ASSERT_NE(doc->addPrimitive(1, makePoint({-1.6f + 0.16f * k, 1.2f, 0.0f}, 0.35f, 0.8f), &error), 0u) << error;
        EXPECT_EQ(doc->undoName(), "Paint");
    }
    doc->endStroke();
    const InstanceStore after = settled(*doc);
    EXPECT_GT(after.instanceCount(), before.instanceCount());
    EXPECT_EQ(doc->undoName(), "Paint");
    ASSERT_TRUE(doc->undo());
    EXPECT_TRUE(settled(*doc) == before);
    EXPECT_FALSE(doc->canUndo()) << "the stroke was more than one step";
    EXPECT_EQ(doc->primitiveIds(1).size(), 0u);
    ASSERT_TRUE(doc->redo());
    EXPECT_TRUE(settled(*doc) == after);
    EXPECT_EQ(doc->primitiveIds(1).size(), 20u);
    // Undo in the middle of a stroke ends it and undoes all of it.
    doc->beginStroke("Sculpt");
    for (int k = 0; k < 5; ++k) doc->addPrimitive(0, makePoint({0.2f * k, -1.0f, 0.1f}, 0.3f, 0.8f), &error);
    ASSERT_TRUE(doc->undo());
    EXPECT_FALSE(doc->inStroke());
    EXPECT_TRUE(settled(*doc) == after);
    // An empty stroke leaves no step.
    doc->beginStroke();
    doc->endStroke();
    EXPECT_EQ(doc->undoName(), "Paint");
}

TEST(DocumentCommand, SettingsEditsInstantiateEverythingAgain) {
    TempDir dir;
    auto doc = openDoc(writeProject(dir.path() / "scene.json", projectJson(modelsDir())), optionsFor(dir));
    ASSERT_TRUE(doc);
    std::string error;
    const InstanceStore s0 = settled(*doc);
    ASSERT_TRUE(doc->setSeed(99, &error)) << error;
    const InstanceStore s1 = settled(*doc);
    EXPECT_FALSE(s1 == s0);
    InstancingDesc desc = doc->project().detail_types[0].instancing;
    desc.strategy = PriorityStrategy::Random;
    ASSERT_TRUE(doc->setInstancing(0, desc, &error)) << error;
    const InstanceStore s2 = settled(*doc);
    EXPECT_FALSE(s2 == s1);
    // Settings that do not compile are refused and change nothing.
    InstancingDesc bad = desc;
    bad.layer_m = -1.0f;
    EXPECT_FALSE(doc->setInstancing(0, bad, &error));
    EXPECT_NE(error.find("/detail_types/0/instancing/layer_m"), std::string::npos) << error;
    EXPECT_EQ(doc->project().detail_types[0].instancing.layer_m, desc.layer_m);
    EXPECT_EQ(doc->undoName(), "Instancing settings");
    ASSERT_TRUE(doc->undo());
    EXPECT_TRUE(settled(*doc) == s1);
    ASSERT_TRUE(doc->undo());
    EXPECT_TRUE(settled(*doc) == s0);
    EXPECT_EQ(doc->project().instantiation_seed, 1u);
}

// ---- the live instancer ----------------------------------------------------------------------------------------

// What a renderer keeps: per tile, its ids, refreshed only for the tiles a poll says changed.
struct TileMirror {
    std::map<uint64_t, std::vector<uint32_t>> tiles;
    void apply(const LiveResult& r) {
        for (uint64_t key : r.changed_tiles) {
            const int64_t t = r.store->findTile(key);
            if (t < 0) {
                tiles.erase(key);
            } else {
                std::vector<uint32_t> ids;
                r.store->tileIds(size_t(t), &ids);
                tiles[key] = ids;
            }
        }
    }
    bool matches(const InstanceStore& store) const {
        std::map<uint64_t, std::vector<uint32_t>> want;
        for (size_t t = 0; t < store.tileCount(); ++t) store.tileIds(t, &want[store.tileKey(t)]);
        return want == tiles;
    }
};

TEST(LiveInstancer, ABurstOfCoalescedEditsEndsEqualToAFullRun) {
    TempDir dir;
    auto doc = openDoc(writeProject(dir.path() / "scene.json", projectJson(modelsDir())), optionsFor(dir));
    ASSERT_TRUE(doc);
    std::string error;
    TileMirror mirror;
    LiveResult r;
    doc->live().waitIdle();
    ASSERT_TRUE(doc->live().poll(&r));
    EXPECT_TRUE(r.full);
    mirror.apply(r);
    EXPECT_TRUE(mirror.matches(*r.store));

    // A stroke faster than the worker: stamps, moves and erasures, with a frame's poll now and then.
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(-1.6f, 1.6f);
    std::vector<uint64_t> ids;
    int polls = 0;
    doc->beginStroke("Sculpt");
    for (int k = 0; k < 60; ++k) {
        const size_t type = size_t(k % 2);
        if (k % 7 == 6 && !ids.empty()) {
            ASSERT_TRUE(doc->removePrimitive(ids.back(), &error)) << error;
            ids.pop_back();
        } else if (k % 5 == 4 && !ids.empty()) {
            ASSERT_TRUE(doc->setPrimitive(ids[0], makePoint({u(rng), u(rng), 0.1f}, 0.4f, 0.9f), &error)) << error;
        } else {
            ids.push_back(doc->addPrimitive(type, makePoint({u(rng), u(rng), 0.0f}, 0.3f, 0.8f), &error));
            ASSERT_NE(ids.back(), 0u) << error;
        }
        if (k % 10 == 0 && doc->live().poll(&r)) {
            ++polls;
            mirror.apply(r);
        }
    }
    doc->endStroke();
    const uint64_t last = doc->live().generation();
    doc->live().waitIdle();
    EXPECT_FALSE(doc->live().pending());
    ASSERT_TRUE(doc->live().poll(&r));
    EXPECT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.generation, last);
    mirror.apply(r);
    EXPECT_GT(r.store->instanceCount(), 50u);
    EXPECT_TRUE(*r.store == fullRun(*doc)) << "the coalesced result is not the final document's";
    EXPECT_TRUE(mirror.matches(*r.store)) << "a tile that changed was not reported";
    EXPECT_FALSE(doc->live().poll(&r)) << "nothing new since the last poll";
}

TEST(LiveInstancer, ANewResetCancelsTheStaleFullRunAndTheResultIsTheNewest) {
    TempDir dir;
    auto doc = openDoc(writeProject(dir.path() / "scene.json", projectJson(modelsDir())), optionsFor(dir));
    ASSERT_TRUE(doc);
    doc->live().waitIdle();
    LiveInstancer live(2);
    InstancerInput in = doc->instancerInput();
    uint64_t gen = 0;
    for (uint64_t seed = 1; seed <= 8; ++seed) {
        in.seed = seed;
        gen = live.reset(in);
    }
    // An edit on top of the pending reset joins it.
    InstancerInput edited = in;
    edited.types[0].field = std::make_shared<const DensityField>(makeBlendField({makePoint({0, 0, 0.2f}, 0.9f)}));
    gen = live.submit(edited.types, {Bounds::everything()});
    live.waitIdle();
    LiveResult r;
    ASSERT_TRUE(live.poll(&r));
    EXPECT_EQ(r.generation, gen);
    EXPECT_TRUE(r.full);
    Instantiator inst;
    std::string error;
    ASSERT_TRUE(inst.setInput(edited, &error)) << error;
    ASSERT_TRUE(inst.instantiateAll({.threads = 2}, nullptr, &error)) << error;
    EXPECT_TRUE(*r.store == inst.store());
    // An input that cannot be instantiated reports why and keeps the last good store.
    InstancerInput bad = edited;
    bad.types[0].layer_m = -1.0f;
    live.reset(bad);
    live.waitIdle();
    ASSERT_TRUE(live.poll(&r));
    EXPECT_FALSE(r.ok);
    EXPECT_FALSE(r.error.empty());
    EXPECT_TRUE(*r.store == inst.store());
}

TEST(LiveInstancer, StopsCleanlyWhileWorking) {
    TempDir dir;
    auto doc = openDoc(writeProject(dir.path() / "scene.json", projectJson(modelsDir())), optionsFor(dir));
    ASSERT_TRUE(doc);
    doc->live().waitIdle();
    const InstancerInput in = doc->instancerInput();
    for (int k = 0; k < 10; ++k) {
        LiveInstancer live(2);
        live.reset(in);
        if (k % 2) live.submit(in.types, {sceneBox()});
        LiveResult r;
        live.poll(&r);
        // Destroyed with a run queued or in progress: cancels, joins, never publishes into freed memory.
    }
    LiveInstancer idle(1);  // never given work
    EXPECT_FALSE(idle.pending());
    EXPECT_EQ(idle.submit(in.types, {}), 0u) << "an edit before any input is ignored";
    EXPECT_FALSE(idle.pending());
    idle.waitIdle();
    EXPECT_EQ(idle.latest().store->instanceCount(), 0u);
}

TEST(LiveInstancer, PollNeverBlocksWhileTheWorkerRuns) {
    TempDir dir;
    auto doc = openDoc(writeProject(dir.path() / "scene.json", projectJson(modelsDir())), optionsFor(dir));
    ASSERT_TRUE(doc);
    std::string error;
    doc->live().waitIdle();
    LiveResult r;
    doc->live().poll(&r);
    ASSERT_TRUE(doc->setSeed(7, &error));
    // The UI's calls return while a run is in progress: a poll that finds nothing is followed by a run
    // still pending (a poll that waited for the run would always come back with its result). No clock: the
    // full run takes thousands of these calls' time.
    bool answered_while_running = false;
    uint64_t polls = 0;
    while (doc->live().pending()) {
        ++polls;
        if (!doc->live().poll(&r) && doc->live().pending()) answered_while_running = true;
    }
    EXPECT_TRUE(answered_while_running) << polls << " polls";
    settled(*doc);
}

// The frame's bounded wait for its own edit: woken by the result, or back at the end of its budget with
// the work still going (the result comes by a later poll).
TEST(LiveInstancer, ATimedWaitReturnsOnceTheResultIsPublished) {
    TempDir dir;
    auto doc = openDoc(writeProject(dir.path() / "scene.json", projectJson(modelsDir())), optionsFor(dir));
    ASSERT_TRUE(doc);
    doc->live().waitIdle();
    EXPECT_TRUE(doc->live().waitIdleFor(std::chrono::milliseconds(0))) << "idle: nothing to wait for";
    LiveResult r;
    doc->live().poll(&r);
    std::string error;
    ASSERT_TRUE(doc->setSeed(7, &error)) << error;
    const uint64_t gen = doc->live().generation();
    // Not a time limit on the run: a bound far past any run (a missed wake-up would hold the test there).
    ASSERT_TRUE(doc->live().waitIdleFor(std::chrono::minutes(10)));
    EXPECT_FALSE(doc->live().pending());
    ASSERT_TRUE(doc->live().poll(&r));
    EXPECT_EQ(r.generation, gen);
    EXPECT_TRUE(*r.store == fullRun(*doc));
}

// ---- files -------------------------------------------------------------------------------------------------

TEST(Document, SaveAsAndReopenGiveTheSameInstancesWithPathsRebased) {
    TempDir dir;
    // The models named relative to the project's folder, so a save elsewhere must rewrite them.
    const fs::path a = dir.path() / "a" / "scene.json";
    const std::string rel = fs::path(modelsDir()).lexically_relative(fs::absolute(a.parent_path())).string();
    auto doc = openDoc(writeProject(a, projectJson(rel)), optionsFor(dir));
    ASSERT_TRUE(doc);
    std::string error;
    doc->beginStroke();
    for (int k = 0; k < 8; ++k) doc->addPrimitive(1, makeSegment({-1.5f, -1.0f + 0.3f * k, 0}, {1.5f, -1.0f + 0.3f * k, 0.1f}, 0.2f, 0.6f), &error);
    doc->endStroke();
    ASSERT_TRUE(doc->setPrimitive(doc->primitiveIds(0)[0], makeCone({0, 0, 0}, 0.5f, {0.5f, 0.5f, 0.4f}, 0.2f, 1.0f), &error));
    const InstanceStore edited = settled(*doc);
    EXPECT_TRUE(doc->isDirty());
    const fs::path b = dir.path() / "b" / "deeper" / "copy.json";
    fs::create_directories(b.parent_path());
    ASSERT_TRUE(doc->saveAs(b.string(), &error)) << error;
    EXPECT_FALSE(doc->isDirty());
    EXPECT_EQ(doc->path(), b.string());
    auto reopened = openDoc(b.string(), optionsFor(dir));
    ASSERT_TRUE(reopened);
    EXPECT_EQ(reopened->cacheOutcome(), CacheOutcome::Loaded);
    EXPECT_TRUE(liveStore(*reopened) == edited);
    EXPECT_EQ(reopened->primitiveIds(1).size(), 8u);  // the 8 stamps; the wrapped tree stays locked
    // The original file is as it was.
    auto original = openDoc(a.string(), optionsFor(dir));
    ASSERT_TRUE(original);
    EXPECT_EQ(original->primitiveIds(1).size(), 0u);
    // Save (same folder) after another edit, reopen: the same again.
    ASSERT_TRUE(doc->addPrimitive(0, makePoint({-1, 1, 0}, 0.5f), &error));
    EXPECT_TRUE(doc->isDirty());
    ASSERT_TRUE(doc->save(&error)) << error;
    EXPECT_FALSE(doc->isDirty());
    auto again = openDoc(b.string(), optionsFor(dir));
    ASSERT_TRUE(again);
    EXPECT_TRUE(liveStore(*again) == settled(*doc));
}

TEST(Document, SaveAsElsewhereKeepsTheParticleSystemsFound) {
    // A particle file named relative to the project; after a Save As into another folder and a plain Save
    // there, the reopened project still finds it (and grows it on the terrain).
    TempDir dir;
    const fs::path a = dir.path() / "a" / "scene.json";
    fs::create_directories(dir.path() / "particles");
    std::ofstream(dir.path() / "particles" / "grass.json") << R"({"format": "undergrowth-particles",
      "format_version": 1, "generators": [{"kind": "rectangle", "axis_u_m": [0.3, 0, 0], "axis_v_m": [0, 0.3, 0],
      "count": 30, "on_terrain": true}], "walk": {"steps": 4, "step_length_m": 0.01, "strand_radius_m": 0.001}})";
    std::string text = projectJson(modelsDir());
    text.replace(text.find("\"format_version\": 2"), 19, "\"format_version\": 4");
    text.insert(text.rfind('}'), R"(, "particles": [{"file": "../particles/grass.json", "offset_m": [0.5, 0, 0]}])");
    auto doc = openDoc(writeProject(a, text), optionsFor(dir));
    ASSERT_TRUE(doc);
    ASSERT_EQ(doc->particles()->size(), 1u);
    EXPECT_EQ((*doc->particles())[0].name, "grass");
    EXPECT_NE((*doc->particles())[0].scene.terrain, nullptr);
    const fs::path b = dir.path() / "b" / "deeper" / "copy.json";
    fs::create_directories(b.parent_path());
    std::string error;
    ASSERT_TRUE(doc->saveAs(b.string(), &error)) << error;
    ASSERT_TRUE(doc->save(&error)) << error;
    EXPECT_EQ(doc->project().particles[0].file, "../../particles/grass.json");
    auto reopened = openDoc(b.string(), optionsFor(dir));
    ASSERT_TRUE(reopened);
    ASSERT_EQ(reopened->particles()->size(), 1u);
    EXPECT_EQ((*reopened->particles())[0].scene.generators[0].center_m, glm::vec3(0.5f, 0.0f, 0.0f));
}

TEST(Document, ParticleEditsAreUndoableSharedByTheFileAndSavedToIt) {
    // One particle file placed twice (the second 1 m along x, renamed): moving an attractor of the first
    // moves the second's by the same amount at its own offset; undo and redo give each state back; Save
    // writes the file under its own name and offsets, and a reopened project reads the edit back.
    TempDir dir;
    const fs::path a = dir.path() / "scene.json";
    const fs::path grass = dir.path() / "grass.json";
    std::ofstream(grass) << R"({"format": "undergrowth-particles", "format_version": 1, "name": "grass",
      "generators": [{"kind": "rectangle", "axis_u_m": [0.3, 0, 0], "axis_v_m": [0, 0.3, 0], "count": 30}],
      "attractors": [{"kind": "point", "a_m": [0, 0, 1], "influence_m": 0.5, "charge": 1}],
      "walk": {"steps": 4, "step_length_m": 0.01, "strand_radius_m": 0.001}})";
    std::string text = projectJson(modelsDir());
    text.replace(text.find("\"format_version\": 2"), 19, "\"format_version\": 4");
    text.insert(text.rfind('}'), R"(, "particles": [{"file": "grass.json"},
        {"file": "grass.json", "name": "grass_east", "offset_m": [1, 0, 0]}])");
    auto doc = openDoc(writeProject(a, text), optionsFor(dir));
    ASSERT_TRUE(doc);
    ASSERT_EQ(doc->particles()->size(), 2u);
    const uint64_t generation = doc->particlesGeneration();
    std::string error;
    ParticleSystemFile edited = (*doc->particles())[0];
    edited.scene.attractors[0].a_m = {0.25f, 0.0f, 0.75f};
    ASSERT_TRUE(doc->setParticleSystem(0, edited, &error)) << error;
    EXPECT_NE(doc->particlesGeneration(), generation);
    EXPECT_TRUE(doc->isDirty());
    EXPECT_EQ(doc->undoName(), "Edit particles");
    EXPECT_EQ((*doc->particles())[0].scene.attractors[0].a_m, glm::vec3(0.25f, 0.0f, 0.75f));
    EXPECT_EQ((*doc->particles())[1].scene.attractors[0].a_m, glm::vec3(1.25f, 0.0f, 0.75f));
    EXPECT_EQ((*doc->particles())[1].name, "grass_east");
    ASSERT_TRUE(doc->undo());
    EXPECT_EQ((*doc->particles())[0].scene.attractors[0].a_m, glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ((*doc->particles())[1].scene.attractors[0].a_m, glm::vec3(1.0f, 0.0f, 1.0f));
    EXPECT_FALSE(doc->isDirty());
    ASSERT_TRUE(doc->redo());
    // Bad input is refused naming the entry and the field, and changes nothing.
    ParticleSystemFile bad = edited;
    bad.scene.attractors[0].charge[0].charge = std::nanf("");
    EXPECT_FALSE(doc->setParticleSystem(1, bad, &error));
    EXPECT_NE(error.find("particles[1] (grass_east): attractors[0].charge[0].charge"), std::string::npos) << error;
    EXPECT_FALSE(doc->setParticleSystem(2, edited, &error));
    // A system without a generator would save a file that does not load: refused too.
    ParticleSystemFile bare = edited;
    bare.scene.generators.clear();
    EXPECT_FALSE(doc->setParticleSystem(0, bare, &error));
    EXPECT_NE(error.find("particles[0] (grass): generators: at least one"), std::string::npos) << error;
    EXPECT_EQ((*doc->particles())[0].scene.attractors[0].a_m, glm::vec3(0.25f, 0.0f, 0.75f));
    // Nothing lost in a crash: the autosave keeps the edited systems, and a recovery shows them (dirty).
    ASSERT_TRUE(doc->autosave(&error)) << error;
    {
        auto recovered = Document::recover(a.string(), optionsFor(dir), &error);
        ASSERT_TRUE(recovered) << error;
        EXPECT_TRUE(recovered->isDirty());
        ASSERT_EQ(recovered->particles()->size(), 2u);
        EXPECT_EQ((*recovered->particles())[0].scene.attractors[0].a_m, glm::vec3(0.25f, 0.0f, 0.75f));
        EXPECT_EQ((*recovered->particles())[1].scene.attractors[0].a_m, glm::vec3(1.25f, 0.0f, 0.75f));
        EXPECT_EQ((*recovered->particles())[1].name, "grass_east");
        EXPECT_NE((*recovered->particles())[1].scene.terrain, nullptr);
    }
    ASSERT_TRUE(doc->save(&error)) << error;
    EXPECT_FALSE(doc->isDirty());
    ParticleSystemFile on_disk;
    ASSERT_TRUE(loadParticleSystem(grass.string(), &on_disk, &error)) << error;
    EXPECT_EQ(on_disk.name, "grass");
    EXPECT_EQ(on_disk.scene.attractors[0].a_m, glm::vec3(0.25f, 0.0f, 0.75f));
    EXPECT_EQ(on_disk.scene.generators[0].center_m, glm::vec3(0.0f));
    auto reopened = openDoc(a.string(), optionsFor(dir));
    ASSERT_TRUE(reopened);
    EXPECT_EQ((*reopened->particles())[1].scene.attractors[0].a_m, glm::vec3(1.25f, 0.0f, 0.75f));
    // A save with no particle edit leaves the file alone.
    ASSERT_TRUE(doc->addPrimitive(0, makePoint({-1, 1, 0}, 0.5f), &error)) << error;
    fs::remove(grass);
    ASSERT_TRUE(doc->save(&error)) << error;
    EXPECT_FALSE(fs::exists(grass));
}

// A 0.6 m patch of 30 strands of 4 steps, named "grass", on the project's terrain when asked.
ParticleSystemFile smallGrass(bool on_terrain) {
    ParticleSystemFile grass;
    grass.name = "grass";
    ParticleGenerator g;
    g.axis_u_m = {0.3f, 0.0f, 0.0f};
    g.axis_v_m = {0.0f, 0.3f, 0.0f};
    g.count = 30;
    g.on_terrain = on_terrain;
    grass.scene.generators.push_back(g);
    grass.scene.walk.steps = 4;
    return grass;
}

TEST(Document, ANewParticleSystemIsAFileBesideTheProjectAndOneUndoStepAndRemovingItToo) {
    // A project without systems gets one: its file written at once under particles/, the project's list
    // naming it, one undo step; a second with the same name is renamed and filed apart; Save writes the
    // list and the edits, a reopened project grows both; an autosave recovered after a crash keeps them.
    TempDir dir;
    const fs::path a = dir.path() / "scene.json";
    auto doc = openDoc(writeProject(a, projectJson(modelsDir())), optionsFor(dir));
    ASSERT_TRUE(doc);
    ASSERT_TRUE(doc->particles()->empty());
    const ParticleSystemFile grass = smallGrass(true);
    const uint64_t generation = doc->particlesGeneration();
    std::string error;
    ASSERT_TRUE(doc->addParticleSystem(grass, &error)) << error;
    EXPECT_NE(doc->particlesGeneration(), generation);
    EXPECT_EQ(doc->undoName(), "Add particle system");
    ASSERT_EQ(doc->project().particles.size(), 1u);
    EXPECT_EQ(doc->project().particles[0].file, "particles/grass.json");
    ASSERT_EQ(doc->particles()->size(), 1u);
    EXPECT_NE((*doc->particles())[0].scene.terrain, nullptr);  // seeds on the project's ground
    ParticleSystemFile on_disk;
    ASSERT_TRUE(loadParticleSystem((dir.path() / "particles" / "grass.json").string(), &on_disk, &error)) << error;
    EXPECT_EQ(on_disk.name, "grass");
    EXPECT_EQ(on_disk.scene.generators, (*doc->particles())[0].scene.generators);
    // The same name again: renamed, in its own file.
    ASSERT_TRUE(doc->addParticleSystem(grass, &error)) << error;
    ASSERT_EQ(doc->particles()->size(), 2u);
    EXPECT_EQ((*doc->particles())[1].name, "grass_2");
    EXPECT_EQ(doc->project().particles[1].file, "particles/grass_2.json");
    // Undo takes the entry away (its file stays, unreferenced); redo brings it back.
    EXPECT_TRUE(doc->undoRevertsParticles(doc->particlesGeneration()));  // Cancel of its growth may undo it
    ASSERT_TRUE(doc->undo());
    EXPECT_EQ(doc->particles()->size(), 1u);
    EXPECT_EQ(doc->project().particles.size(), 1u);
    EXPECT_FALSE(doc->undoRevertsParticles(doc->particlesGeneration()));  // an undo's growth: not an edit
    ASSERT_TRUE(doc->redo());
    ASSERT_EQ(doc->particles()->size(), 2u);
    EXPECT_TRUE(doc->undoRevertsParticles(doc->particlesGeneration()));
    // A drag is one step: while it is open nothing is undone by a Cancel; once closed, the whole drag.
    doc->beginStroke("Move generator");
    ParticleSystemFile moved = (*doc->particles())[1];
    for (int k = 1; k <= 3; ++k) {
        moved.scene.generators[0].center_m.x = 0.1f * float(k);
        ASSERT_TRUE(doc->setParticleSystem(1, moved, &error)) << error;
    }
    EXPECT_FALSE(doc->undoRevertsParticles(doc->particlesGeneration()));
    doc->endStroke();
    EXPECT_TRUE(doc->undoRevertsParticles(doc->particlesGeneration()));
    ASSERT_TRUE(doc->undo());
    EXPECT_EQ((*doc->particles())[1].scene.generators[0].center_m.x, 0.0f);
    // Another kind of edit on top: a Cancel would undo it, so it is not the particles' edit.
    ASSERT_TRUE(doc->redo());
    ASSERT_TRUE(doc->addPrimitive(0, makePoint({-1, 1, 0}, 0.5f), &error)) << error;
    EXPECT_FALSE(doc->undoRevertsParticles(doc->particlesGeneration()));
    ASSERT_TRUE(doc->undo());
    ASSERT_TRUE(doc->undo());  // the drag again: back to the system as added
    // An invalid system is refused naming the field (a project never saved: below).
    ParticleSystemFile bad = grass;
    bad.scene.walk.trials = 0;
    EXPECT_FALSE(doc->addParticleSystem(bad, &error));
    EXPECT_NE(error.find("walk.trials"), std::string::npos) << error;
    EXPECT_EQ(doc->particles()->size(), 2u);
    // Edited, autosaved, recovered: the new systems and their edit are there.
    ParticleSystemFile edited = (*doc->particles())[1];
    edited.scene.generators[0].center_m = {0.5f, 0.0f, 0.0f};
    ASSERT_TRUE(doc->setParticleSystem(1, edited, &error)) << error;
    ASSERT_TRUE(doc->autosave(&error)) << error;
    {
        auto recovered = Document::recover(a.string(), optionsFor(dir), &error);
        ASSERT_TRUE(recovered) << error;
        ASSERT_EQ(recovered->particles()->size(), 2u);
        EXPECT_EQ((*recovered->particles())[1].scene.generators[0].center_m, glm::vec3(0.5f, 0.0f, 0.0f));
    }
    ASSERT_TRUE(doc->save(&error)) << error;
    auto reopened = openDoc(a.string(), optionsFor(dir));
    ASSERT_TRUE(reopened);
    ASSERT_EQ(reopened->particles()->size(), 2u);
    EXPECT_EQ((*reopened->particles())[1].name, "grass_2");
    EXPECT_EQ((*reopened->particles())[1].scene.generators[0].center_m, glm::vec3(0.5f, 0.0f, 0.0f));
    // Removing the first: one undo step that puts it back in its place; saved, the project names only the
    // second (the first's file stays on disk).
    ASSERT_TRUE(doc->removeParticleSystem(0, &error)) << error;
    EXPECT_EQ(doc->undoName(), "Remove particle system");
    ASSERT_EQ(doc->particles()->size(), 1u);
    EXPECT_EQ((*doc->particles())[0].name, "grass_2");
    ASSERT_TRUE(doc->undo());
    ASSERT_EQ(doc->particles()->size(), 2u);
    EXPECT_EQ((*doc->particles())[0].name, "grass");
    EXPECT_EQ(doc->project().particles[0].file, "particles/grass.json");
    ASSERT_TRUE(doc->redo());
    EXPECT_FALSE(doc->removeParticleSystem(1, &error));  // there is one left, at 0
    ASSERT_TRUE(doc->save(&error)) << error;
    auto pruned = openDoc(a.string(), optionsFor(dir));
    ASSERT_TRUE(pruned);
    ASSERT_EQ(pruned->particles()->size(), 1u);
    EXPECT_EQ((*pruned->particles())[0].name, "grass_2");
    EXPECT_TRUE(fs::exists(dir.path() / "particles" / "grass.json"));
}

TEST(Document, AParticleEntryIsRenamedAndMovedAsOneUndoStepAndSavedWithItsFileUnchanged) {
    TempDir dir;
    const fs::path a = dir.path() / "scene.json";
    auto doc = openDoc(writeProject(a, projectJson(modelsDir())), optionsFor(dir));
    ASSERT_TRUE(doc);
    ParticleSystemFile grass = smallGrass(false);
    Attractor up;
    up.a_m = {0.0f, 0.0f, 1.0f};
    grass.scene.attractors.push_back(up);
    std::string error;
    ASSERT_TRUE(doc->addParticleSystem(grass, &error)) << error;
    ASSERT_TRUE(doc->addParticleSystem(grass, &error)) << error;  // "grass_2"
    const std::string file = (dir.path() / "particles" / "grass.json").string();
    std::string file_before;
    ASSERT_TRUE(readTextFile(file, &file_before, &error)) << error;
    const ParticleSystemFile before = (*doc->particles())[0];
    // Renamed: the system's name and the entry's, one step.
    ASSERT_TRUE(doc->setParticleEntry(0, "meadow_grass", glm::vec3(0.0f), &error)) << error;
    EXPECT_EQ(doc->undoName(), "Rename particle system");
    EXPECT_EQ((*doc->particles())[0].name, "meadow_grass");
    EXPECT_EQ(doc->project().particles[0].name, "meadow_grass");
    // Moved by a drag: three stamps, one step; every part moved by the offset.
    doc->beginStroke("Move particle system");
    for (int k = 1; k <= 3; ++k)
        ASSERT_TRUE(doc->setParticleEntry(0, "meadow_grass", glm::vec3(0.5f * float(k), 0.0f, 0.25f), &error)) << error;
    doc->endStroke();
    const ParticleScene& moved = (*doc->particles())[0].scene;
    EXPECT_EQ(moved.generators[0].center_m, before.scene.generators[0].center_m + glm::vec3(1.5f, 0.0f, 0.25f));
    EXPECT_EQ(moved.attractors[0].a_m, before.scene.attractors[0].a_m + glm::vec3(1.5f, 0.0f, 0.25f));
    EXPECT_EQ(doc->project().particles[0].offset_m, glm::vec3(1.5f, 0.0f, 0.25f));
    // Refused: another system's name, a slash, an offset beyond the limit; nothing changes.
    EXPECT_FALSE(doc->setParticleEntry(0, "grass_2", glm::vec3(0.0f), &error));
    EXPECT_NE(error.find("another system is named 'grass_2'"), std::string::npos) << error;
    EXPECT_FALSE(doc->setParticleEntry(0, "a/b", glm::vec3(0.0f), &error));
    EXPECT_NE(error.find("'/'"), std::string::npos) << error;
    EXPECT_FALSE(doc->setParticleEntry(0, "x", glm::vec3(2e5f, 0.0f, 0.0f), &error));
    EXPECT_NE(error.find("offset_m"), std::string::npos) << error;
    EXPECT_EQ((*doc->particles())[0].name, "meadow_grass");
    // Saved: the project names the entry with its name and offset; the particle file is as it was.
    ASSERT_TRUE(doc->save(&error)) << error;
    std::string file_after;
    ASSERT_TRUE(readTextFile(file, &file_after, &error)) << error;
    EXPECT_EQ(file_after, file_before);
    auto reopened = openDoc(a.string(), optionsFor(dir));
    ASSERT_TRUE(reopened);
    EXPECT_EQ((*reopened->particles())[0].name, "meadow_grass");
    EXPECT_EQ((*reopened->particles())[0].scene.generators[0].center_m, moved.generators[0].center_m);
    // Undo: the drag, then the rename; an empty name is the file's own.
    ASSERT_TRUE(doc->undo());
    EXPECT_EQ((*doc->particles())[0].scene.generators, before.scene.generators);
    ASSERT_TRUE(doc->undo());
    EXPECT_EQ((*doc->particles())[0].name, "grass");
    EXPECT_EQ(doc->project().particles[0].offset_m, glm::vec3(0.0f));
    EXPECT_NE(doc->project().particles[0].name, "meadow_grass");
    ASSERT_TRUE(doc->setParticleEntry(1, "", glm::vec3(0.0f), &error)) << error;
    EXPECT_EQ((*doc->particles())[1].name, "grass_2");
}


TEST(Document, AFailedSaveKeepsTheDocumentDirtyAndTheFileUntouched) {
    TempDir dir;
    const std::string path = writeProject(dir.path() / "scene.json", projectJson(modelsDir()));
    std::string before_text;
    std::string error;
    ASSERT_TRUE(readTextFile(path, &before_text, &error));
    auto doc = openDoc(path, optionsFor(dir));
    ASSERT_TRUE(doc);
    const uint64_t id = doc->addPrimitive(0, makePoint({-1, 1, 0}, 0.5f), &error);
    ASSERT_NE(id, 0u);
    const InstanceStore edited = settled(*doc);
    // A file used as a folder.
    const fs::path blocker = dir.path() / "blocker";
    std::ofstream(blocker) << "not a folder";
    const std::string bad = (blocker / "scene.json").string();
    EXPECT_FALSE(doc->saveAs(bad, &error));
    EXPECT_NE(error.find(bad), std::string::npos) << error;
    EXPECT_TRUE(doc->isDirty());
    EXPECT_EQ(doc->path(), path);
    EXPECT_TRUE(doc->findPrimitive(id, nullptr, nullptr));
    EXPECT_TRUE(settled(*doc) == edited);
    // A folder in the way of the file itself.
    const fs::path folder = dir.path() / "folder.json";
    fs::create_directories(folder / "inside");
    EXPECT_FALSE(doc->saveAs(folder.string(), &error));
    EXPECT_NE(error.find(folder.string()), std::string::npos) << error;
    EXPECT_TRUE(fs::is_directory(folder / "inside"));
    EXPECT_TRUE(doc->isDirty());
    std::string after_text;
    ASSERT_TRUE(readTextFile(path, &after_text, &error));
    EXPECT_EQ(after_text, before_text);
    for (const auto& entry : fs::directory_iterator(dir.path()))
        EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << "left " << entry.path();
    // Still savable where it belongs.
    ASSERT_TRUE(doc->save(&error)) << error;
    EXPECT_FALSE(doc->isDirty());
}

TEST(Document, AutosaveAndRecoveryRestoreTheEditsAfterACrash) {
    TempDir dir;
    const std::string path = writeProject(dir.path() / "scene.json", projectJson(modelsDir()));
    const DocumentOptions options = optionsFor(dir);
    std::string error;
    std::vector<std::pair<uint64_t, Primitive>> rock_prims, pebble_prims;
    InstanceStore autosaved;
    {
        auto doc = openDoc(path, options);
        ASSERT_TRUE(doc);
        EXPECT_FALSE(doc->maybeAutosave(0.0, &error)) << "nothing to save";
        doc->addPrimitive(0, makePoint({-1, 1, 0}, 0.5f, 0.9f), &error);
        EXPECT_FALSE(doc->maybeAutosave(1.0, &error)) << "the interval has not passed";
        doc->beginStroke();
        for (int k = 0; k < 6; ++k) doc->addPrimitive(1, makePoint({-1.5f + 0.5f * k, -1.2f, 0}, 0.3f, 0.8f), &error);
        doc->endStroke();
        doc->removePrimitive(doc->primitiveIds(0)[0], &error);
        EXPECT_FALSE(doc->maybeAutosave(10.5, &error));
        EXPECT_TRUE(doc->maybeAutosave(11.0, &error)) << error;
        EXPECT_FALSE(doc->maybeAutosave(30.0, &error)) << "nothing new since the autosave";
        autosaved = settled(*doc);
        for (uint64_t id : doc->primitiveIds(0)) {
            Primitive p;
            doc->findPrimitive(id, nullptr, &p);
            rock_prims.push_back({id, p});
        }
        for (uint64_t id : doc->primitiveIds(1)) {
            Primitive p;
            doc->findPrimitive(id, nullptr, &p);
            pebble_prims.push_back({id, p});
        }
        // Edits after the last autosave are what a crash loses.
        doc->addPrimitive(0, makePoint({1, -1, 0}, 0.5f), &error);
        // The crash: the document goes away without saving or closing.
    }
    RecoveryInfo info;
    ASSERT_TRUE(findRecovery(options.config_dir, path, &info));
    EXPECT_EQ(info.project_path, fs::absolute(path).lexically_normal().string());
    EXPECT_GT(info.saved_unix_s, 0);
    std::unique_ptr<Document> doc = Document::recover(path, options, &error);
    ASSERT_TRUE(doc) << error;
    EXPECT_TRUE(doc->isDirty());
    EXPECT_EQ(doc->path(), path);
    ASSERT_EQ(doc->primitiveIds(0).size(), rock_prims.size());
    ASSERT_EQ(doc->primitiveIds(1).size(), pebble_prims.size());
    for (size_t k = 0; k < rock_prims.size(); ++k) {
        Primitive p;
        ASSERT_TRUE(doc->findPrimitive(doc->primitiveIds(0)[k], nullptr, &p));
        EXPECT_TRUE(samePrimitive(p, rock_prims[k].second));
    }
    for (size_t k = 0; k < pebble_prims.size(); ++k) {
        Primitive p;
        ASSERT_TRUE(doc->findPrimitive(doc->primitiveIds(1)[k], nullptr, &p));
        EXPECT_TRUE(samePrimitive(p, pebble_prims[k].second));
    }
    EXPECT_TRUE(settled(*doc) == autosaved);
    // The recovery stays until the user saves; the save removes it.
    EXPECT_TRUE(findRecovery(options.config_dir, path, nullptr));
    ASSERT_TRUE(doc->save(&error)) << error;
    EXPECT_FALSE(findRecovery(options.config_dir, path, nullptr));
    EXPECT_FALSE(fs::exists(recoveryPath(options.config_dir, path)));

    // Close removes it too; a file saved after the autosave (by anyone) makes it stale.
    doc->addPrimitive(0, makePoint({1, 1, 0}, 0.5f), &error);
    ASSERT_TRUE(doc->autosave(&error)) << error;
    EXPECT_TRUE(findRecovery(options.config_dir, path, nullptr));
    doc->close();
    EXPECT_FALSE(findRecovery(options.config_dir, path, nullptr));
    auto doc2 = openDoc(path, options);
    ASSERT_TRUE(doc2);
    doc2->addPrimitive(0, makePoint({1, 1, 0}, 0.5f), &error);
    ASSERT_TRUE(doc2->autosave(&error)) << error;
    fs::last_write_time(path, fs::last_write_time(recoveryPath(options.config_dir, path)) + std::chrono::seconds(5));
    EXPECT_FALSE(findRecovery(options.config_dir, path, nullptr));
    // No recovery: recover() says so.
    discardRecovery(options.config_dir, path);
    EXPECT_FALSE(Document::recover(path, options, &error));
    EXPECT_NE(error.find(path), std::string::npos) << error;
}

TEST(Document, RecentFilesAreNewestFirstAndCapped) {
    TempDir dir;
    const std::string config = (dir.path() / "config").string();
    std::string error;
    EXPECT_TRUE(loadRecentFiles(config).empty());
    for (int k = 0; k < 12; ++k)
        ASSERT_TRUE(addRecentFile(config, (dir.path() / ("s" + std::to_string(k) + ".json")).string(), &error)) << error;
    std::vector<std::string> files = loadRecentFiles(config);
    ASSERT_EQ(files.size(), kMaxRecentFiles);
    EXPECT_EQ(files.front(), (dir.path() / "s11.json").string());
    EXPECT_EQ(files.back(), (dir.path() / "s2.json").string());
    ASSERT_TRUE(addRecentFile(config, (dir.path() / "s5.json").string(), &error));
    files = loadRecentFiles(config);
    ASSERT_EQ(files.size(), kMaxRecentFiles);
    EXPECT_EQ(files[0], (dir.path() / "s5.json").string());
    EXPECT_EQ(files[1], (dir.path() / "s11.json").string());
    EXPECT_EQ(std::count(files.begin(), files.end(), (dir.path() / "s5.json").string()), 1);
    // Opening a document puts it first; a corrupt list reads as empty and is replaced.
    const std::string path = writeProject(dir.path() / "scene.json", projectJson(modelsDir()));
    DocumentOptions options = optionsFor(dir);
    auto doc = openDoc(path, options);
    ASSERT_TRUE(doc);
    EXPECT_EQ(loadRecentFiles(config).front(), fs::absolute(path).lexically_normal().string());
    std::ofstream(fs::path(config) / "recent.json") << "{not json";
    EXPECT_TRUE(loadRecentFiles(config).empty());
    ASSERT_TRUE(addRecentFile(config, path, &error)) << error;
    EXPECT_EQ(loadRecentFiles(config).size(), 1u);
}

TEST(Document, ANewProjectWithNoDensityOpensEmptyAndFillsAsYouPaint) {
    TempDir dir;
    Project project;
    std::string error;
    std::string text = projectJson(modelsDir(), /*with_extent=*/false);
    ASSERT_TRUE(parseProject(text, "new.json", &project, &error)) << error;
    for (DetailTypeDesc& t : project.detail_types) t.density = DensityField{};
    std::unique_ptr<Document> doc = Document::create(project, "", optionsFor(dir), &error);
    ASSERT_TRUE(doc) << error;
    EXPECT_EQ(liveStore(*doc).instanceCount(), 0u);
    EXPECT_FALSE(doc->save(&error));
    EXPECT_NE(error.find("Save As"), std::string::npos);
    // A particle system is a file beside the project: none before it has a folder.
    EXPECT_FALSE(doc->addParticleSystem(ParticleSystemFile{}, &error));
    EXPECT_NE(error.find("save the project first"), std::string::npos) << error;
    EXPECT_TRUE(doc->particles()->empty());
    const uint64_t id = doc->addPrimitive(0, makePoint({0.2f, 0.2f, 0.0f}, 0.7f), &error);
    ASSERT_NE(id, 0u) << error;
    // The extent is derived from the densities, as the CLI will derive it from the saved file.
    EXPECT_FALSE(doc->compiled().extent.empty());
    const InstanceStore painted = settled(*doc);
    EXPECT_GT(painted.instanceCount(), 0u);
    // Growing the density grows the derived extent: instantiated again, still exact.
    ASSERT_TRUE(doc->setPrimitive(id, makePoint({0.2f, 0.2f, 0.3f}, 1.2f), &error)) << error;
    settled(*doc);
    ASSERT_TRUE(doc->undo());
    EXPECT_TRUE(settled(*doc) == painted);
    ASSERT_TRUE(doc->undo());
    EXPECT_EQ(liveStore(*doc).instanceCount(), 0u);
    EXPECT_TRUE(doc->compiled().extent.empty());
}

TEST(Document, TheAngleOfReposeIsTheTypesSettingOneUndoStepSavedAndInstantiatesNothing) {
    TempDir dir;
    const fs::path a = dir.path() / "scene.json";
    auto doc = openDoc(writeProject(a, projectJson(modelsDir())), optionsFor(dir));
    ASSERT_TRUE(doc);
    const float before = doc->project().detail_types[0].angle_of_repose_deg;
    const uint64_t live = doc->live().generation();
    std::string error;
    ASSERT_TRUE(doc->setAngleOfRepose(0, 28.0f, &error)) << error;
    EXPECT_EQ(doc->project().detail_types[0].angle_of_repose_deg, 28.0f);
    EXPECT_EQ(doc->undoName(), "Angle of repose");
    EXPECT_EQ(doc->live().generation(), live);  // only the sculpt brush reads it
    EXPECT_TRUE(doc->isDirty());
    EXPECT_FALSE(doc->setAngleOfRepose(0, 95.0f, &error));
    EXPECT_NE(error.find("angle_of_repose_deg"), std::string::npos) << error;
    EXPECT_FALSE(doc->setAngleOfRepose(7, 30.0f, &error));
    ASSERT_TRUE(doc->save(&error)) << error;
    auto reopened = openDoc(a.string(), optionsFor(dir));
    ASSERT_TRUE(reopened);
    EXPECT_EQ(reopened->project().detail_types[0].angle_of_repose_deg, 28.0f);
    ASSERT_TRUE(doc->undo());
    EXPECT_EQ(doc->project().detail_types[0].angle_of_repose_deg, before);
}

}  // namespace
}  // namespace ug
