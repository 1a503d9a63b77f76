// A uniform grid over the XY plane for "which points lie near this column" queries: settling and the
// measurements of engine/analysis look straight down. Built once over a fixed set of points: cells are
// sorted keys with ranges into one index array, so a query is a few binary searches and no hashing.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace ug {

class XyGrid {
public:
    XyGrid(std::span<const glm::vec3> points, float cell_m);

    // f(point index) for every point whose cell meets the square of half-side `radius` around xy
    // (a superset of the points within `radius`; callers test the distance).
    template <typename F>
    void forEachNear(glm::vec2 xy, float radius, F&& f) const {
        const int x0 = cellOf(xy.x - radius), x1 = cellOf(xy.x + radius);
        const int y0 = cellOf(xy.y - radius), y1 = cellOf(xy.y + radius);
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const int64_t c = find(x, y);
                if (c < 0) continue;
                for (uint32_t k = begin_[size_t(c)]; k < begin_[size_t(c) + 1]; ++k) f(items_[k]);
            }
    }

private:
    int cellOf(float v) const;
    int64_t find(int x, int y) const;
    static uint64_t key(int x, int y) { return (uint64_t(uint32_t(x)) << 32) | uint32_t(y); }

    float cell_;
    std::vector<uint64_t> keys_;    // occupied cells, ascending
    std::vector<uint32_t> begin_;   // keys_.size() + 1
    std::vector<uint32_t> items_;   // point indices grouped by cell
};

}  // namespace ug
