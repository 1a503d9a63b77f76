#include "scene/scene_load.h"

#include <chrono>
#include <cmath>

#include "scene/scene_particles.h"

namespace ug {

namespace {

std::string sceneName(const Project& project) { return project.source.empty() ? project.name : project.source; }

// The editor's extent for a project the compiler refuses only for having no density yet: the project's
// own, else empty. Any other reason (an unbounded field without an extent) still stands.
bool emptyExtentScene(const Project& project, const std::shared_ptr<const HeightField>& terrain,
                      const std::shared_ptr<const EnvScene>& environment, CompiledScene* out, std::string* error) {
    if (project.extent) return false;
    CompiledScene scene;
    scene.terrain = terrain;
    scene.environment = environment;
    scene.types.resize(project.detail_types.size());
    for (size_t t = 0; t < scene.types.size(); ++t)
        if (!compileDetailType(project, t, terrain, &scene.types[t], error, environment)) return false;
    const Bounds e = computeSceneExtent(project, scene);
    bool flat = false;
    for (int a = 0; a < 3; ++a) flat = flat || !(e.lo[a] < e.hi[a]);
    if (!e.empty() && !flat) return false;
    scene.extent = Bounds{};
    *out = std::move(scene);
    return true;
}

// The systems' "details" generators seed on the instances the project makes, so they are placed once
// the Ghost Tile and the densities are known (scene_particles.h placeOnDetails).
bool placeParticlesOnDetails(const Project& project, int threads, LoadedScene* scene, std::string* error) {
    bool any = false;
    for (const ParticleSystemFile& s : *scene->particles) any = any || growsOnDetails(s.scene);
    if (!any) return true;
    const InstancerInput instancer = instancerInputOf(*scene->tile, *scene->models, scene->compiled, project.instantiation_seed);
    const SettleInput settle =
        settleInput(project, scene->terrain, *scene->tile, *scene->models, scene->environment.get());
    if (settle.settings.enabled && !validateSettleInput(settle, error)) return false;
    const DetailPlacement placement{.instancer = &instancer, .settle = &settle, .models = scene->models, .threads = threads};
    auto systems = std::make_shared<std::vector<ParticleSystemFile>>(*scene->particles);
    for (size_t i = 0; i < systems->size(); ++i)
        if (growsOnDetails((*systems)[i].scene) && !placeOnDetails(placement, &(*systems)[i].scene, error)) {
            *error = "/particles/" + std::to_string(i) + ": " + *error;
            return false;
        }
    scene->particles = std::move(systems);
    return true;
}

}  // namespace

bool loadScene(const Project& project, const SceneLoadOptions& options, LoadedScene* out, std::string* error) {
    const std::string name = sceneName(project);
    LoadedScene scene;
    if (!loadTerrain(project, &scene.terrain, error)) return false;
    const auto t0 = std::chrono::steady_clock::now();
    scene.models = std::make_shared<std::vector<DetailModel>>();
    if (!loadProjectModels(project, scene.models.get(), error)) {
        if (project.source.empty()) *error = name + ": " + *error;  // else the message starts with the file
        return false;
    }
    scene.models_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // The environment before the densities (scattered types read theirs from it) and before the particle
    // systems (they grow around its objects). Both before the Ghost Tile: a bad file fails at once, not
    // after the tile's build.
    auto env = std::make_shared<EnvScene>();
    if (!compileEnvScene(project.environment, project.base_dir, name, scene.terrain, env.get(), error)) return false;
    scene.environment = std::move(env);
    auto particles = std::make_shared<std::vector<ParticleSystemFile>>();
    if (!loadSceneParticles(project, scene.terrain, scene.environment.get(), particles.get(), error)) return false;
    scene.particles = std::move(particles);
    const GhostTileInput input = ghostTileInput(project, *scene.models);
    scene.tile = std::make_shared<GhostTile>();
    if (!loadOrBuildGhostTile(options.cache_dir, input,
                              BuildOptions{.threads = options.threads, .progress = options.tile_progress},
                              scene.tile.get(), &scene.outcome, &scene.cache_note, error)) {
        *error = name + ": " + *error;
        return false;
    }
    if (!compileScene(project, scene.terrain, &scene.compiled, error, scene.environment)) {
        std::string first = *error;
        if (!options.allow_empty_extent ||
            !emptyExtentScene(project, scene.terrain, scene.environment, &scene.compiled, error)) {
            *error = first;
            return false;
        }
    }
    if (!placeParticlesOnDetails(project, options.threads, &scene, error)) {
        *error = name + ": " + *error;
        return false;
    }
    scene.variant_models = std::make_shared<std::vector<std::vector<DetailModel>>>();
    if (!loadScatterVariantModels(project, scene.variant_models.get(), error)) {
        if (project.source.empty()) *error = name + ": " + *error;
        return false;
    }
    *out = std::move(scene);
    return true;
}

}  // namespace ug
