// The environment tools in the viewport (issue 13), GL-free: with the Environment window open, the Select
// tool picks an environmental object by its origin on screen and drags its top-level node (or, with Ctrl,
// its own node inside a group) over the ground, keeping its height above the ground (it stays on the surface below as the terrain rises and
// falls); the weather brushes leave local fields (footprints, warm, wet, piles, ...) behind the mouse. Each step is a Document::setEnvironment inside one stroke: the effects follow live and the whole
// drag or trail is one undo step.
#pragma once

#include <cstddef>
#include <string>

#include <glm/glm.hpp>

#include "editor/tools.h"
#include "env/env_tree_edits.h"
#include "scene/document.h"

namespace ug::editor {

// A walker's stride and the feet's distance from the walked line (the footprint brush).
constexpr float kFootprintStrideM = 0.4f;
constexpr float kFootprintHalfGaitM = 0.09f;

// The node that a click on the view picks: the object whose origin is nearest the cursor on screen within
// max_px, and of it its top-level node (a click: a group moves as one) or, `nested`, its own node (Ctrl +
// click: a node inside a group, or the reference a reusable group's object came from). Empty for none.
EnvPath pickEnvNode(const Document& doc, const glm::mat4& view_proj, float width_px, float height_px,
                    glm::vec2 cursor_px, float max_px, bool nested);

// Where a click along `ray` places a new object: the first point of the ray (in 2 cm steps, up to where it
// meets the ground) at or just above what an object dropped there would stand on (the terrain, or the top
// of another object's base geometry: a pavement slab, a table, a roof), at that surface's height. False
// when the ray misses the ground.
bool placementPoint(const Document& doc, const Ray& ray, glm::vec3* out);

// The environment with node `path` moved to (x, y) in the world, at its height above the ground kept
// (unchanged when the path leads nowhere).
EnvironmentDesc withNodeMovedTo(const Document& doc, const EnvPath& path, glm::vec2 xy_m);

class EnvObjectDrag {
  public:
    bool active() const { return doc_ != nullptr; }
    const EnvPath& path() const { return path_; }
    bool begin(Document* doc, const EnvPath& path, const Ray& ray);
    // False with *error when the document refuses the move (the drag stays open; end() closes it).
    bool drag(const Ray& ray, std::string* error);
    void end();
    int moves() const { return moves_; }

  private:
    Document* doc_ = nullptr;
    EnvPath path_;
    glm::vec3 start_m_{0.0f};  // the node's origin in the world
    glm::vec3 grab_m_{0.0f};
    glm::vec3 applied_offset_m_{0.0f};
    int moves_ = 0;
};

// The weather brushes (Fig. 3 step 6 and §4's local fields): each stamp adds a field of the environment
// at the ground under the brush (world space, in the global fields), so the effects follow it.
//   footprints  a trail: one footprint (footprintField) every kFootprintStrideM, left and right in turn
//   warm, cold  temperature +/- 8 degrees x strength over the brush's radius (snow melts, icicles go)
//   wet         humidity +0.5 x strength (wet leaves, longer icicles)
//   leaves, trash, grass   a pile: the channel +1 x strength (the scattered types fill it)
//   erase       removes the local fields whose skeleton the brush covers (footprints, spots, piles: their
//               centre; a trail: any point of its segment)
// Other stamps come every radius / 2 along the drag.
enum class WeatherBrush : int { Footprints, Warm, Cold, Wet, Leaves, Trash, Grass, Erase };
constexpr int kWeatherBrushCount = int(WeatherBrush::Erase) + 1;
const char* weatherBrushName(WeatherBrush brush);  // "footprints", "warm", ...
bool weatherBrushFromName(const std::string& name, WeatherBrush* out);

struct WeatherSettings {
    WeatherBrush brush = WeatherBrush::Footprints;
    float radius_m = 0.5f;  // > 0 (footprints: their own size)
    float strength = 1.0f;  // > 0
};

// The field one stamp adds at `at` (not for footprints, whose size is their own, nor erase).
EnvFieldDesc weatherField(const WeatherSettings& settings, glm::vec3 at);

class WeatherStroke {
  public:
    bool active() const { return doc_ != nullptr; }
    // False with *error when the settings are unusable or the document refuses the first stamp.
    bool begin(Document* doc, const WeatherSettings& settings, glm::vec3 ground_m, std::string* error);
    bool drag(glm::vec3 ground_m, std::string* error);
    void end();
    int stamps() const { return stamps_; }  // footprints left, spots added, or erase stamps
    int erased() const { return erased_; }  // fields erase removed

  private:
    float spacing() const;
    bool stamp(glm::vec3 at, glm::vec2 heading, std::string* error);

    Document* doc_ = nullptr;
    WeatherSettings settings_;
    glm::vec3 last_m_{0.0f};  // the last stamp's point on the walked line
    int stamps_ = 0, erased_ = 0;
};

}  // namespace ug::editor
