#include "cli/strands_job.h"

#include <cstdio>

#include "scene/scene_particles.h"

namespace ug::cli {

bool computeSceneStrands(const SceneJob& job, int threads, const Bounds* region, bool quiet,
                         std::vector<MeshInstances>* meshes, nlohmann::json* stats, std::string* error) {
    *stats = nullptr;
    if (!job.particles || job.particles->empty()) return true;
    SceneStrandStats st;
    if (!growSceneParticles(*job.particles, job.path, threads, region, meshes, &st, error)) return false;
    *stats = {{"systems", st.systems},
              {"strands", st.strands},
              {"points", st.points},
              {"triangles", st.triangles},
              {"seconds", st.seconds}};
    if (!quiet)
        std::fprintf(stderr, "  particles: %zu systems, %llu strands, %llu triangles in %.3f s\n", st.systems,
                     static_cast<unsigned long long>(st.strands), static_cast<unsigned long long>(st.triangles),
                     st.seconds);
    return true;
}

}  // namespace ug::cli
