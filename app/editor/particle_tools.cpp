#include "editor/particle_tools.h"

namespace ug::editor {

size_t pickAttractor(const Document& doc, size_t system, const glm::mat4& view_proj, float width, float height,
                     glm::vec2 cursor, float max_px) {
    if (system >= doc.particles()->size()) return kNoAttractor;
    std::vector<glm::vec3> centres;
    for (const Attractor& a : (*doc.particles())[system].scene.attractors) centres.push_back(a.a_m);
    return nearestOnScreen(centres, view_proj, width, height, cursor, max_px);
}

bool AttractorDrag::begin(Document* doc, size_t system, size_t attractor, const Ray& ray) {
    if (active()) end();
    if (system >= doc->particles()->size() || attractor >= (*doc->particles())[system].scene.attractors.size())
        return false;
    const Attractor& a = (*doc->particles())[system].scene.attractors[attractor];
    doc_ = doc;
    system_ = system;
    attractor_ = attractor;
    start_a_ = a.a_m;
    start_b_ = a.b_m;
    grab_m_ = dragGrab(ray, a.a_m);
    applied_offset_m_ = glm::vec3(0.0f);
    moves_ = 0;
    doc_->beginStroke("Move attractor");
    return true;
}

bool AttractorDrag::drag(const Ray& ray, bool vertical, std::string* error) {
    if (!active()) return true;
    glm::vec3 offset;
    if (!dragOffset(ray, grab_m_, applied_offset_m_, vertical, &offset)) return true;
    // Below a millimetre the strands would not visibly change: a still mouse does not re-grow them.
    if (glm::length(offset - applied_offset_m_) < 1e-3f) return true;
    if (system_ >= doc_->particles()->size()) return true;  // the systems changed under the drag
    ParticleSystemFile system = (*doc_->particles())[system_];
    if (attractor_ >= system.scene.attractors.size()) return true;
    Attractor& a = system.scene.attractors[attractor_];
    a.a_m = start_a_ + offset;
    if (a.kind == AttractorKind::Segment) a.b_m = start_b_ + offset;  // a segment moves whole
    if (!doc_->setParticleSystem(system_, system, error)) return false;
    applied_offset_m_ = offset;
    ++moves_;
    return true;
}

void AttractorDrag::end() {
    if (!active()) return;
    doc_->endStroke();
    doc_ = nullptr;
}

}  // namespace ug::editor
