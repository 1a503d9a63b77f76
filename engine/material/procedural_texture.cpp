#include "material/procedural_texture.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <vector>

#include "core/hash.h"

namespace ug {
namespace {

// Positive modulo for lattice wrap-around.
int wrap(int i, int n) {
    const int m = i % n;
    return m < 0 ? m + n : m;
}

float frac(float x) {
    return x - std::floor(x);
}

float clamp01(float x) {
    return std::min(1.0f, std::max(0.0f, x));
}

float smooth(float t) {
    return t * t * (3.0f - 2.0f * t);
}

// Value noise on a lattice of px by py cells over the unit tile, wrapping in both directions: (u, v)
// and (u + 1, v) or (u, v + 1) give the same value. Range [0, 1).
float periodicNoise(float u, float v, int px, int py, uint64_t seed) {
    const float x = u * float(px), y = v * float(py);
    const float fx = std::floor(x), fy = std::floor(y);
    const int ix = int(fx), iy = int(fy);
    const float tx = smooth(x - fx), ty = smooth(y - fy);
    auto at = [&](int i, int j) {
        return unitFloat(hashWords(seed, uint64_t(wrap(i, px)), uint64_t(wrap(j, py))));
    };
    const float a = at(ix, iy), b = at(ix + 1, iy), c = at(ix, iy + 1), d = at(ix + 1, iy + 1);
    const float top = a + (b - a) * tx, bottom = c + (d - c) * tx;
    return top + (bottom - top) * ty;
}

// Octaves of periodicNoise, each twice the lattice of the last; normalized to [0, 1).
float periodicFbm(float u, float v, int px, int py, int octaves, uint64_t seed) {
    float sum = 0.0f, amp = 1.0f, total = 0.0f;
    for (int o = 0; o < octaves; ++o) {
        sum += amp * periodicNoise(u, v, px << o, py << o, hashWords(seed, uint64_t(o)));
        total += amp;
        amp *= 0.5f;
    }
    return sum / total;
}

// A per-pixel hash in [0, 1): grit and speckle, which wrap because they are per pixel.
float pixelHash(uint64_t seed, int x, int y, uint64_t channel) {
    return unitFloat(hashWords(seed, uint64_t(x), uint64_t(y), channel));
}

struct Texel {
    glm::vec3 rgb{1.0f};  // the pattern, any positive scale (normalized afterwards)
    bool covered = true;
};

using Pattern = Texel (*)(float u, float v, int x, int y, int size, bool cutout, uint64_t seed);

Texel rockTexel(float u, float v, int x, int y, int, bool, uint64_t seed) {
    const float grain = periodicFbm(u, v, 4, 4, 5, hashWords(seed, 1));
    float value = 0.7f + 0.6f * grain;
    const float speck = pixelHash(seed, x, y, 2);
    if (speck > 0.94f) value *= 0.72f;       // dark mineral grains
    else if (speck < 0.04f) value *= 1.22f;  // light ones
    // Cracks: thin bands around one level of a coarse noise, a few curves per repeat.
    const float crack = std::min(std::fabs(periodicFbm(u, v, 3, 3, 3, hashWords(seed, 3)) - 0.5f),
                                 std::fabs(periodicFbm(u, v, 2, 4, 3, hashWords(seed, 6)) - 0.5f));
    if (crack < 0.012f) value *= 0.5f + 0.5f * (crack / 0.012f);
    // A slight warm-cool drift, so a grey rock is not one flat grey.
    const float drift = 0.08f * (periodicNoise(u, v, 2, 2, hashWords(seed, 4)) - 0.5f);
    return {value * glm::vec3(1.0f + drift, 1.0f, 1.0f - drift)};
}

Texel leafTexel(float u, float v, int, int, int, bool cutout, uint64_t seed) {
    // The leaf lies along u, centred on the tile's corner (u = v = 0), so a leaf model centred on its
    // origin and long along X, textured with texture_scale_m = its length, gets the texture's midrib on
    // its own (the starter leaves are). a runs along the midrib from 0 to 1, b across it (midrib at 0.5).
    const float a = frac(u + 0.5f), b = frac(v + 0.5f);
    const float d = std::fabs(b - 0.5f);  // distance from the midrib
    float value = 0.88f + 0.22f * periodicFbm(u, v, 8, 8, 3, hashWords(seed, 1));
    // Lateral veins run from the midrib outwards and towards the tip (larger a); 7 pairs per leaf.
    const float phase = frac((a - 0.6f * d) * 7.0f);
    const float vein = std::fabs(phase - 0.5f);
    if (vein < 0.03f) value *= 1.18f;
    if (d < 0.008f) value *= 1.35f;          // the midrib
    value *= 1.0f - 0.25f * d;               // a little darker towards the margin
    Texel t{glm::vec3(value * 1.02f, value, value * 0.96f)};
    if (cutout) {
        // One leaf per repeat: half-width along the midrib, pointed at both ends, finely serrated. It
        // reaches neither the sides (d <= 0.36) nor the ends, so the alpha wraps.
        const float s = 4.0f * a * (1.0f - a);
        const float half_width = 0.36f * s * (1.2f - 0.2f * s) * (1.0f - 0.05f * frac(a * 24.0f));
        t.covered = d < half_width;
    }
    return t;
}

Texel barkTexel(float u, float v, int, int, int, bool, uint64_t seed) {
    // Fibres along u: a lattice much finer across (v) than along (u). In the box projection u follows X
    // on the sides facing Y and Z, so a branch modelled along X (the starter twig) gets fibres along it.
    const float fibre = periodicFbm(u, v, 3, 48, 3, hashWords(seed, 1));
    float value = 0.78f + 0.44f * fibre;
    // Furrows: dark valleys where a coarse, also elongated noise crosses its middle.
    const float furrow = std::fabs(periodicFbm(u, v, 1, 8, 3, hashWords(seed, 2)) - 0.5f);
    if (furrow < 0.09f) value *= 0.5f + 0.5f * (furrow / 0.09f);
    const float drift = 0.06f * (periodicNoise(u, v, 1, 3, hashWords(seed, 3)) - 0.5f);
    return {value * glm::vec3(1.0f + drift, 1.0f, 1.0f - drift)};
}

Texel grassTexel(float u, float v, int, int, int, bool cutout, uint64_t seed) {
    constexpr int kBlades = 24;
    // Offset by half a blade so the tile's edge runs down the middle of one, not between two.
    const float x = u * float(kBlades) + 0.5f;
    const int blade = wrap(int(std::floor(x)), kBlades);
    const float t = 2.0f * frac(x) - 1.0f;  // -1..1 across the blade
    const float shade = 0.8f + 0.4f * unitFloat(hashWords(seed, 1, uint64_t(blade)));
    const float hue = 0.14f * (unitFloat(hashWords(seed, 2, uint64_t(blade))) - 0.5f);
    const float along = 0.9f + 0.2f * periodicNoise(u, v, kBlades, 4, hashWords(seed, 3));
    const float value = shade * along * (1.12f - 0.3f * t * t);  // a lighter centre line
    Texel out{value * glm::vec3(1.0f + hue, 1.0f, 1.0f - hue)};
    if (cutout) out.covered = std::fabs(t) < 0.8f;
    return out;
}

Texel groundTexel(float u, float v, int x, int y, int, bool, uint64_t seed) {
    const float soil = periodicFbm(u, v, 4, 4, 5, hashWords(seed, 1));
    glm::vec3 rgb(0.7f + 0.6f * soil);
    // Pebbles: at most one per cell of a 16 x 16 grid, a disc of radius 0.15-0.4 cell at a random spot;
    // neighbouring cells are looked at too, since a disc may spill over.
    constexpr int kCells = 16;
    const float cx = u * float(kCells), cy = v * float(kCells);
    const int ix = int(std::floor(cx)), iy = int(std::floor(cy));
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            const uint64_t cell = hashWords(seed, 2, uint64_t(wrap(ix + i, kCells)), uint64_t(wrap(iy + j, kCells)));
            if (unitFloat(cell) > 0.4f) continue;  // 40% of the cells hold a pebble
            const float px = float(ix + i) + unitFloat(hashWords(cell, 1));
            const float py = float(iy + j) + unitFloat(hashWords(cell, 2));
            const float r = 0.15f + 0.25f * unitFloat(hashWords(cell, 3));
            const float dx = cx - px, dy = cy - py, d2 = dx * dx + dy * dy;
            if (d2 < r * r) {
                const float lum = 0.85f + 0.6f * unitFloat(hashWords(cell, 4));
                const float rim = 1.0f - 0.25f * d2 / (r * r);  // rounded: darker towards the edge
                rgb = lum * rim * glm::vec3(0.9f, 1.0f, 1.2f);     // greyer than the brown soil
            }
        }
    const float grit = pixelHash(seed, x, y, 5);
    if (grit > 0.9f) rgb *= 0.7f + 3.0f * (grit - 0.9f) * 1.8f;  // 0.7 .. 1.24
    return {rgb};
}

Texel hayTexel(float u, float v, int, int, int, bool, uint64_t seed) {
    // Three layers of straws, each a family of parallel lines x = u * N + m * v (m integer, so a line
    // leaving the bottom of the tile re-enters at the top where its continuation starts); the upper
    // layer covers the lower ones.
    struct Layer {
        int n, m;
    };
    static constexpr Layer kLayers[] = {{20, 3}, {16, -4}, {24, 1}};
    float value = 0.45f;  // the dark gaps between straws
    for (int k = 0; k < 3; ++k) {
        const float x = u * float(kLayers[k].n) + float(kLayers[k].m) * v;
        const float t = 2.0f * frac(x) - 1.0f;
        const float cover = periodicNoise(u, v, 6, 6, hashWords(seed, 10, uint64_t(k)));
        if (std::fabs(t) < 0.6f && cover > 0.3f) {
            const float shine = 0.85f + 0.35f * periodicNoise(u, v, 12, 12, hashWords(seed, 20, uint64_t(k)));
            value = shine * (1.1f - 0.35f * t * t);
        }
    }
    return {glm::vec3(value * 1.03f, value, value * 0.9f)};
}

Pattern patternOf(TextureKind kind) {
    switch (kind) {
        case TextureKind::Rock: return rockTexel;
        case TextureKind::Leaf: return leafTexel;
        case TextureKind::Bark: return barkTexel;
        case TextureKind::Grass: return grassTexel;
        case TextureKind::Ground: return groundTexel;
        case TextureKind::Hay: return hayTexel;
        case TextureKind::None: break;
    }
    return nullptr;
}

// sRGB code thresholds: code c is the largest with decode((c - 0.5) / 255) <= v, i.e. rounding in sRGB
// space. x^2.4 = x^2 * (x^2)^(1/5), the fifth root by Newton's method from above (monotone, fixed
// iteration count): only IEEE basic operations, so every machine gets the same table.
double srgbDecode(double x) {
    if (x <= 0.04045) return x / 12.92;
    const double y = (x + 0.055) / 1.055, a = y * y;
    double r = 1.0;
    for (int i = 0; i < 64; ++i) r = (4.0 * r + a / (r * r * r * r)) / 5.0;
    return a * r;
}

struct SrgbTables {
    std::array<double, 255> thresholds;  // linear value where code c rounds up to c + 1
    std::array<float, 256> decoded;
    SrgbTables() {
        for (int c = 0; c < 255; ++c) thresholds[size_t(c)] = srgbDecode((double(c) + 0.5) / 255.0);
        for (int c = 0; c < 256; ++c) decoded[size_t(c)] = float(srgbDecode(double(c) / 255.0));
    }
};

const SrgbTables& srgbTables() {
    static const SrgbTables tables;
    return tables;
}

}  // namespace

