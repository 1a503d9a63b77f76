#include "editor/default_view.h"

#include <algorithm>
#include <cmath>

namespace ug::editor {

Bounds framingBounds(const Bounds& extent, const TriangleMesh* terrain, const ResidentTiles* instances) {
    if (instances && !instances->tile_coord.empty()) {
        const float size = instances->tile_size_m;
        Bounds b{glm::vec3(1e30f), glm::vec3(-1e30f)};
        for (const glm::ivec3& t : instances->tile_coord) {
            b.lo = glm::min(b.lo, glm::vec3(t) * size);
            b.hi = glm::max(b.hi, glm::vec3(t + 1) * size);
        }
        return b;
    }
    if (!terrain || terrain->positions.empty()) return extent;
    const Bounds3 b = meshBounds(*terrain);
    return Bounds{b.min, b.max};
}

Bounds openingBounds(const Bounds& extent, const TriangleMesh* terrain, const ResidentTiles* instances,
                     const std::vector<DetailLodMesh>& meshes) {
    Bounds b = framingBounds(extent, terrain, instances);
    if (!instances || instances->instances_per_type.empty()) return b;
    size_t dominant = 0;
    for (size_t i = 1; i < instances->instances_per_type.size(); ++i)
        if (instances->instances_per_type[i] > instances->instances_per_type[dominant]) dominant = i;
    if (dominant >= meshes.size() || instances->instances_per_type[dominant] == 0) return b;
    const float diameter = 2.0f * meshes[dominant].radius_m * meshes[dominant].scale_max;
    // frameBounds stands about 2.4 half-widths away from a flat box (45-degree field, 90 % fill, 35
    // degrees up): a half-width of d / (2.4 f tan(fov / 2)) puts a d-wide object at f of the height.
    const float half_fov = 0.5f * OrbitCamera{}.fov_y_rad;
    const float half_width = diameter / (2.4f * kOpeningDetailFraction * 2.0f * std::tan(half_fov));
    const glm::vec2 centre = 0.5f * (glm::vec2(b.lo) + glm::vec2(b.hi));
    const glm::vec2 lo = glm::max(glm::vec2(b.lo), centre - half_width), hi = glm::min(glm::vec2(b.hi), centre + half_width);
    return Bounds{glm::vec3(lo, b.lo.z), glm::vec3(hi, b.hi.z)};
}

OrbitCamera defaultView(const Bounds& framing, float aspect) {
    OrbitCamera camera;
    camera.aspect = std::max(aspect, 1e-3f);
    frameBounds(framing, &camera);
    return camera;
}

}  // namespace ug::editor
