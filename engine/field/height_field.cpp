// Height fields: the terrain the Ghost Tile paper's layers and solids are defined against (Ghost Tile
// §6.1, "density fields are modified by computing the difference with ... the terrain"; §6.1 Figure 20,
// "the dried grass density field was automatically computed from the input height field").
//
// Bilinear patches are the simplest interpolant that is exact at the samples and continuous; their
// gradient is analytic inside a cell and jumps across cell edges, which is fine for the density kernels
// (they only need a gradient for orientation constraints, not for root finding).
#include "field/height_field.h"

#include <algorithm>
#include <limits>
#include <cassert>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <utility>

#include <stb_image.h>

#include "core/hash.h"

namespace ug {

HeightField::HeightField(glm::vec2 origin_m, float cell_size_m, int width, int height, std::vector<float> heights_m)
    : origin_m_(origin_m), cell_size_m_(cell_size_m), width_(width), height_(height), heights_m_(std::move(heights_m)) {
    assert(std::isfinite(cell_size_m) && cell_size_m > 0.0f);
    assert(width >= 1 && height >= 1 && width <= kMaxHeightFieldSide && height <= kMaxHeightFieldSide);
    assert(heights_m_.size() == size_t(width) * size_t(height));
    min_height_m_ = heights_m_[0];
    max_height_m_ = heights_m_[0];
    for (float h : heights_m_) {
        assert(std::isfinite(h));
        min_height_m_ = std::min(min_height_m_, h);
        max_height_m_ = std::max(max_height_m_, h);
    }
}

namespace {

}  // namespace

glm::vec3 HeightField::sampleWithGradient(float x_m, float y_m) const {
    assert(!empty());
    const height_detail::AxisCell cx = height_detail::locate(x_m, origin_m_.x, cell_size_m_, width_);
    const height_detail::AxisCell cy = height_detail::locate(y_m, origin_m_.y, cell_size_m_, height_);
    const float h00 = at(cx.i0, cy.i0), h10 = at(cx.i1, cy.i0);
    const float h01 = at(cx.i0, cy.i1), h11 = at(cx.i1, cy.i1);
    const float gx = 1.0f - cx.f, gy = 1.0f - cy.f;
    // Written so that at a sample (f = 0 or 1) the result is that sample exactly: x * 1 + y * 0 == x.
    const float bottom = h00 * gx + h10 * cx.f;
    const float top = h01 * gx + h11 * cx.f;
    const float h = bottom * gy + top * cy.f;
    const float dhdx = ((h10 - h00) * gy + (h11 - h01) * cy.f) / cell_size_m_ * cx.inside;
    const float dhdy = (top - bottom) / cell_size_m_ * cy.inside;
    return glm::vec3(h, dhdx, dhdy);
}

glm::vec2 HeightField::heightRange(glm::vec2 lo_m, glm::vec2 hi_m) const {
    assert(!empty());
    // Sample index span of the cells covering [lo, hi] per axis; infinite or far-out coordinates clamp.
    auto span = [&](float lo, float hi, float origin, int n, int* first, int* last) {
        const float ulo = (lo - origin) / cell_size_m_, uhi = (hi - origin) / cell_size_m_;
        const float top = float(n - 1);
        *first = int(std::floor(std::clamp(ulo, 0.0f, top)));
        *last = int(std::ceil(std::clamp(uhi, 0.0f, top)));
        if (!(ulo <= top)) *first = n - 1;  // also catches NaN
        if (!(uhi >= 0.0f)) *last = 0;
        if (*last < *first) std::swap(*first, *last);
    };
    int i0, i1, j0, j1;
    span(lo_m.x, hi_m.x, origin_m_.x, width_, &i0, &i1);
    span(lo_m.y, hi_m.y, origin_m_.y, height_, &j0, &j1);
    if ((i1 - i0 + 1) * int64_t(j1 - j0 + 1) >= int64_t(width_) * height_) return {min_height_m_, max_height_m_};
    float mn = std::numeric_limits<float>::infinity(), mx = -mn;
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
            const float h = at(i, j);
            mn = std::min(mn, h);
            mx = std::max(mx, h);
        }
    return {mn, mx};
}



glm::vec2 HeightField::gradient(float x_m, float y_m) const {
    const glm::vec3 s = sampleWithGradient(x_m, y_m);
    return glm::vec2(s.y, s.z);
}

