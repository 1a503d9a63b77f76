// Axis-aligned bounds in world space (metres), used for primitive supports, tiles and whole fields.
// Infinite extents are allowed (a half-space, a terrain layer in XY): lo/hi may be -inf/+inf.
// The empty box is lo = +inf, hi = -inf on every axis (the default); every predicate below treats it
// consistently (overlaps nothing, contains nothing, is the identity of unite()).
#pragma once

#include <limits>

#include <glm/glm.hpp>

namespace ug {

struct Bounds {
    glm::vec3 lo{std::numeric_limits<float>::infinity()};
    glm::vec3 hi{-std::numeric_limits<float>::infinity()};

    bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }

    static Bounds everything() {
        const float inf = std::numeric_limits<float>::infinity();
        return Bounds{glm::vec3(-inf), glm::vec3(inf)};
    }
    static Bounds fromCenterHalf(glm::vec3 center, glm::vec3 half) { return Bounds{center - half, center + half}; }
};

// Closed-box overlap: touching boxes overlap. Empty boxes overlap nothing.
inline bool overlaps(const Bounds& a, const Bounds& b) {
    return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
           b.lo.z <= a.hi.z;
}

inline bool contains(const Bounds& b, glm::vec3 p) {
    return b.lo.x <= p.x && p.x <= b.hi.x && b.lo.y <= p.y && p.y <= b.hi.y && b.lo.z <= p.z && p.z <= b.hi.z;
}

inline Bounds unite(const Bounds& a, const Bounds& b) { return Bounds{glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)}; }

// The intersection; may be empty (then lo > hi on some axis, and empty() is true).
inline Bounds intersect(const Bounds& a, const Bounds& b) {
    return Bounds{glm::max(a.lo, b.lo), glm::min(a.hi, b.hi)};
}

}  // namespace ug
