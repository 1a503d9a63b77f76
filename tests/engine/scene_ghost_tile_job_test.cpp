// The Ghost Tile panel's engine side: a background job that loads changed models and builds (or loads)
// the tile with progress and cancel, applied to the document as one undo step whose undo gives back the
// exact previous instance set; cancelled, failed and refused jobs leave the document as it was.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <thread>

#include "instancer/instance_query.h"
#include "instancer/instance_store.h"
#include "instancer/instantiator.h"
#include "scene/document.h"
#include "scene/ghost_tile_job.h"
#include "scene_test_util.h"

namespace ug {
namespace {

namespace fs = std::filesystem;

// Every test's own folder.
class TempDir : public test::TempDir {
public:
    TempDir() : test::TempDir("ug_ghost_job_test_") {}
};

// Rocks and pebbles on a small procedural terrain, the models from assets/models (absolute paths).
std::string writeScene(const fs::path& dir) {
    const std::string models = (fs::path(UG_SOURCE_DIR) / "assets" / "models").string();
    const std::string text = R"({"format": "undergrowth-project", "format_version": 2, "name": "ghost_job_test",
 "ghost_tile": {"tile_size_m": 0.5, "delta_m": -0.002, "seed": 7},
 "terrain": {"procedural": {"origin": [-2, -2], "cell_size_m": 0.25, "width": 17, "height": 17, "seed": 3,
                            "octaves": 2, "amplitude_m": 0.15, "feature_size_m": 2}},
 "extent": {"min": [-2, -2, -0.5], "max": [2, 2, 0.8]},
 "detail_types": [
  {"name": "rock", "model": {"mesh": ")" + models + R"(/rock.glb"}, "candidates": {"count": 100, "scale": [0.8, 1.2]},
   "density": {"blend": [{"point": {"center": [0.5, 0.5, 0], "radius": 0.9, "weight": 0.8}}]}},
  {"name": "pebble", "model": {"mesh": ")" + models + R"(/pebble.glb"}, "candidates": {"count": 160, "scale": [0.8, 1.2]},
   "density": {"blend": [{"point": {"center": [-0.5, -0.5, 0], "radius": 1.0, "weight": 0.7}}]}}]})";
    const fs::path path = dir / "scene.json";
    std::ofstream(path) << text;
    return path.string();
}

// writeScene's project in scene_dir, with its own copy of the models in dir/models, which the file names
// by `models_ref` (a path relative to scene_dir, or absolute).
std::string writeSceneWithOwnModels(const fs::path& dir, const fs::path& scene_dir, const std::string& models_ref) {
    const fs::path source_models = fs::path(UG_SOURCE_DIR) / "assets" / "models";
    fs::create_directories(dir / "models");
    fs::create_directories(scene_dir);
    for (const char* m : {"rock.glb", "pebble.glb"}) fs::copy_file(source_models / m, dir / "models" / m);
    std::string text;
    {
        std::ifstream in(writeScene(dir));
        text.assign(std::istreambuf_iterator<char>(in), {});
    }
    for (size_t at; (at = text.find(source_models.string())) != std::string::npos;)
        text.replace(at, source_models.string().size(), models_ref);
    const fs::path project = scene_dir / "scene.json";
    std::ofstream(project) << text;
    return project.string();
}

DocumentOptions optionsFor(const TempDir& dir) {
    return DocumentOptions{.cache_dir = (dir.path() / "cache").string(), .config_dir = "", .threads = 2};
}

std::unique_ptr<Document> openScene(const TempDir& dir) {
    std::string error;
    std::unique_ptr<Document> doc = Document::open(writeScene(dir.path()), optionsFor(dir), &error);
    EXPECT_TRUE(doc) << error;
    return doc;
}

// The live result, checked against a fresh full run of what the document holds now.
InstanceStore settled(Document& doc) {
    const LiveResult r = doc.waitForResult();
    EXPECT_TRUE(r.ok) << r.error;
    InstancerInput in = doc.instancerInput();
    Instantiator inst;
    std::string error;
    EXPECT_TRUE(inst.setInput(in, &error)) << error;
    EXPECT_TRUE(inst.instantiateAll({.threads = 2}, nullptr, &error)) << error;
    EXPECT_TRUE(*r.store == inst.store()) << "live result differs from a full run";
    return *r.store;
}

