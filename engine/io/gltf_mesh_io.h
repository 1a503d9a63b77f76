// Plain-mesh glTF 2.0 reading and writing (tinygltf), for detail models and starter assets.
//
//   TriangleMesh mesh;
//   std::string error;
//   if (!loadGltfMesh("assets/models/rock.glb", &mesh, &error)) { report(error); }
//   convertYUpToZUp(&mesh);  // glTF files are Y up; the engine is Z up
//
// Scene export with instancing lives elsewhere (docs/architecture.md "Files and interfaces"); this file only
// moves single meshes in and out.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "mesh/triangle_mesh.h"

namespace ug {

// Loads every TRIANGLES primitive reachable from the default scene (scene 0 when none is marked
// default; every mesh when the file has no scene), with node transforms (matrix or TRS) applied, into
// one mesh. Indexed (ubyte/ushort/uint) and non-indexed primitives; POSITION must be float VEC3.
// Coordinates stay in the file's axes (glTF: Y up, metres): call convertYUpToZUp for engine space.
// base_color comes from the first triangle primitive's material pbrMetallicRoughness.baseColorFactor
// (else the TriangleMesh default). Normals are recomputed (area-weighted).
// .glb is chosen by the "glTF" magic, anything else is read as JSON .gltf (external buffers resolved
// next to the file). Limits (mesh/mesh_readers.h): the file and its external files together at most
// kMaxMeshFileBytes (checked before tinygltf reads them), the loaded model (all instances) at most
// kMaxMeshVertices vertices and kMaxMeshTriangles triangles. Images are not decoded. Returns false, out
// untouched, with "<path>: <reason>" (tinygltf's text included for parse errors) on a missing file, bad
// data, out-of-range accessors, index counts that are not a multiple of 3, a node reached twice (glTF
// nodes form trees), exceeded limits or no triangles; non-finite positions and out-of-range indices
// name the mesh, primitive and element ("mesh 2 primitive 0: index 5 is 99 but POSITION has 8
// vertices").
bool loadGltfMesh(const std::string& path, TriangleMesh* out, std::string* error);

// Writes one glTF mesh and one node per entry (name, mesh), all in the default scene. The meshes are in
// engine space (Z up) and are written Y up: (x, y, z) -> (x, z, -y). Each gets POSITION and NORMAL
// (recomputed when the mesh has none) float accessors with min/max, uint32 indices, and a PBR material
// from base_color (metallic 0, roughness 0.9). ".glb" writes binary, any other extension JSON with the
// buffer embedded as a data URI. Written atomically: a temporary file in the same folder, then
// renamed over `path`. Every mesh must pass validateMesh (else false, nothing written).
bool writeGltfMeshes(const std::string& path,
                     const std::vector<std::pair<std::string, const TriangleMesh*>>& meshes,
                     std::string* error);

// A folder of generated models (the starter sets): <dir>/<name>.glb for each name, one mesh each, made by
// `make(name, &mesh)`; the folder is created when missing. False with "<path>: <reason>" on the first
// failure.
bool writeModelFolder(const std::string& dir, const std::vector<std::string>& names,
                      const std::function<void(const std::string& name, TriangleMesh* mesh)>& make,
                      std::string* error);

}  // namespace ug
