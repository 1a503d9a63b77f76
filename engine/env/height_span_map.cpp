#include "env/height_span_map.h"

#include <algorithm>
#include <cmath>

namespace ug {

namespace {

// Calls f(cell index, z, step) for every cell centre inside the triangle's XY projection (edges included:
// a centre on an edge shared by two triangles is counted by both, which only repeats a crossing); step is
// +1 where the vertical line going up enters the solid (a down-facing face), -1 where it leaves it.
template <typename F>
void rasterTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec2 origin, float cell, int nx, int ny, F&& f) {
    const float area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    if (std::fabs(area) < 1e-12f) return;  // vertical: crosses no vertical line
    const float lo_x = std::min({a.x, b.x, c.x}), hi_x = std::max({a.x, b.x, c.x});
    const float lo_y = std::min({a.y, b.y, c.y}), hi_y = std::max({a.y, b.y, c.y});
    const int i0 = std::max(0, int(std::ceil((lo_x - origin.x) / cell - 0.5f)));
    const int i1 = std::min(nx - 1, int(std::floor((hi_x - origin.x) / cell - 0.5f)));
    const int j0 = std::max(0, int(std::ceil((lo_y - origin.y) / cell - 0.5f)));
    const int j1 = std::min(ny - 1, int(std::floor((hi_y - origin.y) / cell - 0.5f)));
    const float inv = 1.0f / area;
    for (int j = j0; j <= j1; ++j) {
        const float y = origin.y + (float(j) + 0.5f) * cell;
        for (int i = i0; i <= i1; ++i) {
            const float x = origin.x + (float(i) + 0.5f) * cell;
            const float w0 = ((b.x - x) * (c.y - y) - (c.x - x) * (b.y - y)) * inv;
            const float w1 = ((c.x - x) * (a.y - y) - (a.x - x) * (c.y - y)) * inv;
            const float w2 = 1.0f - w0 - w1;
            const float tol = -1e-6f;
            if (w0 < tol || w1 < tol || w2 < tol) continue;
            // Counter-clockwise seen from above: the face looks up, so going up the line leaves the solid.
            f(size_t(j) * size_t(nx) + size_t(i), w0 * a.z + w1 * b.z + w2 * c.z, area > 0.0f ? -1 : 1);
        }
    }
}

}  // namespace

HeightSpanMap::HeightSpanMap(const TriangleMesh& mesh, bool skip_blocks) {
    const Bounds3 b = meshBounds(mesh);
    const glm::vec2 size(b.max.x - b.min.x, b.max.y - b.min.y);
    cell_ = kShelterCellM;
    // Coarsen so the grid stays bounded for a large mesh (a whole building block).
    while (double(size.x / cell_ + 3.0f) * double(size.y / cell_ + 3.0f) > double(kMaxSpanMapCells)) cell_ *= 2.0f;
    origin_ = glm::vec2(b.min.x, b.min.y) - glm::vec2(cell_);
    nx_ = int(std::ceil(size.x / cell_)) + 2;
    ny_ = int(std::ceil(size.y / cell_)) + 2;
    const size_t cells = size_t(nx_) * size_t(ny_);
    std::vector<uint32_t> count(cells + 1, 0);
    auto each = [&](auto&& f) {
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
            rasterTriangle(mesh.positions[mesh.indices[t]], mesh.positions[mesh.indices[t + 1]],
                           mesh.positions[mesh.indices[t + 2]], origin_, cell_, nx_, ny_, f);
    };
    each([&](size_t cell, float, int) { ++count[cell + 1]; });
    for (size_t c = 0; c < cells; ++c) count[c + 1] += count[c];
    first_ = count;
    std::vector<std::pair<float, int>> crossings(first_[cells]);
    each([&](size_t cell, float z, int step) { crossings[count[cell]++] = {z, step}; });
    z_.resize(crossings.size());
    depth_.resize(crossings.size());
    for (size_t c = 0; c < cells; ++c) {
        // By height, and at one height the entries before the exits (a face shared by two parts).
        std::sort(crossings.begin() + first_[c], crossings.begin() + first_[c + 1],
                  [](const auto& l, const auto& r) { return l.first < r.first || (l.first == r.first && l.second > r.second); });
        int depth = 0;
        for (uint32_t k = first_[c]; k < first_[c + 1]; ++k) {
            z_[k] = crossings[k].first;
            depth += crossings[k].second;
            depth_[k] = int16_t(std::clamp(depth, -32000, 32000));
        }
    }
    if (!skip_blocks) return;
    constexpr float kInf = std::numeric_limits<float>::infinity();
    block_nx_ = (nx_ + kSpanBlockCells - 1) / kSpanBlockCells;
    const int block_ny = (ny_ + kSpanBlockCells - 1) / kSpanBlockCells;
    blocks_.assign(size_t(block_nx_) * size_t(block_ny), SpanBlock{kInf, -kInf});
    for (int j = 0; j < ny_; ++j)
        for (int i = 0; i < nx_; ++i) {
            const size_t c = size_t(j) * size_t(nx_) + size_t(i);
            if (first_[c] == first_[c + 1]) continue;
            SpanBlock& block = blocks_[size_t(j / kSpanBlockCells) * size_t(block_nx_) + size_t(i / kSpanBlockCells)];
            block.bottom = std::min(block.bottom, z_[first_[c]]);
            block.top = std::max(block.top, depth_[first_[c + 1] - 1] > 0 ? kInf : z_[first_[c + 1] - 1]);
        }
}

