// Small mesh utilities every loader and generator shares.
#include "mesh/triangle_mesh.h"

#include <cassert>
#include <cmath>
#include <string>

namespace ug {

void computeNormals(TriangleMesh* mesh) {
    mesh->normals.assign(mesh->positions.size(), glm::vec3(0.0f));
    const size_t vertex_count = mesh->positions.size();
    for (size_t t = 0; t + 2 < mesh->indices.size(); t += 3) {
        const uint32_t a = mesh->indices[t], b = mesh->indices[t + 1], c = mesh->indices[t + 2];
        if (a >= vertex_count || b >= vertex_count || c >= vertex_count) continue;
        // The unnormalized cross product is twice the area times the unit normal: summing it weights
        // each face by its area, and a degenerate face adds (close to) zero.
        const glm::vec3 n = glm::cross(mesh->positions[b] - mesh->positions[a],
                                       mesh->positions[c] - mesh->positions[a]);
        if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) continue;
        mesh->normals[a] += n;
        mesh->normals[b] += n;
        mesh->normals[c] += n;
    }
    for (glm::vec3& n : mesh->normals) {
        const float len = glm::length(n);
        // note: isolated vertices and vertices of only degenerate faces get +Z, so the "unit length"
        // guarantee holds everywhere.
        n = len > 1e-30f ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
    }
}

Bounds3 meshBounds(const TriangleMesh& mesh) {
    Bounds3 b;
    if (mesh.positions.empty()) return b;
    b.min = b.max = mesh.positions[0];
    for (const glm::vec3& p : mesh.positions) {
        b.min = glm::min(b.min, p);
        b.max = glm::max(b.max, p);
    }
    return b;
}

bool validateMesh(const TriangleMesh& mesh, std::string* error) {
    auto fail = [&](const std::string& why) {
        if (error) *error = why;
        return false;
    };
    if (mesh.indices.size() % 3 != 0)
        return fail("index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
    if (mesh.indices.empty()) return fail("no triangles");
    const size_t vertex_count = mesh.positions.size();
    for (size_t i = 0; i < mesh.indices.size(); ++i) {
        if (mesh.indices[i] >= vertex_count)
            return fail("triangle " + std::to_string(i / 3) + " references vertex " +
                        std::to_string(mesh.indices[i]) + " of " + std::to_string(vertex_count));
    }
    for (size_t i = 0; i < vertex_count; ++i) {
        const glm::vec3& p = mesh.positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return fail("vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
    if (!mesh.normals.empty() && mesh.normals.size() != vertex_count)
        return fail("normal count " + std::to_string(mesh.normals.size()) + " differs from vertex count " +
                    std::to_string(vertex_count));
    return true;
}

}  // namespace ug

namespace ug {

void convertZUpToYUp(TriangleMesh* mesh) {
    for (glm::vec3& p : mesh->positions) p = glm::vec3(p.x, p.z, -p.y);
    for (glm::vec3& n : mesh->normals) n = glm::vec3(n.x, n.z, -n.y);
}

void convertYUpToZUp(TriangleMesh* mesh) {
    for (glm::vec3& p : mesh->positions) p = glm::vec3(p.x, -p.z, p.y);
    for (glm::vec3& n : mesh->normals) n = glm::vec3(n.x, -n.z, n.y);
}

void scaleMesh(TriangleMesh* mesh, float factor) {
    assert(factor > 0.0f);
    for (glm::vec3& p : mesh->positions) p *= factor;
}

void appendMesh(TriangleMesh* dst, const TriangleMesh& src) {
    const bool keep_normals = (dst->positions.empty() || dst->normals.size() == dst->positions.size()) &&
                              src.normals.size() == src.positions.size();
    const uint32_t offset = uint32_t(dst->positions.size());
    dst->positions.insert(dst->positions.end(), src.positions.begin(), src.positions.end());
    if (keep_normals)
        dst->normals.insert(dst->normals.end(), src.normals.begin(), src.normals.end());
    else
        dst->normals.clear();
    for (uint32_t i : src.indices) dst->indices.push_back(i + offset);
}

}  // namespace ug
