// Procedural starter assets. Three shape builders cover everything:
//   - displaced icospheres (rock, flat stone, pebble),
//   - closed thin sheets, a two-sided surface with a little thickness that meets at the rim and at both
//     ends (leaf blades, grass blades): thin but closed, so the sphere fitter sees a thin solid,
//   - tubes along polylines and surfaces of revolution (twigs, stems, needles, mushroom).
// Random choices come from hashWords(seed, part, k), never from generator state.
#include "mesh/procedural_models.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <functional>
#include <map>

#include "core/hash.h"
#include "io/gltf_mesh_io.h"

namespace ug {
namespace {

constexpr float kPi = 3.14159265358979f;

// Uniform in [lo, hi) from (seed, a, b).
float rnd(uint64_t seed, uint64_t a, uint64_t b, float lo, float hi) {
    return lo + (hi - lo) * unitFloat(hashWords(seed, a, b));
}

// Smooth value noise in [-1, 1] on the integer lattice.
float valueNoise(const glm::vec3& p, uint64_t seed) {
    const glm::vec3 f = glm::floor(p);
    const glm::vec3 t = p - f;
    const glm::vec3 w = t * t * (3.0f - 2.0f * t);
    auto corner = [&](int dx, int dy, int dz) {
        const uint64_t h = hashWords(seed, uint64_t(int64_t(f.x) + dx), uint64_t(int64_t(f.y) + dy),
                                     uint64_t(int64_t(f.z) + dz));
        return unitFloat(h) * 2.0f - 1.0f;
    };
    const float x00 = glm::mix(corner(0, 0, 0), corner(1, 0, 0), w.x);
    const float x10 = glm::mix(corner(0, 1, 0), corner(1, 1, 0), w.x);
    const float x01 = glm::mix(corner(0, 0, 1), corner(1, 0, 1), w.x);
    const float x11 = glm::mix(corner(0, 1, 1), corner(1, 1, 1), w.x);
    return glm::mix(glm::mix(x00, x10, w.y), glm::mix(x01, x11, w.y), w.z);
}

float fbm(const glm::vec3& p, uint64_t seed, int octaves) {
    float sum = 0.0f, amp = 0.5f, freq = 1.0f;
    for (int o = 0; o < octaves; ++o) {
        sum += amp * valueNoise(p * freq, hashWords(seed, uint64_t(o)));
        amp *= 0.5f;
        freq *= 2.03f;
    }
    return sum;
}

struct Builder {
    TriangleMesh mesh;
    uint32_t vertex(const glm::vec3& p) {
        mesh.positions.push_back(p);
        return uint32_t(mesh.positions.size() - 1);
    }
    void tri(uint32_t a, uint32_t b, uint32_t c) { mesh.indices.insert(mesh.indices.end(), {a, b, c}); }
};

// Unit icosphere, outward (counter-clockwise seen from outside) winding.
TriangleMesh icosphere(int subdivisions) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    TriangleMesh m;
    m.positions = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                   {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (glm::vec3& p : m.positions) p = glm::normalize(p);
    m.indices = {0, 11, 5, 0, 5,  1, 0,  1, 7, 0,  7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,  11, 10, 2,  10, 7, 6, 7, 1, 8,
                 3, 9,  4, 3, 4,  2, 3,  2, 6, 3,  6, 8,  3, 8,  9,  4, 9, 5, 2, 4,  11, 6,  2,  10, 8,  6, 7, 9, 8, 1};
    for (int s = 0; s < subdivisions; ++s) {
        std::vector<uint32_t> next;
        std::vector<std::pair<uint64_t, uint32_t>> cache;  // (edge key, midpoint), small: linear scan per tri is fine
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const uint64_t key = a < b ? (uint64_t(a) << 32 | b) : (uint64_t(b) << 32 | a);
            for (const auto& [k, v] : cache)
                if (k == key) return v;
            m.positions.push_back(glm::normalize(m.positions[a] + m.positions[b]));
            const uint32_t v = uint32_t(m.positions.size() - 1);
            cache.push_back({key, v});
            return v;
        };
        for (size_t i = 0; i < m.indices.size(); i += 3) {
            const uint32_t a = m.indices[i], b = m.indices[i + 1], c = m.indices[i + 2];
            const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        m.indices = std::move(next);
    }
    return m;
}

// A closed thin sheet over (s, t) in [0,1] x [-1,1]: pos(s, t) is the mid-surface, both ends (s = 0, 1)
// collapse to a tip and the rims (t = +-1) are where the two faces meet. half_thickness(s) is the
// half thickness along the middle (t = 0), tapering to 0 at the rims.
void addSheet(Builder* b, int rows, int cols, const std::function<glm::vec3(float, float)>& pos,
              const std::function<float(float)>& half_thickness) {
    assert(rows >= 3 && cols >= 2 && cols % 2 == 0);
    const float e = 1e-3f;
    std::vector<uint32_t> top((rows - 1) * (cols + 1)), bottom((rows - 1) * (cols + 1));
    for (int i = 1; i < rows; ++i) {
        const float s = float(i) / float(rows);
        for (int j = 0; j <= cols; ++j) {
            const float t = -1.0f + 2.0f * float(j) / float(cols);
            const glm::vec3 p = pos(s, t);
            const size_t k = size_t(i - 1) * size_t(cols + 1) + size_t(j);
            if (j == 0 || j == cols) {
                top[k] = bottom[k] = b->vertex(p);
                continue;
            }
            const glm::vec3 ds = pos(s + e, t) - pos(s - e, t), dt = pos(s, t + e) - pos(s, t - e);
            const glm::vec3 n = glm::normalize(glm::cross(ds, dt));
            const float h = half_thickness(s) * std::sqrt(std::max(0.0f, 1.0f - t * t));
            top[k] = b->vertex(p + h * n);
            bottom[k] = b->vertex(p - h * n);
        }
    }
    auto at = [&](const std::vector<uint32_t>& v, int i, int j) { return v[size_t(i - 1) * size_t(cols + 1) + size_t(j)]; };
    for (int i = 1; i + 1 < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            b->tri(at(top, i, j), at(top, i + 1, j), at(top, i, j + 1));
            b->tri(at(top, i + 1, j), at(top, i + 1, j + 1), at(top, i, j + 1));
            b->tri(at(bottom, i, j), at(bottom, i, j + 1), at(bottom, i + 1, j));
            b->tri(at(bottom, i + 1, j), at(bottom, i, j + 1), at(bottom, i + 1, j + 1));
        }
    const uint32_t tip0 = b->vertex(pos(0.0f, 0.0f)), tip1 = b->vertex(pos(1.0f, 0.0f));
    for (int j = 0; j < cols; ++j) {
        b->tri(tip0, at(top, 1, j), at(top, 1, j + 1));
        b->tri(tip0, at(bottom, 1, j + 1), at(bottom, 1, j));
        b->tri(tip1, at(top, rows - 1, j + 1), at(top, rows - 1, j));
        b->tri(tip1, at(bottom, rows - 1, j), at(bottom, rows - 1, j + 1));
    }
}

// A closed tube along a polyline (at least 2 points) with per-point radii and flat end caps.
void addTube(Builder* b, const std::vector<glm::vec3>& line, const std::vector<float>& radii, int sides) {
    assert(line.size() >= 2 && radii.size() == line.size() && sides >= 3);
    // Parallel transport keeps the rings from twisting along the line.
    glm::vec3 t0 = glm::normalize(line[1] - line[0]);
    glm::vec3 n1 = std::abs(t0.z) < 0.9f ? glm::normalize(glm::cross(t0, glm::vec3(0, 0, 1)))
                                         : glm::normalize(glm::cross(t0, glm::vec3(1, 0, 0)));
    std::vector<uint32_t> rings;
    for (size_t k = 0; k < line.size(); ++k) {
        const glm::vec3 t = glm::normalize(k + 1 < line.size() ? line[k + 1] - line[k] : line[k] - line[k - 1]);
        const glm::vec3 tk = k > 0 && k + 1 < line.size() ? glm::normalize(line[k + 1] - line[k - 1]) : t;
        n1 = glm::normalize(n1 - glm::dot(n1, tk) * tk);
        const glm::vec3 n2 = glm::cross(tk, n1);  // (n1, n2, t) right-handed
        for (int j = 0; j < sides; ++j) {
            const float a = 2.0f * kPi * float(j) / float(sides);
            rings.push_back(b->vertex(line[k] + radii[k] * (std::cos(a) * n1 + std::sin(a) * n2)));
        }
    }
    auto ring = [&](size_t k, int j) { return rings[k * size_t(sides) + size_t(j % sides)]; };
    for (size_t k = 0; k + 1 < line.size(); ++k)
        for (int j = 0; j < sides; ++j) {
            b->tri(ring(k, j), ring(k, j + 1), ring(k + 1, j));
            b->tri(ring(k, j + 1), ring(k + 1, j + 1), ring(k + 1, j));
        }
    const uint32_t c0 = b->vertex(line.front()), c1 = b->vertex(line.back());
    const size_t last = line.size() - 1;
    for (int j = 0; j < sides; ++j) {
        b->tri(c0, ring(0, j + 1), ring(0, j));
        b->tri(c1, ring(last, j), ring(last, j + 1));
    }
}

// A closed surface of revolution about the vertical axis through `base`. The profile (r, z) runs from
// the top pole (r = 0) to the bottom pole (r = 0); interior points must have r > 0.
void addRevolution(Builder* b, const glm::vec3& base, const std::vector<glm::vec2>& profile, int segments) {
    assert(profile.size() >= 3);
    const size_t rings = profile.size() - 2;
    std::vector<uint32_t> v(rings * size_t(segments));
    for (size_t i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const float a = 2.0f * kPi * float(j) / float(segments);
            const glm::vec2 rz = profile[i + 1];
            v[i * size_t(segments) + size_t(j)] = b->vertex(base + glm::vec3(rz.x * std::cos(a), rz.x * std::sin(a), rz.y));
        }
    auto at = [&](size_t i, int j) { return v[i * size_t(segments) + size_t(j % segments)]; };
    for (size_t i = 0; i + 1 < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            b->tri(at(i, j), at(i + 1, j), at(i, j + 1));
            b->tri(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
        }
    const uint32_t top = b->vertex(base + glm::vec3(0, 0, profile.front().y));
    const uint32_t bottom = b->vertex(base + glm::vec3(0, 0, profile.back().y));
    for (int j = 0; j < segments; ++j) {
        b->tri(top, at(0, j), at(0, j + 1));
        b->tri(bottom, at(rings - 1, j + 1), at(rings - 1, j));
    }
}

TriangleMesh finish(Builder* b, const glm::vec3& color) {
    TriangleMesh m = std::move(b->mesh);
    const Bounds3 box = meshBounds(m);
    const glm::vec3 centre = 0.5f * (box.min + box.max);
    for (glm::vec3& p : m.positions) p -= centre;
    m.base_color = color;
    computeNormals(&m);
    return m;
}

// A noisy ellipsoid with semi-axes `axes_m`; `roughness` scales the radial displacement.
TriangleMesh displacedEllipsoid(uint64_t seed, const glm::vec3& axes_m, float roughness, float frequency,
                                const glm::vec3& color) {
    Builder b;
    b.mesh = icosphere(3);  // 1280 triangles
    const glm::vec3 offset(rnd(seed, 1, 0, 0, 100), rnd(seed, 1, 1, 0, 100), rnd(seed, 1, 2, 0, 100));
    for (glm::vec3& p : b.mesh.positions) {
        const float d = 1.0f + roughness * fbm(p * frequency + offset, seed, 4);
        p = p * d * axes_m;
    }
    return finish(&b, color);
}

// How a leaf blade is shaped. The defaults are the fresh autumn leaf (leaf_oak, leaf_birch); the dry and
// wet variants change the ranges and add the rolled edges and crinkles, so every leaf shares one outline
// and one builder.
struct LeafShape {
    float length_m = 0.09f;
    std::function<float(float)> half_width_m;  // outline over s in [0, 1], base to tip
    float max_half_width_m = 0.03f;
    int rows = 32;
    int cols = 10;
    glm::vec3 color{0.5f};
    // Ranges the seed picks from: across-blade cupping (rim lift over the widest half width), lengthwise
    // curl (z over the length, about a point 35 % along) and twist.
    glm::vec2 cup{0.25f, 0.45f}, bend{0.10f, 0.20f}, twist{-0.15f, 0.15f};
    // Rolling the cross-section on an arc of this curvature (rad/m), which keeps the blade's width as
    // arc length, so the edges curl up and over as a drying leaf's do; 0 leaves the parabolic cup alone.
    float roll_per_m = 0.0f;
    float crinkle_m = 0.0f;          // amplitude of the wrinkles across the blade (0: smooth)
    float crinkle_wavelength_m = 0.01f;
    bool stem = true;
};

// A leaf blade along +X from the origin, with a stem behind it.
TriangleMesh leaf(uint64_t seed, const LeafShape& shape) {
    Builder b;
    const float length_m = shape.length_m, max_half_width_m = shape.max_half_width_m;
    const float cup = rnd(seed, 2, 0, shape.cup.x, shape.cup.y);    // across-blade cupping
    const float bend = rnd(seed, 2, 1, shape.bend.x, shape.bend.y);   // lengthwise curl
    const float twist = rnd(seed, 2, 2, shape.twist.x, shape.twist.y);
    const uint64_t crinkle_seed = hashWords(seed, 20);
    auto pos = [&](float s, float t) {
        float y = t * shape.half_width_m(s);
        float z = cup * y * y / max_half_width_m + bend * length_m * (s - 0.35f) * (s - 0.35f) + twist * y * s;
        // Only the variants take these branches: the fresh leaves' vertices stay bit for bit what they were.
        if (shape.roll_per_m > 0.0f) {
            const float a = shape.roll_per_m * y;  // y is the arc length from the midrib here
            z += (1.0f - std::cos(a)) / shape.roll_per_m;
            y = std::sin(a) / shape.roll_per_m;
        }
        if (shape.crinkle_m > 0.0f) {
            const glm::vec3 q(s * length_m, t * shape.half_width_m(s), 0.0f);
            z += shape.crinkle_m * fbm(q / shape.crinkle_wavelength_m, crinkle_seed, 2);
        }
        return glm::vec3(s * length_m, y, z);
    };
    addSheet(&b, shape.rows, shape.cols, pos, [&](float s) { return 0.0006f * (1.0f - 0.6f * s); });
    if (shape.stem) {
        // Stem: from behind the blade into its base, bending down a little.
        const float stem_m = 0.2f * length_m;
        const glm::vec3 base = pos(0.0f, 0.0f);
        std::vector<glm::vec3> line;
        std::vector<float> radii;
        for (int k = 0; k <= 6; ++k) {
            const float u = float(k) / 6.0f;
            line.push_back(base + glm::vec3(-stem_m * (1.0f - u) + 0.04f * length_m * u, 0.0f,
                                            -0.15f * stem_m * (1.0f - u) * (1.0f - u)));
            radii.push_back(0.0009f - 0.0003f * u);
        }
        addTube(&b, line, radii, 6);
    }
    return finish(&b, shape.color);
}

// The oak and birch outlines, shared by the fresh, dry and wet leaves (`seed` already salted per model).
LeafShape oakLeafShape(uint64_t seed) {
    LeafShape shape;
    shape.length_m = rnd(seed, 3, 0, 0.085f, 0.095f);
    const float width_m = 0.032f;
    const float lobes = 4.5f;
    shape.half_width_m = [=](float s) {
        // Obovate outline (widest beyond the middle) cut into rounded lobes.
        const float envelope = std::pow(std::max(0.0f, std::sin(kPi * s)), 0.8f) * (0.55f + 0.45f * s);
        const float lobe = 0.55f + 0.45f * std::pow(std::abs(std::cos(kPi * lobes * s)), 0.6f);
        return std::max(width_m * envelope * lobe, 0.0008f);
    };
    shape.max_half_width_m = width_m;
    shape.rows = 48;
    shape.color = {0.55f, 0.30f, 0.09f};
    return shape;
}

LeafShape birchLeafShape(uint64_t seed) {
    LeafShape shape;
    shape.length_m = rnd(seed, 3, 0, 0.070f, 0.080f);
    const float width_m = 0.016f;
    shape.half_width_m = [=](float s) {
        // Narrow, pointed (lanceolate), widest at about a third of the length, finely serrated.
        const float envelope = std::pow(std::max(0.0f, std::sin(kPi * std::pow(s, 0.75f))), 1.1f);
        const float serration = 1.0f - 0.06f * std::abs(std::sin(kPi * 14.0f * s));
        return std::max(width_m * envelope * serration, 0.0006f);
    };
    shape.max_half_width_m = width_m;
    shape.rows = 32;
    shape.color = {0.80f, 0.62f, 0.12f};
    return shape;
}

// Dry: strongly cupped and curled, the edges rolled up (1.9 rad, about 110 degrees, where the half width
// reaches max_half_width_m) and crinkled; browner and duller than the fresh leaf.
LeafShape dryLeafShape(LeafShape shape, const glm::vec3& color) {
    shape.cup = {0.35f, 0.55f};
    shape.bend = {0.45f, 0.65f};
    shape.twist = {-0.35f, 0.35f};
    shape.roll_per_m = 1.9f / shape.max_half_width_m;
    // More columns for the crinkles, whose wavelength spans about three of them across the blade.
    shape.cols = 14;
    shape.crinkle_wavelength_m = 6.0f * shape.max_half_width_m / float(shape.cols);
    shape.crinkle_m = 0.16f * shape.crinkle_wavelength_m;  // steep enough to see, not folding the 1 mm sheet
    shape.color = color;
    return shape;
}

// Wet: lying flat on the ground (a few mm of relief at most), darker and more saturated.
LeafShape wetLeafShape(LeafShape shape, const glm::vec3& color) {
    shape.cup = {0.0f, 0.04f};
    shape.bend = {0.0f, 0.02f};
    shape.twist = {-0.02f, 0.02f};
    shape.color = color;
    return shape;
}

}  // namespace

TriangleMesh makeRock(uint64_t seed) {
    return displacedEllipsoid(hashWords(seed, 101), {0.060f, 0.047f, 0.038f}, 0.32f, 1.7f, {0.42f, 0.42f, 0.40f});
}

TriangleMesh makeFlatStone(uint64_t seed) {
    return displacedEllipsoid(hashWords(seed, 102), {0.075f, 0.055f, 0.018f}, 0.16f, 1.4f, {0.47f, 0.41f, 0.34f});
}

TriangleMesh makePebble(uint64_t seed) {
    return displacedEllipsoid(hashWords(seed, 103), {0.020f, 0.015f, 0.011f}, 0.04f, 1.0f, {0.56f, 0.54f, 0.50f});
}

TriangleMesh makeOakLeaf(uint64_t seed) {
    seed = hashWords(seed, 104);
    return leaf(seed, oakLeafShape(seed));
}

TriangleMesh makeBirchLeaf(uint64_t seed) {
    seed = hashWords(seed, 105);
    return leaf(seed, birchLeafShape(seed));
}

TriangleMesh makeOakLeafDry(uint64_t seed) {
    seed = hashWords(seed, 112);
    return leaf(seed, dryLeafShape(oakLeafShape(seed), {0.42f, 0.29f, 0.16f}));
}

TriangleMesh makeBirchLeafDry(uint64_t seed) {
    seed = hashWords(seed, 113);
    return leaf(seed, dryLeafShape(birchLeafShape(seed), {0.60f, 0.48f, 0.24f}));
}

TriangleMesh makeOakLeafWet(uint64_t seed) {
    seed = hashWords(seed, 114);
    return leaf(seed, wetLeafShape(oakLeafShape(seed), {0.36f, 0.14f, 0.03f}));
}

TriangleMesh makeBirchLeafWet(uint64_t seed) {
    seed = hashWords(seed, 115);
    return leaf(seed, wetLeafShape(birchLeafShape(seed), {0.62f, 0.40f, 0.02f}));
}

TriangleMesh makePetal(uint64_t seed) {
    seed = hashWords(seed, 116);
    LeafShape shape;
    shape.length_m = rnd(seed, 3, 0, 0.032f, 0.038f);
    const float width_m = 0.6f * shape.length_m;
    const float widest = 0.62f;  // obovate: widest beyond the middle
    shape.half_width_m = [=](float s) {
        // A narrow claw widening to the broadest point, then a semicircle-like rounded tip.
        const float u = s < widest ? std::pow(s / widest, 0.7f)
                                   : std::sqrt(std::max(0.0f, 1.0f - std::pow((s - widest) / (1.0f - widest), 2.0f)));
        return std::max(0.5f * width_m * u, 0.0004f);
    };
    shape.max_half_width_m = 0.5f * width_m;
    shape.rows = 26;
    shape.cup = {0.30f, 0.45f};  // slightly cupped
    shape.bend = {0.10f, 0.18f};
    shape.twist = {-0.08f, 0.08f};
    shape.stem = false;
    shape.color = {0.96f, 0.76f, 0.82f};
    return leaf(seed, shape);
}

TriangleMesh makeTrashCan(uint64_t seed) {
    seed = hashWords(seed, 117);
    Builder b;
    // A 330 ml can standing on the origin: recessed lid, rim, neck, body, tapered foot and domed base.
    const float h = 0.118f, r = 0.033f;
    std::vector<glm::vec2> profile = {{0.0f, h - 0.004f}, {0.020f, h - 0.004f}, {0.0265f, h - 0.002f}, {0.0272f, h},
                                      {0.0285f, h - 0.002f}, {0.0300f, h - 0.008f}, {0.0322f, h - 0.014f}};
    const int body = 16;
    for (int i = 0; i <= body; ++i) profile.push_back({r, glm::mix(h - 0.018f, 0.014f, float(i) / float(body))});
    profile.insert(profile.end(), {{0.0310f, 0.008f}, {0.0270f, 0.002f}, {0.0250f, 0.0f}, {0.0225f, 0.002f},
                                   {0.0150f, 0.006f}, {0.0f, 0.008f}});
    addRevolution(&b, {0, 0, 0}, profile, 24);
    // Crushed as by a foot: the middle pressed flat (squeezed in x, which is the vertical once the can
    // lies on its side, and, the metal keeping its length around, spread in y) with crumpled folds there and a slight kink, and a dent in the lower part.
    // Each step moves vertices by a one-to-one, orientation-preserving map of space, so the surface stays
    // closed and outward.
    const float pinch = rnd(seed, 21, 0, 0.60f, 0.70f), pinch_z = rnd(seed, 21, 1, 0.50f, 0.58f) * h;
    const float dent_phi = rnd(seed, 21, 2, 0.0f, 2.0f * kPi), dent_z = rnd(seed, 21, 3, 0.18f, 0.26f) * h;
    const float kink = rnd(seed, 21, 4, -0.12f, 0.12f);
    const uint64_t folds_seed = hashWords(seed, 22);
    for (glm::vec3& p : b.mesh.positions) {
        const float rr = std::sqrt(p.x * p.x + p.y * p.y);
        const float phi = std::atan2(p.y, p.x);
        // A flat-topped band (super-Gaussian) with short transitions to the round ends.
        const float g = std::exp(-std::pow((p.z - pinch_z) / (0.17f * h), 4.0f));
        // Folds: the radius rippled around and along the band (at most 12 %, so still one-to-one).
        const float fold =
            1.0f + 0.12f * g * valueNoise(glm::vec3(3.0f * std::cos(phi), 3.0f * std::sin(phi), p.z / 0.010f), folds_seed);
        const float dphi = std::remainder(phi - dent_phi, 2.0f * kPi);
        const float dent = 0.40f * std::exp(-std::pow(dphi / 0.55f, 2.0f) - std::pow((p.z - dent_z) / (0.09f * h), 2.0f));
        const float scale = rr > 1e-6f ? fold * (1.0f - dent) : 1.0f;
        p.x *= scale * (1.0f - pinch * g);
        p.y *= scale * (1.0f + 0.75f * pinch * g);
        p.y += kink * std::max(0.0f, p.z - pinch_z);  // a shear: the top end leans over a little
    }
    // Lying on its side: the axis along X (a proper rotation about Y, so the winding stays outward).
    for (glm::vec3& p : b.mesh.positions) p = glm::vec3(p.z, p.y, -p.x);
    return finish(&b, {0.72f, 0.08f, 0.09f});
}

TriangleMesh makeTrashPaper(uint64_t seed) {
    seed = hashWords(seed, 118);
    Builder b;
    b.mesh = icosphere(3);  // 1280 triangles
    // Crumpled paper is flat facets meeting at sharp edges, with a few creases pressed in. The facets:
    // the ball is cut by random planes (the radius in each direction is the nearest plane's, a random
    // convex polyhedron); the creases: V-shaped grooves along other planes. Both only move vertices
    // radially, so the ball stays star-shaped about its centre and never self-intersects.
    auto direction = [&](uint64_t part, int k) {
        const float z = rnd(seed, part, uint64_t(2 * k), -1.0f, 1.0f);
        const float phi = rnd(seed, part, uint64_t(2 * k + 1), 0.0f, 2.0f * kPi);
        const float rxy = std::sqrt(std::max(0.0f, 1.0f - z * z));
        return glm::vec3(rxy * std::cos(phi), rxy * std::sin(phi), z);
    };
    const int facets = 16, creases = 6;
    for (size_t v = 0; v < b.mesh.positions.size(); ++v) {
        const glm::vec3 p = b.mesh.positions[v];
        float r = 1.0f;
        for (int k = 0; k < facets; ++k) {
            const float c = glm::dot(p, direction(22, k));
            if (c > 0.05f) r = std::min(r, rnd(seed, 23, uint64_t(k), 0.70f, 0.90f) / c);
        }
        for (int k = 0; k < creases; ++k) {
            const float d = std::abs(glm::dot(p, direction(24, k)) - rnd(seed, 25, uint64_t(k), -0.4f, 0.4f));
            r -= 0.13f * std::max(0.0f, 1.0f - d / 0.16f);
        }
        r += 0.04f * (unitFloat(hashWords(seed, 26, v)) - 0.5f);
        b.mesh.positions[v] = p * std::max(r, 0.5f) * glm::vec3(0.038f, 0.036f, 0.033f);
    }
    return finish(&b, {0.90f, 0.89f, 0.84f});
}

TriangleMesh makeTrashCup(uint64_t seed) {
    seed = hashWords(seed, 119);
    Builder b;
    // An open paper cup as one closed revolution with a 1 mm wall: from the middle of the inside floor out
    // and up the inner wall, over the rolled lip, down the outer wall, round the recessed foot to the
    // middle underneath.
    const float h = rnd(seed, 26, 0, 0.086f, 0.092f), r_top = 0.037f, r_foot = 0.0255f, wall = 0.001f;
    const float floor_z = 0.008f, lip = 0.0018f;
    auto outer = [=](float z) { return glm::mix(r_foot, r_top, z / h); };
    std::vector<glm::vec2> profile = {{0.0f, floor_z}, {0.012f, floor_z}};
    const int wall_rows = 10;
    for (int i = 0; i <= wall_rows; ++i) {
        const float z = glm::mix(floor_z, h - lip, float(i) / float(wall_rows));
        profile.push_back({outer(z) - wall, z});
    }
    const glm::vec2 bead(outer(h - lip) + lip - 0.5f * wall, h - lip);
    for (int i = 1; i < 9; ++i) {  // from the inner side over the top to underneath the bead
        const float a = kPi - 1.5f * kPi * float(i) / 9.0f;
        profile.push_back(bead + lip * glm::vec2(std::cos(a), std::sin(a)));
    }
    for (int i = 0; i <= wall_rows; ++i) {
        const float z = glm::mix(h - 2.0f * lip, 0.0f, float(i) / float(wall_rows));
        profile.push_back({outer(z), z});
    }
    profile.insert(profile.end(), {{r_foot - wall, 0.0f}, {r_foot - wall, floor_z - wall}, {0.012f, floor_z - wall},
                                   {0.0f, floor_z - wall}});
    addRevolution(&b, {0, 0, 0}, profile, 32);
    // Lying on its side.
    for (glm::vec3& p : b.mesh.positions) p = glm::vec3(p.z, p.y, -p.x);
    return finish(&b, {0.93f, 0.93f, 0.91f});
}

TriangleMesh makeTrashBottle(uint64_t seed) {
    seed = hashWords(seed, 120);
    Builder b;
    // A 0.5 l bottle: base, body with two grooves, shoulder, neck with its collar, and a ribbed cap.
    const float h = rnd(seed, 27, 0, 0.190f, 0.200f), r = 0.032f;
    std::vector<glm::vec2> profile = {{0.0f, h}, {0.011f, h}, {0.0145f, h - 0.001f}, {0.0150f, h - 0.004f},
                                      {0.0150f, h - 0.016f}, {0.0148f, h - 0.018f}, {0.0128f, h - 0.018f},
                                      {0.0128f, h - 0.021f}, {0.0165f, h - 0.022f}, {0.0165f, h - 0.024f},
                                      {0.0130f, h - 0.025f}, {0.0130f, h - 0.030f}};
    const float shoulder_top = h - 0.030f, shoulder_bottom = h - 0.080f;
    for (int i = 1; i <= 8; ++i) {
        const float u = float(i) / 8.0f;
        profile.push_back({glm::mix(0.0130f, r, 0.5f - 0.5f * std::cos(kPi * u)), glm::mix(shoulder_top, shoulder_bottom, u)});
    }
    const int body = 14;
    for (int i = 1; i <= body; ++i) {
        const float z = glm::mix(shoulder_bottom, 0.012f, float(i) / float(body));
        const float groove = 0.0025f * (std::exp(-std::pow((z - 0.45f * h) / 0.004f, 2.0f)) +
                                        std::exp(-std::pow((z - 0.30f * h) / 0.004f, 2.0f)));
        profile.push_back({r - groove, z});
    }
    profile.insert(profile.end(), {{0.030f, 0.004f}, {0.026f, 0.0f}, {0.016f, 0.0015f}, {0.0f, 0.004f}});
    addRevolution(&b, {0, 0, 0}, profile, 24);
    // Lying on its side, the cap towards +X.
    for (glm::vec3& p : b.mesh.positions) p = glm::vec3(p.z, p.y, -p.x);
    return finish(&b, {0.36f, 0.64f, 0.62f});
}

TriangleMesh makeTwig(uint64_t seed) {
    seed = hashWords(seed, 106);
    Builder b;
    auto branch = [&](glm::vec3 start, glm::vec3 dir, float length_m, float r0, float r1, int points, int sides, uint64_t part) {
        std::vector<glm::vec3> line;
        std::vector<float> radii;
        glm::vec3 p = start;
        dir = glm::normalize(dir);
        for (int k = 0; k < points; ++k) {
            line.push_back(p);
            radii.push_back(glm::mix(r0, r1, float(k) / float(points - 1)));
            // A gentle random walk of the heading: twigs are never straight.
            dir = glm::normalize(dir + glm::vec3(rnd(seed, part, uint64_t(3 * k), -0.12f, 0.12f),
                                                 rnd(seed, part, uint64_t(3 * k + 1), -0.12f, 0.12f),
                                                 rnd(seed, part, uint64_t(3 * k + 2), -0.05f, 0.05f)));
            p += dir * (length_m / float(points - 1));
        }
        addTube(&b, line, radii, sides);
        return line;
    };
    const std::vector<glm::vec3> main = branch({0, 0, 0}, {1, 0, 0}, 0.30f, 0.0065f, 0.0018f, 16, 10, 1);
    const glm::vec3 a = main[6], c = main[10];
    const glm::vec3 da = glm::normalize(main[7] - main[6]), dc = glm::normalize(main[11] - main[10]);
    const glm::vec3 side(0, 1, 0);
    branch(a, da + 0.85f * side + glm::vec3(0, 0, 0.1f), 0.10f, 0.0032f, 0.0011f, 8, 7, 2);
    branch(c, dc - 0.75f * side, 0.07f, 0.0024f, 0.0009f, 7, 6, 3);
    return finish(&b, {0.36f, 0.25f, 0.15f});
}

TriangleMesh makeGrassTuft(uint64_t seed) {
    seed = hashWords(seed, 107);
    Builder b;
    const int blades = 14;
    for (int k = 0; k < blades; ++k) {
        const float phi = 2.0f * kPi * (float(k) + rnd(seed, 4, uint64_t(k), 0.0f, 0.8f)) / float(blades);
        const float ring_m = rnd(seed, 5, uint64_t(k), 0.0f, 0.010f);
        const float height_m = rnd(seed, 6, uint64_t(k), 0.065f, 0.105f);
        const float lean = rnd(seed, 7, uint64_t(k), 0.15f, 0.55f);
        const float width_m = rnd(seed, 8, uint64_t(k), 0.0018f, 0.0028f);
        const glm::vec3 out(std::cos(phi), std::sin(phi), 0.0f), across(-std::sin(phi), std::cos(phi), 0.0f);
        const glm::vec3 base = ring_m * out;
        auto pos = [=](float s, float t) {
            const float w = width_m * std::min(1.0f, 0.35f + 6.0f * s) * std::pow(std::max(0.0f, 1.0f - s), 0.8f);
            // Rising then arching outward: the lean grows with the square of the height fraction.
            const glm::vec3 centre = base + glm::vec3(0, 0, height_m * s * (1.0f - 0.25f * lean * s)) +
                                     out * (lean * height_m * s * s);
            return centre + t * w * across;
        };
        addSheet(&b, 10, 2, pos, [](float s) { return 0.0003f * (1.0f - 0.7f * s); });
    }
    return finish(&b, {0.24f, 0.48f, 0.12f});
}

TriangleMesh makeGrassTuftDried(uint64_t seed) {
    seed = hashWords(seed, 121);
    Builder b;
    const int blades = 16;
    for (int k = 0; k < blades; ++k) {
        const float phi = 2.0f * kPi * (float(k) + rnd(seed, 4, uint64_t(k), 0.0f, 0.8f)) / float(blades);
        const float ring_m = rnd(seed, 5, uint64_t(k), 0.0f, 0.008f);
        const float length_m = rnd(seed, 6, uint64_t(k), 0.070f, 0.110f);
        const float width_m = rnd(seed, 8, uint64_t(k), 0.0011f, 0.0018f);
        // Angle from the vertical: a lean at the foot that droops further towards the tip, and for about
        // one blade in three a sharp fold part way up where the dry stalk gave way.
        const float lean = rnd(seed, 7, uint64_t(k), 0.25f, 0.75f);
        const float droop = rnd(seed, 9, uint64_t(k), 0.5f, 1.3f);
        const bool bent = rnd(seed, 10, uint64_t(k), 0.0f, 1.0f) < 0.35f;
        const float fold_s = rnd(seed, 11, uint64_t(k), 0.35f, 0.65f), fold = bent ? rnd(seed, 12, uint64_t(k), 0.9f, 1.4f) : 0.0f;
        const glm::vec3 out(std::cos(phi), std::sin(phi), 0.0f), across(-std::sin(phi), std::cos(phi), 0.0f);
        const glm::vec3 base = ring_m * out;
        auto angle = [=](float s) {
            const float f = glm::clamp((s - fold_s) / 0.06f + 0.5f, 0.0f, 1.0f);
            return std::min(lean + droop * s * s + fold * f * f * (3.0f - 2.0f * f), 0.55f * kPi);
        };
        auto pos = [=](float s, float t) {
            // The centre line integrates its heading (midpoint rule, a fixed number of steps so it is smooth in s).
            const int steps = 24;
            glm::vec2 rz(0.0f);
            for (int i = 0; i < steps; ++i) {
                const float a = angle(s * (float(i) + 0.5f) / float(steps));
                rz += (s * length_m / float(steps)) * glm::vec2(std::sin(a), std::cos(a));
            }
            const float w = width_m * std::min(1.0f, 0.35f + 6.0f * s) * std::pow(std::max(0.0f, 1.0f - s), 0.8f);
            return base + rz.x * out + glm::vec3(0, 0, rz.y) + t * w * across;
        };
        addSheet(&b, 14, 2, pos, [](float s) { return 0.00025f * (1.0f - 0.7f * s); });
    }
    return finish(&b, {0.71f, 0.61f, 0.36f});
}

TriangleMesh makeMushroom(uint64_t seed) {
    seed = hashWords(seed, 108);
    Builder b;
    const float stem_h = rnd(seed, 9, 0, 0.065f, 0.075f);
    const float cap_r = rnd(seed, 9, 1, 0.040f, 0.048f), cap_h = rnd(seed, 9, 2, 0.024f, 0.030f);
    // Stem: slightly bulbous foot, narrowing to the cap.
    std::vector<glm::vec2> stem = {{0.0f, stem_h}};
    for (int i = 0; i <= 10; ++i) {
        const float u = float(i) / 10.0f;  // 0 at the top
        const float r = 0.0085f + 0.0025f * u + 0.0030f * std::pow(u, 6.0f);
        stem.push_back({r, stem_h * (1.0f - u)});
    }
    stem.push_back({0.0f, 0.0f});
    addRevolution(&b, {0, 0, 0}, stem, 16);
    // Cap: dome from the top pole over the rim, then the gill side back to the stem.
    std::vector<glm::vec2> cap;
    const float z0 = stem_h - 0.006f;
    const int dome = 12;
    for (int i = 0; i <= dome; ++i) {
        const float a = (0.5f * kPi + 0.35f) * float(i) / float(dome);
        cap.push_back({cap_r * std::sin(a), z0 + 0.004f + cap_h * std::cos(a)});
    }
    const glm::vec2 rim = cap.back();
    for (int i = 1; i <= 5; ++i) {
        const float u = float(i) / 5.0f;
        cap.push_back({glm::mix(rim.x, 0.008f, u), glm::mix(rim.y, z0, std::sqrt(u))});
    }
    cap.push_back({0.0f, z0});
    addRevolution(&b, {0, 0, 0}, cap, 28);
    return finish(&b, {0.58f, 0.30f, 0.17f});
}

TriangleMesh makePineNeedles(uint64_t seed) {
    seed = hashWords(seed, 109);
    Builder b;
    // Sheath holding the bundle together.
    addTube(&b, {{0, 0, 0}, {0, 0, 0.004f}, {0, 0, 0.008f}}, {0.0022f, 0.0020f, 0.0016f}, 8);
    const int needles = 18;
    for (int k = 0; k < needles; ++k) {
        const float phi = 2.0f * kPi * (float(k) + rnd(seed, 10, uint64_t(k), 0.0f, 0.6f)) / float(needles);
        const float tilt = rnd(seed, 11, uint64_t(k), 0.12f, 0.45f);
        const float length_m = rnd(seed, 12, uint64_t(k), 0.060f, 0.075f);
        const glm::vec3 out(std::cos(phi), std::sin(phi), 0.0f);
        std::vector<glm::vec3> line;
        std::vector<float> radii;
        const int points = 6;
        for (int i = 0; i < points; ++i) {
            const float s = float(i) / float(points - 1);
            const float a = tilt * (1.0f + 0.6f * s);  // needles splay more towards their tips
            line.push_back(glm::vec3(0, 0, 0.004f) + 0.0012f * out +
                           length_m * s * (std::cos(a) * glm::vec3(0, 0, 1) + std::sin(a) * out));
            radii.push_back(glm::mix(0.00065f, 0.00025f, s));
        }
        addTube(&b, line, radii, 4);
    }
    return finish(&b, {0.10f, 0.24f, 0.10f});
}

TriangleMesh makeHayWisp(uint64_t seed) {
    seed = hashWords(seed, 111);
    Builder b;
    // Loose straws lying across each other: long, thin, nearly flat, each crossing the middle at its own
    // heading and height, bowed a little (hay as it falls from a fork, not a bundle tied at one end).
    const int straws = 14;
    for (int k = 0; k < straws; ++k) {
        const float heading = kPi * (float(k) + rnd(seed, 13, uint64_t(k), 0.0f, 0.9f)) / float(straws);
        const float length_m = rnd(seed, 14, uint64_t(k), 0.13f, 0.19f);
        const float rise = rnd(seed, 15, uint64_t(k), -0.18f, 0.18f);
        const float bow = rnd(seed, 16, uint64_t(k), -0.012f, 0.012f);
        const glm::vec3 offset(rnd(seed, 17, uint64_t(k), -0.012f, 0.012f), rnd(seed, 18, uint64_t(k), -0.012f, 0.012f),
                               rnd(seed, 19, uint64_t(k), 0.0f, 0.014f));
        const glm::vec3 along(std::cos(heading), std::sin(heading), rise), side(-std::sin(heading), std::cos(heading), 0);
        std::vector<glm::vec3> line;
        std::vector<float> radii;
        const int points = 6;
        for (int i = 0; i < points; ++i) {
            const float s = float(i) / float(points - 1) - 0.5f;
            line.push_back(offset + length_m * s * along + bow * (1.0f - 4.0f * s * s) * side);
            radii.push_back(0.0011f);
        }
        addTube(&b, line, radii, 4);
    }
    return finish(&b, {0.62f, 0.52f, 0.24f});
}

TriangleMesh makeScannedRock(uint32_t target_triangles, uint64_t seed) {
    seed = hashWords(seed, 110);
    const uint32_t target = std::clamp<uint32_t>(target_triangles, 20u, 50'000'000u);
    const uint32_t k = std::max<uint32_t>(1, uint32_t(std::lround(std::sqrt(double(target) / 20.0))));
    // The icosahedron of icosphere(0); each face becomes a triangular grid of k x k cells. Vertices on
    // the 30 edges are made once (by the lower-numbered corner's direction) so the faces share them.
    const TriangleMesh ico = icosphere(0);
    Builder b;
    b.mesh.positions = ico.positions;
    b.mesh.positions.reserve(10 * size_t(k) * k + 2);
    b.mesh.indices.reserve(60 * size_t(k) * k);
    // (lo, hi) -> its k - 1 inner vertices from lo to hi.
    std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> edges;
    // The vertex s/k of the way from corner u to corner v, s in [1, k).
    auto edgeVertex = [&](uint32_t u, uint32_t v, uint32_t s) {
        const uint32_t lo = std::min(u, v), hi = std::max(u, v);
        auto it = edges.find({lo, hi});
        if (it == edges.end()) {
            std::vector<uint32_t> ids(k - 1);
            for (uint32_t i = 1; i < k; ++i)
                ids[i - 1] = b.vertex(glm::mix(ico.positions[lo], ico.positions[hi], float(i) / float(k)));
            it = edges.emplace(std::make_pair(lo, hi), std::move(ids)).first;
        }
        return it->second[lo == u ? s - 1 : k - s - 1];
    };
    std::vector<uint32_t> grid;  // (i, j), i + j <= k: corner A + i/k (B - A) + j/k (C - A)
    for (size_t f = 0; f < ico.indices.size(); f += 3) {
        const uint32_t A = ico.indices[f], B = ico.indices[f + 1], C = ico.indices[f + 2];
        const glm::vec3 pa = ico.positions[A], pb = ico.positions[B], pc = ico.positions[C];
        grid.assign(size_t(k + 1) * (k + 1), 0);
        auto at = [&](uint32_t i, uint32_t j) -> uint32_t& { return grid[size_t(i) * (k + 1) + j]; };
        for (uint32_t i = 0; i <= k; ++i)
            for (uint32_t j = 0; i + j <= k; ++j) {
                uint32_t id;
                if (i == 0 && j == 0) {
                    id = A;
                } else if (i == k) {
                    id = B;
                } else if (j == k) {
                    id = C;
                } else if (j == 0) {
                    id = edgeVertex(A, B, i);
                } else if (i == 0) {
                    id = edgeVertex(A, C, j);
                } else if (i + j == k) {
                    id = edgeVertex(B, C, j);
                } else {
                    id = b.vertex(pa + (pb - pa) * (float(i) / float(k)) + (pc - pa) * (float(j) / float(k)));
                }
                at(i, j) = id;
            }
        for (uint32_t i = 0; i < k; ++i)
            for (uint32_t j = 0; i + j < k; ++j) {
                b.tri(at(i, j), at(i + 1, j), at(i, j + 1));  // same winding as (A, B, C): outward
                if (i + j + 1 < k) b.tri(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            }
    }
    // Radial displacement of the unit sphere keeps the surface closed and star-shaped. Scales: the
    // boulder's lumpy outline, knobs of a few cm, mm bumps, and scan noise a fraction of an edge long.
    const glm::vec3 axes_m(0.50f, 0.40f, 0.30f);
    const glm::vec3 offset(rnd(seed, 1, 0, 0, 100), rnd(seed, 1, 1, 0, 100), rnd(seed, 1, 2, 0, 100));
    const float edge = 1.2f / float(k);  // about the unit sphere's edge length
    for (size_t v = 0; v < b.mesh.positions.size(); ++v) {
        const glm::vec3 dir = glm::normalize(b.mesh.positions[v]);
        const glm::vec3 q = dir + offset;
        const float d = 1.0f + 0.26f * fbm(q * 1.5f, hashWords(seed, 2), 4) +
                        0.035f * fbm(q * 9.0f, hashWords(seed, 3), 3) +
                        0.006f * fbm(q * 55.0f, hashWords(seed, 4), 2) +
                        0.15f * edge * (unitFloat(hashWords(seed, 5, v)) - 0.5f);
        b.mesh.positions[v] = dir * d * axes_m;
    }
    return finish(&b, {0.45f, 0.43f, 0.40f});
}

const std::vector<std::string>& starterAssetNames() {
    static const std::vector<std::string> names = {"rock",      "flat_stone", "pebble",   "leaf_oak",    "leaf_birch",
                                                   "twig",      "grass_tuft", "mushroom", "pine_needles",
                                                   "hay_wisp",
                                                   // Appended (the order above is the committed assets' order).
                                                   "leaf_oak_dry", "leaf_birch_dry", "leaf_oak_wet", "leaf_birch_wet",
                                                   "petal", "trash_can", "trash_paper", "trash_cup", "trash_bottle",
                                                   "grass_tuft_dried"};
    return names;
}

bool makeStarterAsset(const std::string& name, uint64_t seed, TriangleMesh* out) {
    using Maker = TriangleMesh (*)(uint64_t);
    static const std::pair<const char*, Maker> makers[] = {
        {"rock", makeRock},         {"flat_stone", makeFlatStone}, {"pebble", makePebble},
        {"leaf_oak", makeOakLeaf},  {"leaf_birch", makeBirchLeaf}, {"twig", makeTwig},
        {"grass_tuft", makeGrassTuft}, {"mushroom", makeMushroom}, {"pine_needles", makePineNeedles},
        {"hay_wisp", makeHayWisp},
        {"leaf_oak_dry", makeOakLeafDry}, {"leaf_birch_dry", makeBirchLeafDry},
        {"leaf_oak_wet", makeOakLeafWet}, {"leaf_birch_wet", makeBirchLeafWet}, {"petal", makePetal},
        {"trash_can", makeTrashCan},      {"trash_paper", makeTrashPaper},    {"trash_cup", makeTrashCup},
        {"trash_bottle", makeTrashBottle}, {"grass_tuft_dried", makeGrassTuftDried}};
    for (const auto& [n, make] : makers)
        if (name == n) {
            *out = make(seed);
            return true;
        }
    return false;
}

bool writeStarterAssets(const std::string& dir, std::string* error) {
    return writeModelFolder(
        dir, starterAssetNames(), [](const std::string& name, TriangleMesh* mesh) { makeStarterAsset(name, kStarterAssetSeed, mesh); }, error);
}

}  // namespace ug
