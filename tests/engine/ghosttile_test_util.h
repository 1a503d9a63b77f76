// Hand-made detail models for Ghost Tile tests: sphere sets only, no mesh files needed.
#pragma once

#include <vector>

#include "core/hash.h"
#include "ghosttile/ghost_tile.h"

namespace ug::test {

// A model whose collision proxy is `spheres`, with anchors at the sphere centres.
inline DetailModel sphereModel(const char* name, std::vector<Sphere> spheres) {
    DetailModel m;
    m.name = name;
    m.spheres = std::move(spheres);
    glm::vec3 c(0.0f);
    for (const Sphere& s : m.spheres) c += s.center;
    c /= float(m.spheres.size());
    float r = 0.0f;
    for (const Sphere& s : m.spheres) {
        r = std::max(r, glm::length(s.center - c) + s.radius);
        m.anchors.push_back(s.center);
    }
    m.bounds = {c, r};
    return m;
}

// A rod of `count` spheres along X (a crude twig), length ~ 2 * half_length.
inline DetailModel rodModel(int count, float half_length, float radius) {
    std::vector<Sphere> s;
    for (int k = 0; k < count; ++k) {
        float t = count == 1 ? 0.0f : -half_length + 2.0f * half_length * float(k) / float(count - 1);
        s.push_back({glm::vec3(t, 0.0f, 0.0f), radius});
    }
    return sphereModel("rod", s);
}

// An irregular blob of `count` spheres (a crude rock), deterministic in seed.
inline DetailModel blobModel(int count, float size, uint64_t seed) {
    std::vector<Sphere> s;
    for (int k = 0; k < count; ++k) {
        glm::vec3 p(unitFloat(hashWords(seed, k, 1)) - 0.5f, unitFloat(hashWords(seed, k, 2)) - 0.5f,
                    unitFloat(hashWords(seed, k, 3)) - 0.5f);
        s.push_back({p * size, size * (0.15f + 0.2f * unitFloat(hashWords(seed, k, 4)))});
    }
    return sphereModel("blob", s);
}

}  // namespace ug::test
