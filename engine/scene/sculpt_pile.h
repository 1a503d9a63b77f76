// Sculpted piles (the editor's Sculpt tool, app/editor/tools.h): where poured material comes to rest and
// the shape it takes, as pure math on density primitives, so the tool's behaviour is tested without a
// window and does not depend on the camera.
//
// Material poured at one spot runs down the sides of its heap until they are no steeper than its angle of
// repose θ (DetailTypeDesc::angle_of_repose_deg): it builds a cone whose axis is vertical and whose height
// is tan θ times its base radius, wherever the viewer stands. A held brush is therefore not a column of
// balls but ONE primitive grown in place: a Segment from the base up the vertical axis whose falloff radius
// shrinks towards the top (primitive.h, a "generalized cylinder" piece), sized so that its f = iso
// isosurface is that cone with a rounded tip. One primitive per held spot is also what makes a stroke one
// thing to select, move, delete and re-weight (the issue: a 4 s hold used to leave ~50 loose balls).
//
//   PileCone cone = pileConeForVolume(base, n * sculptStampVolume(brush_r, w, iso), theta_deg);
//   Primitive prim = pileConePrimitive(cone, w, iso);            // its f = iso surface is the cone
//   PileMeasure m = measurePile(thickness_at, centre_xy, search_r, cell);   // tests and replay statistics
#pragma once

#include <functional>
#include <vector>
#include <glm/glm.hpp>

#include "field/density_field.h"
#include "field/primitive.h"

namespace ug {

// Where a single primitive of `weight` reaches `iso` (value = weight * (1 - d²/R²)³): at d = factor * R.
// 0 when weight <= iso (the isosurface does not exist).
float isoRadiusFactor(float weight, float iso);

// The volume one stamp of a sculpt brush adds: the half above the ground of the ball a point primitive of
// that radius and weight makes at `iso` (what one stamp of the old brush added, so a held brush fills as
// fast as before).
float sculptStampVolume(float brush_radius_m, float weight, float iso);

struct PileCone {
    glm::vec3 base_m{0.0f};     // the centre of its base, where the material lands
    float base_radius_m = 0.0f;  // on the base's level
    float height_m = 0.0f;       // of the tip above the base: tan(angle of repose) * base_radius_m
};

// The cone of `volume_m3` whose sides stand at the angle of repose (degrees, clamped to (0, 89]):
// V = π r² h / 3 with h = r tan θ.
PileCone pileConeForVolume(glm::vec3 base_m, float volume_m3, float angle_of_repose_deg);

// What a new cone is poured onto: the height of the pile already there (the sculpt type's surface) above
// the cone's base level, on a square grid of (2 half_cells + 1)² cells of `cell_m` centred on its axis,
// row by row from -y; 0 where there is none and beyond the grid.
struct PileBed {
    glm::vec2 centre_m{0.0f};
    float cell_m = 0.0f;
    int half_cells = 0;
    std::vector<float> height_m;
    float maxHeight() const;
};

// The cone on a bed: material runs down a heap until its slopes stand at the angle of repose, so what is
// poured at one spot onto a pile raises the surface to max(old surface, a cone at the angle of repose),
// and the cone's apex height H is the one whose material above the bed, ∫ max(0, cone_H − bed) dx,
// equals `volume_m3`. Its base stays on the base level (the ground): a stroke dragged slowly over its own
// pile builds a ridge that stops growing taller once each new spot's material fills its stretch, instead
// of stacking each cone on the last one's flank (the ramp a slow drag used to climb). On an empty bed this
// is pileConeForVolume's cone exactly, and so on a bed whose heights do not fill its grid.
PileCone pileConeOnBed(glm::vec3 base_m, const PileBed& bed, float volume_m3, float angle_of_repose_deg);

// The tip's rounding, as a fraction of the base radius: small enough that the cone reads as a cone, and
// at most half the height so flat piles keep a positive axis.
float pileTipFraction(float angle_of_repose_deg);

// A Segment from the base straight up, radius falling linearly from the base radius to the tip's, weight
// `weight` (> iso): its f = iso isosurface, alone, is a cone of base radius cone.base_radius_m on the base's
// level and a rounded tip at cone.height_m above it. Its axis is vertical for any cone.
Primitive pileConePrimitive(const PileCone& cone, float weight, float iso);

// True for what pileConePrimitive makes (a Segment going straight up, narrowing): the outliner calls it a pile.
bool isPileCone(const Primitive& prim);

// What a pile measures: from vertical columns on a grid of `cell_m` within `search_radius_m` of
// `centre_xy`, each with the pile's thickness there (the height of the type's isosurface above the ground;
// <= min_thickness_m: no pile).
struct PileMeasure {
    bool found = false;
    glm::vec2 centroid_m{0.0f};  // volume-weighted centre, XY
    float height_m = 0.0f;       // the thickest column
    float radius_m = 0.0f;       // of the disc with the footprint's area
    float volume_m3 = 0.0f;
    int columns = 0;             // columns on the pile
};
PileMeasure measurePile(const std::function<float(glm::vec2)>& thickness_m, glm::vec2 centre_xy,
                        float search_radius_m, float cell_m, float min_thickness_m = 0.02f);

// A pile's thickness in `field` at xy over flat ground at ground_z: the highest f = iso crossing below
// top_z, minus ground_z (0 where a vertical ray from top_z meets no isosurface above the ground).
float pileThicknessOverPlane(const DensityField& field, float iso, glm::vec2 xy_m, float ground_z, float top_z);

}  // namespace ug
