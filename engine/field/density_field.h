// Density fields f_i: one per detail type, a BlobTree of skeletal primitives (Ghost Tile §5, WGG99).
// f_i(p) <= 0 means "no detail of type i here"; positive values are its relative density.
//
// Layout (flat, stable, cheap to copy and hash):
//   primitives    the leaves (primitive.h), in a fixed order;
//   nodes         operator nodes; a node's children are children[first_child, first_child + child_count);
//                 every child is a primitive or an EARLIER node (children come before parents), so one
//                 pass over nodes [0, root] evaluates the tree; nodes after the root are ignored;
//   children      child references: primitiveChild(i) or nodeChild(n);
//   height_fields shared, read-only terrains referred to by terrain primitives' height_field index.
//
// Operators, for children c_0 .. c_k (values v, gradients g):
//   Blend         v = sum of v_i (in child order, starting from +0)     g = sum of g_i
//   Union         v = max of v_i                                        g = g of the first child with that max
//   Intersection  v = min of v_i                                        g = g of the first child with that min
//   Difference    v = v_0 - sum_{i>=1} max(v_i, 0) where v_0 > 0,       g = g_0 - sum of g_i over v_i > 0
//                 v = v_0 where v_0 <= 0                                 (g = g_0 there)
//                 (the solid b only removes where it is positive: a - max(b, 0); where a <= 0 there is
//                 nothing to remove, so the solids are not even evaluated)
//   An operator with no children is 0.
//
// Exactness (docs/architecture.md "Instantiation as a pure function"): no value depends on who computed it.
// evaluate(), evaluateWithGradient(), evaluateBatch() with or without a tile list all run the same code
// and return the same bits for the same point (the w of evaluateWithGradient equals evaluate()). A tile
// list leaves out primitives whose support misses its box; they are exactly +0 there, sums skip them
// (x + 0 == x, and the running sum starts at +0 so it is never -0), and max/min/difference keep a zero
// in their place, so the operators' semantics and tie-breaking are unchanged.
//
// Usage:
//   DensityField grass = makeBlendField({makePoint({0, 0, 0}, 2.0f), makeSegment({0, 0, 0}, {5, 0, 0}, 1.0f)});
//   uint32_t ground = addHeightField(&grass, terrain);                 // std::shared_ptr<const HeightField>
//   subtractSolids(&grass, {makeTerrainSolid(ground, 0.05f)});
//   std::string error;
//   if (!validate(grass, &error)) ...
//   TileFieldList list;
//   buildTileList(grass, tile_box, &list);                             // once per tile
//   evaluateBatch(grass, &list, anchors, anchor_count, densities);     // anchors inside tile_box
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "field/bounds.h"
#include "field/external_field.h"
#include "field/height_field.h"
#include "field/primitive.h"

