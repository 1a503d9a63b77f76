// The editor's document (issue 4, "Document"): a project being edited, everything derived from it, the
// undo stack and the live instantiation. GL-free, so tests, scripted runs and the GUI share it.
//
//   DocumentOptions options{.cache_dir = "cache", .config_dir = defaultConfigDir()};
//   RecoveryInfo info;
//   std::unique_ptr<Document> doc = findRecovery(options.config_dir, path, &info) && user_agrees
//                                       ? Document::recover(path, options, &error)
//                                       : Document::open(path, options, &error);
//   uint64_t id = doc->addPrimitive(type, makePoint(p, 0.5f), &error);     // one undo step
//   doc->beginStroke("Paint");  ... doc->addPrimitive(...) per stamp ...  doc->endStroke();  // one step
//   doc->undo();  doc->redo();
//   every frame:   LiveResult r; if (doc->live().poll(&r)) upload(r);  doc->maybeAutosave(now_s, &error);
//   doc->save(&error);  doc->saveAs(other, &error);  doc->close();
//
// What is kept:
//   project       the file's content, edited in place (densities keep the file's DensityField; the ids of
//                 the user primitives live in a side table, edit_commands.h)
//   models, Ghost Tile, terrain   loaded at open (Ghost Tile from the verified cache, or built); the tile and
//                 models are replaced by a background GhostTileJob applied as one undo step (ghost_tile_job.h)
//   compiled      one InstanceTypeSettings per type, recompiled for the types an edit touches
//   live          the LiveInstancer, fed after every edit, undo and redo
// The document is used from one thread (the UI's); only the LiveInstancer's worker runs beside it.
//
// Files under the config folder (defaultConfigDir(): $XDG_CONFIG_HOME/undergrowth, else
// ~/.config/undergrowth):
//   recent.json                          {"format": "undergrowth-recent", "files": [absolute paths]},
//                                        newest first, at most kMaxRecentFiles
//   recovery/<16 hex digits>.json        the autosaved project (hex: hash of the absolute project path)
//   recovery/<16 hex digits>.meta.json   {"format": "undergrowth-recovery", "path": "<absolute path>",
//                                         "saved_unix_s": <time>}
// Every write is atomic (core/atomic_file.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ghosttile/ghost_tile.h"
#include "ghosttile/ghost_tile_cache.h"
#include "instancer/instantiator.h"
#include "mesh/detail_model.h"
#include "scene/detail_looks.h"
#include "scene/edit_commands.h"
#include "scene/env_commands.h"
#include "scene/ghost_tile_command.h"
#include "scene/ghost_tile_job.h"
#include "scene/live_instancer.h"
#include "scene/particle_commands.h"
#include "scene/project.h"
#include "scene/scene_compile.h"
#include "scene/scene_load.h"

namespace ug {

constexpr size_t kMaxRecentFiles = 10;
constexpr size_t kMaxUndoSteps = 1000;  // the oldest steps are dropped beyond this

struct DocumentOptions {
    std::string cache_dir;             // Ghost Tile cache folder
    std::string config_dir;            // recent files and recovery; empty: neither is written
    int threads = 0;                   // Ghost Tile build and instantiation (0 = all hardware threads)
    double autosave_interval_s = 60.0; // maybeAutosave(): at most this long between a change and its autosave
};

// $XDG_CONFIG_HOME/undergrowth, else $HOME/.config/undergrowth, else "" (no config).
std::string defaultConfigDir();

// ---- recent files ----------------------------------------------------------------------------------------
// A missing or unreadable list is empty (recent files are a convenience, never a reason to fail).
std::vector<std::string> loadRecentFiles(const std::string& config_dir);
// Puts the absolute path first (removing an older entry for it), keeps kMaxRecentFiles; atomic.
bool addRecentFile(const std::string& config_dir, const std::string& path, std::string* error);

// ---- recovery --------------------------------------------------------------------------------------------
struct RecoveryInfo {
    std::string project_path;   // absolute
    std::string recovery_path;  // the autosaved project
    int64_t saved_unix_s = 0;
};
// The recovery file of a project path (absolute, normalized, hashed). An empty path (an untitled
// document) has the key "untitled".
std::string recoveryPath(const std::string& config_dir, const std::string& project_path);
// True when an autosave of `project_path` exists that is newer than the file (or the file is gone).
bool findRecovery(const std::string& config_dir, const std::string& project_path, RecoveryInfo* out);
// Removes the recovery files of a path (after a save, a close, or when the user declines to recover).
void discardRecovery(const std::string& config_dir, const std::string& project_path);

class Document {
public:
    // Loads the project, its models, the Ghost Tile (cache or build) and the terrain, compiles it and starts
    // instantiating in the background. Adds the path to the recent files. Errors name the file.
    static std::unique_ptr<Document> open(const std::string& path, const DocumentOptions& options,
                                          std::string* error);
    // The autosaved state of `path` (findRecovery), as a dirty document that saves to `path`.
    static std::unique_ptr<Document> recover(const std::string& path, const DocumentOptions& options,
                                             std::string* error);
    // A document for a project in memory ("New"; path may be empty until saveAs). Relative paths in the
    // project resolve against project.base_dir.
    static std::unique_ptr<Document> create(Project project, const std::string& path,
                                            const DocumentOptions& options, std::string* error);
    ~Document();  // stops the worker; leaves any recovery file (close() removes it)
    Document(const Document&) = delete;
    Document& operator=(const Document&) = delete;

