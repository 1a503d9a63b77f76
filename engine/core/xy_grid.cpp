#include "core/xy_grid.h"

#include <algorithm>
#include <cmath>

namespace ug {

XyGrid::XyGrid(std::span<const glm::vec3> points, float cell_m) : cell_(cell_m) {
    std::vector<std::pair<uint64_t, uint32_t>> keyed(points.size());
    for (size_t i = 0; i < points.size(); ++i)
        keyed[i] = {key(cellOf(points[i].x), cellOf(points[i].y)), uint32_t(i)};
    std::sort(keyed.begin(), keyed.end());
    items_.reserve(keyed.size());
    for (size_t i = 0; i < keyed.size(); ++i) {
        if (i == 0 || keyed[i].first != keyed[i - 1].first) {
            keys_.push_back(keyed[i].first);
            begin_.push_back(uint32_t(i));
        }
        items_.push_back(keyed[i].second);
    }
    begin_.push_back(uint32_t(items_.size()));
}

int XyGrid::cellOf(float v) const {
    // Clamped so that far-away or non-finite coordinates cannot overflow the cell index.
    const float c = std::floor(v / cell_);
    if (!(c > -1e9f)) return -1000000000;
    return c < 1e9f ? int(c) : 1000000000;
}

int64_t XyGrid::find(int x, int y) const {
    const uint64_t k = key(x, y);
    auto it = std::lower_bound(keys_.begin(), keys_.end(), k);
    if (it == keys_.end() || *it != k) return -1;
    return it - keys_.begin();
}

}  // namespace ug