// Runs a job to its end; its state.
GhostTileJobState runJob(GhostTileJob& job) {
    job.wait();
    return job.state();
}

TEST(GhostTileJob, AppliedBuildIsOneUndoStepAndUndoRedoGiveTheExactInstanceSets) {
    TempDir dir;
    auto doc = openScene(dir);
    ASSERT_TRUE(doc);
    const InstanceStore before = settled(*doc);
    ASSERT_GT(before.instanceCount(), 20u);
    const uint64_t before_hash = instanceStoreHash(before);
    const GhostTileSpec old_spec = ghostTileSpec(doc->project());
    const std::shared_ptr<const GhostTile> old_tile = doc->tileAssets().tile;
    const uint64_t generation0 = doc->tileGeneration();

    GhostTileSpec spec = old_spec;
    spec.types[0].candidate_count = 170;
    spec.settings.delta_m = -0.001f;
    std::string error;
    std::unique_ptr<GhostTileJob> job = doc->startGhostTileJob(spec, &error);
    ASSERT_TRUE(job) << error;
    ASSERT_EQ(runJob(*job), GhostTileJobState::Done) << job->error();
    EXPECT_EQ(job->progress(), 1.0f);
    // The document is untouched until the result is applied.
    EXPECT_EQ(doc->tileAssets().tile, old_tile);
    EXPECT_TRUE(ghostTileSpec(doc->project()) == old_spec);
    GhostTileBuild build = job->take();
    EXPECT_EQ(build.models_loaded, 0u) << "no model source changed: the document's models are reused";
    EXPECT_EQ(build.outcome, CacheOutcome::BuiltMissing);
    const std::shared_ptr<const GhostTile> new_tile = build.tile;
    EXPECT_EQ(new_tile->candidates.type_begin[1], 170u);
    ASSERT_TRUE(doc->applyGhostTile(std::move(build), &error)) << error;
    EXPECT_EQ(doc->undoName(), "Ghost Tile");
    EXPECT_TRUE(doc->isDirty());
    EXPECT_NE(doc->tileGeneration(), generation0);
    EXPECT_EQ(doc->tileLiveGeneration(), doc->live().generation()) << "results from here on use the new tile";
    EXPECT_EQ(doc->ghostTile().candidates.size(), 170u + 160u);
    EXPECT_TRUE(ghostTileSpec(doc->project()) == spec);
    const InstanceStore after = settled(*doc);
    EXPECT_NE(instanceStoreHash(after), before_hash) << "a new tile gives another instance set";

    const uint64_t generation1 = doc->tileGeneration();
    ASSERT_TRUE(doc->undo());
    EXPECT_EQ(doc->tileAssets().tile, old_tile) << "undo swaps the old tile back, no rebuild";
    EXPECT_TRUE(ghostTileSpec(doc->project()) == old_spec);
    EXPECT_NE(doc->tileGeneration(), generation1);
    const InstanceStore undone = settled(*doc);
    EXPECT_TRUE(undone == before);
    EXPECT_EQ(instanceStoreHash(undone), before_hash);
    EXPECT_FALSE(doc->isDirty());

    ASSERT_TRUE(doc->redo());
    EXPECT_EQ(doc->tileAssets().tile, new_tile);
    EXPECT_TRUE(settled(*doc) == after);

    // Saved and opened again: the same settings, the tile from the cache, the same instances.
    const std::string saved = (dir.path() / "saved.json").string();
    ASSERT_TRUE(doc->saveAs(saved, &error)) << error;
    std::unique_ptr<Document> reopened = Document::open(saved, optionsFor(dir), &error);
    ASSERT_TRUE(reopened) << error;
    EXPECT_TRUE(ghostTileSpec(reopened->project()) == spec);
    EXPECT_EQ(reopened->cacheOutcome(), CacheOutcome::Loaded);
    EXPECT_EQ(reopened->ghostTile().key, new_tile->key);
    EXPECT_TRUE(settled(*reopened) == after);
}

