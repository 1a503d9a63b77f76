// The environmental objects' effects of a scene job (snow cover, icicles, the objects' base geometry), for
// the CLI's exports: computed once, reported on stderr and in the statistics, handed to the exporter as
// static meshes.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/scene_job.h"
#include "env/env_effects.h"
#include "io/mesh_instances.h"

namespace ug::cli {

struct SceneEnvironmentOutput {
    EnvEffects effects;
    std::vector<MeshInstances> meshes;  // env/<type>, snow/..., icicles/... (env/env_outputs.h)
    nlohmann::json stats;               // {"objects", "effect_computations", "snow_triangles", ...}; null when
                                        // the scene has no environmental objects
    double seconds = 0.0;
};

// Nothing to do (and true) when the project has no environment. `region` (may be null): only the objects
// whose origin lies in it (env_effects.h). Errors name the scene file, the JSON Pointer and the reason.
bool computeSceneEnvironment(const SceneJob& job, int threads, const Bounds* region, bool quiet,
                             SceneEnvironmentOutput* out, std::string* error);

}  // namespace ug::cli
