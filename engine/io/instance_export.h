// From an instantiation result to a glTF file: rebuilds each instance's frame from its Ghost Tile
// candidate and tile, groups instances by detail type, adds the terrain mesh and the statistics, and
// writes through writeSceneGltf (EXT_mesh_gpu_instancing, chunked). Shared by the CLI and the editor.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "field/bounds.h"
#include "field/height_field.h"
#include "ghosttile/ghost_tile.h"
#include "instancer/instance_store.h"
#include "instancer/settling.h"
#include "io/gltf_scene_export.h"
#include "material/material.h"
#include "mesh/detail_model.h"

namespace ug {

struct InstanceExportOptions {
    float chunk_size_m = 8.0f;
    bool use_instancing_extension = true;
    int terrain_max_cells_per_side = 512;  // the terrain mesh is decimated beyond this
    // Optional, for a caller on a background thread (the editor): called with the fraction done in [0, 1)
    // while instances are gathered and the terrain is meshed; returning false stops the export before
    // anything is written (error "<path>: cancelled"). The final write (writeSceneGltf) is one atomic step
    // and reports no progress.
    std::function<bool(float fraction)> progress;
    // Settled drops of the store's instances (instancer/settling.h), or null: instances where their
    // candidates are.
    const SettledDrops* drops = nullptr;
    // The scene's materials (scene_compile.h, compileSceneMaterials), or null: every mesh with its own
    // base colour, untextured (the look before materials). Types: one per model, same order.
    const SceneMaterials* materials = nullptr;
    // Static meshes written after the detail types and the terrain (io/mesh_instances.h: environmental
    // objects, snow, icicles), or null: none.
    const std::vector<MeshInstances>* static_meshes = nullptr;
    // Looks (scene/detail_looks.h): when instance_looks is set, instances are written per look instead
    // of per type, look l as look_models[l] with materials->types[l]; instance_looks holds each instance's
    // look in the store's order (InstanceStore::forEach), worked out once by the caller (a scattered
    // type's variants: wet leaves in the puddle). Looks [0, types) are the types.
    std::vector<const DetailModel*> look_models;
    const std::vector<uint32_t>* instance_looks = nullptr;
};

// The world frame of candidate j in the tile with packed key tile_key, lowered by its settled drop.
InstanceTransform instanceTransform(const GhostTile& tile, uint64_t tile_key, uint32_t j, float drop_m = 0.0f);

// `terrain` may be null. `stats_json` is a JSON object stored in the scene's extras.
bool exportInstancedScene(const std::string& path, const GhostTile& tile, const std::vector<DetailModel>& models,
                          const InstanceStore& store, const HeightField* terrain, const Bounds& extent,
                          const InstanceExportOptions& options, const std::string& stats_json, std::string* error);

}  // namespace ug
