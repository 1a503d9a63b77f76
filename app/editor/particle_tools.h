// The particle tool in the viewport (issue 14), GL-free: with the Particles window open, the Select tool
// picks an attractor of the window's system by its dot on screen and drags it like a primitive (on the
// horizontal plane at its height; Shift: up and down). Each step of the drag is a
// Document::setParticleSystem in one stroke, so the strands re-grow as the mouse moves (live_strands.h)
// and the drag is one undo step.
#pragma once

#include <cstddef>
#include <string>

#include <glm/glm.hpp>

#include "editor/tools.h"
#include "scene/document.h"

namespace ug::editor {

constexpr size_t kNoAttractor = SIZE_MAX;

// The attractor of `system` whose centre is nearest the cursor on screen, within max_px; kNoAttractor for
// none. view_proj maps world to clip space of a width x height viewport (pixels, y down from the top).
size_t pickAttractor(const Document& doc, size_t system, const glm::mat4& view_proj, float width_px, float height_px,
                     glm::vec2 cursor_px, float max_px);

class AttractorDrag {
  public:
    bool active() const { return doc_ != nullptr; }
    size_t system() const { return system_; }
    size_t attractor() const { return attractor_; }
    bool begin(Document* doc, size_t system, size_t attractor, const Ray& ray);
    // False with *error when the document refuses the move (the drag stays open; end() closes it).
    bool drag(const Ray& ray, bool vertical, std::string* error);
    void end();
    int moves() const { return moves_; }

  private:
    Document* doc_ = nullptr;
    size_t system_ = 0, attractor_ = 0;
    glm::vec3 start_a_{0.0f}, start_b_{0.0f};
    glm::vec3 grab_m_{0.0f};
    glm::vec3 applied_offset_m_{0.0f};
    int moves_ = 0;
};

}  // namespace ug::editor
