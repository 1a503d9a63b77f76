#include "field/ray_cast.h"

#include <algorithm>
#include <cmath>

namespace ug {

bool clipRayToBounds(const Ray& ray, const Bounds& box, float max_t_m, float* t0, float* t1) {
    if (box.empty()) return false;
    float lo = 0.0f, hi = max_t_m;
    for (int a = 0; a < 3; ++a) {
        const float o = ray.origin_m[a], d = ray.direction[a];
        if (std::abs(d) < 1e-12f) {
            if (o < box.lo[a] || o > box.hi[a]) return false;
            continue;
        }
        // Infinite box sides give infinite t, which min/max handle.
        float ta = (box.lo[a] - o) / d, tb = (box.hi[a] - o) / d;
        if (ta > tb) std::swap(ta, tb);
        lo = std::max(lo, ta);
        hi = std::min(hi, tb);
        if (lo > hi) return false;
    }
    *t0 = lo;
    *t1 = hi;
    return true;
}

bool rayHeightField(const HeightField& terrain, const Ray& ray, float max_t_m, float* t_m) {
    if (terrain.empty()) return false;
    auto above = [&](float t) {
        const glm::vec3 p = ray.at(t);
        return p.z - terrain.sample(p.x, p.y);
    };
    // Skip the part of the ray that is above the highest sample or below the lowest: a camera 100 m up
    // does not march 100 m of air in half-cell steps. The slab is a millimetre thicker on either side:
    // over flat ground it has no thickness, and the ray's ends in it, rounded, could both stay a hair above
    // the ground, so that a ray aimed straight at it missed (the street samples' flat terrain did).
    constexpr float kSlabPadM = 1e-3f;
    const Bounds slab{glm::vec3(-INFINITY, -INFINITY, terrain.minHeight() - kSlabPadM),
                      glm::vec3(INFINITY, INFINITY, terrain.maxHeight() + kSlabPadM)};
    float t0 = 0.0f, t1 = 0.0f;
    if (!clipRayToBounds(ray, slab, max_t_m, &t0, &t1)) return false;
    if (above(0.0f) < 0.0f) return false;  // starts under the ground
    // Half a cell per step: a bilinear patch can only be crossed twice within a cell, so this finds the
    // first crossing except where the ray grazes a ridge by less than a step (then it finds the next).
    const float step = 0.5f * terrain.cellSize();
    float prev_t = t0, prev_h = above(t0);
    if (prev_h <= 0.0f) {
        *t_m = t0;
        return true;
    }
    for (float t = t0 + step;; t += step) {
        const float tt = std::min(t, t1);
        const float h = above(tt);
        if (h <= 0.0f) {
            float a = prev_t, b = tt;  // above at a, at or below at b
            for (int i = 0; i < 40 && b - a > 1e-4f * terrain.cellSize(); ++i) {
                const float m = 0.5f * (a + b);
                (above(m) > 0.0f ? a : b) = m;
            }
            *t_m = b;
            return true;
        }
        prev_t = tt;
        prev_h = h;
        if (tt >= t1) return false;
    }
}

bool rayDensityIsosurface(const DensityField& field, const Ray& ray, float iso, float max_t_m, float step_m,
                          float* t_m) {
    if (!(step_m > 0.0f) || field.root == kNoNode) return false;
    float t0 = 0.0f, t1 = 0.0f;
    // Where f > 0 is possible; iso > 0 lies inside it. (An iso <= 0 surface may reach past it; the
    // editor asks for 0.5.)
    Bounds box = positiveBounds(field);
    if (!clipRayToBounds(ray, box, max_t_m, &t0, &t1)) return false;
    float prev_t = t0;
    bool prev_inside = evaluate(field, ray.at(t0)) >= iso;
    for (float t = t0 + step_m;; t += step_m) {
        const float tt = std::min(t, t1);
        const bool inside = evaluate(field, ray.at(tt)) >= iso;
        if (inside && !prev_inside) {
            float a = prev_t, b = tt;
            for (int i = 0; i < 40 && b - a > 1e-4f * step_m; ++i) {
                const float m = 0.5f * (a + b);
                (evaluate(field, ray.at(m)) >= iso ? b : a) = m;
            }
            *t_m = b;
            return true;
        }
        prev_t = tt;
        prev_inside = inside;
        if (tt >= t1) return false;
    }
}

}  // namespace ug
