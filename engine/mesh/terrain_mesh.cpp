// Height field -> triangle mesh. Grid lines follow the field's own sample lines so that a mesh at full
// resolution carries the exact sample heights (no resampling blur), and decimation keeps every
// stride-th line, aligned to multiples of the stride so that meshes of neighbouring extents share lines.
#include "mesh/terrain_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace ug {
namespace {

bool fail(std::string* error, const std::string& why) {
    if (error) *error = "terrain mesh: " + why;
    return false;
}

std::string formatRange(double lo, double hi) {
    char text[64];
    std::snprintf(text, sizeof(text), "[%g, %g]", lo, hi);
    return text;
}

// One grid line along an axis: its coordinate, and the field sample index it lies on (-1: a clip border
// between sample lines, whose heights are bilinear).
struct Stop {
    float coord = 0.0f;
    int index = -1;
};

// Grid lines along one axis for the clipped range [lo, hi] (inside the field's range, lo < hi).
std::vector<Stop> axisStops(float origin, float cell, int samples, double lo, double hi, int max_cells) {
    // A border within a thousandth of a cell of a sample line snaps to it: no sliver cells, and an
    // extent aligned to the samples reproduces them exactly.
    constexpr double kSnap = 1e-3;
    auto border = [&](double at) {
        const double u = (at - origin) / cell;
        const double r = std::round(u);
        if (std::fabs(u - r) < kSnap && r >= 0 && r <= samples - 1) {
            const int i = int(r);
            return Stop{origin + float(i) * cell, i};
        }
        return Stop{float(at), -1};
    };
    Stop first = border(lo), last = border(hi);
    if (!(last.coord > first.coord))
        first = Stop{float(lo), -1}, last = Stop{float(hi), -1};  // a sliver range
    // Sample lines strictly inside, clear of the borders by kSnap cells.
    const double u_lo = (lo - origin) / cell, u_hi = (hi - origin) / cell;
    const int i_first = int(std::floor(u_lo + kSnap)) + 1;
    const int i_last = int(std::ceil(u_hi - kSnap)) - 1;
    const int interior = std::max(0, i_last - i_first + 1);

    std::vector<Stop> stops{first};
    if (interior > 0 && max_cells > 1) {
        // Interior lines used <= ceil(interior / stride) <= max_cells - 1, so cells <= max_cells.
        const int stride = (interior + (max_cells - 2)) / (max_cells - 1);
        for (int i = (i_first + stride - 1) / stride * stride; i <= i_last; i += stride)
            stops.push_back(Stop{origin + float(i) * cell, i});
    }
    stops.push_back(last);
    return stops;
}

}  // namespace

bool heightFieldMesh(const HeightField& hf, const Bounds& extent, int max_cells_per_side, TriangleMesh* out,
                     std::string* error) {
    if (hf.empty()) return fail(error, "the height field is empty");
    if (hf.width() < 2 || hf.height() < 2)
        return fail(error, "the height field has " + std::to_string(hf.width()) + " x " +
                               std::to_string(hf.height()) + " samples; at least 2 x 2 are needed");
    if (max_cells_per_side < 1 || max_cells_per_side > kMaxHeightFieldSide)
        return fail(error, "max_cells_per_side " + std::to_string(max_cells_per_side) + " is outside [1, " +
                               std::to_string(kMaxHeightFieldSide) + "]");
    for (int a = 0; a < 2; ++a)
        if (std::isnan(extent.lo[a]) || std::isnan(extent.hi[a]))
            return fail(error, "the extent has NaN bounds");
    if (!(extent.lo.x <= extent.hi.x && extent.lo.y <= extent.hi.y))
        return fail(error, "the extent is empty");

    const glm::vec2 origin = hf.origin();
    const float cell = hf.cellSize();
    const double field_x0 = origin.x, field_x1 = double(origin.x) + double(hf.width() - 1) * cell;
    const double field_y0 = origin.y, field_y1 = double(origin.y) + double(hf.height() - 1) * cell;
    const double x0 = std::max<double>(extent.lo.x, field_x0), x1 = std::min<double>(extent.hi.x, field_x1);
    const double y0 = std::max<double>(extent.lo.y, field_y0), y1 = std::min<double>(extent.hi.y, field_y1);
    if (x0 > x1 || y0 > y1)
        return fail(error, "the extent x " + formatRange(extent.lo.x, extent.hi.x) + ", y " +
                               formatRange(extent.lo.y, extent.hi.y) +
                               " does not overlap the height field x " + formatRange(field_x0, field_x1) +
                               ", y " + formatRange(field_y0, field_y1));
    if (!(x1 > x0 && y1 > y0)) return fail(error, "the extent touches the height field only along a line");

    const std::vector<Stop> xs = axisStops(origin.x, cell, hf.width(), x0, x1, max_cells_per_side);
    const std::vector<Stop> ys = axisStops(origin.y, cell, hf.height(), y0, y1, max_cells_per_side);
    if (!(xs.back().coord > xs.front().coord && ys.back().coord > ys.front().coord))
        return fail(error, "the overlap of the extent and the height field is too thin to mesh");
    const size_t nx = xs.size(), ny = ys.size();

    TriangleMesh mesh;
    mesh.base_color = kTerrainColor;
    mesh.positions.reserve(nx * ny);
    for (const Stop& y : ys) {
        for (const Stop& x : xs) {
            const float z =
                (x.index >= 0 && y.index >= 0) ? hf.at(x.index, y.index) : hf.sample(x.coord, y.coord);
            mesh.positions.emplace_back(x.coord, y.coord, z);
        }
    }
    mesh.indices.reserve((nx - 1) * (ny - 1) * 6);
    for (size_t j = 0; j + 1 < ny; ++j) {
        for (size_t i = 0; i + 1 < nx; ++i) {
            const uint32_t a = uint32_t(j * nx + i), b = a + 1, d = uint32_t((j + 1) * nx + i), c = d + 1;
            // Counter-clockwise seen from +Z (X right, Y up), so the faces point up.
            mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
        }
    }
    computeNormals(&mesh);
    *out = std::move(mesh);
    return true;
}

}  // namespace ug
