// The engine's plain mesh: indexed triangles in model space, metres, Z up.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace ug {

struct TriangleMesh {
    std::vector<glm::vec3> positions;  // metres, Z up
    std::vector<glm::vec3> normals;    // unit length, one per position (may be empty before computeNormals)
    std::vector<uint32_t> indices;     // 3 per triangle, each < positions.size()
    glm::vec3 base_color{0.6f, 0.6f, 0.6f};  // linear RGB in [0,1], for viewers and the renderer

    size_t triangleCount() const { return indices.size() / 3; }
};

// Area-weighted vertex normals; degenerate triangles contribute nothing.
void computeNormals(TriangleMesh* mesh);

// Axis-aligned bounds of the positions; {0,0} for an empty mesh.
struct Bounds3 {
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};
};
Bounds3 meshBounds(const TriangleMesh& mesh);

// Checks what every consumer relies on: at least one triangle, indices in range, finite positions.
// Returns false with a reason ("triangle 12 references vertex 900 of 400") otherwise.
bool validateMesh(const TriangleMesh& mesh, std::string* error);

// Axis conventions. glTF is Y up, the engine Z up; these are exact inverses of each other:
//   Z up -> Y up: rotate -90 degrees about X, (x, y, z) -> (x, z, -y)
//   Y up -> Z up: rotate +90 degrees about X, (x, y, z) -> (x, -z, y)
// Both rotate positions and normals.
void convertZUpToYUp(TriangleMesh* mesh);
void convertYUpToZUp(TriangleMesh* mesh);

// Multiplies every position by `factor` (> 0, asserted); normals are unchanged.
void scaleMesh(TriangleMesh* mesh, float factor);

// Appends `src` to `dst` (indices offset; normals kept only when both meshes have them). dst's
// base_color is kept.
void appendMesh(TriangleMesh* dst, const TriangleMesh& src);

}  // namespace ug
