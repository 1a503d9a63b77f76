// The project's particle systems for the CLI's exports (scene/scene_particles.h): grown once, reported on
// stderr and in the statistics ("particles"), handed to the exporter as static meshes beside the
// environment's.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/scene_job.h"
#include "io/mesh_instances.h"

namespace ug::cli {

// Appends one mesh "strands/<name>" per system (the region's only, when `region` is set) to *meshes.
// *stats: {"systems", "strands", "points", "triangles", "seconds"}, or null when the project has none.
bool computeSceneStrands(const SceneJob& job, int threads, const Bounds* region, bool quiet,
                         std::vector<MeshInstances>* meshes, nlohmann::json* stats, std::string* error);

}  // namespace ug::cli
