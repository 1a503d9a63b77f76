// What the instantiator needs to know about one detail type besides its Ghost Tile candidates: the density
// field f_i, the priority strategy (Ghost Tile §5.2) and the orientation and size constraints (§5.3,
// Figures 17 and 22). The scene document (engine/scene) compiles these from the project file; the editor
// swaps in new fields after each edit.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

#include "field/density_field.h"
#include "field/direction_field.h"
#include "field/height_field.h"

namespace ug {

// Keys compare across detail types (the collision graph spans them), so types that meet should share a
// strategy: a Random type has layer 0, which sorts before every Elevation layer above z = 0. The order is
// still total and deterministic when they differ.
enum class PriorityStrategy : uint8_t {
    Random,              // no priority: only the weighted random number orders candidates (scattered layers)
    Elevation,           // lower first, in layers of layer_m (compact piles, §5.2)
    DistanceToBoundary,  // nearer the field's boundary first, in layers of layer_m (shells, §5.2)
};

const char* priorityStrategyName(PriorityStrategy s);  // "random", "elevation", "distance_to_boundary"

// §5.3 "Control": a candidate is kept when dot(z axis of its frame, u(origin)) >= min_cos.
struct OrientationConstraint {
    bool enabled = false;
    DirectionField direction;  // u: constant (Fig. 17 left) or the gradient of a field (Fig. 17 right)
    float min_cos = 0.866f;    // cos of the largest accepted angle, in [-1, 1]
};

// Figure 22: a size field prescribes the scale of the objects near the openings. A candidate is kept when
// its scale is within `tolerance` (relative) of the field's target at its origin:
// |scale / target - 1| <= tolerance.
struct SizeConstraint {
    bool enabled = false;
    SizeField target;
    float tolerance = 0.25f;  // >= 0
};

// Candidates that would sink into the ground: rejected like a constraint (issue "piles that rest": half of
// the beaver dam's grass tufts reached more than 2 cm below the terrain they were exported with). A
// candidate is kept when none of its lowest collision spheres reaches more than max_sink_m below the
// ground under its centre: the terrain, or without one the scene's ground plane (a pile on a floor: the
// rock pile's bottom rocks reached up to 5 cm into it). Off with neither.
struct SinkConstraint {
    std::shared_ptr<const HeightField> terrain;  // null: the plane below, if any
    float ground_z = std::numeric_limits<float>::quiet_NaN();  // without a terrain: the plane z = ground_z; NaN: off
    float max_sink_m = 0.02f;                    // >= 0
    bool enabled() const { return terrain || std::isfinite(ground_z); }
};

struct InstanceTypeSettings {
    std::shared_ptr<const DensityField> field;  // f_i (solids already subtracted); null = nowhere
    PriorityStrategy strategy = PriorityStrategy::Random;
    float layer_m = 0.02f;  // Elevation / DistanceToBoundary: thickness of one priority layer, > 0
    OrientationConstraint orientation;
    SizeConstraint size;
    SinkConstraint sink;
};

}  // namespace ug
