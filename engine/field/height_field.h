// A height field: terrain elevation z = h(x, y) on a regular grid over an XY rectangle (metres, Z up).
//
//   sample (i, j), i in [0, width), j in [0, height), sits at origin_m + (i, j) * cell_size_m and holds
//   heights_m[j * width + i]. Between samples h is the bilinear patch of the cell's four corners; outside
//   the rectangle the coordinates are clamped to it (the border extends flat, so the gradient's component
//   along a clamped axis is 0).
//
// The class only protects one invariant: the cached min/max heights (used for primitive bounds) match
// the samples. Building one:
//   HeightField hf;
//   std::string error;
//   if (!makeProceduralHeightField(ProceduralTerrainDesc{.seed = 7}, &hf, &error)) ...
//   if (!loadHeightFieldPng("terrain.png", HeightFieldImageDesc{.max_height_m = 40}, &hf, &error)) ...
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace ug {

namespace height_detail {

// Where a world coordinate falls along one axis of n samples: the cell's first sample, the fraction in
// [0, 1] across it, and whether the coordinate was inside the covered span (not clamped).
struct AxisCell {
    int i0;
    int i1;
    float f;
    float inside;  // 1 inside, 0 when clamped: multiplies the derivative along this axis
};

inline AxisCell locate(float coord_m, float origin_m, float cell_m, int n) {
    const float last = float(n - 1);
    float u = (coord_m - origin_m) / cell_m;
    AxisCell c;
    c.inside = (u >= 0.0f && u <= last) ? 1.0f : 0.0f;
    u = std::clamp(u, 0.0f, last);  // callers pass finite points (a NaN would clamp to garbage)
    if (n == 1) return AxisCell{0, 0, 0.0f, 0.0f};
    c.i0 = std::min(int(u), n - 2);
    c.i1 = c.i0 + 1;
    c.f = u - float(c.i0);
    return c;
}

}  // namespace height_detail

// The largest accepted grid: per axis, and in samples (8192² = 64 Mi samples = 256 MiB of floats; a
// procedural grid of that size takes about 20 s to compute on two cores, a larger one is refused up front).
constexpr int kMaxHeightFieldSide = 16384;
constexpr uint64_t kMaxHeightFieldSamples = uint64_t(8192) * 8192;
// A terrain is a surface: at least 2 samples per axis (a 1 x N field has no cells to mesh or sample).
constexpr int kMinTerrainSide = 2;

class HeightField {
public:
    HeightField() = default;
    // Asserts: cell_size_m > 0 and finite, 1 <= width, height <= kMaxHeightFieldSide,
    // heights_m.size() == width * height, every height finite.
    HeightField(glm::vec2 origin_m, float cell_size_m, int width, int height, std::vector<float> heights_m);

    bool empty() const { return heights_m_.empty(); }
    glm::vec2 origin() const { return origin_m_; }  // world XY of sample (0, 0), metres
    float cellSize() const { return cell_size_m_; }  // metres between neighbouring samples
    int width() const { return width_; }             // samples along X
    int height() const { return height_; }           // samples along Y
    float at(int i, int j) const { return heights_m_[size_t(j) * size_t(width_) + size_t(i)]; }
    const std::vector<float>& heights() const { return heights_m_; }
    float minHeight() const { return min_height_m_; }  // over all samples, metres
    float maxHeight() const { return max_height_m_; }

    // Bilinear height at world (x, y), clamped to the rectangle. Must not be called on an empty field.
    // Inline: the hot path of every terrain primitive. The same expressions as sampleWithGradient(), so
    // the bits agree.
    float sample(float x_m, float y_m) const {
        const height_detail::AxisCell cx = height_detail::locate(x_m, origin_m_.x, cell_size_m_, width_);
        const height_detail::AxisCell cy = height_detail::locate(y_m, origin_m_.y, cell_size_m_, height_);
        const float h00 = at(cx.i0, cy.i0), h10 = at(cx.i1, cy.i0);
        const float h01 = at(cx.i0, cy.i1), h11 = at(cx.i1, cy.i1);
        const float gx = 1.0f - cx.f, gy = 1.0f - cy.f;
        const float bottom = h00 * gx + h10 * cx.f;
        const float top = h01 * gx + h11 * cx.f;
        return bottom * gy + top * cy.f;
    }
    // Analytic gradient (dh/dx, dh/dy) of the same bilinear patch (dimensionless, m per m); the component
    // along an axis where (x, y) is outside the rectangle is 0. On a cell edge the cell with the larger
    // index is used (the last cell on the far border).
    glm::vec2 gradient(float x_m, float y_m) const;
    // Both at once: (h, dh/dx, dh/dy), exactly the values sample() and gradient() return.
    glm::vec3 sampleWithGradient(float x_m, float y_m) const;
    // (min, max) of every sample of the cells that cover the XY rectangle [lo, hi] (clamped to the field):
    // bilinear heights inside the rectangle lie within it, up to float rounding (pad by a few ulps).
    // Tiles use it to bound a terrain layer's support tightly (instead of the whole field's range).
    glm::vec2 heightRange(glm::vec2 lo_m, glm::vec2 hi_m) const;

private:
    glm::vec2 origin_m_{0.0f};
    float cell_size_m_ = 1.0f;
    int width_ = 0;
    int height_ = 0;
    std::vector<float> heights_m_;
    float min_height_m_ = 0.0f;
    float max_height_m_ = 0.0f;
};

// Seeded fBm of value noise: height = base_height_m + amplitude_m * sum_k gain^k n(p * lacunarity^k /
// feature_size_m) / sum_k gain^k, with n in [-1, 1], so heights stay within base ± amplitude_m. The
// lattice values are hashes of (seed, octave, i, j): the same desc gives the same heights on any machine.
struct ProceduralTerrainDesc {
    glm::vec2 origin_m{0.0f};
    float cell_size_m = 1.0f;      // > 0
    int width = 129;               // samples, in [kMinTerrainSide, kMaxHeightFieldSide], width * height <=
                                   // kMaxHeightFieldSamples
    int height = 129;
    uint64_t seed = 1;
    int octaves = 5;               // in [1, 16]
    float base_height_m = 0.0f;
    float amplitude_m = 2.0f;      // >= 0
    float feature_size_m = 32.0f;  // wavelength of the first octave, > 0
    float lacunarity = 2.0f;       // frequency ratio between octaves, > 0
    float gain = 0.5f;             // amplitude ratio between octaves, in (0, 1]
};

// Returns false with *error naming the bad setting when the desc is invalid; *out is untouched then.
bool makeProceduralHeightField(const ProceduralTerrainDesc& desc, HeightField* out, std::string* error);

// How a grayscale image maps to a height field: pixel value 0 -> min_height_m, the format's maximum
// (255 or 65535) -> max_height_m, linearly. Image row 0 is the top of the picture and maps to the
// largest Y (the picture reads like a map seen from above, X right, Y up).
struct HeightFieldImageDesc {
    glm::vec2 origin_m{0.0f};
    float cell_size_m = 1.0f;  // > 0
    float min_height_m = 0.0f;
    float max_height_m = 1.0f;  // >= min_height_m
};

// Loads an 8- or 16-bit PNG (PNG only; colour is converted to luminance). Returns false with
// *error = "<path>: <reason>" for a missing or unreadable file, a file that is not a PNG, a PNG whose
// chunks run past the file or lack IHDR / IDAT / IEND (or hold an empty IDAT), an image larger than
// kMaxHeightFieldSide on a side or kMaxHeightFieldSamples in all, or one whose header claims more pixels
// than its compressed data could hold (deflate packs at most ~1032:1) — all refused from the chunk walk
// and the header, before any pixel memory is taken; *out is untouched then.
bool loadHeightFieldPng(const std::string& path, const HeightFieldImageDesc& desc, HeightField* out,
                        std::string* error);

}  // namespace ug
