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
    // Without looks each type is its own look.
    std::vector<const DetailModel*> looks = options.look_models;
    if (options.instance_looks && options.instance_looks->size() != store.instanceCount()) {
        if (error) *error = path + ": " + std::to_string(options.instance_looks->size()) + " looks for " +
                            std::to_string(store.instanceCount()) + " instances";
        return false;
    }
    if (!options.instance_looks) {
        looks.clear();
        for (const DetailModel& m : models) looks.push_back(&m);
    }
    if (looks.size() < models.size()) {
        if (error) *error = path + ": " + std::to_string(looks.size()) + " looks for " + std::to_string(models.size()) +
                            " detail types";
        return false;
    }
    if (options.materials && options.materials->types.size() < looks.size()) {
        if (error) *error = path + ": " + std::to_string(options.materials->types.size()) + " materials for " +
                            std::to_string(looks.size()) + " detail looks";
        return false;
    }
    SceneExport scene;
    scene.delta_m = tile.settings.delta_m;
    scene.chunk_size_m = options.chunk_size_m;
    scene.use_instancing_extension = options.use_instancing_extension;
    scene.scene_extras_json = stats_json;
    scene.types.resize(looks.size());
    for (size_t i = 0; i < looks.size(); ++i) {
        scene.types[i].name = looks[i]->name;
        scene.types[i].mesh = &looks[i]->mesh;
        scene.types[i].collision_spheres = looks[i]->spheres;
        if (options.materials) scene.types[i].material = &options.materials->types[i];
    }
    // Gathering is most of the work before the write: 0.8 of the reported fraction, polled every 16k
    // instances (a callback per instance would cost more than the transform).
    const uint64_t total = store.instanceCount();
    uint64_t done = 0;
    bool cancelled = false;
    uint64_t index = 0;
    bool bad_look = false;
    forEachSettled(store, options.drops, [&](uint64_t key, uint32_t j, float drop_m) {
        if (cancelled || bad_look) return;
        const InstanceTransform t = instanceTransform(tile, key, j, drop_m);
        const uint32_t look = options.instance_looks ? (*options.instance_looks)[index++] : c.type[j];
        if (look >= scene.types.size()) {
            bad_look = true;
            return;
        }
        scene.types[look].instances.push_back(t);
        if (options.progress && (++done & 0x3fff) == 0)
            cancelled = !options.progress(0.8f * float(done) / float(total));
    });
    if (bad_look) {
        if (error) *error = path + ": an instance's look is beyond the " + std::to_string(looks.size()) + " looks";
        return false;
    }
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