TEST(GhostTileJob, CancelLeavesTheDocumentUnchanged) {
    TempDir dir;
    auto doc = openScene(dir);
    ASSERT_TRUE(doc);
    const InstanceStore before = settled(*doc);
    const GhostTileSpec old_spec = ghostTileSpec(doc->project());
    const uint64_t generation = doc->tileGeneration();
    GhostTileSpec spec = old_spec;
    spec.types[1].candidate_count = 6000;  // a build of seconds: the cancel lands inside it
    std::string error;
    std::unique_ptr<GhostTileJob> job = doc->startGhostTileJob(spec, &error);
    ASSERT_TRUE(job) << error;
    job->cancel();
    EXPECT_EQ(runJob(*job), GhostTileJobState::Cancelled) << job->error();
    EXPECT_LT(job->progress(), 1.0f);
    EXPECT_TRUE(ghostTileSpec(doc->project()) == old_spec);
    EXPECT_EQ(doc->tileGeneration(), generation);
    EXPECT_FALSE(doc->canUndo());
    EXPECT_TRUE(settled(*doc) == before);
    // Cancelled in the middle of the collision graph: the progress was moving, the build stops.
    job = doc->startGhostTileJob(spec, &error);
    ASSERT_TRUE(job) << error;
    while (!job->finished() && job->progress() < 0.2f) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    const float at_cancel = job->progress();
    job->cancel();
    EXPECT_EQ(runJob(*job), GhostTileJobState::Cancelled) << "progress " << at_cancel << " " << job->error();
    EXPECT_GE(at_cancel, 0.2f);
    EXPECT_TRUE(ghostTileSpec(doc->project()) == old_spec);
    EXPECT_FALSE(doc->canUndo());
    // A cancelled build writes no cache file.
    size_t cache_files = 0;
    for (const auto& e : fs::directory_iterator(dir.path() / "cache")) cache_files += e.is_regular_file();
    EXPECT_EQ(cache_files, 1u) << "only the opened tile's";
}

TEST(GhostTileJob, ACorruptModelFailsNamingTheFileAndTheDocumentIsUnchanged) {
    TempDir dir;
    auto doc = openScene(dir);
    ASSERT_TRUE(doc);
    const InstanceStore before = settled(*doc);
    const GhostTileSpec old_spec = ghostTileSpec(doc->project());
    const fs::path bad = dir.path() / "broken_rock.glb";
    std::ofstream(bad, std::ios::binary) << "glTF\x02\x00\x00\x00 this is not a binary glTF";
    GhostTileSpec spec = old_spec;
    spec.models[0].mesh_path = bad.filename().string();  // relative: resolved against the project's folder
    std::string error;
    std::unique_ptr<GhostTileJob> job = doc->startGhostTileJob(spec, &error);
    ASSERT_TRUE(job) << error;
    ASSERT_EQ(runJob(*job), GhostTileJobState::Failed);
    EXPECT_NE(job->error().find("broken_rock.glb"), std::string::npos) << job->error();
    EXPECT_NE(job->error().find("'rock'"), std::string::npos) << job->error();
    EXPECT_TRUE(ghostTileSpec(doc->project()) == old_spec);
    EXPECT_FALSE(doc->canUndo());
    EXPECT_TRUE(settled(*doc) == before);

    // A missing file: the same.
    spec.models[0].mesh_path = "no_such_model.glb";
    job = doc->startGhostTileJob(spec, &error);
    ASSERT_TRUE(job) << error;
    ASSERT_EQ(runJob(*job), GhostTileJobState::Failed);
    EXPECT_NE(job->error().find("no_such_model.glb"), std::string::npos) << job->error();
}

