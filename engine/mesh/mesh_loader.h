// One entry point for every mesh format the engine reads.
#pragma once

#include <string>

#include "mesh/triangle_mesh.h"

namespace ug {

// Loads a triangle mesh by file extension (case-insensitive):
//   .glb / .gltf             -> loadGltfMesh (tinygltf), node transforms applied
//   .obj / .ply / .off / .stl -> OpenMesh IO; polygons are triangulated (fan)
// Coordinates stay in the file's axes and units (convert with convertYUpToZUp / scaleMesh).
// Normals are recomputed. Returns false with "<path>: <reason>" on a missing file, an unsupported
// extension, a corrupt file, non-finite coordinates or no triangles; `out` is untouched then.
// note: OpenMesh drops faces it cannot add to a manifold half-edge mesh (complex edges), so a
// non-manifold OBJ may lose a few triangles.
bool loadMeshFile(const std::string& path, TriangleMesh* out, std::string* error);

}  // namespace ug
