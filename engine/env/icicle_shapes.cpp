// The icicle shape library (§5.2): each shape is a chain of spheres along -Z from the top down, radius
// and spacing decreasing, each centre nudged horizontally, blended as a Blob-Tree (sum of Wyvill kernels,
// iso 1/2) and cut by the plane z = 0 where it meets the object. Polygonized once by root finding: on
// horizontal slices the blended surface is star-shaped about the chain's axis, so each ring vertex is the
// outermost iso crossing along a ray from the axis; rings are denser towards the tip, where the profile
// turns fastest. Closed: a flat top disc (fan), the rings, and a tip vertex found along the axis.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

#include "core/hash.h"
#include "env/icicles.h"

namespace ug {
namespace {

constexpr float kLengths_m[kIcicleShapeLengths] = {0.06f, 0.12f, 0.22f, 0.35f};
constexpr uint32_t kSegments = 12;  // vertices per ring
constexpr uint32_t kRings = 18;     // rings from the top disc (ring 0) towards the tip
constexpr float kIso = 0.5f;
// (1 - t)^3 = 1/2 at t = 1 - 2^(-1/3): an isolated sphere of support R shows radius R * sqrt(t).
constexpr float kVisibleFraction = 0.45432646f;
constexpr float kTwoPi = 6.28318530718f;

struct Sphere {
    glm::vec3 centre;
    float support;  // R: the kernel reaches zero there
};

// The blended field of the chain at p (z <= 0).
float field(const std::vector<Sphere>& chain, const glm::vec3& p) {
    float f = 0.0f;
    for (const Sphere& s : chain) {
        const glm::vec3 d = p - s.centre;
        if (std::abs(d.z) >= s.support) continue;
        const float t = glm::dot(d, d) / (s.support * s.support);
        if (t < 1.0f) f += (1.0f - t) * (1.0f - t) * (1.0f - t);
    }
    return f;
}

// The paper's sphere list for one shape: from the top (the origin) down, each sphere's visible radius
// follows a slightly concave cone r(z) = r_tip + (r_top - r_tip) (1 - |z| / L)^1.2 (a carrot: thick at the
// root, a fine point), and the next centre lies 0.7 r below (spacing shrinks with the radius, so the
// blend stays smooth with faint ripples, like real icicles). Each centre drifts from the previous one by
// up to 30% of its radius (a damped random walk: the icicle bends gently rather than jitters).
std::vector<Sphere> sphereChain(float length, float top_radius, uint32_t seed) {
    constexpr size_t kMaxSpheres = 160;
    const float tip_radius = 0.1f * top_radius;
    const float chain_length = 0.97f * length;  // the tip's cap adds the rest; exact length set later
    std::vector<Sphere> chain;
    glm::vec2 offset(0.0f);
    float depth = 0.0f;
    for (uint32_t k = 0; depth < chain_length && k < kMaxSpheres; ++k) {
        const float u = depth / chain_length;
        const float radius = tip_radius + (top_radius - tip_radius) * std::pow(1.0f - u, 1.2f);
        if (k > 0) {
            const uint64_t h = hashWords(seed, uint64_t(k), 0x1c1c1e);
            const glm::vec2 jitter(unitFloat(h) * 2.0f - 1.0f, unitFloat(mix64(h)) * 2.0f - 1.0f);
            offset = 0.6f * offset + 0.3f * radius * jitter;
        }
        chain.push_back({glm::vec3(offset, -depth), radius / kVisibleFraction});
        depth += 0.7f * radius;
    }
    return chain;
}

// The chain's axis at height z: centres interpolated by height (they descend strictly).
glm::vec3 axisAt(const std::vector<Sphere>& chain, float z) {
    if (z >= chain.front().centre.z) return glm::vec3(glm::vec2(chain.front().centre), z);
    for (size_t k = 1; k < chain.size(); ++k) {
        const glm::vec3 a = chain[k - 1].centre, b = chain[k].centre;
        if (z >= b.z) {
            const float u = (a.z - z) / (a.z - b.z);
            return glm::vec3(glm::mix(glm::vec2(a), glm::vec2(b), u), z);
        }
    }
    return glm::vec3(glm::vec2(chain.back().centre), z);
}

// Bisection between an inside point (field >= iso) and an outside one.
glm::vec3 bisect(const std::vector<Sphere>& chain, glm::vec3 inside, glm::vec3 outside) {
    for (int it = 0; it < 30; ++it) {
        const glm::vec3 mid = 0.5f * (inside + outside);
        (field(chain, mid) >= kIso ? inside : outside) = mid;
    }
    return 0.5f * (inside + outside);
}

// The lowest point of the surface straight below the last centre (the field falls monotonically there,
// moving away from every centre).
float tipHeight(const std::vector<Sphere>& chain) {
    const Sphere& last = chain.back();
    const float step = last.support / 32.0f;
    glm::vec3 inside = last.centre;
    for (int it = 0; it < 64; ++it) {
        const glm::vec3 below = inside - glm::vec3(0, 0, step);
        if (field(chain, below) < kIso) return bisect(chain, inside, below).z;
        inside = below;
    }
    return inside.z;
}

// The outermost iso crossing along a horizontal ray from the axis (marching inwards from outside).
glm::vec3 ringVertex(const std::vector<Sphere>& chain, const glm::vec3& axis, const glm::vec3& dir, float reach) {
    constexpr int kSteps = 48;
    const float step = reach / float(kSteps);
    for (int k = kSteps - 1; k >= 0; --k) {
        const glm::vec3 p = axis + (float(k) * step) * dir;
        if (field(chain, p) >= kIso) return bisect(chain, p, p + step * dir);
    }
    return axis + 1e-5f * dir;  // the axis itself is outside: a vanishing ring, still closed
}

TriangleMesh polygonize(const std::vector<Sphere>& chain, float length, float top_radius) {
    const float z_tip = tipHeight(chain);
    const float reach = 4.0f * top_radius;
    TriangleMesh m;
    m.positions.push_back(glm::vec3(0.0f));  // top centre
    for (uint32_t j = 0; j < kRings; ++j) {
        const float s = float(j) / float(kRings);
        const float z = j == 0 ? 0.0f : z_tip * (1.0f - std::pow(1.0f - s, 1.5f));
        const glm::vec3 axis = axisAt(chain, z);
        for (uint32_t k = 0; k < kSegments; ++k) {
            const float phi = kTwoPi * float(k) / float(kSegments);
            glm::vec3 p = ringVertex(chain, axis, glm::vec3(std::cos(phi), std::sin(phi), 0.0f), reach);
            p.z = z;  // exact slice height (bisection moved only horizontally, up to rounding)
            m.positions.push_back(p);
        }
    }
    m.positions.push_back(glm::vec3(glm::vec2(chain.back().centre), z_tip));
    // The shape's length is exactly `length`: the vertical stretch this needs is a few percent.
    const float stretch = length / -z_tip;
    for (glm::vec3& p : m.positions) p.z *= stretch;
    m.positions.back().z = -length;

    const auto ring = [](uint32_t j, uint32_t k) { return 1 + j * kSegments + k % kSegments; };
    const uint32_t tip = 1 + kRings * kSegments;
    for (uint32_t k = 0; k < kSegments; ++k) {
        m.indices.insert(m.indices.end(), {0, ring(0, k), ring(0, k + 1)});  // top disc faces +Z
        for (uint32_t j = 0; j + 1 < kRings; ++j) {
            const uint32_t a = ring(j, k), b = ring(j, k + 1), c = ring(j + 1, k + 1), d = ring(j + 1, k);
            m.indices.insert(m.indices.end(), {a, d, c, a, c, b});
        }
        m.indices.insert(m.indices.end(), {tip, ring(kRings - 1, k + 1), ring(kRings - 1, k)});
    }
    computeNormals(&m);
    m.base_color = glm::vec3(0.82f, 0.90f, 0.96f);  // clear ice, slightly blue
    return m;
}

float meanTopRadius(const TriangleMesh& m) {
    float sum = 0.0f;
    for (uint32_t k = 0; k < kSegments; ++k) sum += glm::length(glm::vec2(m.positions[1 + k]));
    return sum / float(kSegments);
}

std::vector<IcicleShape> buildShapes() {
    std::vector<IcicleShape> shapes;
    for (size_t c = 0; c < kIcicleShapeLengths; ++c)
        for (uint32_t seed = 0; seed < kIcicleShapeSeeds; ++seed) shapes.push_back(makeIcicleShape(c, seed));
    return shapes;
}

}  // namespace

IcicleShape makeIcicleShape(size_t length_class, uint32_t seed) {
    assert(length_class < kIcicleShapeLengths && seed < kIcicleShapeSeeds);
    const float length = kLengths_m[length_class];
    // Longer icicles are thicker; the blend of overlapping spheres widens the chain by about 35%, so a
    // 0.35 m icicle is about 4.5 cm across at the top, a 6 cm one about 1.3 cm.
    const float chain_top_radius = 0.0025f + 0.04f * length;
    IcicleShape shape;
    shape.mesh = polygonize(sphereChain(length, chain_top_radius, seed), length, chain_top_radius);
    shape.length_m = length;
    shape.top_radius_m = meanTopRadius(shape.mesh);
    shape.seed = seed;
    return shape;
}

const std::vector<IcicleShape>& icicleShapes() {
    static const std::vector<IcicleShape> shapes = buildShapes();
    return shapes;
}

}  // namespace ug