TEST(GhostTileJob, AbsurdSettingsAreRefusedAtOnceWithTheSettingNamed) {
    TempDir dir;
    auto doc = openScene(dir);
    ASSERT_TRUE(doc);
    const GhostTileSpec good = ghostTileSpec(doc->project());
    struct Case {
        const char* what;
        GhostTileSpec spec;
        const char* expect;
    };
    std::vector<Case> cases;
    cases.push_back({"count 0", good, "candidate_count is 0"});
    cases.back().spec.types[0].candidate_count = 0;
    cases.push_back({"NaN delta", good, "delta_m"});
    cases.back().spec.settings.delta_m = std::numeric_limits<float>::quiet_NaN();
    cases.push_back({"huge count", good, "exceeds the limit"});
    cases.back().spec.types[1].candidate_count = 50'000'000;
    cases.push_back({"over the limit in all", good, "in all"});
    cases.back().spec.types[0].candidate_count = kMaxCandidatesPerTile / 2 + 1;
    cases.back().spec.types[1].candidate_count = kMaxCandidatesPerTile / 2 + 1;
    cases.push_back({"inverted scale", good, "scale range"});
    cases.back().spec.types[0].scale_min = 2.0f;
    cases.back().spec.types[0].scale_max = 1.0f;
    cases.push_back({"zero tile", good, "tile_size_m"});
    cases.back().spec.settings.tile_size_m = 0.0f;
    cases.push_back({"no model", good, "no model file"});
    cases.back().spec.models[1].mesh_path.clear();
    cases.push_back({"renamed", good, "cannot be renamed"});
    cases.back().spec.types[1].name = "gravel";
    for (const Case& c : cases) {
        std::string error;
        EXPECT_FALSE(doc->startGhostTileJob(c.spec, &error)) << c.what;
        EXPECT_NE(error.find(c.expect), std::string::npos) << c.what << ": " << error;
    }
    EXPECT_FALSE(doc->canUndo());
    std::string error;
    EXPECT_TRUE(doc->startGhostTileJob(good, &error)) << "the unchanged settings are fine: " << error;
}

TEST(GhostTileJob, AChangedModelIsLoadedAndTheOldTileIsFreedOnceNothingHoldsIt) {
    TempDir dir;
    auto doc = openScene(dir);
    ASSERT_TRUE(doc);
    settled(*doc);
    const std::weak_ptr<const GhostTile> opened_tile = doc->tileAssets().tile;
    GhostTileSpec spec = ghostTileSpec(doc->project());
    spec.models[1].mesh_path = spec.models[0].mesh_path;  // pebbles drawn as rocks
    spec.models[1].scale = 0.5f;
    std::string error;
    std::unique_ptr<GhostTileJob> job = doc->startGhostTileJob(spec, &error);
    ASSERT_TRUE(job) << error;
    ASSERT_EQ(runJob(*job), GhostTileJobState::Done) << job->error();
    GhostTileBuild build = job->take();
    EXPECT_EQ(build.models_loaded, 1u);
    // The pebble's model is now the rock's mesh at half scale: its sphere set is the rock's halved.
    const DetailModel& rock = doc->models()[0];
    const DetailModel& pebble = (*build.models)[1];
    ASSERT_EQ(pebble.spheres.size(), rock.spheres.size());
    EXPECT_NEAR(pebble.bounds.radius, 0.5f * rock.bounds.radius, 1e-4f * rock.bounds.radius);
    const std::weak_ptr<const GhostTile> built_tile = build.tile;
    ASSERT_TRUE(doc->applyGhostTile(std::move(build), &error)) << error;
    job.reset();
    settled(*doc);
    EXPECT_FALSE(opened_tile.expired()) << "the undo step keeps the opened tile";
    ASSERT_TRUE(doc->undo());
    // A new edit drops the redo step, the only holder of the built tile once the worker is done with it.
    ASSERT_TRUE(doc->setSeed(5, &error)) << error;
    settled(*doc);
    EXPECT_TRUE(built_tile.expired());
    EXPECT_FALSE(opened_tile.expired());
}

