#include "editor/default_view.h"

#include <algorithm>

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

OrbitCamera defaultView(const Bounds& framing, float aspect) {
    OrbitCamera camera;
    camera.aspect = std::max(aspect, 1e-3f);
    frameBounds(framing, &camera);
    return camera;
}

}  // namespace ug::editor