namespace ug {

enum class FieldOp : uint8_t { Blend, Union, Intersection, Difference };

const char* fieldOpName(FieldOp op);  // "blend", "union", ...

constexpr uint32_t kNoNode = 0xffffffffu;
// Child references: the top bit tells primitives from nodes. kZeroChild (only in tile lists) stands for
// left-out primitives: exactly (+0 gradient, +0 value).
constexpr uint32_t kPrimitiveChildBit = 0x80000000u;
constexpr uint32_t kZeroChild = 0xffffffffu;
inline uint32_t primitiveChild(uint32_t primitive_index) { return primitive_index | kPrimitiveChildBit; }
inline uint32_t nodeChild(uint32_t node_index) { return node_index; }
inline bool isPrimitiveChild(uint32_t ref) { return (ref & kPrimitiveChildBit) != 0 && ref != kZeroChild; }
inline uint32_t childIndex(uint32_t ref) { return ref & ~kPrimitiveChildBit; }

struct FieldNode {
    FieldOp op = FieldOp::Blend;
    uint32_t first_child = 0;  // into DensityField::children
    uint32_t child_count = 0;
};

struct DensityField {
    std::vector<Primitive> primitives;
    std::vector<FieldNode> nodes;
    std::vector<uint32_t> children;
    uint32_t root = kNoNode;  // kNoNode: the field is 0 everywhere
    std::vector<std::shared_ptr<const HeightField>> height_fields;
    // External terms referred to by External primitives (external_field.h): scattered effects.
    std::vector<std::shared_ptr<const ExternalField>> externals;
};

// ---- building --------------------------------------------------------------------------------------
// Appends and returns the index. Children must already exist (primitives or earlier nodes).
uint32_t addPrimitive(DensityField* field, const Primitive& primitive);
uint32_t addNode(DensityField* field, FieldOp op, std::span<const uint32_t> child_refs);
uint32_t addHeightField(DensityField* field, std::shared_ptr<const HeightField> height_field);
uint32_t addExternal(DensityField* field, std::shared_ptr<const ExternalField> external);

// A generalized cylinder along a polyline: vertices_m[k] = (x, y, z, radius at that vertex). Adds one
// Segment primitive per edge (radius interpolated along it) under a Union node (an Intersection node when
// weight < 0), so the value is weight * max over edges of K(d_edge, R_edge(t)): no bulge at the joints,
// continuous everywhere, and per-edge bounds let tile lists keep only the nearby edges of a long river.
// Returns false (and adds nothing) with *error naming the vertex and the reason when there are fewer
// than 2 vertices or a coordinate / radius is not finite or a radius is <= 0; else *out_ref = the node.
bool addPolyline(DensityField* field, std::span<const glm::vec4> vertices_m, float weight, uint32_t* out_ref,
                 std::string* error);

// The common painting case: root = Blend of the given primitives in order.
DensityField makeBlendField(std::span<const Primitive> primitives);
DensityField makeBlendField(std::initializer_list<Primitive> primitives);

// root := Difference(root, Union(solids)): every solid is removed where it is positive (an empty field
// stays empty; with no solids nothing changes). Terrain solids must refer to this field's height fields.
void subtractSolids(DensityField* field, std::span<const Primitive> solids);
void subtractSolids(DensityField* field, std::initializer_list<Primitive> solids);

// Checks every primitive (validatePrimitive), height field references (in range, non-null), node
// operators, child ranges and references (no forward or self references, no kZeroChild), and the root.
// *error names the primitive or node index and the reason.
bool validate(const DensityField& field, std::string* error);

// ---- evaluating --------------------------------------------------------------------------------------
// The field must be valid (validate()); points must be finite.
float evaluate(const DensityField& field, glm::vec3 p_m);
// (gradient.xyz, value): analytic gradient, per operator as in the table above.
glm::vec4 evaluateWithGradient(const DensityField& field, glm::vec3 p_m);

// The primitives and the pruned tree of one box (a tile). Reuse one across tiles: buildTileList clears
// and refills it without freeing memory. A list is valid for the field it was built from, unchanged:
// rebuild it after any edit of that field.
struct TileNode {
    uint32_t node = 0;  // the field node this evaluates
    FieldOp op = FieldOp::Blend;
    uint32_t first_child = 0;  // into TileFieldList::children
    uint32_t child_count = 0;
};
struct TileFieldList {
    Bounds box;
    std::vector<uint32_t> primitives;  // ascending indices of every primitive whose support touches box
    std::vector<TileNode> nodes;       // nodes that may be non-zero in box, in evaluation order
    std::vector<uint32_t> children;    // pruned child references (kZeroChild for left-out ones)
    std::vector<uint8_t> node_live;    // per field node: 1 when it is in `nodes`
    bool root_live = false;
    // The field is exactly 0 everywhere in box: the tile can be skipped.
    bool empty() const { return !root_live; }
};

// Fills *out for box. With `parent` (a list built for a box containing this one, e.g. a region around
// tiles), only the parent's primitives are tested: hierarchical refinement in O(parent list).
void buildTileList(const DensityField& field, const Bounds& box, TileFieldList* out,
                   const TileFieldList* parent = nullptr);
TileFieldList buildTileList(const DensityField& field, const Bounds& box);

// out[k] = the field at points_m[k], k < count, bit-identical to evaluate(). With a list, every point
// must lie inside list->box (outside it the result is unspecified). No allocation for trees of up to 64
// nodes (a thread-local scratch beyond).
void evaluateBatch(const DensityField& field, const TileFieldList* list, const glm::vec3* points_m, size_t count,
                   float* out);
// out[k] = (gradient.xyz, value), bit-identical to evaluateWithGradient().
void evaluateBatchWithGradient(const DensityField& field, const TileFieldList* list, const glm::vec3* points_m,
                               size_t count, glm::vec4* out);

// AABB of the positive support {p : f(p) > 0} (conservative): Blend and Union unite their children's,
// Intersection intersects them, Difference keeps its first child's; a primitive with weight <= 0 has
// none. Use it to know which tiles to visit (it may be infinite: intersect it with the scene's extent).
Bounds positiveBounds(const DensityField& field);

// A conservative AABB of {p in list.box : f(p) > 0}, from the list's pruned tree with the same rules as
// positiveBounds() and primitivePositiveBoundsIn() per primitive. Empty when the field cannot be positive
// in the box. A point outside it has f <= 0 without evaluating anything.
Bounds positiveBoundsIn(const DensityField& field, const TileFieldList& list);

}  // namespace ug
