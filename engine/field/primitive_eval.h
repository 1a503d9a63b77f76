// Internal: the one implementation of primitive evaluation, inlined into every caller (single
// primitives, scalar and batched field evaluation), so values agree bit for bit whoever asked.
// Not part of the public API; include only from engine/field/*.cpp.
#pragma once

#include <cmath>
#include <type_traits>

#include <glm/glm.hpp>

#include "field/height_field.h"
#include "field/primitive.h"

namespace ug::field_detail {

// A field sample: the value alone, or (gradient.xyz, value) when the gradient is asked for.
template <bool kGrad>
using Sample = std::conditional_t<kGrad, glm::vec4, float>;

inline float sampleValue(float s) { return s; }
inline float sampleValue(const glm::vec4& s) { return s.w; }

// Wyvill's kernel weight * (1 - d²/R²)³ (WGG99). half_grad_d2 = ½∇(d²) for a fixed R (for a varying R
// the caller folds ∇R into it; see Segment). Outside the support it returns exactly +0 in every
// component, never weight * 0: a primitive that a tile list leaves out must contribute the same bits as
// one that is evaluated and found outside its support (density_field.cpp relies on it).
template <bool kGrad>
inline Sample<kGrad> kernel(float weight, float d2, float r2, glm::vec3 half_grad_d2) {
    if (!(d2 < r2)) return Sample<kGrad>(0.0f);
    const float t = 1.0f - d2 / r2;
    if (!(t > 0.0f)) return Sample<kGrad>(0.0f);  // d2 / r2 rounded up to 1
    const float t2 = t * t;
    const float value = weight * (t2 * t);
    if constexpr (kGrad) {
        // dK/dp = 3 t² · (-∇(d²) / R²) = -6 t² / R² · ½∇(d²)
        return glm::vec4((weight * (-6.0f * t2 / r2)) * half_grad_d2, value);
    } else {
        (void)half_grad_d2;
        return value;
    }
}

// The height under one point, shared by the terrain primitives evaluated there (a layer and the ground
// solid ask for the same h(x, y)): the same call gives the same bits, and the second one is free.
struct HeightCache {
    const HeightField* hf = nullptr;
    glm::vec3 hs{0.0f};
};

template <bool kGrad>
inline glm::vec3 terrainHeight(const HeightField* hf, glm::vec3 p, HeightCache* cache) {
    if (cache && cache->hf == hf) return cache->hs;
    const glm::vec3 hs = kGrad ? hf->sampleWithGradient(p.x, p.y) : glm::vec3(hf->sample(p.x, p.y), 0.0f, 0.0f);
    if (cache) *cache = HeightCache{hf, hs};
    return hs;
}

// `cache` (optional) must belong to this point p and to one value of kGrad.
template <bool kGrad>
inline Sample<kGrad> evalPrimitive(const Primitive& pr, const HeightField* hf, glm::vec3 p,
                                   HeightCache* cache = nullptr) {
    const float r2 = pr.radius_m * pr.radius_m;
    switch (pr.kind) {
        case PrimitiveKind::Point: {
            const glm::vec3 dp = p - pr.center_m;
            return kernel<kGrad>(pr.weight, glm::dot(dp, dp), r2, dp);
        }
        case PrimitiveKind::Segment: {
            // Generalized cylinder piece: R(t) = lerp(R_a, R_b, t) at the projection parameter t of p,
            // clamped to [0, 1]. With q = d²/R(t)², ½R²∇q = (p - c) - d² R'(t) ∇t / R, ∇t = ab / |ab|².
            const glm::vec3 ab = pr.end_m - pr.center_m;
            const float len2 = glm::dot(ab, ab);
            float t = 0.0f;
            bool interior = false;
            if (len2 > 0.0f) {
                t = glm::dot(p - pr.center_m, ab) / len2;
                if (t <= 0.0f) {
                    t = 0.0f;
                } else if (t >= 1.0f) {
                    t = 1.0f;
                } else {
                    interior = true;
                }
            }
            const glm::vec3 dp = p - (pr.center_m + t * ab);
            const float d2 = glm::dot(dp, dp);
            const float dr = pr.end_radius_m - pr.radius_m;
            const float radius = pr.radius_m + dr * t;
            glm::vec3 half = dp;
            if constexpr (kGrad) {
                if (interior && dr != 0.0f) half -= (d2 * dr / (radius * len2)) * ab;
            }
            return kernel<kGrad>(pr.weight, d2, radius * radius, half);
        }
        case PrimitiveKind::Disc: {
            const glm::vec3 v = p - pr.center_m;
            const float h = glm::dot(v, pr.normal);
            const glm::vec3 radial = v - h * pr.normal;
            const float rho2 = glm::dot(radial, radial);
            const float rd = pr.disc_radius_m;
            if (rho2 <= rd * rd) return kernel<kGrad>(pr.weight, h * h, r2, h * pr.normal);
            const float rho = std::sqrt(rho2);
            const float out = rho - rd;
            const glm::vec3 dp = radial * (out / rho) + h * pr.normal;
            return kernel<kGrad>(pr.weight, h * h + out * out, r2, dp);
        }
        case PrimitiveKind::Box: {
            const glm::vec3 q = p - pr.center_m;
            const glm::vec3 outside = glm::max(glm::abs(q) - pr.half_extents_m, glm::vec3(0.0f));
            const glm::vec3 dp(q.x < 0.0f ? -outside.x : outside.x, q.y < 0.0f ? -outside.y : outside.y,
                               q.z < 0.0f ? -outside.z : outside.z);
            return kernel<kGrad>(pr.weight, glm::dot(outside, outside), r2, dp);
        }
        case PrimitiveKind::HalfSpace: {
            const float s = glm::dot(p - pr.center_m, pr.normal);
            if (s <= 0.0f) return kernel<kGrad>(pr.weight, 0.0f, r2, glm::vec3(0.0f));
            return kernel<kGrad>(pr.weight, s * s, r2, s * pr.normal);
        }
        case PrimitiveKind::TerrainLayer: {
            // Vertical distance only (the layer is "thickness above the ground" as an artist reads it);
            // d = h - z below the ground, z - (h + thickness) above the layer, with ∇d from ∇h.
            const glm::vec3 hs = terrainHeight<kGrad>(hf, p, cache);
            const float below = hs.x - p.z;
            if (below > 0.0f) return kernel<kGrad>(pr.weight, below * below, r2, below * glm::vec3(hs.y, hs.z, -1.0f));
            const float above = p.z - (hs.x + pr.thickness_m);
            if (above > 0.0f) return kernel<kGrad>(pr.weight, above * above, r2, above * glm::vec3(-hs.y, -hs.z, 1.0f));
            return kernel<kGrad>(pr.weight, 0.0f, r2, glm::vec3(0.0f));
        }
        case PrimitiveKind::TerrainSolid: {
            const glm::vec3 hs = terrainHeight<kGrad>(hf, p, cache);
            if (!(p.z < hs.x)) return Sample<kGrad>(0.0f);  // exactly 0 on and above the ground
            const float d = p.z - (hs.x - pr.radius_m);
            if (d <= 0.0f) return kernel<kGrad>(pr.weight, 0.0f, r2, glm::vec3(0.0f));
            return kernel<kGrad>(pr.weight, d * d, r2, d * glm::vec3(-hs.y, -hs.z, 1.0f));
        }
        case PrimitiveKind::External: return Sample<kGrad>(0.0f);  // resolved by density_field.cpp
    }
    return Sample<kGrad>(0.0f);
}

}  // namespace ug::field_detail
