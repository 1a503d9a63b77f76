#include "cli/env_job.h"

#include <chrono>
#include <cstdio>

#include "env/env_outputs.h"

namespace ug::cli {

bool computeSceneEnvironment(const SceneJob& job, int threads, const Bounds* region, bool quiet,
                             SceneEnvironmentOutput* out, std::string* error) {
    *out = SceneEnvironmentOutput{};
    if (!job.environment || job.environment->empty()) return true;
    const auto t0 = std::chrono::steady_clock::now();
    if (!computeEnvEffects(*job.environment, {.threads = threads, .region = region}, &out->effects, error)) {
        *error = job.path + ": " + *error;
        return false;
    }
    out->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    out->meshes = envMeshInstances(*job.environment, out->effects);
    const EnvEffectsStats& st = out->effects.stats;
    size_t copies = 0;  // every mesh copy the exported static meshes draw (an entry without instances: one)
    for (const MeshInstances& m : out->meshes) copies += m.instances.empty() ? 1 : m.instances.size();
    out->stats = {{"objects", st.objects},
                  {"fields", job.environment->fields().size()},
                  {"effect_computations", st.effect_computations},
                  {"snow_triangles", st.snow_triangles},
                  {"snow_triangles_computed", st.snow_triangles_unique},
                  {"terrain_snow_chunks", st.terrain_chunks},
                  {"icicles", st.icicles},
                  {"static_mesh_copies", copies},
                  {"seconds", out->seconds}};
    if (!quiet)
        std::fprintf(stderr, "  environment: %zu objects, %zu effect computations, %llu snow triangles, %llu icicles in %.3f s\n",
                     st.objects, st.effect_computations, static_cast<unsigned long long>(st.snow_triangles),
                     static_cast<unsigned long long>(st.icicles), out->seconds);
    return true;
}

}  // namespace ug::cli
