#include "env/env_outputs.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <glm/gtc/quaternion.hpp>

namespace ug {

namespace {

constexpr float kDegToRad = 0.017453292519943295f;

InstanceTransform placed(const EnvPlacement& p) {
    InstanceTransform t;
    t.position = p.t;
    t.rotation = glm::angleAxis(p.yaw_deg * kDegToRad, glm::vec3(0.0f, 0.0f, 1.0f));
    t.scale = p.scale;
    return t;
}

// An icicle (object space: anchor, turn about +Z, scale) placed with its object.
InstanceTransform placedIcicle(const EnvPlacement& p, const IcicleInstance& ic) {
    InstanceTransform t;
    t.position = p.toWorld(ic.anchor);
    t.rotation = glm::angleAxis(p.yaw_deg * kDegToRad + ic.yaw_rad, glm::vec3(0.0f, 0.0f, 1.0f));
    t.scale = p.scale * ic.scale;
    return t;
}

SurfaceMaterial makeSurface(glm::vec3 color, float roughness) {
    Material m;
    m.base_color = color;
    m.roughness = roughness;
    return resolveMaterial(m, color);
}

// The library's shapes as shared meshes, made once: every result names the same mesh objects, so a viewer
// that keeps per-mesh work (the editor's levels of detail) keeps it across edits.
const std::shared_ptr<const TriangleMesh>& icicleShapeMesh(uint32_t shape) {
    static const std::vector<std::shared_ptr<const TriangleMesh>> meshes = [] {
        std::vector<std::shared_ptr<const TriangleMesh>> out;
        for (const IcicleShape& s : icicleShapes()) out.push_back(std::make_shared<const TriangleMesh>(s.mesh));
        return out;
    }();
    return meshes[shape];
}


}  // namespace

const SurfaceMaterial& snowMaterial() {
    static const SurfaceMaterial m = makeSurface(glm::vec3(0.86f, 0.89f, 0.93f), 0.75f);
    return m;
}

const SurfaceMaterial& iceMaterial() {
    static const SurfaceMaterial m = makeSurface(glm::vec3(0.70f, 0.82f, 0.92f), 0.08f);
    return m;
}

std::vector<MeshInstances> envMeshInstances(const EnvScene& scene, const EnvEffects& effects,
                                            const std::vector<uint8_t>* hidden) {
    std::vector<MeshInstances> out;
    const auto& objects = scene.objects();
    auto shown = [&](uint32_t o) { return !hidden || o >= hidden->size() || (*hidden)[o] == 0; };
    auto snow = std::make_shared<const SurfaceMaterial>(snowMaterial());
    auto ice = std::make_shared<const SurfaceMaterial>(iceMaterial());
    // Base geometry, per type, only the objects in the result (its region).
    for (size_t t = 0; t < scene.types().size(); ++t) {
        // Members come class by class: put them back in object order so the file does not depend on how
        // the classes formed.
        std::vector<std::pair<uint32_t, InstanceTransform>> ordered;
        for (const EffectClass& c : effects.classes)
            for (uint32_t o : c.members)
                if (objects[o].type == t && shown(o)) ordered.push_back({o, placed(objects[o].placement)});
        if (ordered.empty()) continue;
        std::sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        MeshInstances m;
        const EnvObjectType& type = scene.types()[t];
        m.name = "env/" + type.desc.name;
        m.mesh = type.mesh;
        m.material = std::make_shared<const SurfaceMaterial>(resolveMaterial(type.desc.material, type.mesh->base_color));
        for (auto& [o, tr] : ordered) m.instances.push_back(tr);
        out.push_back(std::move(m));
    }
    // Snow covers, one per computed class, and icicles per library shape.
    std::map<uint32_t, std::vector<InstanceTransform>> icicles;
    for (size_t c = 0; c < effects.classes.size(); ++c) {
        const EffectClass& cls = effects.classes[c];
        if (cls.members.empty()) continue;
        if (cls.snow && !cls.snow->indices.empty()) {
            MeshInstances m;
            m.name = "snow/" + scene.types()[cls.type].desc.name + "/" + std::to_string(c);
            m.mesh = cls.snow;
            m.material = snow;
            for (uint32_t o : cls.members)
                if (shown(o)) m.instances.push_back(placed(objects[o].placement));
            if (!m.instances.empty()) out.push_back(std::move(m));
        }
        for (uint32_t o : cls.members)
            if (shown(o))
                for (const IcicleInstance& ic : cls.icicles) icicles[ic.shape].push_back(placedIcicle(objects[o].placement, ic));
    }
    for (auto& [shape, transforms] : icicles) {
        MeshInstances m;
        m.name = "icicles/" + std::to_string(shape);
        m.mesh = icicleShapeMesh(shape);
        m.material = ice;
        m.instances = std::move(transforms);
        out.push_back(std::move(m));
    }
    for (const TerrainSnowChunk& ch : effects.terrain_snow) {
        if (!ch.mesh || ch.mesh->indices.empty()) continue;
        MeshInstances m;
        m.name = "snow/terrain/" + std::to_string(ch.ix) + "_" + std::to_string(ch.iy);
        m.mesh = ch.mesh;
        m.material = snow;
        m.ground_layer = true;
        out.push_back(std::move(m));
    }
    return out;
}

}  // namespace ug
