// The selected environmental node's handles in the view (issue 13), GL-free: with the Environment window
// open and a node selected, a ring lies on the ground around the objects the node expands to, centred on
// its origin (the pivot), with two handles on it:
//   turn   a dot where the node's +x axis meets the ring: dragged around the ring, it turns the node about
//          its origin (Ctrl: in 15 degree steps);
//   scale  a square on the opposite side: dragged away from or toward the origin, it scales the node by the
//          ratio of the distances (Ctrl: in steps of 0.05), between 0.05 and 20 (the window's limits).
// Nested nodes (inside groups) turn and scale in the world as top-level ones do (env_tree_edits.h
// setEnvWorldTransform). A whole drag is one undo step ("Turn object", "Scale object").
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "editor/markers.h"
#include "editor/tools.h"
#include "env/env_tree_edits.h"
#include "scene/document.h"

namespace ug::editor {

enum class EnvHandle { None, Turn, Scale };

// Where the handles of a node are drawn and picked.
struct EnvHandleFrame {
    glm::vec3 origin{0.0f};  // the node's origin in the world: the pivot
    float radius_m = 0.0f;   // the ring's, around every object of the node
    float yaw_deg = 0.0f;    // the node's turn in the world
    float lift_z = 0.0f;     // the ring's height: the origin's or the ground's, whichever is higher, plus a little
};

constexpr float kEnvHandleMinScale = 0.05f, kEnvHandleMaxScale = 20.0f;

// False when the path leads nowhere or the node has no object.
bool envHandleFrame(const Document& doc, const EnvPath& path, EnvHandleFrame* out);
glm::vec3 envHandlePoint(const EnvHandleFrame& frame, EnvHandle handle);
// The handle whose point is within max_px of the cursor on screen (the nearer one), else None.
EnvHandle pickEnvHandle(const EnvHandleFrame& frame, const glm::mat4& view_proj, float width_px, float height_px,
                        glm::vec2 cursor_px, float max_px);
// The ring and its two handles (`active`: the one being dragged, brighter).
void addEnvHandleMarkers(const EnvHandleFrame& frame, EnvHandle active, MarkerGeometry* out);

class EnvHandleDrag {
public:
    bool active() const { return doc_ != nullptr; }
    EnvHandle handle() const { return handle_; }
    // Grabs `handle` of the node where the ray meets the ring's plane; false (nothing opened) when the
    // node has no frame or the ray misses the plane.
    bool begin(Document* doc, const EnvPath& path, EnvHandle handle, const Ray& ray);
    // False with *error when the document refuses the edit (the drag stays open; end() closes it).
    bool drag(const Ray& ray, bool snap, std::string* error);
    void end();
    int moves() const { return moves_; }

private:
    Document* doc_ = nullptr;
    EnvPath path_;
    EnvHandle handle_ = EnvHandle::None;
    EnvHandleFrame frame_;
    EnvTransform start_;           // the node's world transform when grabbed
    glm::vec2 grab_{0.0f};         // the grab point relative to the origin (XY)
    EnvTransform applied_;         // the last world transform applied
    int moves_ = 0;
};

}  // namespace ug::editor
