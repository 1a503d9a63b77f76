#include "cli/scene_job.h"

#include <cstdio>

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
    return true;
}

InstancerInput instancerInput(const SceneJob& job, uint64_t seed) {
    InstancerInput in;
    in.tile = &job.tile;
    for (const DetailModel& m : job.models) in.models.push_back(&m);
    in.types = job.compiled.types;
    in.extent = job.compiled.extent;
    in.seed = seed;
    return in;
}

}  // namespace ug::cli
