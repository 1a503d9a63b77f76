// The particle tool in the viewport (issue 14), GL-free: with the Particles window open, the Select tool
// picks a handle of the window's system by its dot on screen (an attractor's centre, a generator's centre,
// a cutter's centre or, for a plane, the point where it cuts) and drags it like a primitive (on the
// horizontal plane at its height; Shift: up and down). Each step of the drag is a
// Document::setParticleSystem in one stroke, so the strands re-grow as the mouse moves (live_strands.h)
// and the drag is one undo step.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "editor/tools.h"
#include "scene/document.h"

namespace ug::editor {

enum class ParticlePart : uint8_t { None, Attractor, Generator, Cutter };

// One draggable part of a particle system: which list and where in it, and whether it is the part's tilt
// dot (a flat generator's or a plane cutter's normal, drawn at the normal's tip) rather than its place.
struct ParticleHandle {
    ParticlePart part = ParticlePart::None;
    size_t index = 0;
    bool tilt = false;

    bool operator==(const ParticleHandle&) const = default;
    explicit operator bool() const { return part != ParticlePart::None; }
};

const char* particlePartName(ParticlePart part);  // "attractor", "generator", "cutter" ("" for None)

// Where each handle's dot is drawn and picked: attractors first, then generators (a seed-on-terrain
// rectangle's dot on the ground under its centre), then cutters (a plane's dot where it cuts), then the
// tilt dots: a rectangle generator's (not on the terrain, which keeps it level) at its centre + the normal
// times its larger half side, a plane cutter's at its cut point + 0.1 m along the normal (the tip of the
// normal the markers draw). Where a tilt dot covers its place's dot on screen (seen along the normal),
// the place is picked (the first of equals).
struct ParticleHandlePoint {
    ParticleHandle handle;
    glm::vec3 position_m{0.0f};
};
std::vector<ParticleHandlePoint> particleHandlePoints(const ParticleScene& scene);

// The handle of `system` whose dot is nearest the cursor on screen, within max_px; none for none (or no
// such system). view_proj maps world to clip space of a width x height viewport (pixels, y down from the
// top).
ParticleHandle pickParticleHandle(const Document& doc, size_t system, const glm::mat4& view_proj, float width_px,
                                  float height_px, glm::vec2 cursor_px, float max_px);

// The same scene with the handle moved by `offset` (a segment attractor moves whole); false when there is
// no such handle.
bool moveParticleHandle(ParticleScene* scene, ParticleHandle handle, glm::vec3 offset);

// The same scene with the tilt handle's part turned so that its normal is `normal` (unit): a rectangle
// generator's axes turned by the shortest arc from its normal (about its centre), a plane cutter's normal
// set with its cut point kept (the centre moves along the new normal); false for other parts.
bool tiltParticleHandle(ParticleScene* scene, ParticleHandle handle, glm::vec3 normal);

// A square generator of `count` strands at `at`, horizontal, dropped onto the terrain when asked: where
// the Particles window's new generators and systems start.
ParticleGenerator groundPatch(glm::vec3 at, float half_side_m, uint32_t count, float heading_cone_deg, bool on_terrain);

// A new part of the system at `at` on a surface with unit normal `normal` (the Particles window's Add at
// the view's centre, normal up, and its click to place, on what the click meets: surface_pick.h):
//   generator  a square of strands lying on the surface: on the terrain (on_terrain) a 0.5 m square of
//              400 dropped onto it; elsewhere a 0.2 m square of 64 across the normal (an object's top or
//              side: smaller, so that it stays on the face)
//   attractor  a point 30 cm out along the normal, attracting within 30 cm
//   cutter     a plane 20 cm out along the normal, across it, that stops the strands
// Returns the new part's handle.
ParticleHandle addParticlePart(ParticleScene* scene, ParticlePart part, glm::vec3 at, glm::vec3 normal, bool on_terrain);

// A generator on the detail instances of `detail_type` around `at` (a click on one of them): a details
// generator (moss on rocks) over their faces turned up (normal z >= 0.45) whose origins lie within a 1 m
// cube centred there, 4,000 strands, headings in a 30 degree cone; the project places it on the instances
// as it instantiates them. Returns its handle.
ParticleHandle addDetailsGenerator(ParticleScene* scene, const std::string& detail_type, glm::vec3 at);

// How a critical state acts (the Particles window's "acts by"): by one action, or by a table (§5.2) taken
// by priority or at random (StrandAction::table). Changing it keeps what the state did: one action
// becomes a table of one, a table becomes its first action; weights go back to 1 outside a random table.
enum class ActionMode : uint8_t { Single, Priority, Random };
ActionMode actionMode(const StrandAction& action);
void setActionMode(StrandAction* action, ActionMode mode);

// The system the Particles window's "New system" adds: a patch of grass blades (a 0.6 m square of 600
// strands at `at`, dropped onto the terrain when there is one) pulled up by a far attractor, with
// collisions on; somewhere to start from.
ParticleSystemFile newGrassSystem(glm::vec3 at, bool on_terrain);

class ParticleHandleDrag {
  public:
    bool active() const { return doc_ != nullptr; }
    size_t system() const { return system_; }
    ParticleHandle handle() const { return handle_; }
    // Opens the stroke "Move attractor" (generator, cutter), or for a tilt dot "Tilt generator" (cutter);
    // false when there is no such handle.
    bool begin(Document* doc, size_t system, ParticleHandle handle, const Ray& ray);
    // False with *error when the document refuses the move (the drag stays open; end() closes it). A tilt
    // dot follows the ray on the sphere around its pivot through where it was grabbed (the point nearest
    // the sphere where the ray misses it): the normal points there.
    bool drag(const Ray& ray, bool vertical, std::string* error);
    void end();
    int moves() const { return moves_; }

  private:
    bool tilt(const Ray& ray, std::string* error);
    Document* doc_ = nullptr;
    size_t system_ = 0;
    ParticleHandle handle_;
    ParticleScene start_;  // the system's scene when the drag began: each step moves it by the whole offset
    glm::vec3 grab_m_{0.0f};
    glm::vec3 applied_offset_m_{0.0f};
    glm::vec3 pivot_m_{0.0f};       // a tilt: the part's centre (cut point), and the dot's distance from it
    float tilt_radius_m_ = 0.0f;
    glm::vec3 applied_normal_{0.0f};
    int moves_ = 0;
};

}  // namespace ug::editor
