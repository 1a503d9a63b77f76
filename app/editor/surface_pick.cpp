#include "editor/surface_pick.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "env/env_scene.h"

namespace ug::editor {

namespace {

// The ray's entry distance into an axis-aligned box, or +infinity when it misses it.
float rayBoxEntry(const Ray& ray, const Bounds& box) {
    float lo = 0.0f, hi = std::numeric_limits<float>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (std::abs(ray.direction[a]) < 1e-12f) {
            if (ray.origin_m[a] < box.lo[a] || ray.origin_m[a] > box.hi[a]) return std::numeric_limits<float>::infinity();
            continue;
        }
        float t0 = (box.lo[a] - ray.origin_m[a]) / ray.direction[a];
        float t1 = (box.hi[a] - ray.origin_m[a]) / ray.direction[a];
        if (t0 > t1) std::swap(t0, t1);
        lo = std::max(lo, t0);
        hi = std::min(hi, t1);
        if (lo > hi) return std::numeric_limits<float>::infinity();
    }
    return lo;
}

// The nearest triangle of `mesh` along o + t·d (t > 0; d need not be unit: t is then the caller's
// parameter), with that triangle's normal (by its winding, unnormalised). Brute force: one object's
// mesh, once a frame while placing.
float nearestTriangle(const TriangleMesh& mesh, glm::vec3 o, glm::vec3 d, float max_t, glm::vec3* normal) {
    float best = max_t;
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::vec3 a = mesh.positions[mesh.indices[3 * t]];
        const glm::vec3 e1 = mesh.positions[mesh.indices[3 * t + 1]] - a;
        const glm::vec3 e2 = mesh.positions[mesh.indices[3 * t + 2]] - a;
        const glm::vec3 h = glm::cross(d, e2);
        const float det = glm::dot(e1, h);
        if (std::abs(det) < 1e-20f) continue;
        const glm::vec3 s = o - a;
        const float u = glm::dot(s, h) / det;
        if (u < 0.0f || u > 1.0f) continue;
        const glm::vec3 q = glm::cross(s, e1);
        const float v = glm::dot(d, q) / det;
        if (v < 0.0f || u + v > 1.0f) continue;
        const float hit = glm::dot(e2, q) / det;
        if (hit > 1e-6f && hit < best) {
            best = hit;
            *normal = glm::cross(e1, e2);
        }
    }
    return best;
}

// The distance along the unit ray to where it enters the ball (c, r), 0 when it starts inside; +infinity
// when it misses it.
float rayBallEntry(const Ray& ray, glm::vec3 c, float r) {
    const glm::vec3 oc = c - ray.origin_m;
    const float along = glm::dot(oc, ray.direction);
    const float d2 = glm::dot(oc, oc) - along * along;
    if (d2 > r * r) return std::numeric_limits<float>::infinity();
    const float half = std::sqrt(r * r - d2);
    if (along + half < 0.0f) return std::numeric_limits<float>::infinity();
    return std::max(0.0f, along - half);
}

// The detail instances' models along the ray, nearer than *best: each one's ball (around its origin,
// reaching its farthest vertex) first, then its triangles in its own frame.
void pickInstances(const Document& doc, const Ray& ray, std::span<const PlacedInstance> instances, float* best,
                   ScenePick* out) {
    const std::vector<DetailModel>& models = doc.models();
    std::vector<float> reach(models.size(), -1.0f);  // per type, computed when first met
    for (size_t i = 0; i < instances.size(); ++i) {
        const PlacedInstance& inst = instances[i];
        if (inst.type >= models.size() || !(inst.scale > 0.0f)) continue;
        const TriangleMesh& mesh = models[inst.type].mesh;
        if (reach[inst.type] < 0.0f) {
            reach[inst.type] = 0.0f;
            for (const glm::vec3& p : mesh.positions) reach[inst.type] = std::max(reach[inst.type], glm::length(p));
        }
        if (!(rayBallEntry(ray, inst.position, inst.scale * reach[inst.type] * 1.001f + 1e-4f) < *best)) continue;
        // In the model's frame the ray is o + t·d with the world's t (rotation and uniform scale).
        const glm::quat inverse = glm::inverse(inst.rotation);
        const glm::vec3 o = inverse * (ray.origin_m - inst.position) / inst.scale;
        const glm::vec3 d = inverse * ray.direction / inst.scale;
        glm::vec3 n_local(0.0f);
        const float t = nearestTriangle(mesh, o, d, *best, &n_local);
        if (!(t < *best)) continue;
        *best = t;
        glm::vec3 n = inst.rotation * n_local;
        n = glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0.0f, 0.0f, 1.0f);
        if (glm::dot(n, ray.direction) > 0.0f) n = -n;
        out->hit = SurfaceHit{.hit = true, .point_m = ray.at(t), .normal = n, .on_pile = false};
        out->object = -1;
        out->instance = int64_t(i);
        out->detail_type = inst.type;
    }
}

}  // namespace

ScenePick pickSceneSurface(const Document& doc, const Ray& ray, std::span<const PlacedInstance> instances) {
    ScenePick out;
    out.hit = pickGround(doc, ray);
    float best = out.hit.hit ? glm::distance(ray.origin_m, out.hit.point_m) : std::numeric_limits<float>::infinity();
    pickInstances(doc, ray, instances, &best, &out);
    const EnvScene* env = doc.environment().get();
    if (!env) return out;
    for (size_t i = 0; i < env->objects().size(); ++i) {
        const EnvObject& object = env->objects()[i];
        const EnvObjectType& type = env->types()[object.type];
        if (!type.mesh || !(rayBoxEntry(ray, object.bounds) < best)) continue;
        // The placement is affine, so the ray's parameter is the same in the object's frame.
        const glm::vec3 o = object.placement.toLocal(ray.origin_m);
        const glm::vec3 d = object.placement.toLocal(ray.origin_m + ray.direction) - o;
        glm::vec3 n_local(0.0f);
        const float t = nearestTriangle(*type.mesh, o, d, best, &n_local);
        if (!(t < best)) continue;
        best = t;
        glm::vec3 n = object.placement.toWorld(n_local) - object.placement.toWorld(glm::vec3(0.0f));
        n = glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0.0f, 0.0f, 1.0f);
        if (glm::dot(n, ray.direction) > 0.0f) n = -n;  // the face seen, whatever its winding
        out.hit.hit = true;
        out.hit.point_m = ray.at(t);
        out.hit.normal = n;
        out.hit.on_pile = false;
        out.object = int64_t(i);
        out.instance = -1;
    }
    return out;
}

}  // namespace ug::editor
