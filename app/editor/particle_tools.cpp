#include "editor/particle_tools.h"

#include <algorithm>

namespace ug::editor {

const char* particlePartName(ParticlePart part) {
    switch (part) {
        case ParticlePart::Attractor: return "attractor";
        case ParticlePart::Generator: return "generator";
        case ParticlePart::Cutter: return "cutter";
        case ParticlePart::None: break;
    }
    return "";
}

std::vector<ParticleHandlePoint> particleHandlePoints(const ParticleScene& scene) {
    std::vector<ParticleHandlePoint> points;
    // An "objects" attractor is where its objects are: it moves with them, not by a handle of its own.
    for (size_t i = 0; i < scene.attractors.size(); ++i)
        if (scene.attractors[i].kind != AttractorKind::Objects)
            points.push_back({{ParticlePart::Attractor, i}, scene.attractors[i].a_m});
    for (size_t i = 0; i < scene.generators.size(); ++i) {
        const ParticleGenerator& g = scene.generators[i];
        if (g.kind == GeneratorKind::Objects) continue;  // it moves with its objects
        glm::vec3 p = g.center_m;
        if (g.on_terrain && scene.terrain) p.z = scene.terrain->sample(p.x, p.y) + 0.01f;
        points.push_back({{ParticlePart::Generator, i}, p});
    }
    for (size_t i = 0; i < scene.cutters.size(); ++i) {
        const Cutter& c = scene.cutters[i];
        const glm::vec3 p = c.kind == CutterKind::Plane ? c.center_m + c.normal * c.threshold_m : c.center_m;
        points.push_back({{ParticlePart::Cutter, i}, p});
    }
    return points;
}

ParticleHandle pickParticleHandle(const Document& doc, size_t system, const glm::mat4& view_proj, float width,
                                  float height, glm::vec2 cursor, float max_px) {
    if (system >= doc.particles()->size()) return {};
    const std::vector<ParticleHandlePoint> handles = particleHandlePoints((*doc.particles())[system].scene);
    std::vector<glm::vec3> dots;
    for (const ParticleHandlePoint& h : handles) dots.push_back(h.position_m);
    // Ties go to the first: an attractor sitting on a generator's centre is the one picked.
    const size_t nearest = nearestOnScreen(dots, view_proj, width, height, cursor, max_px);
    return nearest < handles.size() ? handles[nearest].handle : ParticleHandle{};
}

bool moveParticleHandle(ParticleScene* scene, ParticleHandle handle, glm::vec3 offset) {
    switch (handle.part) {
        case ParticlePart::Attractor: {
            if (handle.index >= scene->attractors.size()) return false;
            Attractor& a = scene->attractors[handle.index];
            a.a_m += offset;
            if (a.kind == AttractorKind::Segment) a.b_m += offset;  // a segment moves whole
            return true;
        }
        case ParticlePart::Generator:
            if (handle.index >= scene->generators.size()) return false;
            scene->generators[handle.index].center_m += offset;
            return true;
        case ParticlePart::Cutter:
            if (handle.index >= scene->cutters.size()) return false;
            scene->cutters[handle.index].center_m += offset;
            return true;
        case ParticlePart::None: break;
    }
    return false;
}

ParticleGenerator groundPatch(glm::vec3 at, float half_side_m, uint32_t count, float heading_cone_deg, bool on_terrain) {
    ParticleGenerator g;
    g.center_m = at;
    g.axis_u_m = {half_side_m, 0.0f, 0.0f};
    g.axis_v_m = {0.0f, half_side_m, 0.0f};
    g.count = count;
    g.heading_cone_deg = heading_cone_deg;
    g.on_terrain = on_terrain;
    return g;
}

ParticleSystemFile newGrassSystem(glm::vec3 at, bool on_terrain) {
    ParticleSystemFile s;
    s.name = s.file_name = "strands";
    s.scene.generators.push_back(groundPatch(at, 0.3f, 600, 12.0f, on_terrain));
    Attractor up;  // far above: the strands grow upwards, a little each way
    up.a_m = at + glm::vec3(0.0f, 0.0f, 60.0f);
    s.scene.attractors.push_back(up);
    WalkSettings& w = s.scene.walk;
    w.steps = 20;
    w.trials = 8;
    w.cone_deg = 22.0f;
    w.step_length_m = 0.012f;
    w.strand_radius_m = 0.0015f;
    w.collisions = true;
    s.mesh.shape = StrandShape::Blade;
    s.mesh.blade_width_m = 0.005f;
    s.mesh.blade_tip = 0.15f;
    s.material.base_color = glm::vec3(0.3f, 0.46f, 0.12f);
    s.material.roughness = 0.85f;
    return s;
}

bool ParticleHandleDrag::begin(Document* doc, size_t system, ParticleHandle handle, const Ray& ray) {
    if (active()) end();
    if (system >= doc->particles()->size()) return false;
    const ParticleScene& scene = (*doc->particles())[system].scene;
    const std::vector<ParticleHandlePoint> handles = particleHandlePoints(scene);
    const auto it = std::find_if(handles.begin(), handles.end(),
                                 [&](const ParticleHandlePoint& h) { return h.handle == handle; });
    if (it == handles.end()) return false;
    doc_ = doc;
    system_ = system;
    handle_ = handle;
    start_ = scene;
    grab_m_ = dragGrab(ray, it->position_m);
    applied_offset_m_ = glm::vec3(0.0f);
    moves_ = 0;
    doc_->beginStroke(std::string("Move ") + particlePartName(handle.part));
    return true;
}

bool ParticleHandleDrag::drag(const Ray& ray, bool vertical, std::string* error) {
    if (!active()) return true;
    glm::vec3 offset;
    if (!dragOffset(ray, grab_m_, applied_offset_m_, vertical, &offset)) return true;
    // Below a millimetre the strands would not visibly change: a still mouse does not re-grow them.
    if (glm::length(offset - applied_offset_m_) < 1e-3f) return true;
    if (system_ >= doc_->particles()->size()) return true;  // the systems changed under the drag
    ParticleSystemFile system = (*doc_->particles())[system_];
    // The rest of the system as the document holds it now; the handle from where the drag began.
    ParticleScene moved = start_;
    if (!moveParticleHandle(&moved, handle_, offset)) return true;
    switch (handle_.part) {
        case ParticlePart::Attractor:
            if (handle_.index >= system.scene.attractors.size()) return true;
            system.scene.attractors[handle_.index] = moved.attractors[handle_.index];
            break;
        case ParticlePart::Generator:
            if (handle_.index >= system.scene.generators.size()) return true;
            system.scene.generators[handle_.index] = moved.generators[handle_.index];
            break;
        case ParticlePart::Cutter:
            if (handle_.index >= system.scene.cutters.size()) return true;
            system.scene.cutters[handle_.index] = moved.cutters[handle_.index];
            break;
        case ParticlePart::None: return true;
    }
    if (!doc_->setParticleSystem(system_, system, error)) return false;
    applied_offset_m_ = offset;
    ++moves_;
    return true;
}

void ParticleHandleDrag::end() {
    if (!active()) return;
    doc_->endStroke();
    doc_ = nullptr;
    start_ = ParticleScene{};
}

}  // namespace ug::editor
