#include "scene/scene_particles.h"

#include <chrono>
#include <set>

#include "analysis/placed_instances.h"
#include "particles/particle_output.h"

namespace ug {

namespace {

ParticleObstacle obstacleOf(const EnvScene& environment, uint32_t object) {
    const EnvObject& o = environment.objects()[object];
    return ParticleObstacle{.mesh = environment.types()[o.type].mesh,
                            .translation = o.placement.t,
                            .cos_yaw = o.placement.c,
                            .sin_yaw = o.placement.s,
                            .scale = o.placement.scale};
}

int64_t envTypeNamed(const EnvScene* environment, const std::string& name) {
    if (environment)
        for (size_t t = 0; t < environment->types().size(); ++t)
            if (environment->types()[t].desc.name == name) return int64_t(t);
    return -1;
}

// Appends the part of triangle abc (object space) at or below height h, as 0, 1 or 2 triangles.
void clipBelow(glm::vec3 a, glm::vec3 b, glm::vec3 c, float h, std::vector<glm::vec3>* out) {
    const glm::vec3 in[3] = {a, b, c};
    glm::vec3 poly[4];
    int n = 0;
    for (int i = 0; i < 3; ++i) {
        const glm::vec3 p = in[i], q = in[(i + 1) % 3];
        const bool p_in = p.z <= h, q_in = q.z <= h;
        if (p_in) poly[n++] = p;
        if (p_in != q_in) poly[n++] = p + (q - p) * ((h - p.z) / (q.z - p.z));
    }
    for (int i = 1; i + 1 < n; ++i) out->insert(out->end(), {poly[0], poly[i], poly[i + 1]});
}

// Gathered surfaces beyond this are refused before they are built (a street of facades, unbanded).
constexpr size_t kMaxGatheredTriangles = 4'000'000;

// An objects generator's surfaces: every object of its type, in the scene's order, the triangles that
// face sideways (when asked) clipped to the height band, in world coordinates; null when none is left.
bool objectSurfaces(const EnvScene& environment, uint32_t type, const ParticleGenerator& g,
                    std::shared_ptr<const TriangleMesh>* out_mesh, std::string* error) {
    out_mesh->reset();
    const TriangleMesh& m = *environment.types()[type].mesh;
    std::vector<glm::vec3> local;  // the kept pieces of one object, three corners each
    for (size_t t = 0; t < m.triangleCount(); ++t) {
        const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                        c = m.positions[m.indices[3 * t + 2]];
        const glm::vec3 n = glm::cross(b - a, c - a);
        const float len = glm::length(n);
        if (!(len > 0.0f)) continue;
        // A turn about z keeps a normal's height: sideways in the model is sideways in the world.
        if (g.sides_only && std::abs(n.z / len) > 0.5f) continue;
        if (g.max_height_m > 0.0f) clipBelow(a, b, c, g.max_height_m, &local);
        else local.insert(local.end(), {a, b, c});
    }
    if (local.empty()) return true;
    size_t objects = 0;
    for (const EnvObject& o : environment.objects()) objects += o.type == type;
    if (objects * (local.size() / 3) > kMaxGatheredTriangles) {
        *error = "the " + std::to_string(objects) + " '" + environment.types()[type].desc.name + "' objects give " +
                 std::to_string(objects * (local.size() / 3)) + " triangles to seed on, more than " +
                 std::to_string(kMaxGatheredTriangles) + " (a max_height_m or sides_only takes fewer)";
        return false;
    }
    auto out = std::make_shared<TriangleMesh>();
    for (size_t o = 0; o < environment.objects().size(); ++o) {
        if (environment.objects()[o].type != type) continue;
        const ParticleObstacle placement = obstacleOf(environment, uint32_t(o));
        for (const glm::vec3& p : local) {
            out->indices.push_back(uint32_t(out->positions.size()));
            out->positions.push_back(placement.toWorld(p));
        }
    }
    if (!out->positions.empty()) *out_mesh = std::move(out);
    return true;
}

bool sameMesh(const std::shared_ptr<const TriangleMesh>& a, const std::shared_ptr<const TriangleMesh>& b) {
    return a == b || (a && b && a->positions == b->positions && a->indices == b->indices);
}

}  // namespace

bool placeAmongObjects(const EnvScene* environment, ParticleScene* scene, std::string* error) {
    // The objects generators first: the reach below grows from what they seed on.
    for (size_t i = 0; i < scene->generators.size(); ++i) {
        ParticleGenerator& g = scene->generators[i];
        if (g.kind != GeneratorKind::Objects) continue;
        const int64_t type = envTypeNamed(environment, g.object_type);
        if (type < 0) {
            *error = "generators[" + std::to_string(i) + "].object_type: the project has no environmental-object type '" +
                     g.object_type + "'";
            return false;
        }
        g.center_m = glm::vec3(0.0f);
        g.scale = 1.0f;
        std::shared_ptr<const TriangleMesh> surfaces;
        if (environment->types()[size_t(type)].mesh &&
            !objectSurfaces(*environment, uint32_t(type), g, &surfaces, error)) {
            *error = "generators[" + std::to_string(i) + "].object_type: " + *error;
            return false;
        }
        if (!sameMesh(g.mesh, surfaces)) g.mesh = std::move(surfaces);
    }
    const Bounds reach = particleReach(*scene);
    std::vector<uint32_t> near;  // the objects within reach, in the scene's order
    if (environment)
        for (size_t o = 0; o < environment->objects().size(); ++o)
            if (overlaps(environment->objects()[o].bounds, reach)) near.push_back(uint32_t(o));
    std::vector<ParticleObstacle> obstacles;
    for (uint32_t o : near)
        if (environment->types()[environment->objects()[o].type].mesh) obstacles.push_back(obstacleOf(*environment, o));
    scene->obstacles = std::move(obstacles);

    for (size_t i = 0; i < scene->attractors.size(); ++i) {
        Attractor& a = scene->attractors[i];
        if (a.kind != AttractorKind::Objects) continue;
        const int64_t type = envTypeNamed(environment, a.object_type);
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
                const ParticleObstacle placement = obstacleOf(*environment, o);
                for (const glm::vec3& q : *local) points.push_back(placement.toWorld(q));
            }
        }
        if (!a.points || *a.points != points) a.points = std::make_shared<const std::vector<glm::vec3>>(std::move(points));
    }
    return true;
}