namespace {

// Lattice value in [-1, 1] from a counter-based hash: no generator state, so any sample can be computed
// alone and the same seed gives the same terrain everywhere.
float latticeValue(uint64_t seed, int octave, int64_t i, int64_t j) {
    return unitFloat(hashWords(seed, uint64_t(octave), uint64_t(i), uint64_t(j))) * 2.0f - 1.0f;
}

// Quintic fade (Perlin 2002): C2 across lattice lines, so the fBm has no visible creases.
double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

double valueNoise(uint64_t seed, int octave, double x, double y) {
    const double fx = std::floor(x), fy = std::floor(y);
    const int64_t i = int64_t(fx), j = int64_t(fy);
    const double tx = fade(x - fx), ty = fade(y - fy);
    const double v00 = latticeValue(seed, octave, i, j), v10 = latticeValue(seed, octave, i + 1, j);
    const double v01 = latticeValue(seed, octave, i, j + 1), v11 = latticeValue(seed, octave, i + 1, j + 1);
    const double a = v00 + (v10 - v00) * tx;
    const double b = v01 + (v11 - v01) * tx;
    return a + (b - a) * ty;
}

bool fail(std::string* error, std::string message) {
    if (error) *error = std::move(message);
    return false;
}

bool finitePositive(float v) { return std::isfinite(v) && v > 0.0f; }

std::string stbReason() {
    const char* r = stbi_failure_reason();
    return r ? r : "unknown reason";
}

// PNG's structure, walked from the header before stb_image sees the file: the signature, IHDR first, each
// chunk inside the file, IDAT chunks non-empty, an IEND. Only PNG is taken: stb_image also reads PNM, BMP,
// PSD, ... whose headers it trusts further than we want (a PGM width of 2^31 overflows its parser). The
// pixels are deflate-compressed and deflate never packs better than about 1032:1, so the IDAT bytes bound
// the pixels the header may claim: an 85-byte file claiming 16384 x 16384 is refused before a gigabyte
// is allocated for it (see loadHeightFieldPng). Returns false with the reason; *idat_bytes is the total
// of the IDAT chunks.
bool walkPngChunks(FILE* file, uint64_t* idat_bytes_out, std::string* why) {
    static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (std::fseek(file, 0, SEEK_END) != 0) return (*why = "cannot seek in the file", false);
    const long size = std::ftell(file);
    std::rewind(file);
    unsigned char head[8] = {};
    if (size < 8 || std::fread(head, 1, 8, file) != 8 || std::memcmp(head, kSignature, 8) != 0)
        return (*why = "not a PNG file (height fields are read from PNG only)", false);
    uint64_t at = 8, idat_bytes = 0;
    bool first = true, ended = false;
    while (!ended) {
        unsigned char chunk[8];
        if (at + 12 > uint64_t(size) || std::fread(chunk, 1, 8, file) != 8)
            return (*why = "truncated: the chunks end at byte " + std::to_string(at) + " before an IEND", false);
        const uint64_t length = (uint64_t(chunk[0]) << 24) | (uint64_t(chunk[1]) << 16) | (uint64_t(chunk[2]) << 8) | chunk[3];
        const std::string type(reinterpret_cast<const char*>(chunk + 4), 4);
        if (length > uint64_t(size) - at - 12)
            return (*why = "chunk '" + type + "' at byte " + std::to_string(at) + " claims " + std::to_string(length) +
                           " bytes, past the end of the file",
                    false);
        if (first && (type != "IHDR" || length != 13)) return (*why = "the first chunk is not a 13-byte IHDR", false);
        if (type == "IDAT") {
            if (length == 0) return (*why = "an empty IDAT chunk at byte " + std::to_string(at), false);
            idat_bytes += length;
        }
        ended = type == "IEND";
        first = false;
        at += 12 + length;
        if (std::fseek(file, long(at), SEEK_SET) != 0) return (*why = "cannot seek in the file", false);
    }
    std::rewind(file);
    *idat_bytes_out = idat_bytes;
    return true;
}

}  // namespace

bool makeProceduralHeightField(const ProceduralTerrainDesc& d, HeightField* out, std::string* error) {
    assert(out);
    const std::string where = "procedural terrain: ";
    if (!std::isfinite(d.origin_m.x) || !std::isfinite(d.origin_m.y))
        return fail(error, where + "origin_m must be finite");
    if (!finitePositive(d.cell_size_m)) return fail(error, where + "cell_size_m must be finite and > 0");
    if (d.width < kMinTerrainSide || d.height < kMinTerrainSide || d.width > kMaxHeightFieldSide ||
        d.height > kMaxHeightFieldSide)
        return fail(error, where + "width and height must be in [" + std::to_string(kMinTerrainSide) + ", " +
                               std::to_string(kMaxHeightFieldSide) + "], got " + std::to_string(d.width) + "x" +
                               std::to_string(d.height));
    if (uint64_t(d.width) * uint64_t(d.height) > kMaxHeightFieldSamples)
        return fail(error, where + std::to_string(d.width) + "x" + std::to_string(d.height) +
                               " samples exceed the limit of " + std::to_string(kMaxHeightFieldSamples));
    if (d.octaves < 1 || d.octaves > 16)
        return fail(error, where + "octaves must be in [1, 16], got " + std::to_string(d.octaves));
    if (!std::isfinite(d.base_height_m)) return fail(error, where + "base_height_m must be finite");
    if (!std::isfinite(d.amplitude_m) || d.amplitude_m < 0.0f)
        return fail(error, where + "amplitude_m must be finite and >= 0");
    if (!finitePositive(d.feature_size_m)) return fail(error, where + "feature_size_m must be finite and > 0");
    if (!finitePositive(d.lacunarity)) return fail(error, where + "lacunarity must be finite and > 0");
    if (!finitePositive(d.gain) || d.gain > 1.0f) return fail(error, where + "gain must be in (0, 1]");

    double norm = 0.0, amp = 1.0;
    for (int k = 0; k < d.octaves; ++k, amp *= d.gain) norm += amp;

    std::vector<float> heights(size_t(d.width) * size_t(d.height));
    for (int j = 0; j < d.height; ++j) {
        for (int i = 0; i < d.width; ++i) {
            const double x = double(d.origin_m.x) + double(i) * d.cell_size_m;
            const double y = double(d.origin_m.y) + double(j) * d.cell_size_m;
            double sum = 0.0, a = 1.0, freq = 1.0 / d.feature_size_m;
            for (int k = 0; k < d.octaves; ++k, a *= d.gain, freq *= d.lacunarity)
                sum += a * valueNoise(d.seed, k, x * freq, y * freq);
            heights[size_t(j) * size_t(d.width) + size_t(i)] = float(d.base_height_m + d.amplitude_m * sum / norm);
        }
    }
    *out = HeightField(d.origin_m, d.cell_size_m, d.width, d.height, std::move(heights));
    return true;
}

