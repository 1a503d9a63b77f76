#include "cli/scene_job.h"

#include <chrono>
#include <cstdio>

namespace ug::cli {

bool loadSceneJob(const std::string& scene, const std::string& cache_dir, int threads, bool quiet, SceneJob* job,
                  std::string* error) {
    job->path = scene;
    if (!loadProject(scene, &job->project, error)) return false;
    // The terrain first: it is cheap to check, and a bad one must not wait for the models and the tile.
    std::shared_ptr<const HeightField> terrain;
    if (!loadTerrain(job->project, &terrain, error)) return false;
    const auto t0 = std::chrono::steady_clock::now();
    if (!loadProjectModels(job->project, &job->models, error)) return false;
    job->models_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    GhostTileInput input = ghostTileInput(job->project, job->models);
    std::string note;
    int last_percent = -1;
    BuildOptions options{.threads = threads, .progress = [&](float f) {
                             const int percent = int(f * 100.0f);
                             if (!quiet && percent / 10 != last_percent / 10) {
                                 std::fprintf(stderr, "\r  building Ghost Tile: %3d%%", percent);
                                 last_percent = percent;
                             }
                         }};
    const bool ok = loadOrBuildGhostTile(cache_dir, input, options, &job->tile, &job->outcome, &note, error);
    if (last_percent >= 0) std::fprintf(stderr, "\n");
    if (!ok) {
        *error = scene + ": " + *error;
        return false;
    }
    if (!note.empty() && !quiet) std::fprintf(stderr, "  note: %s\n", note.c_str());
    return compileScene(job->project, terrain, &job->compiled, error);
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
