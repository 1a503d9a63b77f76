#include "scene/sculpt_pile.h"

#include <algorithm>
#include <cmath>

#include "field/ray_cast.h"

namespace ug {

namespace {

constexpr float kPi = 3.14159265358979f;

float clampAngle(float deg) { return std::clamp(std::isfinite(deg) ? deg : 35.0f, 0.1f, 89.0f); }

}  // namespace

float isoRadiusFactor(float weight, float iso) {
    if (!(weight > iso) || !(iso > 0.0f)) return 0.0f;
    return std::sqrt(1.0f - std::cbrt(iso / weight));
}

float sculptStampVolume(float brush_radius_m, float weight, float iso) {
    const float r = isoRadiusFactor(weight, iso) * brush_radius_m;
    return 2.0f / 3.0f * kPi * r * r * r;
}

float PileBed::maxHeight() const {
    float m = 0.0f;
    for (float h : height_m) m = std::max(m, h);
    return m;
}

PileCone pileConeOnBed(glm::vec3 base_m, const PileBed& bed, float volume_m3, float angle_of_repose_deg) {
    const PileCone lone = pileConeForVolume(base_m, volume_m3, angle_of_repose_deg);
    const float bed_top = bed.maxHeight();
    const int side = 2 * bed.half_cells + 1;
    if (!(bed_top > 0.0f) || !(lone.height_m > 0.0f) || bed.half_cells < 0 ||
        bed.height_m.size() != size_t(side) * size_t(side))
        return lone;
    const float slope = lone.height_m / lone.base_radius_m;
    const float cell_area = bed.cell_m * bed.cell_m;
    // The bed's cells under material, with how far the cone's side falls from its apex there; the same
    // for every apex height the bisection tries.
    struct Cell {
        float bed_m, fall_m;
    };
    std::vector<Cell> cells;
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            const float b = bed.height_m[size_t(j) * size_t(side) + size_t(i)];
            if (!(b > 0.0f)) continue;
            const glm::vec2 x = bed.centre_m + bed.cell_m * glm::vec2(i - bed.half_cells, j - bed.half_cells);
            cells.push_back({b, slope * glm::length(x - glm::vec2(base_m))});
        }
    // Material above the bed = the cone's volume minus the part of it the bed already fills.
    auto above_bed = [&](float h) {
        float filled = 0.0f;
        for (const Cell& c : cells)
            if (h > c.fall_m) filled += std::min(h - c.fall_m, c.bed_m) * cell_area;
        return kPi * h * h * h / (3.0f * slope * slope) - filled;
    };
    // The lone cone has at most `volume_m3` above the bed; raised by the bed's top, its part above that
    // level alone is the lone cone again, so at least `volume_m3`.
    float lo = lone.height_m, hi = lone.height_m + bed_top;
    for (int k = 0; k < 40 && hi - lo > 1e-5f * hi; ++k) {
        const float mid = 0.5f * (lo + hi);
        (above_bed(mid) >= volume_m3 ? hi : lo) = mid;
    }
    PileCone c;
    c.base_m = base_m;
    c.height_m = hi;
    c.base_radius_m = hi / slope;
    return c;
}

float pileTipFraction(float angle_of_repose_deg) {
    return std::min(0.15f, 0.5f * std::tan(glm::radians(clampAngle(angle_of_repose_deg))));
}

PileCone pileConeForVolume(glm::vec3 base_m, float volume_m3, float angle_of_repose_deg) {
    const float slope = std::tan(glm::radians(clampAngle(angle_of_repose_deg)));
    PileCone c;
    c.base_m = base_m;
    c.base_radius_m = std::cbrt(3.0f * std::max(volume_m3, 0.0f) / (kPi * slope));
    c.height_m = slope * c.base_radius_m;
    return c;
}

Primitive pileConePrimitive(const PileCone& cone, float weight, float iso) {
    const float factor = std::max(isoRadiusFactor(weight, iso), 1e-3f);
    const float r0 = std::max(cone.base_radius_m, 1e-3f);
    const float height = std::max(cone.height_m, 1e-3f);
    // The tip is a ball of radius r_top above the axis' end: the axis stops r_top short of the height.
    const float r_top = std::min(pileTipFraction(glm::degrees(std::atan(height / r0))) * r0, 0.5f * height);
    const glm::vec3 top = cone.base_m + glm::vec3(0.0f, 0.0f, height - r_top);
    return makeCone(cone.base_m, r0 / factor, top, r_top / factor, weight);
}

bool isPileCone(const Primitive& prim) {
    return prim.kind == PrimitiveKind::Segment && prim.end_m.x == prim.center_m.x &&
           prim.end_m.y == prim.center_m.y && prim.end_m.z > prim.center_m.z && prim.end_radius_m < prim.radius_m;
}

PileMeasure measurePile(const std::function<float(glm::vec2)>& thickness_m, glm::vec2 centre_xy,
                        float search_radius_m, float cell_m, float min_thickness_m) {
    PileMeasure m;
    const int n = std::max(1, int(std::ceil(search_radius_m / cell_m)));
    glm::vec2 weighted(0.0f);
    for (int j = -n; j <= n; ++j)
        for (int i = -n; i <= n; ++i) {
            const glm::vec2 d(float(i) * cell_m, float(j) * cell_m);
            if (glm::length(d) > search_radius_m) continue;
            const float t = thickness_m(centre_xy + d);
            if (!(t > min_thickness_m)) continue;
            ++m.columns;
            m.volume_m3 += t * cell_m * cell_m;
            weighted += t * cell_m * cell_m * (centre_xy + d);
            m.height_m = std::max(m.height_m, t);
        }
    if (m.columns == 0) return m;
    m.found = true;
    m.centroid_m = weighted / m.volume_m3;
    m.radius_m = std::sqrt(float(m.columns) * cell_m * cell_m / kPi);
    return m;
}

float pileThicknessOverPlane(const DensityField& field, float iso, glm::vec2 xy_m, float ground_z, float top_z) {
    const Ray down{glm::vec3(xy_m, top_z), glm::vec3(0.0f, 0.0f, -1.0f)};
    float t = 0.0f;
    if (!rayDensityIsosurface(field, down, iso, top_z - ground_z, 0.01f, &t)) return 0.0f;
    return std::max(0.0f, top_z - t - ground_z);
}

}  // namespace ug
