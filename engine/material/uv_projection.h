// Texture coordinates for materials: box (dominant-axis) projection for detail models, planar XY for
// the terrain. One rule, used by the glTF export per triangle and mirrored by the renderer per fragment,
// so both put the texture in the same place.
//
// The rule (model space for detail models, metres, Z up; s = texture_scale_m):
//   n = the triangle's geometric normal (cross(b - a, c - a); in a fragment shader
//       cross(dFdx(p), dFdy(p)) of the model-space position p; only its direction's magnitudes matter)
//   if |n.z| >= |n.x| and |n.z| >= |n.y|:  uv = (p.x, p.y) / s     (ties go to Z, then X)
//   else if |n.x| >= |n.y|:                uv = (p.y, p.z) / s
//   else:                                  uv = (p.x, p.z) / s
// so on the sides v follows Z (grass blades run up the model) and u follows X on the sides facing Y
// and Z (bark fibres run along a branch modelled along X). The terrain always takes
// uv = (world x, world y) / s. Then a material's texture_rotation_deg r turns uv about the origin,
// counter-clockwise: uv' = (cos r * u - sin r * v, sin r * u + cos r * v) (rotateTextureUv; r = 0 keeps
// uv bit for bit, r = 90 gives (-v, u): bark's fibres, along u', then run up an upright trunk). No flip:
// v = 0 is the image's first row in glTF and, uploading the rows in memory order, t = 0 in GL.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "mesh/triangle_mesh.h"

namespace ug {

// 0 = X, 1 = Y, 2 = Z: the axis the projection looks along for a surface with normal n (rule above).
int dominantAxis(glm::vec3 n);

// uv of model-space point p on a surface with normal n (rule above); s > 0.
glm::vec2 boxProjectUv(glm::vec3 p, glm::vec3 n, float texture_scale_m);

// The terrain's uv of world point p.
glm::vec2 planarXyUv(glm::vec3 p, float texture_scale_m);

// uv turned by `degrees` (rule above). Multiples of 90 are exact (no rounding of cos and sin), so a
// quarter turn moves texels and does not resample them.
glm::vec2 rotateTextureUv(glm::vec2 uv, float degrees);
// (cos, sin) of `degrees` as rotateTextureUv uses them: the renderer's uniform.
glm::vec2 textureRotationCosSin(float degrees);

// `mesh` with uvs by the box rule per triangle: a vertex shared by triangles that project along
// different axes is split (one copy per axis, normals kept), so each triangle's uvs follow its own
// axis. Vertices are emitted in first-use order; a mesh whose triangles all share one axis keeps its
// vertex count. Degenerate triangles (zero normal) take Z.
void boxProjectMesh(const TriangleMesh& mesh, float texture_scale_m, TriangleMesh* out, std::vector<glm::vec2>* uvs);

}  // namespace ug
