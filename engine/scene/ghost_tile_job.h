// Ghost Tile builds off the UI thread (issue 4 "Ghost Tile panel"; docs/architecture.md: long jobs run in the
// background with a progress bar and can be cancelled, the UI never freezes).
//
//   GhostTileSpec spec = ghostTileSpec(doc.project());      // what the panel edits, as a pending copy
//   spec.types[0].candidate_count = 400;
//   std::unique_ptr<GhostTileJob> job = doc.startGhostTileJob(spec, &error);   // null: refused at once
//   every frame:  bar(job->progress());  if (cancel_clicked) job->cancel();
//                 if (job->state() == GhostTileJobState::Done) doc.applyGhostTile(job->take(), &error);
//                 else if (job->state() == GhostTileJobState::Failed) show(job->error());
//
// The job loads the models whose source changed (an unchanged source reuses the document's model: no
// reload, no refit), then loads the tile from the verified cache or builds it (ghost_tile_cache.h). It
// never touches the document: the old tile stays in use until the result is applied, as one undo step
// (ghost_tile_command.h).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "ghosttile/ghost_tile.h"
#include "ghosttile/ghost_tile_cache.h"
#include "mesh/detail_model.h"
#include "scene/project.h"

namespace ug {

// Everything of a project that shapes its Ghost Tile, per detail type in project order: the model source
// (mesh path as written in the project, scale, sphere fit, anchors) and the candidate settings (count,
// orientation distribution, scale range, positions), plus the tile settings (size, δ, seed).
// models[t].name and types[t].name are the type's name and must stay the project's.
struct GhostTileSpec {
    GhostTileSettings settings;
    std::vector<DetailModelSource> models;
    std::vector<DetailTypeSettings> types;
};

GhostTileSpec ghostTileSpec(const Project& project);
// Writes the spec into the project (tile settings, every type's model and ghost settings).
void setGhostTileSpec(const GhostTileSpec& spec, Project* project);
bool operator==(const GhostTileSpec& a, const GhostTileSpec& b);
// Every member that decides the loaded model (path, scale, axes, spheres, fit, anchors).
bool sameModelSource(const DetailModelSource& a, const DetailModelSource& b);

// The checks that need no model: tile size, δ (finite, |δ| <= tile), candidate counts (>= 1, at most
// kMaxCandidatesPerTile per type and in all: the memory bound), scale ranges, tilt ranges, a mesh path and
// a positive model scale per type, and the type names of `project` in the same order. Errors name the
// type and the setting ("ghost tile: type 'rock': candidate_count is 0 (at least 1)").
bool validateGhostTileSpec(const GhostTileSpec& spec, const Project& project, std::string* error);

// What a finished job gives: the tile and the models it was built from (shared, immutable), and how it
// was obtained.
// What a model file looked like when it was loaded (size and modification time): a model whose settings are
// unchanged is reused only while its file still looks the same, so a model edited on disk is read again.
struct ModelFileStamp {
    int64_t size = -1;  // -1: missing or unreadable
    int64_t mtime_ns = 0;
    bool operator==(const ModelFileStamp&) const = default;
};
ModelFileStamp modelFileStamp(const std::string& path);

struct GhostTileBuild {
    GhostTileSpec spec;
    std::string base_dir;  // the folder the spec's relative model paths are relative to (the job's context)
    std::shared_ptr<const GhostTile> tile;
    std::shared_ptr<const std::vector<DetailModel>> models;  // one per type, project order
    CacheOutcome outcome = CacheOutcome::BuiltMissing;
    std::string note;            // e.g. a cache that could not be written (the tile is still good)
    double seconds = 0.0;        // wall time of the whole job (models, cache or build)
    uint32_t models_loaded = 0;  // types whose model was (re)loaded from its file
    std::vector<ModelFileStamp> model_files;  // per type, as the models were taken
};

// What the job may reuse and where it writes.
struct GhostTileJobContext {
    std::string base_dir;   // the project's folder: relative mesh paths resolve against it
    std::string cache_dir;  // Ghost Tile cache ("" : build, no cache)
    int threads = 0;        // 0 = all hardware threads
    std::vector<DetailModelSource> current_sources;            // the document's, per type
    std::shared_ptr<const std::vector<DetailModel>> current_models;  // loaded from current_sources
    std::vector<ModelFileStamp> current_files;                      // their files then
};

enum class GhostTileJobState : int { Running, Done, Failed, Cancelled };

class GhostTileJob {
public:
    // Starts the work on its own thread at once. The spec should have passed validateGhostTileSpec.
    GhostTileJob(GhostTileSpec spec, GhostTileJobContext context);
    ~GhostTileJob();  // cancels and joins
    GhostTileJob(const GhostTileJob&) = delete;
    GhostTileJob& operator=(const GhostTileJob&) = delete;

    GhostTileJobState state() const { return state_.load(std::memory_order_acquire); }
    bool finished() const { return state() != GhostTileJobState::Running; }
    float progress() const { return progress_.load(std::memory_order_relaxed); }  // in [0, 1]
    // Asks the job to stop; it ends Cancelled soon after (or Done / Failed when it was already past them).
    void cancel() { cancel_.store(true); }
    void wait();  // blocks until finished (tests, scripted runs)
    // Failed: names the file or setting and the reason ("detail type 'rock': bad.glb: ...").
    const std::string& error() const { return error_; }
    // Done: the result (once; the job keeps nothing afterwards).
    GhostTileBuild take() { return std::move(build_); }
    const GhostTileSpec& spec() const { return build_.spec; }

private:
    void work();

    GhostTileJobContext context_;
    GhostTileBuild build_;
    std::string error_;
    std::atomic<bool> cancel_{false};
    std::atomic<float> progress_{0.0f};
    std::atomic<GhostTileJobState> state_{GhostTileJobState::Running};
    std::thread thread_;  // last: starts after everything above is constructed
};

}  // namespace ug
