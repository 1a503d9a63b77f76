// The editor's tools (issue 4, "Tools"), GL-free: they turn rays (from the mouse through the camera, or
// straight down onto a world XY in scripted runs, replay.h) into document edits. The mouse and the replay
// call the same functions, so a script exercises exactly what a user's drag does.
//
//   BrushStroke stroke;
//   on press:   stroke.begin(doc, ToolKind::Paint, brush, ray, now_s, &error);   // beginStroke + first stamp
//   each frame: stroke.drag(ray, now_s, &error);                                  // stamps as the brush
//   travels on release: stroke.end();                                                     // endStroke: one
//   undo step
//
// What a stamp adds (each one a user primitive, saved in the project). Every primitive a stroke adds carries
// the stroke's tag (Primitive::stroke, Document::newStrokeTag), so Select picks, moves, deletes, duplicates
// and re-weights the stroke as one thing (Document::strokeMembers), whatever its number of stamps:
//   Paint   per painted type i (mix weight m_i > 0): a disc at the surface under the brush (the ground, or
//           a sculpted pile: pickBrushSurface), normal = the surface normal, disc_radius = brush radius, radius = falloff, weight = strength * m_i
//           (negative in subtract mode). A stamp every radius / 3 of travel over the ground.
//   Sculpt  material poured under the cursor, where it would come to rest whatever the view: the cursor's
//           ray meets the ground once (pickGround; the pile does not stop it, so a growing pile never
//           pulls the brush towards the camera), and from above that ground point the brush looks
//           straight down onto the sculpt type's pile (its f = kSculptIso isosurface) or the ground
//           (sculptLanding). There the stroke grows ONE cone primitive (scene/sculpt_pile.h): a vertical
//           Segment standing on the ground under that spot whose isosurface is a cone at the type's angle
//           of repose (DetailTypeDesc::angle_of_repose_deg), as tall as it must be to add the material of
//           all its stamps to the pile already there (pileConeOnBed; each stamp the volume of the old
//           brush's ball, sculptStampVolume; weight kSculptPileWeight * max(1, strength)). Material runs
//           down the heap, so a slow drag over its own pile builds a ridge of steady height rather than
//           stacking each cone on the last one's flank. A stamp every radius / 3 of travel over the ground starts a new cone there;
//           while the brush is held still, every kSculptHoldInterval_s the current cone takes one more
//           stamp's volume in place (the same primitive, Document::setPrimitive), so a held brush is one
//           primitive that grows as a cone, selected, moved, deleted and re-weighted as a unit, and the
//           whole stroke is one undo step. (A dragged stroke leaves one cone per radius / 3 of travel,
//           all with the stroke's tag: one unit for Select too.)
//   Erase   per painted type: a point at the surface under the brush with weight
//           -kEraseWeight * strength * m_i, radius = brush radius: it cancels painted and sculpted density (and the file's) under the brush. We chose
//           negative points over deleting the primitives whose centres are under the brush because it
//           erases any density, also the file's own, and keeps every stroke one exact undo step.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <utility>
#include <vector>

#include "field/bounds.h"
#include "field/ray_cast.h"
#include "scene/document.h"
#include "scene/sculpt_pile.h"

