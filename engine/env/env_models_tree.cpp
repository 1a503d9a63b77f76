// A bare deciduous tree: trunk and three levels of tapered branches in a deterministic recursive pattern.
#include <algorithm>
#include <cmath>

#include "core/hash.h"
#include "env/env_model_makers.h"

namespace ug::envmodels {
using envparts::addLathe;
using envparts::addTube;
using envparts::MeshBuilder;

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr int kMaxLevel = 3;
constexpr float kTreeHeight = 5.0f;

float rnd(uint64_t seed, uint64_t a, uint64_t b, float lo, float hi) {
    return lo + (hi - lo) * unitFloat(hashWords(seed, a, b));
}

// Any unit vector perpendicular to d.
glm::vec3 perpendicular(const glm::vec3& d) {
    return glm::normalize(std::abs(d.z) < 0.9f ? glm::cross(d, glm::vec3(0, 0, 1))
                                               : glm::cross(d, glm::vec3(1, 0, 0)));
}

struct Branch {
    glm::vec3 start;
    glm::vec3 dir;
    float length = 0.0f;
    float radius = 0.0f;  // at the start; the tip is 45 % of it
    int level = 0;
    uint64_t id = 0;  // a path-unique key for the random choices
};

// Adds the branch and, below kMaxLevel, its children. The centre line wanders a little and bends
// upwards (bare crowns reach for the light); children leave between 35 % and 95 % of the way along,
// spread around the parent, each thinner than the parent where it leaves.
void grow(MeshBuilder* b, uint64_t seed, const Branch& br) {
    static const int kSides[kMaxLevel + 1] = {16, 12, 8, 6};
    static const int kPoints[kMaxLevel + 1] = {8, 6, 5, 4};
    const int points = kPoints[br.level];
    std::vector<glm::vec3> line;
    std::vector<float> radii;
    glm::vec3 p = br.start, dir = glm::normalize(br.dir);
    const float wander = br.level == 0 ? 0.04f : 0.18f, lift = br.level == 0 ? 0.0f : 0.07f;
    for (int k = 0; k < points; ++k) {
        line.push_back(p);
        radii.push_back(br.radius * (1.0f - 0.55f * float(k) / float(points - 1)));
        dir = glm::normalize(
            dir + glm::vec3(rnd(seed, br.id, uint64_t(3 * k), -wander, wander),
                            rnd(seed, br.id, uint64_t(3 * k + 1), -wander, wander),
                            lift + rnd(seed, br.id, uint64_t(3 * k + 2), -0.5f * wander, 0.5f * wander)));
        p += dir * (br.length / float(points - 1));
    }
    addTube(b, line, radii, kSides[br.level]);
    if (br.level == kMaxLevel) return;
    const int children = br.level == 0 ? 4 : 3;
    const float phase = rnd(seed, br.id, 100, 0.0f, 2.0f * kPi);
    for (int c = 0; c < children; ++c) {
        const uint64_t id = hashWords(br.id, uint64_t(c) + 1);
        // The first child continues the parent (the leader); the others leave at 35 to 60 degrees.
        const float s = c == 0 ? 1.0f : rnd(seed, id, 1, br.level == 0 ? 0.6f : 0.35f, 0.92f);
        const float at = s * float(points - 1);
        const size_t k = std::min(size_t(at), size_t(points - 2));
        const float f = at - float(k);
        const glm::vec3 start = glm::mix(line[k], line[k + 1], f);
        const float parent_r = glm::mix(radii[k], radii[k + 1], f);
        const glm::vec3 axis = glm::normalize(line[k + 1] - line[k]);
        const glm::vec3 u = perpendicular(axis), v = glm::cross(axis, u);
        const float azimuth =
            phase + 2.0f * kPi * (float(c) + rnd(seed, id, 2, -0.2f, 0.2f)) / float(children);
        const float spread = c == 0 ? rnd(seed, id, 3, 0.1f, 0.3f) : rnd(seed, id, 3, 0.6f, 1.05f);
        const glm::vec3 out = std::cos(azimuth) * u + std::sin(azimuth) * v;
        Branch child;
        child.start = start - 0.3f * parent_r * axis;  // start inside the parent: no gap at the joint
        child.dir = std::cos(spread) * axis + std::sin(spread) * out;
        child.length =
            br.length * (br.level == 0 ? rnd(seed, id, 4, 0.5f, 0.65f) : rnd(seed, id, 4, 0.55f, 0.7f));
        child.radius = parent_r * (c == 0 ? 0.8f : 0.62f);
        child.level = br.level + 1;
        child.id = id;
        grow(b, seed, child);
    }
}

}  // namespace

TriangleMesh makeTree(uint64_t seed) {
    seed = hashWords(seed, 201);
    MeshBuilder b;
    // Root flare, the trunk standing in it, and the crown.
    addLathe(&b, {0, 0, 0}, {{0.0f, 0.0f}, {0.42f, 0.0f}, {0.34f, 0.08f}, {0.27f, 0.3f}, {0.0f, 0.3f}}, 16);
    Branch trunk;
    trunk.start = {0, 0, 0.05f};
    trunk.dir = {0, 0, 1};
    trunk.length = 3.0f;
    trunk.radius = 0.25f;
    trunk.id = 1;
    grow(&b, seed, trunk);
    TriangleMesh m = b.finish({0.30f, 0.25f, 0.20f});
    // Scale to the nominal height about the ground point, so every seed gives a 5 m tree.
    const float top = meshBounds(m).max.z;
    scaleMesh(&m, kTreeHeight / top);
    return m;
}

}  // namespace ug::envmodels