    const Project& project() const { return project_; }
    const std::string& path() const { return path_; }
    const std::vector<DetailModel>& models() const { return *assets_.models; }
    const GhostTile& ghostTile() const { return *assets_.tile; }
    const TileAssets& tileAssets() const { return assets_; }
    const std::shared_ptr<const HeightField>& terrain() const { return terrain_; }
    const CompiledScene& compiled() const { return compiled_; }
    // The environmental objects compiled from project().environment (never null; empty without any).
    const std::shared_ptr<const EnvScene>& environment() const { return environment_; }
    // Changes whenever the environment does (an edit, its undo or redo): its effects follow.
    uint64_t environmentGeneration() const { return environment_generation_; }
    // The project's particle systems, placed (never null after a load; empty for none).
    const std::shared_ptr<const std::vector<ParticleSystemFile>>& particles() const { return particles_; }
    // Changes whenever the particle systems do (an edit, its undo or redo): their strands grow again.
    uint64_t particlesGeneration() const { return particles_generation_; }
    // Every surface's look now (compileSceneMaterials on project() and models()): one SurfaceMaterial per
    // detail type and the terrain's, textures baked. Computed on each call (a few hundred ms for the
    // default scene's five kinds): call it when the project or tileGeneration() changes, not per frame.
    SceneMaterials materials() const { return compileSceneMaterials(project_, models(), variant_models_.get()); }
    // Every look of the detail instances (scene/detail_looks.h): the types', then their scatter variants'.
    DetailLooks looks() const { return detailLooks(project_, models(), *variant_models_, environment_); }
    // The scattered types' variant models ([type][k]), shared and never changed in place: a background
    // job that keeps this pointer may build looks on its own copy of models().
    const std::shared_ptr<const std::vector<std::vector<DetailModel>>>& variantModels() const { return variant_models_; }
    CacheOutcome cacheOutcome() const { return assets_.outcome; }
    // Changes whenever the Ghost Tile and models are swapped (a build applied, its undo or redo): candidate
    // frames, models and meshes derived from them must be made again.
    uint64_t tileGeneration() const { return tile_generation_; }
    // The live instancer's generation from which results are made with the current tile: an older result
    // (finished after the swap) holds candidate ids of another tile and must not be shown.
    uint64_t tileLiveGeneration() const { return tile_live_generation_; }
    // What the instantiator runs on now (points into this document).
    InstancerInput instancerInput() const;
    // The same for `compiled` (an edit's fields before they become the document's).
    InstancerInput instancerInputFor(const CompiledScene& compiled) const;
    // The settling pass's input for the current project and assets (settling off when the project says so).
    SettleInput settleInputOf() const;

    // ---- user primitives (edit_commands.h) ----
    // The ids of `type`'s user primitives, in blend order.
    std::vector<uint64_t> primitiveIds(size_t type) const;
    // The primitive `id` and its type; false for an unknown id.
    bool findPrimitive(uint64_t id, size_t* type, Primitive* out) const;

