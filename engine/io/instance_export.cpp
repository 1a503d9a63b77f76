#include "io/instance_export.h"

#include "instancer/tile_coord.h"
#include "mesh/terrain_mesh.h"

namespace ug {

InstanceTransform instanceTransform(const GhostTile& tile, uint64_t tile_key, uint32_t j, float drop_m) {
    const CandidateSet& c = tile.candidates;
    InstanceTransform t;
    t.position = tileOrigin(unpackTile(tile_key), tile.settings.tile_size_m) + c.position[j];
    t.position.z -= drop_m;
    t.rotation = c.rotation[j];
    t.scale = c.scale[j];
    return t;
}

bool exportInstancedScene(const std::string& path, const GhostTile& tile, const std::vector<DetailModel>& models,
                          const InstanceStore& store, const HeightField* terrain, const Bounds& extent,
                          const InstanceExportOptions& options, const std::string& stats_json, std::string* error) {
    const CandidateSet& c = tile.candidates;
    if (models.size() != c.typeCount()) {
        if (error) *error = path + ": " + std::to_string(models.size()) + " models for " +
                            std::to_string(c.typeCount()) + " detail types";
        return false;
    }
    if (options.materials && options.materials->types.size() != models.size()) {
        if (error) *error = path + ": " + std::to_string(options.materials->types.size()) + " materials for " +
                            std::to_string(models.size()) + " detail types";
        return false;
    }
    SceneExport scene;
    scene.delta_m = tile.settings.delta_m;
    scene.chunk_size_m = options.chunk_size_m;
    scene.use_instancing_extension = options.use_instancing_extension;
    scene.scene_extras_json = stats_json;
    scene.types.resize(models.size());
    for (size_t i = 0; i < models.size(); ++i) {
        scene.types[i].name = models[i].name;
        scene.types[i].mesh = &models[i].mesh;
        scene.types[i].collision_spheres = models[i].spheres;
        if (options.materials) scene.types[i].material = &options.materials->types[i];
    }
    // Gathering is most of the work before the write: 0.8 of the reported fraction, polled every 16k
    // instances (a callback per instance would cost more than the transform).
    const uint64_t total = store.instanceCount();
    uint64_t done = 0;
    bool cancelled = false;
    forEachSettled(store, options.drops, [&](uint64_t key, uint32_t j, float drop_m) {
        if (cancelled) return;
        scene.types[c.type[j]].instances.push_back(instanceTransform(tile, key, j, drop_m));
        if (options.progress && (++done & 0x3fff) == 0)
            cancelled = !options.progress(0.8f * float(done) / float(total));
    });
    auto stopped = [&](float fraction) {
        if (cancelled || (options.progress && !options.progress(fraction))) {
            if (error) *error = path + ": cancelled";
            return true;
        }
        return false;
    };
    if (stopped(0.8f)) return false;
    TriangleMesh terrain_mesh;
    if (terrain) {
        if (!heightFieldMesh(*terrain, extent, options.terrain_max_cells_per_side, &terrain_mesh, error)) {
            if (error) *error = path + ": terrain: " + *error;
            return false;
        }
        scene.terrain = &terrain_mesh;
        if (options.materials) scene.terrain_material = &options.materials->terrain;
    }
    if (stopped(0.9f)) return false;
    if (options.static_meshes) scene.meshes = *options.static_meshes;
    return writeSceneGltf(path, scene, error);
}

}  // namespace ug
