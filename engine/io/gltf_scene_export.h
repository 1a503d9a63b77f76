// glTF 2.0 export of an instantiated scene (DESIGN.md, "Files and interfaces"):
//   - one mesh per detail type, with a simple PBR material from the model's base colour;
//   - its instances through EXT_mesh_gpu_instancing (TRANSLATION, ROTATION, SCALE accessors), split into
//     spatial chunks (one node per type and chunk) so engines can cull;
//   - or, with use_instancing_extension = false, one plain node per instance (viewers without it);
//   - the terrain as one mesh;
//   - every detail mesh's `extras`: {"collision_spheres": [[x, y, z, r], ...] in mesh space, "delta": δ};
//   - the scene's `extras`: the statistics JSON given by the caller.
// Engine space is Z up; glTF is Y up: positions, rotations and spheres are converted on the way out.
// The file is written atomically; .glb (binary) or .gltf (JSON with the buffer embedded as a data URI)
// by the path's extension.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "mesh/detail_model.h"
#include "mesh/triangle_mesh.h"

namespace ug {

// One instance in engine space: world = translate(position) * rotate(rotation) * scale(scale).
struct InstanceTransform {
    glm::vec3 position{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // unit
    float scale = 1.0f;
};

struct ExportDetailType {
    std::string name;
    const TriangleMesh* mesh = nullptr;        // model space, Z up (DetailModel::mesh); not owned
    std::vector<Sphere> collision_spheres;     // model space, Z up
    std::vector<InstanceTransform> instances;  // engine space
};

struct SceneExport {
    std::vector<ExportDetailType> types;
    const TriangleMesh* terrain = nullptr;  // world space, Z up; optional; not owned
    float delta_m = 0.0f;                   // the Ghost Tile's δ, written in every detail mesh's extras
    float chunk_size_m = 8.0f;              // edge of the square XY chunks instances are grouped by, > 0
    bool use_instancing_extension = true;   // false: one plain node per instance
    std::string scene_extras_json = "{}";   // a JSON object stored as the scene's extras (statistics)
};

// Returns false with *error = "<path>: <reason>" (bad input, unwritable path). Nothing is left behind on
// failure (atomic write).
bool writeSceneGltf(const std::string& path, const SceneExport& scene, std::string* error);

}  // namespace ug