    // ---- edits: one undo step each, or one more stamp of the open stroke ----
    // Errors name the type or id and the reason; on failure nothing changed.
    uint64_t addPrimitive(size_t type, const Primitive& prim, std::string* error);  // the new id, 0 on failure
    bool setPrimitive(uint64_t id, const Primitive& prim, std::string* error);
    bool removePrimitive(uint64_t id, std::string* error);
    // A copy of `id` moved by offset_m (its skeleton; terrain kinds are not moved), in the same type, in
    // no stroke.
    uint64_t duplicatePrimitive(uint64_t id, glm::vec3 offset_m, std::string* error);
    // ---- brush strokes as units (Primitive::stroke) ----
    // The user primitives tagged with the same stroke as `id`, in every type, in type then blend order,
    // `id` among them; {id} alone when it has no stroke; empty for an unknown id.
    std::vector<uint64_t> strokeMembers(uint64_t id) const;
    // A stroke tag no user primitive has (1 + the largest in use).
    uint32_t newStrokeTag() const;
    // Several primitives replaced, or removed, as ONE undo step named `name` (or one stamp of an open
    // stroke: a drag) with one recompile; all or nothing. A stroke moves, re-weights and deletes so.
    bool setPrimitives(const std::vector<std::pair<uint64_t, Primitive>>& edits, const std::string& name,
                       std::string* error);
    bool removePrimitives(const std::vector<uint64_t>& ids, const std::string& name, std::string* error);
    // Copies of `ids` moved by offset_m (or each by its own of `offsets_m`, one per id), one undo step; the
    // copies of a stroke's primitives form a new stroke (a fresh tag), untagged ones stay untagged. The new
    // ids in order; empty on failure.
    std::vector<uint64_t> duplicatePrimitives(const std::vector<uint64_t>& ids, glm::vec3 offset_m,
                                              std::string* error);
    std::vector<uint64_t> duplicatePrimitives(const std::vector<uint64_t>& ids,
                                              const std::vector<glm::vec3>& offsets_m, std::string* error);
    bool setInstancing(size_t type, const InstancingDesc& desc, std::string* error);
    bool setSeed(uint64_t seed, std::string* error);
    // The slope the sculpt brush keeps for `type`'s piles, in (0, 89] degrees; one undo step (or a stamp of
    // an open stroke: a slider's drag).
    bool setAngleOfRepose(size_t type, float deg, std::string* error);
    // Entry `index`'s particle system becomes `system` (placed, as particles() holds it); entries naming
    // the same file take it too (particle_commands.h). Refused with the entry and field named when the
    // system is invalid (validateParticleScene). Saving writes the changed particle files.
    bool setParticleSystem(size_t index, const ParticleSystemFile& system, std::string* error);
    // A new system (placed as given, no offset) in a new file beside the project ("particles/<name>.json",
    // particle_commands.h), its name made unique among the project's systems, one undo step. The file is
    // written at once, so an autosave recovered after a crash finds it; Save writes it again with the
    // edits since. Refused for a project never saved (no folder to put the file in) or an invalid system.
    bool addParticleSystem(const ParticleSystemFile& system, std::string* error);
    // Entry `index` and its system out of the project, one undo step (its file stays on disk; Save writes
    // the list without it).
    bool removeParticleSystem(size_t index, std::string* error);
    // Entry `index` of the project's "particles" list under another name ("" : the file's own) and at
    // another offset, its strands moved with it; one undo step, or one stamp of an open stroke (a drag).
    // Refused: a name another system has, or with '/' or control characters; an offset beyond the particle
    // coordinates' limit.
    bool setParticleEntry(size_t index, const std::string& name, glm::vec3 offset_m, std::string* error);
    // The environmental objects' tree and fields become `environment`'s (its type library must be the
    // project's: types are not edited here), one undo step named `name` ("Move object", "Footprints").
    // Compiled at once (errors name the node or field); the scattered types and the settling follow.
    bool setEnvironment(const EnvironmentDesc& environment, const std::string& name, std::string* error);
    // ---- Ghost Tile (ghost_tile_job.h) ----
    // Checks `spec` (validateGhostTileSpec) and starts building it in the background, reusing the models
    // whose source is unchanged; null with *error when refused. The document is not touched by the job.
    std::unique_ptr<GhostTileJob> startGhostTileJob(GhostTileSpec spec, std::string* error) const;
    // A finished job's result, as one undo step (SetGhostTileCommand); instantiates everything again.
    bool applyGhostTile(GhostTileBuild build, std::string* error);
    // Any command (already constructed, not applied). The edits above go through here.
    bool execute(std::unique_ptr<Command> command, std::string* error);

    // A stroke: every edit until endStroke() is one undo step (applied and instantiated as it comes).
    void beginStroke(const std::string& name = "Stroke");
    void endStroke();  // an empty stroke leaves no step
    bool inStroke() const { return stroke_ != nullptr; }
    // Whether Ctrl+Z would take back the edit (or redo) that made the particle systems' `generation`:
    // the editor's Cancel of a slow growth undoes exactly the edit being grown, never another step.
    bool undoRevertsParticles(uint64_t generation) const {
        return !stroke_ && !undo_.empty() && undo_.back().particles_generation == generation;
    }

    bool canUndo() const { return !undo_.empty() || (stroke_ && !stroke_->empty()); }
    bool canRedo() const { return !redo_.empty(); }
    std::string undoName() const;  // "" when there is nothing
    std::string redoName() const;
    bool undo();  // ends an open stroke first; false when there is nothing to undo
    bool redo();

