// A world cut into region jobs for a scheduler (docs/worlds.md): `undergrowth plan` measures the scene and
// writes DIR/plan.json with the Slurm scripts; each task (`instantiate --plan DIR --task I`) writes its
// region's outputs under DIR/regions; `undergrowth join DIR` checks them and puts the world together.
//
// Why this is exact: the instantiator is a pure function of the scene and the seed, and instantiateRegion
// gives disjoint pieces whose union is the whole scene; a task is that function on its region, on any
// machine. The plan pins what decides the outputs (the scene file's hash, the Ghost Tile key, the seed,
// the regions) in its id, and every output carries the id, so a region of another plan, or of a scene
// edited since, is never mistaken for one of this plan.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "field/bounds.h"
#include "instancer/instantiator.h"

namespace ug::cli {

struct PlannedRegion {
    Bounds box;                    // [lo, hi); the outer ones reach past the extent
    uint64_t footprint_bytes = 0;  // measured (measureRegionFootprint) over the box grown by the settle halo
};

struct RegionPlan {
    std::string dir;          // absolute
    std::string scene;        // absolute
    std::string name;         // the project's
    uint64_t scene_hash = 0;  // hashBytes of the scene file
    uint64_t ghost_tile_key = 0;
    uint64_t seed = 0;
    float chunk_size_m = 8.0f;
    Bounds extent;
    // Slurm's --mem per task; the instancer of each task may use half (its max_memory_bytes: the check
    // that refuses oversized jobs), the rest is for the Ghost Tile, the models and the export.
    uint64_t memory_per_job = 0;
    int threads_per_task = 1;
    std::string binary;  // the undergrowth the scripts run
    std::vector<PlannedRegion> regions;
    uint64_t id = 0;  // planId()

    uint64_t instancerBudget() const { return memory_per_job / 2; }
};

constexpr int kMaxPlanTasks = 1000;  // Slurm's default MaxArraySize is 1001 (indices 0..1000)

// The hash of what decides the outputs (scene hash, tile key, seed, chunk, regions).
uint64_t planId(const RegionPlan& plan);

// Cuts the extent into a grid of regions made of whole export chunks (so that no chunk is split between
// two files), as few as fit: starting from one region, the longer side (in chunks per region) is cut once
// more until every region's footprint, grown by halo_m, fits plan->instancerBudget(). Fails when a single
// chunk does not fit, or when more than max_jobs regions would be needed; the message says by how much.
bool cutIntoRegions(const InstancerInput& input, float halo_m, int max_jobs, int threads, RegionPlan* plan,
                    std::string* error);

nlohmann::json planJson(const RegionPlan& plan);
// Reads DIR/plan.json; every field checked (the message names the file, the key and the reason), and the
// stored id must match the fields (a plan edited by hand is refused).
bool readRegionPlan(const std::string& dir, RegionPlan* plan, std::string* error);

// "DIR/regions/region_0007": + ".glb", ".json" (statistics), ".ugi" (instance list, written last).
std::string regionStem(const RegionPlan& plan, size_t task);

// The Slurm scripts: cache.sbatch (the Ghost Tile, once), job.sbatch (the array), join.sbatch, and
// submit.sh, which submits them with dependencies (the cache step only when the plan's cache lacks the
// tile) (extra arguments go to every sbatch: --partition,
// --account, ...). Errors: a path Slurm's #SBATCH lines cannot hold (whitespace, '%').
bool writeSlurmScripts(const RegionPlan& plan, std::string* error);

}  // namespace ug::cli