uint8_t linearToSrgb8(float linear) {
    if (!(linear > 0.0f)) return 0;  // also NaN
    const auto& t = srgbTables().thresholds;
    return uint8_t(std::upper_bound(t.begin(), t.end(), double(linear)) - t.begin());
}

float srgb8ToLinear(uint8_t code) {
    return srgbTables().decoded[code];
}

TextureImage makeDetailMap(TextureKind kind, bool alpha_cutout, uint64_t seed, int size) {
    size = std::clamp(size, kMinTextureSize, kMaxTextureSize);
    assert((size & (size - 1)) == 0 && "texture sizes are powers of two");
    TextureImage image;
    image.width = image.height = size;
    image.rgba.assign(size_t(size) * size_t(size) * 4, 255);
    const Pattern pattern = patternOf(kind);
    if (!pattern) {
        for (size_t p = 0; p < image.rgba.size(); p += 4) image.rgba[p] = image.rgba[p + 1] = image.rgba[p + 2] = kDetailOne;
        return image;
    }
    const uint64_t kind_seed = hashWords(seed, uint64_t(kind));
    std::vector<Texel> texels(size_t(size) * size_t(size));
    glm::dvec3 sum(0.0);
    size_t covered = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            // Pixel centres, so the pattern is sampled the same way at every edge.
            const float u = (float(x) + 0.5f) / float(size), v = (float(y) + 0.5f) / float(size);
            Texel t = pattern(u, v, x, y, size, alpha_cutout, kind_seed);
            texels[size_t(y) * size_t(size) + size_t(x)] = t;
            if (t.covered) {
                sum += glm::dvec3(t.rgb);
                ++covered;
            }
        }
    // Mean 1 per channel over what is drawn, so base_color stays the average colour.
    const glm::dvec3 mean = covered ? sum / double(covered) : glm::dvec3(1.0);
    for (size_t p = 0; p < texels.size(); ++p) {
        const Texel& t = texels[p];
        for (int c = 0; c < 3; ++c) {
            const double d = double(t.rgb[c]) / mean[c];
            image.rgba[p * 4 + size_t(c)] = uint8_t(std::clamp(std::floor(d * kDetailOne + 0.5), 0.0, 255.0));
        }
        image.rgba[p * 4 + 3] = t.covered ? 255 : 0;
    }
    return image;
}

TextureImage bakeTexture(const TextureImage& detail_map, glm::vec3 base_color) {
    TextureImage out = detail_map;
    for (size_t p = 0; p + 3 < out.rgba.size(); p += 4)
        for (int c = 0; c < 3; ++c) {
            const float linear = clamp01(base_color[c]) * (float(detail_map.rgba[p + size_t(c)]) / float(kDetailOne));
            out.rgba[p + size_t(c)] = linearToSrgb8(clamp01(linear));
        }
    return out;
}

TextureImage bakeMaterialTexture(TextureKind kind, bool alpha_cutout, glm::vec3 base_color, uint64_t seed, int size) {
    return bakeTexture(makeDetailMap(kind, alpha_cutout, seed, size), base_color);
}

}  // namespace ug
