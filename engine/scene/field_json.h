// Density fields in the project file: a tree of JSON nodes read into the flat DensityField of
// density_field.h, and written back by walking the tree from its root.
//
// A node is an object with exactly one key, its kind:
//   {"point":         {"center": [x, y, z], "radius": R, "weight": w}}
//   {"segment":       {"a": [x, y, z], "b": [x, y, z], "radius": R, "end_radius": R2, "weight": w}}
//                     (end_radius: the radius at b, default R; R != R2 is a cone)
//   {"disc":          {"center": [..], "normal": [..], "disc_radius": a, "radius": R, "weight": w}}
//   {"box":           {"center": [..], "half_extents": [..], "radius": R, "weight": w}}
//   {"half_space":    {"point": [..], "normal": [..], "radius": R, "weight": w}}
//                     (the solid side is behind the plane: the normal points out of it)
//   {"terrain_layer": {"thickness": t, "radius": R, "weight": w}}            (needs the project's terrain)
//   {"terrain_solid": {"radius": R, "weight": w (default 10000 = kSolidWeight)}}  (the ground as a solid)
//   {"polyline":      {"vertices": [[x, y, z, r], ...] (>= 2), "weight": w}}  (addPolyline)
//   {"blend": [nodes]}  {"union": [nodes]}  {"intersection": [nodes]}  {"difference": [nodes]}
// weight defaults to 1 (terrain_solid: kSolidWeight); every other member of a primitive is required.
// Radii are > 0, thickness, disc_radius and half_extents >= 0, normals non-zero (they are normalized on
// load unless already unit to within 1e-6, so a saved normal reloads bit for bit). Terrain primitives
// always refer to height field 0, the project's terrain, which the document never attaches (the scene
// compiler does, scene_compile.h).
//
// Writing walks from the root, so nodes unreachable from it are dropped and a node referenced twice is
// written twice; a polyline comes back as the Union (Intersection for a negative weight) of its segments,
// which is what addPolyline built, so the reloaded field has the same primitives, nodes and values, bit
// for bit. A field whose root is kNoNode (0 everywhere) has no JSON: the caller leaves the key out.
#pragma once

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

#include "field/density_field.h"
#include "scene/json_reader.h"

namespace ug {

// Refused on load, with the pointer of the node that crosses the limit: deeper trees would only come
// from a generator gone wrong (and would risk the reader's stack), larger ones from a runaway script.
constexpr int kMaxFieldDepth = 64;
constexpr size_t kMaxFieldPrimitives = 1000000;
constexpr size_t kMaxFieldNodes = 1000000;

// Reads the node at `j` (JSON pointer `pointer`) into *out, replacing it. The root is the node; a lone
// primitive is wrapped in a one-child Blend (a root must be a node). has_terrain: whether terrain
// primitives may be used. Errors through `r`: "<file>: <pointer of the offending value>: <reason>".
bool readDensityField(JsonReader& r, const nlohmann::json& j, const std::string& pointer, bool has_terrain,
                      DensityField* out);

// The tree from field.root (see above); null when field.root == kNoNode. The field must be valid.
nlohmann::json densityFieldToJson(const DensityField& field);

// A direction as the document keeps it: normalized unless already unit to within 1e-6 (a normalized
// float vector is unit to ~1e-7, and normalizing it again could move a bit and break the exact round
// trip). A zero vector stays zero (the caller reports it).
glm::vec3 documentUnitVector(glm::vec3 v);

// A float as the shortest decimal that reads back as the same float ("0.1", not 0.10000000149011612).
nlohmann::json jsonFloat(float v);

}  // namespace ug