bool HeightSpanMap::insideSolid(long cell, float z) const {
    const float* lo = z_.data() + first_[size_t(cell)];
    const float* hi = z_.data() + first_[size_t(cell) + 1];
    const float* it = std::upper_bound(lo, hi, z);  // first crossing above z
    return it != lo && depth_[size_t(it - z_.data()) - 1] > 0;
}

long HeightSpanMap::cellAt(float x, float y, int* i, int* j) const {
    if (nx_ == 0) return -1;
    const float fx = (x - origin_.x) / cell_, fy = (y - origin_.y) / cell_;
    if (!(fx >= 0.0f && fy >= 0.0f && fx < float(nx_) && fy < float(ny_))) return -1;
    *i = int(fx);
    *j = int(fy);
    return long(*j) * nx_ + long(*i);
}

bool HeightSpanMap::coveredAbove(glm::vec3 p, float eps) const {
    const long c = cellOf(p.x, p.y);
    if (c < 0 || first_[size_t(c)] == first_[size_t(c) + 1]) return false;
    return z_[first_[size_t(c) + 1] - 1] > p.z + eps;
}

bool HeightSpanMap::coveredAlong(glm::vec3 p, glm::vec2 slope, float eps, float z_bottom, float z_top) const {
    const float drift = glm::length(slope);
    if (drift < 1e-4f) return coveredAbove(p, eps);
    if (nx_ == 0) return false;
    // The heights over which the ray is above the grid (a 2D slab test on its XY path), within the mesh's.
    float lo_z = std::max(p.z + eps, z_bottom), hi_z = z_top;
    const glm::vec2 box_lo = origin_, box_hi = origin_ + glm::vec2(float(nx_), float(ny_)) * cell_;
    for (int a = 0; a < 2; ++a) {
        const float o = a == 0 ? p.x : p.y, d = slope[a];
        if (std::fabs(d) < 1e-9f) {
            if (o < box_lo[a] || o >= box_hi[a]) return false;
            continue;
        }
        float z0 = p.z + (box_lo[a] - o) / d, z1 = p.z + (box_hi[a] - o) / d;
        if (z0 > z1) std::swap(z0, z1);
        lo_z = std::max(lo_z, z0);
        hi_z = std::min(hi_z, z1);
    }
    const float dz = 0.5f * cell_ / drift;  // rise per half-cell step
    if (!(lo_z < hi_z)) return false;
    // Counted steps, not an accumulated height: far from the origin a float would stop advancing.
    const double steps = std::ceil(double(hi_z - lo_z) / double(dz)) + 1.0;
    const long n = long(std::min(steps, 1.0e6));
    for (long k = 0; k < n; ++k) {
        // Each step clipped to the ray's heights: a step reaching below lo_z (the first one does) would
        // look inside the part the point lies on (a slab's top face at its own height is "inside" a few
        // millimetres down), and a half-cell step rises more than 2 eps when the drift is under ~12°.
        const float z0 = std::max(lo_z, lo_z + float(double(k - 1) * double(dz)));
        const float z1 = std::min(hi_z, lo_z + float(double(k) * double(dz)));
        const float z_mid = 0.5f * (z0 + z1);
        const glm::vec2 mid = glm::vec2(p.x, p.y) + slope * (z_mid - p.z);
        int ci = 0, cj = 0;
        const long c = cellAt(mid.x, mid.y, &ci, &cj);
        if (c < 0) continue;
        if (!blocks_.empty()) {
            const int bi = ci / kSpanBlockCells, bj = cj / kSpanBlockCells;
            const SpanBlock& b = blocks_[size_t(bj) * size_t(block_nx_) + size_t(bi)];
            // Above the block's every crossing (and not inside an open part there), or below them all:
            // this step finds nothing, nor do the next ones while their midpoints stay in the block and
            // their heights on the same side (the ray only rises).
            const bool above = z0 > b.top, below = z1 < b.bottom;
            if (above || below) {
                const float limit = below ? b.bottom : std::numeric_limits<float>::infinity();
                k = std::max(k, lastStepInBlock(k, bi, bj, p, slope, lo_z, dz, limit));
                continue;
            }
        }
        const float* first = z_.data() + first_[size_t(c)];
        const float* last = z_.data() + first_[size_t(c) + 1];
        const float* it = std::lower_bound(first, last, z0);
        if (it != last && *it <= z1) return true;
        // Inside a part (a wall seen edge-on by the vertical lines: its faces cross none of them).
        if (insideSolid(c, z_mid)) return true;
    }
    return false;
}

