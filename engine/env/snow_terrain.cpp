// The terrain's snow: the height field itself, resampled over a region and displaced (no border inside
// the region, so g = 1 everywhere). World space.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "env/snow.h"
#include "env/snow_detail.h"

namespace ug {

namespace {

bool fail(std::string* error, const std::string& why) {
    if (error) *error = why;
    return false;
}

// A regular axis of n segments from lo to hi, hi landing exactly on the last sample.
float axisSample(float lo, float hi, uint32_t i, uint32_t n) {
    return i == n ? hi : lo + (hi - lo) * (float(i) / float(n));
}

}  // namespace

bool buildTerrainSnow(const HeightField& hf, const Bounds& region, float cell_m, const SnowSettings& s,
                      const EnvQuery& env, SnowCover* out, std::string* error) {
    if (!validateSnowSettings(s, error)) return false;
    if (hf.empty()) return fail(error, "terrain snow: the height field is empty");
    if (!(cell_m > 0.0f) || !std::isfinite(cell_m))
        return fail(error, "terrain snow: cell_m must be finite and > 0");
    if (std::isnan(region.lo.x) || std::isnan(region.lo.y) || std::isnan(region.hi.x) ||
        std::isnan(region.hi.y))
        return fail(error, "terrain snow: the region is NaN");
    if (!env) return fail(error, "snow: no environment query");

    // The region, clipped to the field's rectangle (an infinite region means the whole field).
    const glm::vec2 f0 = hf.origin();
    const glm::vec2 f1 = f0 + glm::vec2(float(hf.width() - 1), float(hf.height() - 1)) * hf.cellSize();
    const float x0 = std::max(region.lo.x, f0.x), x1 = std::min(region.hi.x, f1.x);
    const float y0 = std::max(region.lo.y, f0.y), y1 = std::min(region.hi.y, f1.y);
    if (!(x0 < x1 && y0 < y1))
        return fail(error, "terrain snow: the region's XY rectangle does not overlap the height field");

    const double nxd = std::max(1.0, std::ceil(double(x1 - x0) / double(cell_m)));
    const double nyd = std::max(1.0, std::ceil(double(y1 - y0) / double(cell_m)));
    const double triangles = 2.0 * nxd * nyd;
    if (triangles > double(kMaxSnowTriangles))
        return fail(error, "terrain snow: about " + std::to_string(uint64_t(std::min(triangles, 1e18))) +
                               " triangles at cell_m " + std::to_string(cell_m) + " (more than " +
                               std::to_string(kMaxSnowTriangles) + "); raise cell_m or shrink the region");
    const uint32_t nx = uint32_t(nxd), ny = uint32_t(nyd);

    snow_detail::SnowLayout layout;
    const size_t verts = size_t(nx + 1) * (ny + 1);
    layout.surface.reserve(verts);
    layout.border_distance.assign(verts, std::numeric_limits<float>::infinity());
    for (uint32_t j = 0; j <= ny; ++j) {
        const float y = axisSample(y0, y1, j, ny);
        for (uint32_t i = 0; i <= nx; ++i) {
            const float x = axisSample(x0, x1, i, nx);
            layout.surface.emplace_back(x, y, hf.sample(x, y));
        }
    }
    snow_detail::appendGridTriangles(nx, ny, &layout.indices);
    return snow_detail::finishSnowCover(std::move(layout), s, env, /*zero_below_min_open=*/true, 1, 1, out,
                                        error);
}

}  // namespace ug
