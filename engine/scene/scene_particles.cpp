#include "scene/scene_particles.h"

#include <chrono>
#include <set>

#include "particles/particle_output.h"

namespace ug {

bool loadSceneParticles(const Project& project, const std::shared_ptr<const HeightField>& terrain,
                        std::vector<ParticleSystemFile>* out, std::string* error) {
    std::vector<ParticleSystemFile> systems;
    std::set<std::string> names;
    for (size_t i = 0; i < project.particles.size(); ++i) {
        const ParticleSystemRef& ref = project.particles[i];
        const std::string at = (project.source.empty() ? project.name : project.source) + ": /particles/" +
                               std::to_string(i);
        ParticleSystemFile system;
        if (!loadParticleSystem(resolveProjectPath(project, ref.file), &system, error)) {
            *error = at + "/file: " + *error;
            return false;
        }
        if (!ref.name.empty()) system.name = ref.name;
        if (!names.insert(system.name).second) {
            *error = at + ": a particle system named '" + system.name +
                     "' is already in the scene; give this one a \"name\" of its own";
            return false;
        }
        translateParticleScene(&system.scene, ref.offset_m);
        system.scene.terrain = terrain;
        // Moved past the coordinate limit the file's own positions were checked against.
        if (!validateParticleScene(system.scene, error)) {
            *error = at + "/offset_m: " + *error;
            return false;
        }
        systems.push_back(std::move(system));
    }
    *out = std::move(systems);
    return true;
}

namespace {

bool centreInside(const Bounds& region, const std::vector<glm::vec3>& points) {
    Bounds b;
    for (const glm::vec3& p : points) b = unite(b, Bounds{p, p});
    const glm::vec3 c = 0.5f * (b.lo + b.hi);
    for (int a = 0; a < 3; ++a)
        if (!(c[a] >= region.lo[a] && c[a] < region.hi[a])) return false;
    return true;
}

}  // namespace

bool growSceneParticles(const std::vector<ParticleSystemFile>& systems, const std::string& source, int threads,
                        const Bounds* region, std::vector<MeshInstances>* meshes, SceneStrandStats* stats,
                        std::string* error) {
    const auto t0 = std::chrono::steady_clock::now();
    *stats = SceneStrandStats{};
    for (const ParticleSystemFile& system : systems) {
        Strands strands;
        std::vector<MeshInstances> own;  // the tubes, then the mesh generators' surfaces
        if (!appendParticleSystemMeshes(system, threads, &strands, &own, error)) {
            *error = source + ": particle system '" + system.name + "': " + *error;
            return false;
        }
        // Grown before the test: where a system lies is known from its strands only.
        if (region && !centreInside(*region, strands.points)) continue;
        ++stats->systems;
        stats->strands += strands.size();
        stats->points += strands.points.size();
        stats->triangles += own.front().mesh->triangleCount();
        for (MeshInstances& m : own) meshes->push_back(std::move(m));
    }
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return true;
}

}  // namespace ug
