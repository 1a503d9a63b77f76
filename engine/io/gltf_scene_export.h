// glTF 2.0 export of an instantiated scene (docs/architecture.md "Files and interfaces"):
//   - one mesh per detail type, with a PBR material: the type's SurfaceMaterial when given (base colour,
//     roughness, a baked procedural texture as an embedded PNG, alpha cut-out), else the model's base
//     colour;
//   - its instances through EXT_mesh_gpu_instancing (TRANSLATION, ROTATION, SCALE accessors), split into
//     spatial chunks (one node per type and chunk) so engines can cull;
//   - or, with use_instancing_extension = false, one plain node per instance (viewers without it);
//   - the terrain and the static meshes (io/mesh_instances.h: environmental objects, snow, icicles), one mesh
//     each, drawn at the identity or at their instances (chunked like the detail types);
//   - every detail mesh's `extras`: {"collision_spheres": [[x, y, z, r], ...] in mesh space, "delta": δ};
//   - the scene's `extras`: the statistics JSON given by the caller.
// Engine space is Z up; glTF is Y up: positions, rotations and spheres are converted on the way out.
// The file is written atomically; .glb (binary) or .gltf (JSON with the buffer embedded as a data URI)
// by the path's extension.
//
// What the file holds, exactly (readers and tests rely on it):
//   - meshes: one per detail type, named after it, in `types` order, then "terrain" when given, then one
//     per static mesh (SceneExport::meshes), named after it, in order. POSITION
//     and NORMAL float VEC3 (POSITION with min/max), indices uint16 when the mesh has at most 65,535
//     vertices, else uint32; material "<type>" (metallic 0, roughness 0.9, single-sided) when the type
//     has no SurfaceMaterial. With one: baseColorFactor = its base colour and roughnessFactor its
//     roughness; with a texture, baseColorFactor is [1, 1, 1, 1] and baseColorTexture the baked texture
//     (which already holds base colour x detail, sRGB), the primitive gets TEXCOORD_0 (float VEC2, the box
//     projection of material/uv_projection.h in engine model space, so vertices on edges between
//     projection axes are split, then turned by texture_rotation_deg), and the material's extras hold
//     {"texture", "texture_scale_m", "tint_variation"} and "texture_rotation_deg" when it is not 0;
//     alpha_cutout adds alphaMode MASK, alphaCutoff 0.5 and doubleSided. The terrain
//     likewise, with uv = world (x, y) / texture_scale_m; a static mesh like a detail type (box projection in
//     its object space). A static mesh's extras are its extras_json (none when empty); the terrain has none.
//   - textures: each distinct image (same size and bytes) is written once, as a PNG in its own buffer
//     view (mimeType image/png), with one sampler: REPEAT in both directions, linear, mipmapped.
//   - chunks: instance i of a type (or of a static mesh with instances) belongs to chunk (ix, iy) = (floor(x / chunk_size_m),
//     floor(y / chunk_size_m)) of its engine-space position. Each non-empty (type, chunk) gets one node
//     named "<type>/chunk_<ix>_<iy>" whose translation is the chunk's XY centre (engine z = 0, converted
//     to Y up); the instance translations are relative to it, so float32 keeps millimetres far from the
//     origin. Chunks are written in (type, ix, iy) order, instances of a chunk in input order.
//   - with the extension, that node carries the mesh and EXT_mesh_gpu_instancing {TRANSLATION, ROTATION
//     (unit x, y, z, w), SCALE}; the extension is listed in extensionsUsed only (not required), so a
//     viewer without it still opens the file and shows one copy per chunk node.
//   - without it, the chunk node has one child per instance, named "<type>/<instance index>", holding the
//     mesh and the instance's translation, rotation and scale. Refused above kMaxPlainNodeInstances.
//   - the terrain: node "terrain" at the origin. A static mesh with no instances: one node named after it
//     at the origin, holding the mesh; with instances: chunk nodes "<name>/chunk_<ix>_<iy>" exactly like a
//     detail type's (with the extension, or one child "<name>/<instance index>" per instance without).
//   - names: the detail types, "terrain" (when given) and the static meshes are all distinct.
//   - the buffer: one; in a .gltf it is embedded as a base64 data URI (no sidecar file to lose).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "io/mesh_instances.h"
#include "material/material.h"
#include "mesh/detail_model.h"
#include "mesh/triangle_mesh.h"

namespace ug {

// Plain-node mode writes one JSON node per instance; beyond this many instances (all types and static meshes together) the
// file would be hundreds of MB of JSON, so writeSceneGltf refuses and suggests the extension.
constexpr size_t kMaxPlainNodeInstances = 200000;

struct ExportDetailType {
    std::string name;
    const TriangleMesh* mesh = nullptr;        // model space, Z up (DetailModel::mesh); not owned
    std::vector<Sphere> collision_spheres;     // model space, Z up
    std::vector<InstanceTransform> instances;  // engine space
    const SurfaceMaterial* material = nullptr;  // null: the mesh's base colour, roughness 0.9; not owned
};

struct SceneExport {
    std::vector<ExportDetailType> types;
    const TriangleMesh* terrain = nullptr;  // world space, Z up; optional; not owned
    const SurfaceMaterial* terrain_material = nullptr;  // null: the terrain mesh's base colour; not owned
    // Written after the detail types and the terrain (which goes through the same path, as one copy at the
    // identity named "terrain").
    std::vector<MeshInstances> meshes;
    float delta_m = 0.0f;                   // the Ghost Tile's δ, written in every detail mesh's extras
    float chunk_size_m = 8.0f;              // edge of the square XY chunks instances are grouped by, > 0
    bool use_instancing_extension = true;   // false: one plain node per instance
    std::string scene_extras_json = "{}";   // a JSON object stored as the scene's extras (statistics)
};

// Returns false with *error = "<path>: <reason>" (bad input, unwritable path). Nothing is left behind on
// failure (atomic write). Bad input: a path not ending in .glb or .gltf; chunk_size_m not finite and > 0;
// delta_m not finite and >= 0; scene_extras_json not a JSON object; a type with an empty or duplicate
// name, a null or invalid mesh (TriangleMesh validateMesh), a non-finite or non-positive sphere; an
// instance with a non-finite value, a non-unit rotation or a non-positive scale (the reason names the
// type and the instance index); an invalid terrain mesh; a static mesh with an empty name or one taken by a
// type, the terrain or another static mesh, a null or invalid mesh, a bad instance (as for the types),
// extras_json neither empty nor a JSON object; a material with a value out of its range or a
// texture whose size does not match its bytes; a result over the 4 GiB glTF limit.
bool writeSceneGltf(const std::string& path, const SceneExport& scene, std::string* error);

}  // namespace ug
