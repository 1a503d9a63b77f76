// A triangle mesh of a height field, for export and previews.
//
//   TriangleMesh ground;
//   if (!heightFieldMesh(hf, scene_bounds, 512, &ground, &error)) report(error);
#pragma once

#include <string>

#include "field/bounds.h"
#include "field/height_field.h"
#include "mesh/triangle_mesh.h"

namespace ug {

// The earthy colour terrain meshes get (linear RGB).
constexpr glm::vec3 kTerrainColor{0.33f, 0.26f, 0.18f};

// A regular grid mesh (world space, metres, Z up) of `hf` over the XY rectangle where the field's sample
// rectangle [origin, origin + (size - 1) * cell] and extent's XY overlap (extent's Z is ignored; an
// infinite extent takes the whole field). Grid lines run along the field's sample lines, every
// `stride`-th one where stride is the smallest that keeps at most max_cells_per_side cells per side, plus
// the rectangle's borders (heights there are the field's bilinear values), so an undecimated mesh
// reproduces the samples exactly. Triangles face +Z, normals are computed, base_color = kTerrainColor.
// Returns false, *out untouched, with a reason when: the field is empty or has fewer than 2 samples on
// a side; max_cells_per_side is outside [1, kMaxHeightFieldSide]; the extent is empty or has NaN bounds;
// the overlap is empty or has zero area.
bool heightFieldMesh(const HeightField& hf, const Bounds& extent, int max_cells_per_side, TriangleMesh* out,
                     std::string* error);

}  // namespace ug
