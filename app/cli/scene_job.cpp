#include "cli/scene_job.h"

#include <cstdio>

#include "instancer/tile_coord.h"
#include "scene/scene_load.h"

namespace ug::cli {

bool loadSceneJob(const std::string& scene, const std::string& cache_dir, int threads, bool quiet, SceneJob* job,
                  std::string* error) {
    job->path = scene;
    if (!loadProject(scene, &job->project, error)) return false;
    int last_percent = -1;
    SceneLoadOptions options{.cache_dir = cache_dir, .threads = threads, .tile_progress = [&](float f) {
                                 const int percent = int(f * 100.0f);
                                 if (!quiet && percent / 10 != last_percent / 10) {
                                     std::fprintf(stderr, "\r  building Ghost Tile: %3d%%", percent);
                                     last_percent = percent;
                                 }
                             }};
    LoadedScene loaded;
    const bool ok = loadScene(job->project, options, &loaded, error);
    if (last_percent >= 0) std::fprintf(stderr, "\n");
    if (!ok) return false;
    if (!loaded.cache_note.empty() && !quiet) std::fprintf(stderr, "  note: %s\n", loaded.cache_note.c_str());
    // The job owns its models and tile by value (the CLI's commands take them by reference).
    job->models = std::move(*loaded.models);
    job->tile = std::move(*loaded.tile);
    job->outcome = loaded.outcome;
    job->models_seconds = loaded.models_seconds;
    job->compiled = std::move(loaded.compiled);
    job->environment = std::move(loaded.environment);
    job->variant_models = std::move(*loaded.variant_models);
    job->particles = std::move(loaded.particles);
    return true;
}

SceneLooks sceneLooks(const SceneJob& job) {
    SceneLooks out;
    out.materials = compileSceneMaterials(job.project, job.models, &job.variant_models);
    out.looks = detailLooks(job.project, job.models, job.variant_models, job.environment);
    return out;
}

std::vector<uint32_t> instanceLooks(const SceneJob& job, const SceneLooks& looks, const InstanceStore& store,
                                    int threads) {
    return ug::instanceLooks(looks.looks, job.tile.candidates, job.tile.settings.tile_size_m, store, threads);
}

nlohmann::json lookCountsJson(const SceneJob& job, const SceneLooks& looks, const InstanceStore& store,
                              const std::vector<uint32_t>& instance_looks) {
    std::vector<uint64_t> counts(looks.looks.size(), 0);
    if (instance_looks.empty())
        store.forEach([&](uint64_t, uint32_t j) { ++counts[job.tile.candidates.type[j]]; });
    else
        for (uint32_t look : instance_looks) ++counts[look];
    nlohmann::json out = nlohmann::json::object();
    for (size_t l = 0; l < counts.size(); ++l) out[looks.looks.models[l]->name] = counts[l];
    return out;
}

void useLooks(const SceneLooks& looks, const std::vector<uint32_t>& instance_looks, InstanceExportOptions* options) {
    options->materials = &looks.materials;
    if (instance_looks.empty()) return;
    options->look_models = looks.looks.models;
    options->instance_looks = &instance_looks;
}

InstancerInput instancerInput(const SceneJob& job, uint64_t seed) {
    return instancerInputOf(job.tile, job.models, job.compiled, seed);
}

}  // namespace ug::cli