// A Save As to another folder between a tile change and its undo: the model paths the undo writes back
// are relative to the new folder (they were relative to the old one), so the file still opens.
TEST(GhostTileJob, UndoAfterSaveAsToAnotherFolderKeepsModelPathsValid) {
    TempDir dir;
    fs::create_directories(dir.path() / "b" / "c");
    const std::string project = writeSceneWithOwnModels(dir.path(), dir.path() / "a", "../models");
    std::string error;
    std::unique_ptr<Document> doc = Document::open(project, optionsFor(dir), &error);
    ASSERT_TRUE(doc) << error;
    ASSERT_EQ(doc->project().detail_types[0].model.mesh_path, "../models/rock.glb");

    GhostTileSpec spec = ghostTileSpec(doc->project());
    spec.types[0].candidate_count = 130;
    std::unique_ptr<GhostTileJob> job = doc->startGhostTileJob(spec, &error);
    ASSERT_TRUE(job) << error;
    ASSERT_EQ(runJob(*job), GhostTileJobState::Done) << job->error();
    ASSERT_TRUE(doc->applyGhostTile(job->take(), &error)) << error;
    const InstanceStore built = settled(*doc);
    ASSERT_TRUE(doc->saveAs((dir.path() / "b" / "c" / "scene.json").string(), &error)) << error;

    auto expectPathsValid = [&](const char* when) {
        for (const DetailTypeDesc& t : doc->project().detail_types) {
            const std::string& path = t.model.mesh_path;
            EXPECT_FALSE(fs::path(path).is_absolute()) << when << ": " << path << " should stay relative";
            EXPECT_TRUE(fs::exists(fs::path(doc->project().base_dir) / path))
                << when << ": " << path << " does not resolve from " << doc->project().base_dir;
        }
    };
    expectPathsValid("after save as");
    ASSERT_TRUE(doc->undo());
    expectPathsValid("after undo");
    EXPECT_EQ(doc->project().detail_types[0].model.mesh_path, "../../models/rock.glb");
    const InstanceStore undone = settled(*doc);
    ASSERT_TRUE(doc->redo());
    expectPathsValid("after redo");
    EXPECT_TRUE(settled(*doc) == built);

    // Saved after the undo, the file opens and gives the undone set.
    ASSERT_TRUE(doc->undo());
    ASSERT_TRUE(doc->save(&error)) << error;
    std::unique_ptr<Document> reopened = Document::open(doc->path(), optionsFor(dir), &error);
    ASSERT_TRUE(reopened) << error;
    EXPECT_TRUE(settled(*reopened) == undone);
}

// A model whose settings are unchanged is reused only while its file looks the same: a model edited on
// disk (here: replaced by another one) is read again by the next build.
TEST(GhostTileJob, AModelEditedOnDiskIsReadAgain) {
    TempDir dir;
    const std::string project =
        writeSceneWithOwnModels(dir.path(), dir.path(), (dir.path() / "models").string());
    std::string error;
    std::unique_ptr<Document> doc = Document::open(project, optionsFor(dir), &error);
    ASSERT_TRUE(doc) << error;
    const float rock_radius = doc->models()[0].bounds.radius;

    GhostTileSpec spec = ghostTileSpec(doc->project());
    spec.types[0].candidate_count = 120;
    std::unique_ptr<GhostTileJob> job = doc->startGhostTileJob(spec, &error);
    ASSERT_TRUE(job) << error;
    ASSERT_EQ(runJob(*job), GhostTileJobState::Done) << job->error();
    EXPECT_EQ(job->take().models_loaded, 0u) << "nothing changed on disk: both models reused";

    // The rock's file now holds the pebble (another size; its time moved on too).
    fs::copy_file(dir.path() / "models" / "pebble.glb", dir.path() / "models" / "rock.glb",
                  fs::copy_options::overwrite_existing);
    fs::last_write_time(dir.path() / "models" / "rock.glb",
                        fs::last_write_time(dir.path() / "models" / "rock.glb") + std::chrono::seconds(5));
    job = doc->startGhostTileJob(spec, &error);
    ASSERT_TRUE(job) << error;
    ASSERT_EQ(runJob(*job), GhostTileJobState::Done) << job->error();
    GhostTileBuild build = job->take();
    EXPECT_EQ(build.models_loaded, 1u) << "the edited file is read again, the other reused";
    ASSERT_TRUE(doc->applyGhostTile(std::move(build), &error)) << error;
    EXPECT_NE(doc->models()[0].bounds.radius, rock_radius);
    EXPECT_EQ(doc->models()[0].bounds.radius, doc->models()[1].bounds.radius) << "the rock type now has the pebble";

    // Applied, the new stamps are the document's: building again reuses both.
    job = doc->startGhostTileJob(spec, &error);
    ASSERT_TRUE(job) << error;
    ASSERT_EQ(runJob(*job), GhostTileJobState::Done) << job->error();
    EXPECT_EQ(job->take().models_loaded, 0u);
}

}  // namespace
}  // namespace ug
