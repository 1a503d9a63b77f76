// A segment-triangle crossing test for the strand tests, written apart from the engine's BVH so that a
// check of "no strand crosses this solid" does not reuse the code under test.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace ug::test {

// Whether segment pq crosses triangle abc (Möller-Trumbore in double) after `from` of its length (a seed
// on a face starts on it: rounding may put that face a hair ahead).
inline bool segmentHitsTriangle(glm::vec3 p, glm::vec3 q, glm::vec3 a, glm::vec3 b, glm::vec3 c, double from = 0.0) {
    const glm::dvec3 d = glm::dvec3(q) - glm::dvec3(p);
    const glm::dvec3 e1 = glm::dvec3(b) - glm::dvec3(a), e2 = glm::dvec3(c) - glm::dvec3(a);
    const glm::dvec3 h = glm::cross(d, e2);
    const double det = glm::dot(e1, h);
    if (std::abs(det) < 1e-15) return false;
    const glm::dvec3 s = glm::dvec3(p) - glm::dvec3(a);
    const double u = glm::dot(s, h) / det;
    if (u < 0.0 || u > 1.0) return false;
    const glm::dvec3 qv = glm::cross(s, e1);
    const double v = glm::dot(d, qv) / det;
    if (v < 0.0 || u + v > 1.0) return false;
    const double t = glm::dot(e2, qv) / det;
    return t > from && t < 1.0;
}

}  // namespace ug::test
