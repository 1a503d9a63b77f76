#include "editor/env_tools.h"

#include <cmath>

namespace ug::editor {

size_t pickEnvNode(const Document& doc, const glm::mat4& view_proj, float width, float height, glm::vec2 cursor,
                   float max_px) {
    std::vector<glm::vec3> origins;
    for (const EnvNode& node : doc.project().environment.roots) origins.push_back(node.transform.translation);
    return nearestOnScreen(origins, view_proj, width, height, cursor, max_px);
}

EnvironmentDesc withRootMovedTo(const Document& doc, size_t root, glm::vec2 xy) {
    EnvironmentDesc env = doc.project().environment;
    if (root >= env.roots.size()) return env;
    glm::vec3& t = env.roots[root].transform.translation;
    const float above = t.z - groundHeightAt(doc, glm::vec2(t));
    t = glm::vec3(xy, groundHeightAt(doc, xy) + above);
    return env;
}

bool EnvObjectDrag::begin(Document* doc, size_t root, const Ray& ray) {
    if (active()) end();
    if (root >= doc->project().environment.roots.size()) return false;
    doc_ = doc;
    root_ = root;
    start_m_ = doc->project().environment.roots[root].transform.translation;
    grab_m_ = dragGrab(ray, start_m_);
    applied_offset_m_ = glm::vec3(0.0f);
    moves_ = 0;
    doc_->beginStroke("Move object");
    return true;
}

bool EnvObjectDrag::drag(const Ray& ray, std::string* error) {
    if (!active()) return true;
    glm::vec3 offset;
    if (!dragOffset(ray, grab_m_, applied_offset_m_, false, &offset)) return true;
    // Below a centimetre the snow would not visibly change: a still mouse does not recompute it.
    if (glm::length(offset - applied_offset_m_) < 0.01f) return true;
    if (root_ >= doc_->project().environment.roots.size()) return true;  // the tree changed under the drag
    if (!doc_->setEnvironment(withRootMovedTo(*doc_, root_, glm::vec2(start_m_ + offset)), "Move object", error))
        return false;
    applied_offset_m_ = offset;
    ++moves_;
    return true;
}

void EnvObjectDrag::end() {
    if (!active()) return;
    doc_->endStroke();
    doc_ = nullptr;
}

bool FootprintDrag::begin(Document* doc, glm::vec3 ground, std::string* error) {
    if (active()) end();
    doc_ = doc;
    footprints_ = 0;
    last_m_ = ground;
    doc_->beginStroke("Footprints");
    return step(ground, glm::vec2(1.0f, 0.0f), error);
}

bool FootprintDrag::drag(glm::vec3 ground, std::string* error) {
    if (!active()) return true;
    // Steps along the straight line from the last one: a fast mouse leaves every footprint in between.
    for (;;) {
        const glm::vec2 d = glm::vec2(ground) - glm::vec2(last_m_);
        const float len = glm::length(d);
        if (len < kFootprintStrideM) return true;
        const glm::vec2 heading = d / len;
        const glm::vec2 xy = glm::vec2(last_m_) + heading * kFootprintStrideM;
        const glm::vec3 at(xy, groundHeightAt(*doc_, xy));
        if (!step(at, heading, error)) return false;
        last_m_ = at;
    }
}

bool FootprintDrag::step(glm::vec3 at, glm::vec2 heading, std::string* error) {
    // Left foot, right foot: half a gait to either side of the walked line.
    const glm::vec2 side = glm::vec2(-heading.y, heading.x) * ((footprints_ % 2 == 0) ? kFootprintHalfGaitM
                                                                                        : -kFootprintHalfGaitM);
    const glm::vec2 xy = glm::vec2(at) + side;
    EnvironmentDesc env = doc_->project().environment;
    env.global_fields.push_back(footprintField(glm::vec3(xy, groundHeightAt(*doc_, xy))));
    if (!doc_->setEnvironment(env, "Footprints", error)) return false;
    ++footprints_;
    return true;
}

void FootprintDrag::end() {
    if (!active()) return;
    doc_->endStroke();
    doc_ = nullptr;
}

}  // namespace ug::editor
