// Internal to the snow builders (engine/env/snow*.cpp): the steps every builder shares once it has laid out
// its undisplaced vertices and triangles. Not part of the public API.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "env/snow.h"

namespace ug::snow_detail {

// A snow mesh before the environment: points on the base surface, their distance to the patch border
// (0 on it, +inf far from it) and the triangles (3 indices each, counter-clockwise seen from `up`).
struct SnowLayout {
    std::vector<glm::vec3> surface;
    std::vector<float> border_distance;
    std::vector<uint32_t> indices;
    // Optional, one per triangle: the base face it refines, in nondecreasing order (geometry snow). When
    // set, base_faces_used counts the distinct faces that keep a triangle.
    std::vector<uint32_t> tri_face;
};

// Two counter-clockwise triangles per cell of an (nx + 1) x (ny + 1) vertex grid stored row by row
// (vertex (i, j) at j * (nx + 1) + i), appended to *indices.
void appendGridTriangles(uint32_t nx, uint32_t ny, std::vector<uint32_t>* indices);

// Queries `env` once for every vertex, displaces each along `up` by snowDisplacement (0 on the border,
// d = 0, whatever θ says, so the snow never lifts off its base there; 0 where zero_below_min_open is set
// and shelter < min_open), drops the triangles whose three vertices stay put,
// drops the vertices no kept triangle uses (order kept), recomputes normals and fills *out. Returns false
// (with a reason, *out untouched) when the environment yields a non-finite displacement.
bool finishSnowCover(SnowLayout&& layout, const SnowSettings& s, const EnvQuery& env,
                     bool zero_below_min_open, size_t base_faces_used_if_any, size_t patch_count,
                     SnowCover* out, std::string* error);

// The first half of buildGeometrySnow, exposed so tests can check the refinement itself (tiling,
// conformity, edge lengths) before the environment drops anything: validation, extraction (one batched
// shelter query at the candidate faces' centroids), the size checks and the subdivision. On success
// *faces_used is the number of extracted faces and *patch_count the number of patches.
bool layOutGeometrySnow(const TriangleMesh& base, const SnowSettings& s, const EnvQuery& env,
                        SnowLayout* layout, size_t* faces_used, size_t* patch_count, std::string* error);

// `up` normalised (validateSnowSettings guarantees it is within 1e-3 of unit length).
inline glm::vec3 unitUp(const SnowSettings& s) {
    return glm::normalize(s.up);
}

}  // namespace ug::snow_detail
