// Small shared helpers for the mesh tests.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include "mesh/triangle_mesh.h"

namespace ug::test {

inline std::string tempPath(const std::string& name) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "ug_mesh_tests";
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

inline void writeText(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

// Unit cube [-0.5, 0.5]^3, outward winding, 12 triangles.
inline TriangleMesh unitCube() {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.emplace_back((i & 1) ? 0.5f : -0.5f, (i & 2) ? 0.5f : -0.5f, (i & 4) ? 0.5f : -0.5f);
    m.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    computeNormals(&m);
    return m;
}

// A flat 1 m x 1 m quad in the z = 0 plane (open, single-sided), 2 triangles.
inline TriangleMesh flatQuad() {
    TriangleMesh m;
    m.positions = {{-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {-0.5f, 0.5f, 0}};
    m.indices = {0, 1, 2, 0, 2, 3};
    computeNormals(&m);
    return m;
}

}  // namespace ug::test
