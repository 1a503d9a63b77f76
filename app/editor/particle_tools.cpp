#include "editor/particle_tools.h"

#include <algorithm>

namespace ug::editor {

namespace {
constexpr float kCutterTiltM = 0.1f;  // a plane cutter's tilt dot: this far along its normal (markers' line)
constexpr float kTiltPreferencePx = 2.0f;  // a tilt dot is picked over a place only this much nearer
}  // namespace

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
    for (size_t i = 0; i < scene.generators.size(); ++i) {
        const ParticleGenerator& g = scene.generators[i];
        if (g.kind != GeneratorKind::Rectangle || g.on_terrain) continue;
        const glm::vec3 n = glm::normalize(glm::cross(g.axis_u_m, g.axis_v_m));
        points.push_back({{ParticlePart::Generator, i, true},
                          g.center_m + n * std::max(glm::length(g.axis_u_m), glm::length(g.axis_v_m))});
    }
    for (size_t i = 0; i < scene.cutters.size(); ++i) {
        const Cutter& c = scene.cutters[i];
        if (c.kind == CutterKind::Plane)
            points.push_back({{ParticlePart::Cutter, i, true}, c.center_m + c.normal * (c.threshold_m + kCutterTiltM)});
    }
    return points;
}

ParticleHandle pickParticleHandle(const Document& doc, size_t system, const glm::mat4& view_proj, float width,
                                  float height, glm::vec2 cursor, float max_px) {
    if (system >= doc.particles()->size()) return {};
    const std::vector<ParticleHandlePoint> handles = particleHandlePoints((*doc.particles())[system].scene);
    std::vector<glm::vec3> places, tilts;
    std::vector<ParticleHandle> place_handles, tilt_handles;
    for (const ParticleHandlePoint& h : handles) {
        (h.handle.tilt ? tilts : places).push_back(h.position_m);
        (h.handle.tilt ? tilt_handles : place_handles).push_back(h.handle);
    }
    // Among places, ties go to the later dot (a generator's centre under an attractor straight above it).
    const size_t place = nearestOnScreen(places, view_proj, width, height, cursor, max_px);
    const size_t tilt = nearestOnScreen(tilts, view_proj, width, height, cursor, max_px);
    if (tilt == SIZE_MAX) return place == SIZE_MAX ? ParticleHandle{} : place_handles[place];
    if (place == SIZE_MAX) return tilt_handles[tilt];
    // A tilt dot seen along its normal covers its place: it is taken only when clearly nearer.
    const auto px = [&](glm::vec3 p) {
        const glm::vec4 c = view_proj * glm::vec4(p, 1.0f);
        return glm::vec2((c.x / c.w * 0.5f + 0.5f) * width, (0.5f - c.y / c.w * 0.5f) * height);
    };
    const float to_tilt = glm::distance(px(tilts[tilt]), cursor), to_place = glm::distance(px(places[place]), cursor);
    return to_tilt + kTiltPreferencePx < to_place ? tilt_handles[tilt] : place_handles[place];
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

bool tiltParticleHandle(ParticleScene* scene, ParticleHandle handle, glm::vec3 normal) {
    if (!handle.tilt) return false;
    if (handle.part == ParticlePart::Generator && handle.index < scene->generators.size()) {
        ParticleGenerator& g = scene->generators[handle.index];
        if (g.kind != GeneratorKind::Rectangle || g.on_terrain) return false;
        const glm::vec3 from = glm::normalize(glm::cross(g.axis_u_m, g.axis_v_m));
        const glm::quat turn(from, normal);  // the shortest arc
        g.axis_u_m = turn * g.axis_u_m;
        g.axis_v_m = turn * g.axis_v_m;
        return true;
    }
    if (handle.part == ParticlePart::Cutter && handle.index < scene->cutters.size()) {
        Cutter& c = scene->cutters[handle.index];
        if (c.kind != CutterKind::Plane) return false;
        const glm::vec3 cut = c.center_m + c.normal * c.threshold_m;
        c.normal = normal;
        c.center_m = cut - normal * c.threshold_m;
        return true;
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

ParticleHandle addParticlePart(ParticleScene* scene, ParticlePart part, glm::vec3 at, glm::vec3 normal, bool on_terrain) {
    switch (part) {
        case ParticlePart::Generator: {
            if (on_terrain || normal == glm::vec3(0.0f, 0.0f, 1.0f)) {
                scene->generators.push_back(groundPatch(at, 0.25f, 400, 10.0f, on_terrain));
            } else {
                // Axes across the normal, u x v = normal (the rectangle's normal: its strands' heading).
                const glm::vec3 ref = std::abs(normal.z) < 0.9f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
                const glm::vec3 u = glm::normalize(glm::cross(ref, normal));
                ParticleGenerator g = groundPatch(at, 0.1f, 64, 10.0f, false);
                g.axis_u_m = u * 0.1f;
                g.axis_v_m = glm::cross(normal, u) * 0.1f;
                scene->generators.push_back(g);
            }
            return {ParticlePart::Generator, scene->generators.size() - 1, false};
        }
        case ParticlePart::Attractor: {
            Attractor a;
            a.a_m = at + normal * 0.3f;
            a.influence_m = 0.3f;
            a.charge = {ChargeKey{0, 1.0f}};
            scene->attractors.push_back(a);
            return {ParticlePart::Attractor, scene->attractors.size() - 1, false};
        }
        case ParticlePart::Cutter: {
            Cutter c;  // its action is a stop
            c.center_m = at + normal * 0.2f;
            c.normal = normal;
            scene->cutters.push_back(c);
            return {ParticlePart::Cutter, scene->cutters.size() - 1, false};
        }
        case ParticlePart::None: break;
    }
    return {};
}

ParticleHandle addDetailsGenerator(ParticleScene* scene, const std::string& detail_type, glm::vec3 at) {
    ParticleGenerator g;
    g.kind = GeneratorKind::Details;
    g.detail_type = detail_type;
    g.center_m = at;
    g.half_extents_m = glm::vec3(0.5f);
    g.min_normal_z = 0.45f;
    g.count = 4000;
    g.heading_cone_deg = 30.0f;
    scene->generators.push_back(g);
    return {ParticlePart::Generator, scene->generators.size() - 1, false};
}

ActionMode actionMode(const StrandAction& action) {
    if (action.table.empty()) return ActionMode::Single;
    return action.choice == ActionChoice::Random ? ActionMode::Random : ActionMode::Priority;
}

void setActionMode(StrandAction* action, ActionMode mode) {
    if (mode == actionMode(*action)) return;
    if (mode == ActionMode::Single) {
        StrandAction first = action->table.front();
        first.weight = 1.0f;
        *action = first;
        return;
    }
    if (action->table.empty()) {
        StrandAction only = *action;
        only.weight = 1.0f;
        action->table = {only};
    }
    action->choice = mode == ActionMode::Random ? ActionChoice::Random : ActionChoice::Priority;
    // A priority table ignores weights; the file keeps 1 so that switching back draws evenly.
    if (mode == ActionMode::Priority)
        for (StrandAction& a : action->table) a.weight = 1.0f;
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
    if (handle.tilt) {
        // The pivot is the place dot of the same part (listed before the tilt dots).
        const auto place = std::find_if(handles.begin(), handles.end(), [&](const ParticleHandlePoint& h) {
            return h.handle == ParticleHandle{handle.part, handle.index, false};
        });
        pivot_m_ = handle.part == ParticlePart::Generator ? scene.generators[handle.index].center_m : place->position_m;
        tilt_radius_m_ = glm::distance(it->position_m, pivot_m_);
        applied_normal_ = glm::normalize(it->position_m - pivot_m_);
    }
    doc_->beginStroke(std::string(handle.tilt ? "Tilt " : "Move ") + particlePartName(handle.part));
    return true;
}

namespace {

// Where the ray meets the sphere (centre c, radius r), of its two points the one nearer `previous` (so a
// dot dragged over the sphere's far side stays there); where it misses, the sphere's point nearest the ray.
glm::vec3 pointOnSphere(const Ray& ray, glm::vec3 c, float r, glm::vec3 previous) {
    const glm::vec3 d = glm::normalize(ray.direction);
    const float along = glm::dot(c - ray.origin_m, d);
    const glm::vec3 closest = ray.origin_m + d * along;
    const float miss2 = glm::dot(closest - c, closest - c);
    if (miss2 > r * r) return c + glm::normalize(closest - c) * r;
    const float half = std::sqrt(r * r - miss2);
    const glm::vec3 front = closest - d * half, back = closest + d * half;
    return glm::distance(front, previous) <= glm::distance(back, previous) ? front : back;
}

}  // namespace

bool ParticleHandleDrag::tilt(const Ray& ray, std::string* error) {
    const glm::vec3 towards =
        pointOnSphere(ray, pivot_m_, tilt_radius_m_, pivot_m_ + applied_normal_ * tilt_radius_m_) - pivot_m_;
    if (!(glm::length(towards) > 1e-6f)) return true;
    const glm::vec3 normal = glm::normalize(towards);
    // Below a fifth of a degree the strands would not visibly change.
    if (glm::dot(normal, applied_normal_) > std::cos(glm::radians(0.2f))) return true;
    if (system_ >= doc_->particles()->size()) return true;
    ParticleSystemFile system = (*doc_->particles())[system_];
    ParticleScene turned = start_;
    if (!tiltParticleHandle(&turned, handle_, normal)) return true;
    if (handle_.part == ParticlePart::Generator && handle_.index < system.scene.generators.size())
        system.scene.generators[handle_.index] = turned.generators[handle_.index];
    else if (handle_.part == ParticlePart::Cutter && handle_.index < system.scene.cutters.size())
        system.scene.cutters[handle_.index] = turned.cutters[handle_.index];
    else
        return true;
    if (!doc_->setParticleSystem(system_, system, error)) return false;
    applied_normal_ = normal;
    ++moves_;
    return true;
}

bool ParticleHandleDrag::drag(const Ray& ray, bool vertical, std::string* error) {
    if (!active()) return true;
    if (handle_.tilt) return tilt(ray, error);
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
