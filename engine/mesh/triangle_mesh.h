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

}  // namespace ug
