// One load-and-compile pipeline for a project, used by the CLI's scene jobs, the bench and the editor's
// document alike, so a scene means the same thing wherever it is opened:
//   terrain (cheap to check, so first) -> detail models -> Ghost Tile (verified cache or built) ->
//   compiled density fields -> the environment (engine/env: the object tree, its fields and effects'
//   inputs).
//
//   LoadedScene scene;
//   if (!loadScene(project, SceneLoadOptions{.cache_dir = "out/cache"}, &scene, &error)) report(error);
//
// Errors name the project file (Project::source, else its name), the JSON Pointer and the reason.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "env/env_scene.h"
#include "ghosttile/ghost_tile.h"
#include "ghosttile/ghost_tile_cache.h"
#include "mesh/detail_model.h"
#include "particles/particle_json.h"
#include "scene/project.h"
#include "scene/scene_compile.h"

namespace ug {

struct SceneLoadOptions {
    std::string cache_dir;                      // Ghost Tile cache folder
    int threads = 0;                            // Ghost Tile build (0 = all hardware threads)
    std::function<void(float)> tile_progress;   // the Ghost Tile build's progress, when it builds
    // A project with no density anywhere yet (a new or erased one) loads with an empty extent instead of
    // failing: the editor opens it, the CLI has nothing to instantiate and refuses it.
    bool allow_empty_extent = false;
};

struct LoadedScene {
    std::shared_ptr<const HeightField> terrain;  // null when the project has none
    std::shared_ptr<std::vector<DetailModel>> models;
    std::shared_ptr<GhostTile> tile;
    CacheOutcome outcome = CacheOutcome::BuiltMissing;
    std::string cache_note;        // why a cache file was refused or could not be written ("" if none)
    double models_seconds = 0.0;   // loading and fitting the detail models
    CompiledScene compiled;
    std::shared_ptr<const EnvScene> environment;  // never null: empty for a project without one
    // Scattered types' variants (loadScatterVariantModels): [type][variant], empty for other types.
    std::shared_ptr<std::vector<std::vector<DetailModel>>> variant_models;
    // The project's particle systems, read and placed (scene/scene_particles.h); grown by the outputs.
    std::shared_ptr<const std::vector<ParticleSystemFile>> particles;
};

bool loadScene(const Project& project, const SceneLoadOptions& options, LoadedScene* out, std::string* error);

}  // namespace ug