namespace ug::editor {

enum class ToolKind : int { Select, Paint, Sculpt, Erase };
const char* toolName(ToolKind tool);  // "select", "paint", "sculpt", "erase"

constexpr double kSculptHoldInterval_s = 0.05;
constexpr float kEraseWeight = 4.0f;
// A pile's weight per unit of strength. The instancer keeps a candidate with probability min(1, density),
// so the density's fall from 1 to 0 is a shell of loose, floating objects around the pile: with weight 1
// the support reaches 2.2 times the isosurface's radius, with 4 only 1.41 times, and the inside is full
// (f >= 1 inside 86 % of the isosurface's radius). 4 = kEraseWeight: an erase of the same strength
// cancels a pile's core.
constexpr float kSculptPileWeight = kEraseWeight;
constexpr float kSculptIso = 0.5f;

struct BrushSettings {
    float radius_m = 1.5f;        // > 0
    float strength = 1.0f;        // > 0
    float falloff_m = 0.5f;       // paint: the disc's falloff radius, > 0
    bool subtract = false;        // paint: negative weights
    std::vector<float> type_mix;  // per detail type: 0 = not painted or erased, else the weight factor (>= 0)
    size_t sculpt_type = 0;  // the pile type: sculpt grows it; paint and erase work on its surface too
                             // (an index past the types: on the ground only)
};

// The brush settings a scene opens with: paint and erase the first type, sculpt the first type with the
// elevation strategy (a pile fills from the bottom), else the first.
BrushSettings defaultBrush(const Document& doc);

struct SurfaceHit {
    bool hit = false;
    glm::vec3 point_m{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    bool on_pile = false;  // the sculpt type's isosurface, not the ground
};

// The ground under a ray: the terrain, or without one the plane z = 0 when the extent holds it, else the
// extent's floor (what the renderer draws as the ground grid).
SurfaceHit pickGround(const Document& doc, const Ray& ray);
// The ground's height at world (x, y): the terrain's, else the ground plane's (what pickGround meets).
float groundHeightAt(const Document& doc, glm::vec2 xy_m);
// The sculpt type's f = kSculptIso isosurface when the ray meets it before the ground, else the ground.
SurfaceHit pickPile(const Document& doc, size_t type, const Ray& ray);

// What a brush works on: the pile type's isosurface (BrushSettings::sculpt_type) where the ray meets it
// before the ground, else the ground; so paint and erase work on sculpted piles too (leaves on a rock pile).
SurfaceHit pickBrushSurface(const Document& doc, const BrushSettings& brush, const Ray& ray);

// A ray straight down onto world (x, y), from above everything (scripted strokes).
Ray rayDownOnto(const Document& doc, glm::vec2 xy_m);

// Where the Sculpt brush pours (see above): the ground under the ray, then straight down onto the `type`'s
// pile there (or the ground). Does not depend on where the ray comes from, only on its ground point.
SurfaceHit sculptLanding(const Document& doc, size_t type, const Ray& ray);

// The `type`'s pile around a cone's base (scene/sculpt_pile.h PileBed): the height of its surface, or of
// the ground where there is no pile, above base_m.z on 25 x 25 columns within radius_m of the base's XY.
PileBed samplePileBed(const Document& doc, size_t type, glm::vec3 base_m, float radius_m);

// The sculpt type's pile around `centre_xy` (scene/sculpt_pile.h measurePile), from vertical columns on a
// grid of `cell_m` within `search_radius_m`: the pile's surface (from top_z down) above the ground.
// Replayed strokes report it (viewer.cpp "pile"), so tests judge the shape the user would see.
PileMeasure measureSculptedPile(const Document& doc, size_t type, glm::vec2 centre_xy, float search_radius_m,
                                float cell_m, float top_z);

class BrushStroke {
  public:
    bool active() const { return doc_ != nullptr; }
    ToolKind tool() const { return tool_; }
    size_t sculptType() const { return brush_.sculpt_type; }
    // Begins a stroke (Document::beginStroke) and stamps where the ray meets the surface. False with
    // *error when a stamp fails (the stroke stays open; end() closes it).
    bool begin(Document* doc, ToolKind tool, const BrushSettings& brush, const Ray& ray, double now_s,
               std::string* error);
    // Stamps when the brush has travelled radius / 3 since the last stamp (sculpt: or was held long enough).
    bool drag(const Ray& ray, double now_s, std::string* error);
    // Closes the stroke: one undo step (none if nothing was stamped).
    void end();

    int stamps() const { return stamps_; }
    // The union of the added primitives' supports (where the fields changed).
    const Bounds& changedBounds() const { return changed_; }
    // Where each stamp landed, in order (sculpt: on the pile or the ground, above the base of the cone it grew).
    const std::vector<glm::vec3>& stampPoints() const { return points_; }
    // Sculpt: the ids of the cones this stroke made (one per spot the brush was held or passed over).
    const std::vector<uint64_t>& pileIds() const { return pile_ids_; }

  private:
    bool stamp(const SurfaceHit& hit, double now_s, std::string* error);
    SurfaceHit pick(const Ray& ray) const;
    float pileWeight() const;   // kSculptPileWeight * max(1, strength)
    float stampVolume() const;  // one stamp's material: the old brush's ball (weight max(1, strength))
    float pileAngleDeg() const;  // the sculpt type's angle of repose
    Primitive pileCone(float volume_m3) const;  // the cone at pile_base_ adding this much to pile_bed_, tagged
    bool startPile(const SurfaceHit& landing, double now_s, std::string* error);
    bool growPile(double now_s, std::string* error);

