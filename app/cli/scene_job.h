// What every scene-level command needs: the project, its models, its Ghost Tile (from the verified cache
// or built and cached) and its compiled fields, ready to instantiate.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ghosttile/ghost_tile.h"
#include "ghosttile/ghost_tile_cache.h"
#include "instancer/instantiator.h"
#include "io/instance_export.h"
#include "particles/particle_json.h"
#include "scene/detail_looks.h"
#include "scene/project.h"
#include "env/env_scene.h"
#include "scene/scene_compile.h"

namespace ug::cli {

struct SceneJob {
    std::string path;
    Project project;
    std::vector<DetailModel> models;
    GhostTile tile;
    CacheOutcome outcome = CacheOutcome::BuiltMissing;
    double models_seconds = 0.0;
    CompiledScene compiled;
    std::shared_ptr<const EnvScene> environment;  // never null after a load
    std::vector<std::vector<DetailModel>> variant_models;  // scattered types' variants, [type][k]
    std::shared_ptr<const std::vector<ParticleSystemFile>> particles;  // the project's, read and placed
};

// What a job's exports look like: a material per look and the looks themselves (scene/detail_looks.h).
struct SceneLooks {
    SceneMaterials materials;
    DetailLooks looks;
};
SceneLooks sceneLooks(const SceneJob& job);
// The job's instanceLooks (scene/detail_looks.h): worked out once for both the statistics and the export
// (a variant's look asks the environment). Empty when no type has variants.
std::vector<uint32_t> instanceLooks(const SceneJob& job, const SceneLooks& looks, const InstanceStore& store,
                                    int threads);
// Points the export's materials and looks at `looks` and `instance_looks`, which must outlive the options.
void useLooks(const SceneLooks& looks, const std::vector<uint32_t>& instance_looks, InstanceExportOptions* options);
// {"<look name>": instances, ...}: what each exported detail mesh holds (the types' counts when no type
// has variants).
nlohmann::json lookCountsJson(const SceneJob& job, const SceneLooks& looks, const InstanceStore& store,
                              const std::vector<uint32_t>& instance_looks);

// Loads the project, fits its models, loads or builds the Ghost Tile (progress on stderr unless quiet) and
// compiles the fields. Errors name the scene file.
bool loadSceneJob(const std::string& scene_path, const std::string& cache_dir, int threads, bool quiet,
                  SceneJob* job, std::string* error);

// The instantiator's input for the job; `seed` overrides the project's instantiation seed.
InstancerInput instancerInput(const SceneJob& job, uint64_t seed);

// The statistics file of an instantiation (CLI `instantiate --stats`, `run`): totals, per type, the
// extent and the Ghost Tile. `region` is null for the whole scene.
nlohmann::json instanceStatsJson(const SceneJob& job, const InstanceStats& stats, uint64_t seed, int threads,
                                 const Bounds* region);

}  // namespace ug::cli
