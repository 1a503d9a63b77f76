// Strands (strand_growth.h) as a closed triangle mesh for the exports: a tube of `sides` vertices around
// every point at its radius, turned along the strand by rotation-minimising frames (a normal carried by
// parallel transport, so tubes do not twist), and closed by a flat fan at both ends. glTF has no curves:
// the tubes are what a renderer draws, and the polylines go beside them in the mesh's extras.
#pragma once

#include <cstdint>
#include <string>

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

}  // namespace ug
