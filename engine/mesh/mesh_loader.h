// One entry point for every mesh format the engine reads.
#pragma once

#include <string>

#include "mesh/triangle_mesh.h"

namespace ug {

// Loads a triangle mesh by file extension (case-insensitive):
//   .glb / .gltf             -> loadGltfMesh (io/gltf_mesh_io.h, tinygltf), node transforms applied
//   .obj / .ply / .off / .stl -> our bounded readers (mesh/mesh_readers.h); polygons fan-triangulated,
//                               STL corners welded
// The whole file is read into memory after its size is checked against kMaxMeshFileBytes (2 GiB); a
// model may have at most kMaxMeshVertices vertices and kMaxMeshTriangles triangles (50 M each).
// Coordinates stay in the file's axes and units (convert with convertYUpToZUp / scaleMesh). Normals
// are recomputed. Returns false with "<path>: <reason>" on a missing file, an unsupported extension,
// a corrupt or truncated file, non-finite coordinates, bad indices, exceeded limits or no triangles;
// the reason names the element (and line, for text formats), e.g.
// "rock.obj: line 40: face 3 refers to vertex 9 but the file has 8 vertices". `out` is untouched
// then. Nothing is printed.
bool loadMeshFile(const std::string& path, TriangleMesh* out, std::string* error);

}  // namespace ug