namespace {

// The instances of `type` whose origin lies in `box`, settled as the project settles them.
bool instancesInBox(const DetailPlacement& in, uint32_t type, const Bounds& box, std::vector<PlacedInstance>* out,
                    std::string* error) {
    out->clear();
    if (!overlaps(box, in.instancer->extent)) return true;
    const bool settled = in.settle && in.settle->settings.enabled;
    // Settled drops depend on the selection a little beyond the box (settling.h, "Locality").
    const float halo = settled ? settleHaloMetres(*in.settle) : 0.0f;
    InstanceStore store;
    InstanceStats stats;
    const InstanceOptions options{.threads = in.threads};
    if (!instantiateRegion(*in.instancer, Bounds{box.lo - halo, box.hi + halo}, options, &store, &stats, error))
        return false;
    SettledDrops drops;
    if (settled) {
        settleAll(*in.settle, store, in.threads, &drops);
        InstanceStore own;
        SettledDrops own_drops;
        cropToRegion(store, drops, *in.instancer->tile, box, &own, &own_drops);
        store = std::move(own);
        drops = std::move(own_drops);
    }
    for (const PlacedInstance& p : placeInstances(store, *in.instancer->tile, settled ? &drops : nullptr))
        if (p.type == type) out->push_back(p);
    return true;
}

}  // namespace

bool growsOnDetails(const ParticleScene& scene) {
    for (const ParticleGenerator& g : scene.generators)
        if (g.kind == GeneratorKind::Details) return true;
    return false;
}

bool placeOnDetails(const DetailPlacement& in, ParticleScene* scene, std::string* error) {
    std::vector<ParticleObstacle> obstacles;
    for (size_t i = 0; i < scene->generators.size(); ++i) {
        ParticleGenerator& g = scene->generators[i];
        if (g.kind != GeneratorKind::Details) continue;
        const std::string at = "generators[" + std::to_string(i) + "].detail_type";
        int64_t type = -1;
        for (size_t t = 0; in.models && t < in.models->size(); ++t)
            if ((*in.models)[t].name == g.detail_type) type = int64_t(t);
        if (type < 0 || !in.instancer) {
            *error = at + ": the project has no detail type '" + g.detail_type + "'";
            return false;
        }
        g.scale = 1.0f;
        std::vector<PlacedInstance> instances;
        if (!instancesInBox(in, uint32_t(type), Bounds::fromCenterHalf(g.center_m, g.half_extents_m), &instances, error)) {
            *error = at + ": " + *error;
            return false;
        }
        // The instances share their type's mesh; the models outlive the obstacles through this alias.
        const std::shared_ptr<const TriangleMesh> mesh(in.models, &(*in.models)[size_t(type)].mesh);
        if (instances.size() * mesh->triangleCount() > kMaxGatheredTriangles) {
            *error = at + ": the " + std::to_string(instances.size()) + " '" + g.detail_type + "' instances in the box give " +
                     std::to_string(instances.size() * mesh->triangleCount()) + " triangles to seed on, more than " +
                     std::to_string(kMaxGatheredTriangles) + " (a smaller box takes fewer)";
            return false;
        }
        auto surfaces = std::make_shared<TriangleMesh>();
        for (const PlacedInstance& p : instances) {
            const ParticleObstacle placed{.mesh = mesh, .translation = p.position, .scale = p.scale, .rotation = p.rotation};
            obstacles.push_back(placed);
            for (size_t t = 0; t < mesh->triangleCount(); ++t) {
                const glm::vec3 a = placed.toWorld(mesh->positions[mesh->indices[3 * t]]),
                                b = placed.toWorld(mesh->positions[mesh->indices[3 * t + 1]]),
                                c = placed.toWorld(mesh->positions[mesh->indices[3 * t + 2]]);
                const glm::vec3 n = glm::cross(b - a, c - a);
                const float len = glm::length(n);
                if (!(len > 0.0f) || n.z < g.min_normal_z * len) continue;
                for (const glm::vec3& q : {a, b, c}) {
                    surfaces->indices.push_back(uint32_t(surfaces->positions.size()));
                    surfaces->positions.push_back(q - g.center_m);
                }
            }
        }
        std::shared_ptr<const TriangleMesh> kept;
        if (!surfaces->positions.empty()) kept = std::move(surfaces);
        if (!sameMesh(g.mesh, kept)) g.mesh = std::move(kept);
    }
    scene->detail_obstacles = std::move(obstacles);
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

bool centreInside(const Bounds& region, const LargeVector<glm::vec3>& points) {
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
