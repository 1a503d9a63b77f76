// The environment tools in the viewport (issue 13), GL-free: with the Environment window open, the Select
// tool picks a top-level environmental object (or group) by its origin on screen and drags it over the
// ground, keeping its height above the ground (it stays on the surface below as the terrain rises and
// falls); the footprint brush walks a trail of footprints (occlusion fields, Fig. 3 step 6) behind the
// mouse. Each step is a Document::setEnvironment inside one stroke: the effects follow live and the whole
// drag or trail is one undo step.
#pragma once

#include <cstddef>
#include <string>

#include <glm/glm.hpp>

#include "editor/tools.h"
#include "scene/document.h"

namespace ug::editor {

constexpr size_t kNoEnvNode = SIZE_MAX;
// A walker's stride and the feet's distance from the walked line.
constexpr float kFootprintStrideM = 0.4f;
constexpr float kFootprintHalfGaitM = 0.09f;

// The top-level node whose origin is nearest the cursor on screen, within max_px; kNoEnvNode for none.
size_t pickEnvNode(const Document& doc, const glm::mat4& view_proj, float width_px, float height_px,
                   glm::vec2 cursor_px, float max_px);

// The environment with top-level node `root` moved to (x, y), at its height above the ground kept.
EnvironmentDesc withRootMovedTo(const Document& doc, size_t root, glm::vec2 xy_m);

class EnvObjectDrag {
  public:
    bool active() const { return doc_ != nullptr; }
    size_t root() const { return root_; }
    bool begin(Document* doc, size_t root, const Ray& ray);
    // False with *error when the document refuses the move (the drag stays open; end() closes it).
    bool drag(const Ray& ray, std::string* error);
    void end();
    int moves() const { return moves_; }

  private:
    Document* doc_ = nullptr;
    size_t root_ = 0;
    glm::vec3 start_m_{0.0f};
    glm::vec3 grab_m_{0.0f};
    glm::vec3 applied_offset_m_{0.0f};
    int moves_ = 0;
};

// Footprints along the ground points the mouse (or a script) passes: one every kFootprintStrideM of
// path, left and right of it in turn.
class FootprintDrag {
  public:
    bool active() const { return doc_ != nullptr; }
    bool begin(Document* doc, glm::vec3 ground_m, std::string* error);
    bool drag(glm::vec3 ground_m, std::string* error);
    void end();
    int footprints() const { return footprints_; }

  private:
    bool step(glm::vec3 at, glm::vec2 heading, std::string* error);

    Document* doc_ = nullptr;
    glm::vec3 last_m_{0.0f};  // where the last footprint's step was taken from the walked line
    int footprints_ = 0;
};

}  // namespace ug::editor
