// One instantiation job from a scene file to glTF and statistics: the work of `undergrowth instantiate`,
// shared by its plain form (one scene or one --region of it) and by a plan's tasks (region_plan.h), so
// that a task writes exactly what `instantiate --region` writes for its region.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cli/scene_job.h"
#include "field/bounds.h"
#include "instancer/instantiator.h"
#include "instancer/settling.h"
#include "io/mesh_instances.h"

namespace ug::cli {

struct InstantiateRequest {
    std::string scene;
    std::string out;         // .glb or .gltf
    std::string stats_path;  // empty: no statistics file
    std::string cache_dir;   // the Ghost Tile cache
    // Plan tasks: the selected ids and drops (io/instance_list_file.h) with this header, for `join`;
    // written last, so that its presence means every output of the task is complete.
    std::string instances_path;
    nlohmann::json instances_header = nlohmann::json::object();
    nlohmann::json stats_extra = nlohmann::json::object();  // merged into the statistics
    int threads = 0;
    std::optional<uint64_t> seed;  // default: the project's instantiation seed
    std::optional<Bounds> region;  // [lo, hi); the export's terrain is cut to it
    float chunk_size_m = -1.0f;    // <= 0: the project's
    bool plain_nodes = false;
    bool measure = false;
    uint64_t max_memory_bytes = InstanceOptions{}.max_memory_bytes;
    uint64_t expected_tile_key = 0;  // plan tasks: the plan's Ghost Tile key (0: any)
};

// Prints the summary line on stdout and errors on stderr (prefixed by `command`); returns the exit code
// (0 done, 1 the job failed).
int runInstantiation(const InstantiateRequest& request, const char* command);

// Writes the job's instances as glTF the way every CLI export does (looks, materials, chunks): `drops` and
// `static_meshes` may be null; the terrain is meshed inside `terrain_box`; chunk_size_m <= 0 is the
// project's. Adds "instances_per_look" to *stats, which goes into the file's extras.
bool exportJobInstances(const SceneJob& job, const InstanceStore& store, const SettledDrops* drops,
                        const std::vector<MeshInstances>* static_meshes, const Bounds& terrain_box,
                        float chunk_size_m, bool plain_nodes, int threads, nlohmann::json* stats, const std::string& out,
                        std::string* error);

// `undergrowth instantiate --plan DIR --task I`: region I of the plan in DIR (region_plan.h).
int runPlanTask(const std::string& plan_dir, const std::string& task, int threads);

}  // namespace ug::cli
