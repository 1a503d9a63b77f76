#include "scene/scene_particles.h"

#include <chrono>
#include <set>

#include "particles/particle_output.h"

namespace ug {

bool placeAmongObjects(const EnvScene* environment, ParticleScene* scene, std::string* error) {
    const Bounds reach = particleReach(*scene);
    std::vector<uint32_t> near;  // the objects within reach, in the scene's order
    if (environment)
        for (size_t o = 0; o < environment->objects().size(); ++o)
            if (overlaps(environment->objects()[o].bounds, reach)) near.push_back(uint32_t(o));
    const auto placementOf = [&](uint32_t o) {
        const EnvPlacement& pl = environment->objects()[o].placement;
        return ParticleObstacle{.mesh = environment->types()[environment->objects()[o].type].mesh,
                                .translation = pl.t, .cos_yaw = pl.c, .sin_yaw = pl.s, .scale = pl.scale};
    };
    std::vector<ParticleObstacle> obstacles;
    for (uint32_t o : near)
        if (environment->types()[environment->objects()[o].type].mesh) obstacles.push_back(placementOf(o));
    scene->obstacles = std::move(obstacles);

    for (size_t i = 0; i < scene->attractors.size(); ++i) {
        Attractor& a = scene->attractors[i];
        if (a.kind != AttractorKind::Objects) continue;
        int64_t type = -1;
        if (environment)
            for (size_t t = 0; t < environment->types().size(); ++t)
                if (environment->types()[t].desc.name == a.object_type) type = int64_t(t);
        if (type < 0) {
            *error = "attractors[" + std::to_string(i) + "].object_type: the project has no environmental-object type '" +
                     a.object_type + "'";
            return false;
        }
        const std::shared_ptr<const TriangleMesh>& mesh = environment->types()[size_t(type)].mesh;
        std::vector<glm::vec3> points;
        if (mesh && mesh->triangleCount() > 0) {
            const auto local = meshAttractorPoints(mesh, a.point_count);
            for (uint32_t o : near) {
                if (environment->objects()[o].type != uint32_t(type)) continue;
                if (points.size() + local->size() > kMaxObjectAttractorPoints) {
                    *error = "attractors[" + std::to_string(i) + "].points: the '" + a.object_type +
                             "' objects within reach times " + std::to_string(a.point_count) +
                             " points exceed " + std::to_string(kMaxObjectAttractorPoints) + " (take fewer points)";
                    return false;
                }
                const ParticleObstacle placement = placementOf(o);
                for (const glm::vec3& q : *local) points.push_back(placement.toWorld(q));
            }
        }
        if (!a.points || *a.points != points) a.points = std::make_shared<const std::vector<glm::vec3>>(std::move(points));
    }
    return true;
}

bool loadSceneParticles(const Project& project, const std::shared_ptr<const HeightField>& terrain,
                        const EnvScene* environment, std::vector<ParticleSystemFile>* out, std::string* error) {
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
        if (!placeAmongObjects(environment, &system.scene, error)) {
            *error = at + ": " + *error;
            return false;
        }
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