    Document* doc_ = nullptr;
    ToolKind tool_ = ToolKind::Paint;
    BrushSettings brush_;
    glm::vec3 last_point_{0.0f};
    double last_time_s_ = 0.0;
    int stamps_ = 0;
    Bounds changed_;
    std::vector<glm::vec3> points_;
    uint32_t stroke_tag_ = 0;  // on every primitive this stroke adds
    // Sculpt: the cone being grown (pile_ids_.back()), its base and its material so far.
    std::vector<uint64_t> pile_ids_;
    glm::vec3 pile_base_{0.0f};  // on the ground under where the material landed
    PileBed pile_bed_;           // the pile it was poured onto
    float pile_volume_m3_ = 0.0f;
};

// Select tool, dragging a user primitive and the rest of its brush stroke (Document::strokeMembers): their
// skeletons follow the cursor on the horizontal plane through the grabbed one's centre (vertical: along Z,
// on the upright plane facing the ray). A sculpted pile's cone that stands on the ground keeps standing on
// it: its base follows the ground's height under its new place (plus any height the drag gave it), so a pile
// moved across a slope neither floats (its top rocks left in the air) nor sinks. Each frame's position is one Document::setPrimitives inside a stroke, so the fill follows live and the whole drag is one undo step; a
// click without motion leaves no step. Terrain kinds have no skeleton to move (begin() refuses them).
class MoveDrag {
  public:
    bool active() const { return doc_ != nullptr; }
    uint64_t id() const { return id_; }
    bool begin(Document* doc, uint64_t id, const Ray& ray);
    // False with *error when the document refuses the move (the drag stays open; end() closes it).
    bool drag(const Ray& ray, bool vertical, std::string* error);
    void end();
    int moves() const { return moves_; }

  private:
    Document* doc_ = nullptr;
    uint64_t id_ = 0;
    std::vector<std::pair<uint64_t, Primitive>> start_;  // the stroke's primitives where the drag began
    std::vector<bool> grounded_;  // per start_ member: a pile cone standing on the ground (it follows it)
    glm::vec3 grab_m_{0.0f};
    glm::vec3 applied_offset_m_{0.0f};
    int moves_ = 0;
};

// A sculpted pile's cone standing on the ground (BrushStroke::startPile stands them there; a centimetre of
// slack for a file's hand-placed ones). Moved or copied, such a cone keeps standing on the ground.
bool standsOnGround(const Document& doc, const Primitive& prim);
// How far `prim` goes when its stroke is moved by offset_m: that far, except that a cone standing on the
// ground (on_ground: standsOnGround where it started) lands on the ground under its new place, raised by
// offset_m.z.
glm::vec3 groundFollowingOffset(const Document& doc, const Primitive& prim, bool on_ground, glm::vec3 offset_m);

// Ctrl+D: a copy of the stroke `id` belongs to, as a new stroke, moved along +X by the primitive's larger
// radius (so it does not land on the original) and following the ground as a move does; one undo step.
// The copies' ids in the stroke's order (Document::strokeMembers); empty with *error on failure.
std::vector<uint64_t> duplicateStroke(Document* doc, uint64_t id, std::string* error);

// A brush stroke edited as a unit through one of its primitives (the Inspector): `id` becomes `edited`, and
// every other member of its stroke (Document::strokeMembers) moves by the same offset of the centre, and has
// its weight and falloff radii scaled by the same factors (from a zero weight: the difference is added).
// Terrain kinds keep their (absent) skeleton. The edits for Document::setPrimitives; empty for an unknown id.
std::vector<std::pair<uint64_t, Primitive>> strokeEdit(const Document& doc, uint64_t id, const Primitive& edited);

// The drags' shared motion: where the ray grabs a thing centred at `centre` (on the horizontal plane
// through it, else the centre itself), and the offset from `grab` the ray has reached: on the horizontal
// plane at the grab's height plus the height applied so far, or (vertical) only the height, on the upright
// plane through the grab point that faces the ray. False when the ray misses the plane (keep the offset).
glm::vec3 dragGrab(const Ray& ray, glm::vec3 centre);
bool dragOffset(const Ray& ray, glm::vec3 grab, glm::vec3 applied, bool vertical, glm::vec3* offset);

// The index of the point nearest the cursor on screen, within max_px (points behind the eye skipped; ties:
// the later); SIZE_MAX for none. view_proj maps world to clip space of a width x height viewport (pixels,
// y down from the top).
size_t nearestOnScreen(const std::vector<glm::vec3>& points, const glm::mat4& view_proj, float width_px,
                       float height_px, glm::vec2 cursor_px, float max_px);

// Select: the user primitive whose centre is nearest the cursor on screen, within max_px; 0 for none.
// view_proj maps world to clip space of a width x height viewport (pixels, y down from the top).
uint64_t pickPrimitive(const Document& doc, const glm::mat4& view_proj, float width_px, float height_px,
                       glm::vec2 cursor_px, float max_px);

// The world ray through a pixel (y down from the top) of a width x height viewport.
Ray rayThroughPixel(const glm::mat4& view_proj, float width_px, float height_px, glm::vec2 cursor_px);

}  // namespace ug::editor
