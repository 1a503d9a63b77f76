// Skeletal density primitives (Ghost Tile §5; Wyvill, Guy, Galin 1999 "Extending the CSG tree").
//
// Every primitive's value at p is
//     value(p) = weight * K(d(p), R),   K(d, R) = (1 - d²/R²)³ for d < R, exactly 0 otherwise,
// where d is the distance from p to the primitive's skeleton (0 inside a box, a half-space or a terrain
// layer) and R = radius_m is the falloff radius. K is 1 on the skeleton, 0.421875 at d = R/2 and C2 at
// d = R, so the support of a primitive is compact and known: bounds() encloses every point where the
// value is not 0. weight may be negative (a subtracting brush) or 0.
//
// | kind         | fields used                                                   | d(p)                          |
// |--------------|---------------------------------------------------------------|-------------------------------|
// | Point        | center_m, radius_m                                            | |p - center|                  |
// | Segment      | center_m (start), end_m, radius_m (at start), end_radius_m   | |p - closest|; R interpolated |
// |              | (at end); radius_m == end_radius_m is a capsule               | at the projection parameter   |
// | Disc         | center_m, normal (unit), disc_radius_m (>= 0), radius_m       | distance to the flat disc     |
// | Box          | center_m, half_extents_m (>= 0, axis-aligned), radius_m       | 0 inside, distance outside    |
// | HalfSpace    | center_m (a point on the plane), normal (unit, pointing out), | 0 where dot(p - c, n) <= 0,   |
// |              | radius_m                                                      | dot(p - c, n) outside         |
// | TerrainLayer | height_field, thickness_m (>= 0), radius_m                    | vertical: 0 for h <= z <=     |
// |              |                                                               | h + thickness, else the gap   |
// | TerrainSolid | height_field, radius_m                                        | see below                     |
// | External     | external, weight                                              | weight · the external field's |
// |              |                                                               | value (external_field.h)      |
//
// TerrainSolid: the ground as a solid to subtract from details (docs/architecture.md "solids subtract so
// details never sink"): full weight at depth >= radius_m below the surface, falling to exactly 0 at the
// surface z = h(x, y) and above (d = max(0, z - (h - R)) with the kernel restricted to z < h). Give it a
// weight larger than any detail field value (kSolidWeight) and put it on the subtracted side of a
// Difference: just below the ground every detail field becomes <= 0, on and above it nothing changes.
//
// A polyline / generalized cylinder is a set of Segment primitives, one per edge, under a Union node:
// see addPolyline() in density_field.h.
//
// Terrain kinds refer to a height field by index (into DensityField::height_fields); the functions here
// take the resolved pointer, which must be non-null for those kinds and is ignored for the others.
// Gradients are analytic: d value / d p, in value units per metre.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "field/bounds.h"

namespace ug {

class HeightField;

enum class PrimitiveKind : uint8_t { Point, Segment, Disc, Box, HalfSpace, TerrainLayer, TerrainSolid, External };

// A weight for solids that dominates any sensible detail density (detail fields are O(1)).
constexpr float kSolidWeight = 1.0e4f;

const char* primitiveKindName(PrimitiveKind kind);  // "point", "segment", ...

struct Primitive {
    PrimitiveKind kind = PrimitiveKind::Point;
    float weight = 1.0f;                 // finite; the value on the skeleton
    float radius_m = 1.0f;               // falloff radius R, finite, > 0 (Segment: R at the start)
    glm::vec3 center_m{0.0f};            // see the table above
    glm::vec3 end_m{0.0f};               // Segment end
    float end_radius_m = 1.0f;           // Segment: R at the end, finite, > 0
    glm::vec3 normal{0.0f, 0.0f, 1.0f};  // Disc, HalfSpace: unit length (|n| - 1 within 1e-4)
    float disc_radius_m = 0.0f;          // Disc: radius of the flat skeleton, >= 0
    glm::vec3 half_extents_m{0.0f};      // Box: >= 0 per axis
    float thickness_m = 0.0f;            // TerrainLayer: >= 0
    uint32_t height_field = 0;           // TerrainLayer, TerrainSolid: index into the field's height fields
    uint32_t external = 0;               // External: index into the field's external fields
    // The brush stroke that made it (0: none): the editor selects, moves, deletes and re-weights a
    // stroke's primitives as one thing. A tag only: it never changes a value.
    uint32_t stroke = 0;
};

// Builders fill the fields their kind uses; normals are normalized here (a zero normal stays zero and
// is reported by validatePrimitive()).
Primitive makePoint(glm::vec3 center_m, float radius_m, float weight = 1.0f);
Primitive makeSegment(glm::vec3 a_m, glm::vec3 b_m, float radius_m, float weight = 1.0f);
Primitive makeCone(glm::vec3 a_m, float radius_a_m, glm::vec3 b_m, float radius_b_m, float weight = 1.0f);
Primitive makeDisc(glm::vec3 center_m, glm::vec3 normal, float disc_radius_m, float radius_m, float weight = 1.0f);
Primitive makeBox(glm::vec3 center_m, glm::vec3 half_extents_m, float radius_m, float weight = 1.0f);
Primitive makeHalfSpace(glm::vec3 point_m, glm::vec3 outward_normal, float radius_m, float weight = 1.0f);
Primitive makeTerrainLayer(uint32_t height_field, float thickness_m, float radius_m, float weight = 1.0f);
Primitive makeTerrainSolid(uint32_t height_field, float falloff_depth_m, float weight = kSolidWeight);
// External kinds never reach the functions below with their field: DensityField resolves them
// (density_field.cpp); here they are bounded by everything and evaluate to 0.
Primitive makeExternal(uint32_t external, float weight = 1.0f);

// The primitive with its skeleton moved by offset_m (centre, and a segment's end). Terrain kinds follow
// their height field and are returned unchanged.
Primitive translatedPrimitive(Primitive prim, glm::vec3 offset_m);

// Checks every field the kind uses (finite, ranges above, height_field < height_field_count for terrain
// kinds). On failure *error = "primitive <index> (<kind>): <field> <reason>".
bool validatePrimitive(const Primitive& prim, size_t index, size_t height_field_count, std::string* error);

// AABB of the support (every point where value != 0 lies inside it, padded a little against rounding).
// Infinite along every axis the support is unbounded on: HalfSpace (bounded on one side only when the
// normal is an axis), TerrainLayer/TerrainSolid in X and Y (the height field is clamped outside its
// rectangle, so they extend forever).
Bounds primitiveBounds(const Primitive& prim, const HeightField* height_field);

// A conservative AABB of {p in box : value(p) > 0}: empty for weight <= 0, else the support clipped to box,
// with terrain kinds bounded in Z by the heights under the box only (HeightField::heightRange), which is
// what lets the instantiator skip most of a terrain layer's tiles and candidates without evaluating them.
Bounds primitivePositiveBoundsIn(const Primitive& prim, const HeightField* height_field, const Bounds& box);

float primitiveValue(const Primitive& prim, const HeightField* height_field, glm::vec3 p_m);
// (gradient.xyz, value) — the value is bit-identical to primitiveValue().
glm::vec4 primitiveValueAndGradient(const Primitive& prim, const HeightField* height_field, glm::vec3 p_m);

}  // namespace ug
