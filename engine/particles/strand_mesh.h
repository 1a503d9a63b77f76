// Strands (strand_growth.h) as triangle meshes for the viewport and the exports (glTF has no curves: the
// meshes are what a renderer draws, and the polylines go beside them in the mesh's extras):
// - tubes: `sides` vertices around every point at its radius, turned along the strand by
//   rotation-minimising frames (a normal carried by parallel transport, so tubes do not twist), closed by
//   a flat fan at both ends;
// - blades: a flat ribbon across every point, its width tapering linearly from the root to the tip, its
//   across-direction carried by parallel transport from a hashed turn about the first segment (blades of
//   a patch face every way), with a front and a back face (each with its own normal, so no renderer needs
//   double-sided materials): 4 triangles a segment where a 3-sided tube takes 6.
#pragma once

#include <cstdint>
#include <string>

#include "io/mesh_instances.h"
#include "mesh/triangle_mesh.h"
#include "particles/particle_json.h"
#include "particles/strand_growth.h"

namespace ug {

// Triangles the tubes of `strands` need: per strand of n points, 2·sides·(n − 1) around it and
// 2·(sides − 2) for its two ends.
uint64_t strandTubeTriangles(const Strands& strands, uint32_t sides);

// False (and nothing allocated) when the tubes would need more than settings.max_triangles triangles.
bool strandTubeMesh(const Strands& strands, const StrandMeshSettings& settings, TriangleMesh* out,
                    std::string* error);

// Triangles the blades need: 4·(n − 1) per strand of n points.
uint64_t strandBladeTriangles(const Strands& strands);
bool strandBladeMesh(const Strands& strands, const StrandMeshSettings& settings, TriangleMesh* out,
                     std::string* error);

// Coarser levels of strandMesh's mesh over its own vertices: the tubes or blades through every 2nd, 4th and
// 8th point of each strand (and its last), each with the farthest a dropped point lies from the chord that
// replaces it (the radius and the ends are kept). Levels that would not save a tenth of the previous one's
// triangles are left out (short strands), so `out` may hold fewer than three.
void strandMeshLevels(const Strands& strands, const StrandMeshSettings& settings, std::vector<MeshLodLevel>* out);

// The settings' shape: strandTubeMesh or strandBladeMesh.
bool strandMesh(const Strands& strands, const StrandMeshSettings& settings, TriangleMesh* out, std::string* error);

}  // namespace ug