    // ---- files ----
    // Unsaved changes: an edit since the last save (undoing back to the saved state makes it clean), or a
    // recovered document not yet saved.
    bool isDirty() const;
    // Atomic (saveProject). On failure *error names the path and the reason, and the document (content,
    // path, dirty flag) is unchanged. A clean save removes the recovery file.
    bool save(std::string* error);
    // Relative model and image paths are rewritten for the new folder. The document then saves to `path`.
    bool saveAs(const std::string& path, std::string* error);
    // Writes the recovery files now (atomic). Needs a config folder.
    bool autosave(std::string* error);
    // Autosaves when there are changes not autosaved and autosave_interval_s has passed since the first of
    // them was seen (now_s: any monotonic clock in seconds, the same on every call). True when it wrote.
    bool maybeAutosave(double now_s, std::string* error);
    // The user closes the document (after saving or choosing to drop the changes): waits for the worker
    // and removes the recovery file. The document must not be edited afterwards.
    void close();

    // ---- live instantiation ----
    LiveInstancer& live() { return *live_; }
    // waitIdle() and then the newest result (tests, scripted runs); changed tiles are left for poll().
    LiveResult waitForResult();

private:
    Document() = default;
    bool load(Project project, const std::string& path, const DocumentOptions& options, std::string* error);
    // The autosave's particle systems (`file`: recovery/<key>.particles.json; none there: nothing to do)
    // replace the ones read from their files, which stay what Save compares with (so Save writes them).
    bool recoverParticles(const std::string& file, std::string* error);
    EditTarget target() { return EditTarget{&project_, &densities_, &assets_, &particles_}; }
    // Recompiles what `effect` touched and feeds the live instancer; false (nothing changed) when the new
    // settings do not compile. It sets effect.particles when the systems had to be placed again among
    // moved objects (placeParticles).
    bool commit(EditEffect& effect, std::string* error);
    // The systems placed among `environment`'s objects and, with `on_details`, on the instances `compiled`
    // makes (scene/scene_particles.h placeAmongObjects, placeOnDetails); *placed stays null when nothing
    // changed.
    bool placeParticles(const EnvScene& environment, const CompiledScene& compiled, bool on_details,
                        std::shared_ptr<const std::vector<ParticleSystemFile>>* placed, std::string* error) const;
    // One system placed as placeParticles places them (on_details: when it grows on detail instances).
    bool placeSystem(const EnvScene& environment, const CompiledScene& compiled, bool on_details, ParticleScene* scene,
                     std::string* error) const;
    bool anySystemOnDetails() const;
    // project().environment compiled (reusing environment()'s meshes) into *env; the scattered types and
    // the region the objects and fields changed in join *effect.
    bool compileEditedEnvironment(std::shared_ptr<const EnvScene>* env, EditEffect* effect, std::string* error);
    uint64_t currentState() const { return undo_.empty() ? 0 : undo_.back().state; }

    struct Step {
        std::unique_ptr<Command> command;
        uint64_t state;  // unique per executed step: tells the saved state apart from any other
        uint64_t particles_generation = 0;  // particlesGeneration() once it was done, if it changed them
    };

    DocumentOptions options_;
    std::string path_;
    Project project_;
    TileAssets assets_;
    uint64_t tile_generation_ = 1;
    uint64_t tile_live_generation_ = 0;
    // What the live instancer was last reset with, and earlier assets its worker may still be reading (a
    // run in progress when the tile was swapped): freed once it is idle, since undo steps that held them
    // may be gone by then.
    TileAssets live_assets_;
    std::vector<TileAssets> retired_;
    std::shared_ptr<const HeightField> terrain_;
    std::shared_ptr<const EnvScene> environment_;
    uint64_t environment_generation_ = 1;
    std::vector<std::shared_ptr<const EnvScene>> retired_environments_;  // freed once the live worker is idle
    std::shared_ptr<const std::vector<ParticleSystemFile>> particles_ =
        std::make_shared<const std::vector<ParticleSystemFile>>();
    // The systems as their files hold them now (loaded or last saved): save writes those that differ.
    std::shared_ptr<const std::vector<ParticleSystemFile>> saved_particles_ = particles_;
    uint64_t particles_generation_ = 1;
    std::shared_ptr<const std::vector<std::vector<DetailModel>>> variant_models_ =
        std::make_shared<const std::vector<std::vector<DetailModel>>>();
    CompiledScene compiled_;
    std::vector<EditableDensity> densities_;
    uint64_t next_id_ = 1;

    std::vector<Step> undo_, redo_;
    std::unique_ptr<CompoundCommand> stroke_;
    uint64_t stroke_particles_generation_ = 0;  // the open stroke's particle edits (Step::particles_generation)
    uint64_t next_state_ = 1;
    uint64_t saved_state_ = 0;        // ~0: never saved (recovered)
    uint64_t edit_count_ = 0;         // every apply, undo and redo
    uint64_t autosaved_edits_ = 0;    // edit_count_ at the last autosave (or load / save)
    double change_seen_s_ = -1.0;     // maybeAutosave: when it first saw unsaved edits; < 0 none

    // Last: destroyed first, since its worker reads the assets and the compiled fields.
    std::unique_ptr<LiveInstancer> live_;
};

}  // namespace ug
