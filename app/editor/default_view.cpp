#include "editor/default_view.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

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
    // Where to look: the densest patch of that size (instances of every type binned on a grid of
    // patches; ties to the one nearest the middle), at its instances' centroid. A field of haystacks opens
    // on a haystack, not on the bare ground between them.
    const glm::vec2 middle = 0.5f * (glm::vec2(b.lo) + glm::vec2(b.hi));
    const float cell = 2.0f * half_width;
    struct Patch {
        uint64_t count = 0;
        glm::dvec2 sum{0.0};
        float z_lo = 1e30f, z_hi = -1e30f;  // its cells' floor and ceiling
    };
    std::map<std::pair<int64_t, int64_t>, Patch> patches;
    const uint32_t types = instances->type_count;
    for (size_t t = 0; t < instances->tileCount(); ++t) {
        uint64_t n = 0;
        for (uint32_t i = 0; i < types; ++i) n += instances->count[t * types + i];
        if (n == 0) continue;
        const glm::vec2 c = (glm::vec2(instances->tile_coord[t]) + 0.5f) * instances->tile_size_m;
        Patch& p = patches[{int64_t(std::floor(c.x / cell)), int64_t(std::floor(c.y / cell))}];
        p.count += n;
        p.sum += glm::dvec2(c) * double(n);
        p.z_lo = std::min(p.z_lo, float(instances->tile_coord[t].z) * instances->tile_size_m);
        p.z_hi = std::max(p.z_hi, float(instances->tile_coord[t].z + 1) * instances->tile_size_m);
    }
    glm::vec2 centre = middle;
    glm::vec2 z_range(b.lo.z, b.hi.z);
    uint64_t best = 0;
    float best_distance = 0.0f;
    for (const auto& [key, p] : patches) {
        const glm::vec2 c = glm::vec2(p.sum / double(p.count));
        const float d = glm::length(c - middle);
        if (p.count > best || (p.count == best && d < best_distance)) {
            best = p.count;
            best_distance = d;
            centre = c;
            z_range = glm::vec2(p.z_lo, p.z_hi);
        }
    }
    const glm::vec2 lo = glm::max(glm::vec2(b.lo), centre - half_width), hi = glm::min(glm::vec2(b.hi), centre + half_width);
    return Bounds{glm::vec3(lo, z_range.x), glm::vec3(hi, z_range.y)};
}

OrbitCamera defaultView(const Bounds& framing, float aspect) {
    OrbitCamera camera;
    camera.aspect = std::max(aspect, 1e-3f);
    frameBounds(framing, &camera);
    return camera;
}

}  // namespace ug::editor
