// Static geometry handed to both outputs (the glTF export, io/gltf_scene_export.h, and the editor's
// renderer): one mesh drawn at zero or more rigid transforms. The terrain, each environmental object's base
// geometry, snow covers (one shared by several objects: instanced), icicle shapes (a dozen meshes, thousands
// of instances) are each one entry of a std::vector<MeshInstances>; neither output knows what they are.
// GL-free and engine-only so the exporter and the renderer read the same list.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "material/material.h"
#include "mesh/triangle_mesh.h"

namespace ug {

// One instance in engine space: world = translate(position) * rotate(rotation) * scale(scale).
struct InstanceTransform {
    glm::vec3 position{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // unit; | |q| - 1 | <= 1e-3 is renormalized, more is an error
    float scale = 1.0f;                          // finite, > 0
};

// A coarser version of a mesh over the same vertices, made by whoever made the mesh (strands: their tubes
// through every 2nd, 4th, 8th point, strand_mesh.h): its triangles, and the farthest (object-space metres)
// any point of the mesh's surface lies from it.
struct MeshLodLevel {
    std::vector<uint32_t> indices;
    float error_m = 0.0f;
};

struct MeshInstances {
    // Unique in a scene (the glTF mesh and node names come from it): "terrain", "env/bench",
    // "snow/bench/3", "icicles/shape_2".
    std::string name;
    std::shared_ptr<const TriangleMesh> mesh;  // object space, Z up; normals computed when missing
    std::shared_ptr<const SurfaceMaterial> material;  // null: the mesh's base_color, roughness 0.9
    std::vector<InstanceTransform> instances;  // engine (world) space; EMPTY means one copy at the identity
    std::string extras_json;  // empty, or a JSON object written as the glTF mesh's extras
    // A layer lying on the terrain (the terrain's snow): a viewer need not draw it into a sun shadow map,
    // as it shadows only itself at grazing sun. Not exported.
    bool ground_layer = false;
    // Optional coarser levels, finest first: a viewer may draw one instead of the mesh where its error covers
    // less than a pixel (rather than simplifying the mesh itself). Not exported.
    std::shared_ptr<const std::vector<MeshLodLevel>> lod_levels;
};

}  // namespace ug
