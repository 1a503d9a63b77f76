#include "material/uv_projection.h"

#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace ug {

int dominantAxis(glm::vec3 n) {
    const glm::vec3 a = glm::abs(n);
    if (a.z >= a.x && a.z >= a.y) return 2;
    return a.x >= a.y ? 0 : 1;
}

glm::vec2 boxProjectUv(glm::vec3 p, glm::vec3 n, float texture_scale_m) {
    switch (dominantAxis(n)) {
        case 0: return glm::vec2(p.y, p.z) / texture_scale_m;
        case 1: return glm::vec2(p.x, p.z) / texture_scale_m;
        default: return glm::vec2(p.x, p.y) / texture_scale_m;
    }
}

glm::vec2 planarXyUv(glm::vec3 p, float texture_scale_m) {
    return glm::vec2(p.x, p.y) / texture_scale_m;
}

glm::vec2 textureRotationCosSin(float degrees) {
    // Quarter turns exactly: cos(pi / 2) in float is -4.4e-8, not 0, and would smear a pure swap.
    const float turns = degrees / 90.0f;
    if (std::abs(turns) <= 4.0f && turns == std::floor(turns)) {
        switch (((int64_t(turns) % 4) + 4) % 4) {
            case 0: return {1.0f, 0.0f};
            case 1: return {0.0f, 1.0f};
            case 2: return {-1.0f, 0.0f};
            default: return {0.0f, -1.0f};
        }
    }
    const double r = double(degrees) * 3.14159265358979323846 / 180.0;
    return {float(std::cos(r)), float(std::sin(r))};
}

glm::vec2 rotateTextureUv(glm::vec2 uv, float degrees) {
    if (degrees == 0.0f) return uv;
    const glm::vec2 cs = textureRotationCosSin(degrees);
    return {cs.x * uv.x - cs.y * uv.y, cs.y * uv.x + cs.x * uv.y};
}

void boxProjectMesh(const TriangleMesh& mesh, float texture_scale_m, TriangleMesh* out, std::vector<glm::vec2>* uvs) {
    TriangleMesh result;
    result.base_color = mesh.base_color;
    const bool has_normals = mesh.normals.size() == mesh.positions.size();
    std::vector<glm::vec2> coords;
    // (source vertex, axis) -> output vertex.
    std::unordered_map<uint64_t, uint32_t> copies;
    result.indices.reserve(mesh.indices.size());
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                        c = mesh.positions[mesh.indices[t + 2]];
        const glm::vec3 n = glm::cross(b - a, c - a);
        const int axis = dominantAxis(n);
        for (int k = 0; k < 3; ++k) {
            const uint32_t src = mesh.indices[t + size_t(k)];
            const uint64_t key = uint64_t(src) * 3 + uint64_t(axis);
            auto [it, inserted] = copies.try_emplace(key, uint32_t(result.positions.size()));
            if (inserted) {
                const glm::vec3 p = mesh.positions[src];
                result.positions.push_back(p);
                if (has_normals) result.normals.push_back(mesh.normals[src]);
                coords.push_back(boxProjectUv(p, axis == 0 ? glm::vec3(1, 0, 0) : axis == 1 ? glm::vec3(0, 1, 0)
                                                                                         : glm::vec3(0, 0, 1),
                                              texture_scale_m));
            }
            result.indices.push_back(it->second);
        }
    }
    *out = std::move(result);
    *uvs = std::move(coords);
}

}  // namespace ug