long HeightSpanMap::lastStepInBlock(long k, int bi, int bj, glm::vec3 p, glm::vec2 slope, float lo_z, float dz,
                                    float z_limit) const {
    // Step k' reaches at most lo_z + k' dz; the ray's XY path leaves the block's square at z_exit.
    double z_exit = double(z_limit);
    for (int a = 0; a < 2; ++a) {
        if (std::fabs(slope[a]) < 1e-9f) continue;  // never leaves across this axis
        const int block = a == 0 ? bi : bj;
        const int edge_cell = (slope[a] > 0.0f ? block + 1 : block) * kSpanBlockCells;
        const double edge = double(origin_[a]) + double(edge_cell) * double(cell_);
        z_exit = std::min(z_exit, double(p.z) + (edge - double(p[a])) / double(slope[a]));
    }
    const double last = std::floor((z_exit - double(lo_z)) / double(dz)) - 1.0;
    return last > double(k) ? long(std::min(last, 1.0e7)) : k;
}

float HeightSpanMap::surfaceAboveNear(glm::vec3 p, float eps) const {
    float best = -std::numeric_limits<float>::infinity();
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            const long c = cellOf(p.x + float(i) * cell_, p.y + float(j) * cell_);
            if (c < 0) continue;
            const float* lo = z_.data() + first_[size_t(c)];
            const float* hi = z_.data() + first_[size_t(c) + 1];
            const float* it = std::upper_bound(lo, hi, p.z + eps);  // first crossing > z + eps
            if (it != hi) best = std::max(best, *it);
        }
    return best;
}

float HeightSpanMap::supportBelow(glm::vec3 p, bool* inside) const {
    *inside = false;
    const long c = cellOf(p.x, p.y);
    if (c < 0) return -std::numeric_limits<float>::infinity();
    const float* lo = z_.data() + first_[size_t(c)];
    const float* hi = z_.data() + first_[size_t(c) + 1];
    const float* it = std::upper_bound(lo, hi, p.z);  // first crossing above z
    if (it == lo) return -std::numeric_limits<float>::infinity();
    *inside = depth_[size_t(it - z_.data()) - 1] > 0;
    return *(it - 1);
}

float HeightSpanMap::highestBelow(glm::vec3 p, float eps) const {
    const long c = cellOf(p.x, p.y);
    if (c < 0) return -std::numeric_limits<float>::infinity();
    const float* lo = z_.data() + first_[size_t(c)];
    const float* hi = z_.data() + first_[size_t(c) + 1];
    const float* it = std::lower_bound(lo, hi, p.z - eps);  // first crossing >= z - eps
    return it == lo ? -std::numeric_limits<float>::infinity() : *(it - 1);
}

}  // namespace ug
