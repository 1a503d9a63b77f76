#include "editor/coverage.h"

#include <algorithm>
#include <cmath>

namespace ug::editor {

namespace {

constexpr int kAzimuths = 8;

// Area (in model units squared) of the union of the triangles projected along -dir.
float silhouetteArea(const std::vector<glm::vec3>& positions, const uint32_t* indices, size_t index_count,
                     const glm::vec3& centre, float radius, const glm::vec3& dir, int n, std::vector<uint8_t>* raster) {
    // The image axes of an eye looking along -dir: right = up x dir, up = dir x right (the model's +Z
    // projected). Straight from above, "up" is taken as -X: the 60-degree view from +X, tilted further.
    const glm::vec3 helper = std::abs(dir.z) > 0.999f ? glm::vec3(-1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 0.0f, 1.0f);
    const glm::vec3 u = glm::normalize(glm::cross(helper, dir)), v = glm::cross(dir, u);
    const float cell = 2.0f * radius / float(n);
    raster->assign(size_t(n) * size_t(n), 0);
    auto toGrid = [&](const glm::vec3& p) {
        const glm::vec3 q = p - centre;
        return glm::vec2((glm::dot(q, u) + radius) / cell, (glm::dot(q, v) + radius) / cell);
    };
    for (size_t t = 0; t + 2 < index_count; t += 3) {
        const glm::vec2 a = toGrid(positions[indices[t]]), b = toGrid(positions[indices[t + 1]]),
                        c = toGrid(positions[indices[t + 2]]);
        const float area2 = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        if (std::abs(area2) < 1e-12f) continue;  // edge-on: no area
        const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x})))),
                  x1 = std::min(n - 1, int(std::ceil(std::max({a.x, b.x, c.x})))),
                  y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y})))),
                  y1 = std::min(n - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
        const float sign = area2 > 0.0f ? 1.0f : -1.0f;
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                // The pixel centre inside (or on an edge of) the triangle, either winding.
                const glm::vec2 p(float(x) + 0.5f, float(y) + 0.5f);
                const float w0 = sign * ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x));
                const float w1 = sign * ((c.x - b.x) * (p.y - b.y) - (c.y - b.y) * (p.x - b.x));
                const float w2 = sign * ((a.x - c.x) * (p.y - c.y) - (a.y - c.y) * (p.x - c.x));
                if (w0 >= 0.0f && w1 >= 0.0f && w2 >= 0.0f) (*raster)[size_t(y) * size_t(n) + size_t(x)] = 1;
            }
    }
    size_t covered = 0;
    for (uint8_t r : *raster) covered += r;
    return float(covered) * cell * cell;
}

// The bounding box's centre and half-diagonal of the indexed vertices.
void bounds(const std::vector<glm::vec3>& positions, const uint32_t* indices, size_t index_count, glm::vec3* centre,
            float* radius) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (size_t i = 0; i < index_count; ++i) {
        lo = glm::min(lo, positions[indices[i]]);
        hi = glm::max(hi, positions[indices[i]]);
    }
    *centre = 0.5f * (lo + hi);
    *radius = std::max(0.5f * glm::length(hi - lo), 1e-9f) * 1.001f;
}

glm::vec3 viewDirection(int elevation_index, float azimuth) {
    const float elevation = float(elevation_index) * 0.5235988f;  // 30 degrees
    return glm::vec3(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
}

}  // namespace

SilhouetteMasks silhouetteMasks(const std::vector<glm::vec3>& positions, const uint32_t* indices, size_t index_count,
                                int resolution) {
    SilhouetteMasks out;
    out.resolution = resolution;
    if (positions.empty() || index_count < 3) return out;
    bounds(positions, indices, index_count, &out.centre, &out.radius);
    for (int e = 0; e < kCoverageElevations; ++e) {
        silhouetteArea(positions, indices, index_count, out.centre, out.radius, viewDirection(e, 0.0f), resolution,
                       &out.mask[size_t(e)]);
        for (uint8_t& m : out.mask[size_t(e)]) m = m ? 255 : 0;
    }
    // The extent: the farthest covered texel's outer edge from the centre, in either axis, plus a texel
    // for the sprite's bilinear filtering.
    int reach = 0;  // in half-texels from the centre
    for (const std::vector<uint8_t>& m : out.mask)
        for (int y = 0; y < resolution; ++y)
            for (int x = 0; x < resolution; ++x)
                if (m[size_t(y) * size_t(resolution) + size_t(x)])
                    reach = std::max({reach, std::abs(2 * x + 1 - resolution) + 1, std::abs(2 * y + 1 - resolution) + 1});
    out.extent = std::min(1.0f, float(reach + 2) / float(resolution));
    return out;
}

CoverageProfile measureCoverage(const std::vector<glm::vec3>& positions, const uint32_t* indices, size_t index_count,
                                int resolution) {
    CoverageProfile out;
    if (positions.empty() || index_count < 3) return out;
    glm::vec3 centre;
    float radius = 0.0f;
    bounds(positions, indices, index_count, &centre, &radius);
    std::vector<uint8_t> raster;
    for (int e = 0; e < kCoverageElevations; ++e) {
        const int azimuths = e == kCoverageElevations - 1 ? 1 : kAzimuths;
        float sum = 0.0f;
        for (int k = 0; k < azimuths; ++k) {
            // Half-step offsets keep the azimuths off the axes, where a box's faces are edge-on.
            const float azimuth = (float(k) + 0.5f) * 6.2831853f / float(azimuths);
            sum += silhouetteArea(positions, indices, index_count, centre, radius, viewDirection(e, azimuth), resolution,
                                  &raster);
        }
        out.area_m2[size_t(e)] = sum / float(azimuths);
        out.mean_m2 += out.area_m2[size_t(e)] / float(kCoverageElevations);
    }
    return out;
}

}  // namespace ug::editor