bool loadHeightFieldPng(const std::string& path, const HeightFieldImageDesc& d, HeightField* out,
                        std::string* error) {
    assert(out);
    const std::string where = path + ": ";
    if (!std::isfinite(d.origin_m.x) || !std::isfinite(d.origin_m.y))
        return fail(error, where + "origin_m must be finite");
    if (!finitePositive(d.cell_size_m)) return fail(error, where + "cell_size_m must be finite and > 0");
    if (!std::isfinite(d.min_height_m) || !std::isfinite(d.max_height_m) || d.max_height_m < d.min_height_m)
        return fail(error, where + "min_height_m and max_height_m must be finite with min <= max");

    FILE* file = std::fopen(path.c_str(), "rb");
    if (!file) return fail(error, where + "cannot open the file (missing or unreadable)");
    std::string why;
    uint64_t idat_bytes = 0;
    if (!walkPngChunks(file, &idat_bytes, &why)) {
        std::fclose(file);
        return fail(error, where + why);
    }
    int w = 0, h = 0, channels = 0;
    // Read the header first so an absurd size is refused before anything is decoded.
    if (!stbi_info_from_file(file, &w, &h, &channels)) {
        std::fclose(file);
        return fail(error, where + "not an image stb_image can read (" + stbReason() + ")");
    }
    const std::string size_text = std::to_string(w) + "x" + std::to_string(h);
    if (w <= 0 || h <= 0) {
        std::fclose(file);
        return fail(error, where + "the image has zero size");
    }
    if (w > kMaxHeightFieldSide || h > kMaxHeightFieldSide || uint64_t(w) * uint64_t(h) > kMaxHeightFieldSamples) {
        std::fclose(file);
        return fail(error, where + "the image is " + size_text + ", larger than the accepted " +
                               std::to_string(kMaxHeightFieldSide) + " per side and " +
                               std::to_string(kMaxHeightFieldSamples) + " pixels in all");
    }
    const bool sixteen = stbi_is_16_bit_from_file(file) != 0;
    if (idat_bytes == 0) {
        std::fclose(file);
        return fail(error, where + "no image data (no IDAT chunk)");
    }
    // Deflate's bound: at least one byte per pixel (two at 16 bits); 1100 leaves room for its headers.
    if (uint64_t(w) * uint64_t(h) * (sixteen ? 2u : 1u) > idat_bytes * 1100u) {
        std::fclose(file);
        return fail(error, where + "the header claims " + size_text +
                               " pixels, more than the file's compressed data can hold (" +
                               std::to_string(idat_bytes) + " bytes of image data; truncated or forged)");
    }
    std::vector<float> heights(size_t(w) * size_t(h));
    const float range = d.max_height_m - d.min_height_m;
    int lw = 0, lh = 0, lc = 0;
    // One conversion for both depths: image row 0 is the largest Y, values map to [min, max] height.
    auto convert = [&](auto* pixels, float full_scale) {
        std::fclose(file);
        if (!pixels || lw != w || lh != h) {
            if (pixels) stbi_image_free(pixels);
            return fail(error, where + "cannot decode the image (" + stbReason() + ")");
        }
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i)
                heights[size_t(j) * size_t(w) + size_t(i)] =
                    d.min_height_m + range * (float(pixels[size_t(h - 1 - j) * size_t(w) + size_t(i)]) / full_scale);
        stbi_image_free(pixels);
        return true;
    };
    const bool decoded = sixteen ? convert(stbi_load_from_file_16(file, &lw, &lh, &lc, 1), 65535.0f)
                                 : convert(stbi_load_from_file(file, &lw, &lh, &lc, 1), 255.0f);
    if (!decoded) return false;
    *out = HeightField(d.origin_m, d.cell_size_m, w, h, std::move(heights));
    return true;
}

}  // namespace ug
