// Skeletal primitives and their compactly supported kernel (Ghost Tile §5: "we rely on density functions
// created from skeletal primitives and combination operators as in the Blob-Tree [WGG99]").
//
// Compact support is what makes per-tile primitive lists possible: a primitive whose bounds miss a tile
// is exactly 0 there, so leaving it out changes no bit of the result (see density_field.cpp).
#include "field/primitive.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "field/height_field.h"
#include "field/primitive_eval.h"

namespace ug {

const char* primitiveKindName(PrimitiveKind kind) {
    switch (kind) {
        case PrimitiveKind::Point: return "point";
        case PrimitiveKind::Segment: return "segment";
        case PrimitiveKind::Disc: return "disc";
        case PrimitiveKind::Box: return "box";
        case PrimitiveKind::HalfSpace: return "half-space";
        case PrimitiveKind::TerrainLayer: return "terrain layer";
        case PrimitiveKind::TerrainSolid: return "terrain solid";
        case PrimitiveKind::External: return "external";
    }
    return "unknown";
}

namespace {

glm::vec3 normalizedOrZero(glm::vec3 n) {
    const float len = glm::length(n);
    return len > 0.0f && std::isfinite(len) ? n / len : n;
}

}  // namespace

Primitive makePoint(glm::vec3 center_m, float radius_m, float weight) {
    Primitive p;
    p.kind = PrimitiveKind::Point;
    p.center_m = center_m;
    p.radius_m = radius_m;
    p.weight = weight;
    return p;
}

Primitive makeCone(glm::vec3 a_m, float radius_a_m, glm::vec3 b_m, float radius_b_m, float weight) {
    Primitive p;
    p.kind = PrimitiveKind::Segment;
    p.center_m = a_m;
    p.end_m = b_m;
    p.radius_m = radius_a_m;
    p.end_radius_m = radius_b_m;
    p.weight = weight;
    return p;
}

Primitive makeSegment(glm::vec3 a_m, glm::vec3 b_m, float radius_m, float weight) {
    return makeCone(a_m, radius_m, b_m, radius_m, weight);
}

Primitive makeDisc(glm::vec3 center_m, glm::vec3 normal, float disc_radius_m, float radius_m, float weight) {
    Primitive p;
    p.kind = PrimitiveKind::Disc;
    p.center_m = center_m;
    p.normal = normalizedOrZero(normal);
    p.disc_radius_m = disc_radius_m;
    p.radius_m = radius_m;
    p.weight = weight;
    return p;
}

Primitive makeBox(glm::vec3 center_m, glm::vec3 half_extents_m, float radius_m, float weight) {
    Primitive p;
    p.kind = PrimitiveKind::Box;
    p.center_m = center_m;
    p.half_extents_m = half_extents_m;
    p.radius_m = radius_m;
    p.weight = weight;
    return p;
}

Primitive makeHalfSpace(glm::vec3 point_m, glm::vec3 outward_normal, float radius_m, float weight) {
    Primitive p;
    p.kind = PrimitiveKind::HalfSpace;
    p.center_m = point_m;
    p.normal = normalizedOrZero(outward_normal);
    p.radius_m = radius_m;
    p.weight = weight;
    return p;
}

Primitive makeTerrainLayer(uint32_t height_field, float thickness_m, float radius_m, float weight) {
    Primitive p;
    p.kind = PrimitiveKind::TerrainLayer;
    p.height_field = height_field;
    p.thickness_m = thickness_m;
    p.radius_m = radius_m;
    p.weight = weight;
    return p;
}

Primitive makeTerrainSolid(uint32_t height_field, float falloff_depth_m, float weight) {
    Primitive p;
    p.kind = PrimitiveKind::TerrainSolid;
    p.height_field = height_field;
    p.radius_m = falloff_depth_m;
    p.weight = weight;
    return p;
}

Primitive makeExternal(uint32_t external, float weight) {
    Primitive p;
    p.kind = PrimitiveKind::External;
    p.external = external;
    p.weight = weight;
    return p;
}

Primitive translatedPrimitive(Primitive prim, glm::vec3 offset_m) {
    if (prim.kind == PrimitiveKind::TerrainLayer || prim.kind == PrimitiveKind::TerrainSolid ||
        prim.kind == PrimitiveKind::External)
        return prim;
    prim.center_m += offset_m;
    if (prim.kind == PrimitiveKind::Segment) prim.end_m += offset_m;
    return prim;
}

namespace {

bool finite3(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string number(float v) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%g", double(v));
    return buf;
}

}  // namespace

bool validatePrimitive(const Primitive& pr, size_t index, size_t height_field_count, std::string* error) {
    std::string where = "primitive " + std::to_string(index) + " (" + primitiveKindName(pr.kind) + "): ";
    auto fail = [&](const std::string& what) {
        if (error) *error = where + what;
        return false;
    };
    if (int(pr.kind) > int(PrimitiveKind::External)) return fail("kind " + std::to_string(int(pr.kind)) + " is unknown");
    if (!std::isfinite(pr.weight)) return fail("weight " + number(pr.weight) + " is not finite");
    if (!std::isfinite(pr.radius_m) || !(pr.radius_m > 0.0f))
        return fail("radius_m " + number(pr.radius_m) + " must be finite and > 0");
    const bool terrain = pr.kind == PrimitiveKind::TerrainLayer || pr.kind == PrimitiveKind::TerrainSolid;
    if (!terrain && pr.kind != PrimitiveKind::External && !finite3(pr.center_m)) return fail("center_m is not finite");
    auto checkNormal = [&]() {
        if (!finite3(pr.normal)) return fail("normal is not finite");
        const float len = glm::length(pr.normal);
        if (len == 0.0f) return fail("normal is zero");
        if (std::abs(len - 1.0f) > 1e-4f) return fail("normal has length " + number(len) + ", must be unit");
        return true;
    };
    switch (pr.kind) {
        case PrimitiveKind::Point: break;
        case PrimitiveKind::Segment:
            if (!finite3(pr.end_m)) return fail("end_m is not finite");
            if (!std::isfinite(pr.end_radius_m) || !(pr.end_radius_m > 0.0f))
                return fail("end_radius_m " + number(pr.end_radius_m) + " must be finite and > 0");
            break;
        case PrimitiveKind::Disc:
            if (!checkNormal()) return false;
            if (!std::isfinite(pr.disc_radius_m) || pr.disc_radius_m < 0.0f)
                return fail("disc_radius_m " + number(pr.disc_radius_m) + " must be finite and >= 0");
            break;
        case PrimitiveKind::Box:
            if (!finite3(pr.half_extents_m)) return fail("half_extents_m is not finite");
            if (pr.half_extents_m.x < 0.0f || pr.half_extents_m.y < 0.0f || pr.half_extents_m.z < 0.0f)
                return fail("half_extents_m must be >= 0 on every axis");
            break;
        case PrimitiveKind::HalfSpace:
            if (!checkNormal()) return false;
            break;
        case PrimitiveKind::TerrainLayer:
            if (!std::isfinite(pr.thickness_m) || pr.thickness_m < 0.0f)
                return fail("thickness_m " + number(pr.thickness_m) + " must be finite and >= 0");
            [[fallthrough]];
        case PrimitiveKind::TerrainSolid:
            if (pr.height_field >= height_field_count)
                return fail("height_field " + std::to_string(pr.height_field) + " is out of range (" +
                            std::to_string(height_field_count) + " height fields)");
            break;
        case PrimitiveKind::External: break;  // the index is checked by validate(DensityField)
    }
    return true;
}

namespace {

// Pads finite bounds outward by a relative 1e-5 (+1e-6 m): far more than the few float roundings between
// the bounds and the kernel's d² < R² test, so no point outside the padded box can evaluate non-zero.
Bounds padded(Bounds b) {
    const glm::vec3 lo_pad = glm::abs(b.lo) * 1e-5f + 1e-6f;
    const glm::vec3 hi_pad = glm::abs(b.hi) * 1e-5f + 1e-6f;
    for (int i = 0; i < 3; ++i) {
        if (std::isfinite(b.lo[i])) b.lo[i] -= lo_pad[i];
        if (std::isfinite(b.hi[i])) b.hi[i] += hi_pad[i];
    }
    return b;
}

}  // namespace

Bounds primitiveBounds(const Primitive& pr, const HeightField* hf) {
    const float inf = std::numeric_limits<float>::infinity();
    const float r = pr.radius_m;
    switch (pr.kind) {
        case PrimitiveKind::Point: return padded(Bounds::fromCenterHalf(pr.center_m, glm::vec3(r)));
        case PrimitiveKind::Segment: {
            const float rmax = std::max(pr.radius_m, pr.end_radius_m);
            return padded(Bounds{glm::min(pr.center_m, pr.end_m) - rmax, glm::max(pr.center_m, pr.end_m) + rmax});
        }
        case PrimitiveKind::Disc: {
            // A disc of radius a with unit normal n spans a·sqrt(1 - n_i²) along axis i.
            const glm::vec3 n2 = pr.normal * pr.normal;
            const glm::vec3 half = pr.disc_radius_m * glm::sqrt(glm::max(glm::vec3(1.0f) - n2, glm::vec3(0.0f))) + r;
            return padded(Bounds::fromCenterHalf(pr.center_m, half));
        }
        case PrimitiveKind::Box: return padded(Bounds::fromCenterHalf(pr.center_m, pr.half_extents_m + r));
        case PrimitiveKind::HalfSpace: {
            Bounds b = Bounds::everything();
            // Bounded on one side only when the normal is an axis (the plane is axis-aligned).
            for (int i = 0; i < 3; ++i) {
                const int j = (i + 1) % 3, k = (i + 2) % 3;
                if (pr.normal[j] != 0.0f || pr.normal[k] != 0.0f) continue;
                if (pr.normal[i] > 0.0f) b.hi[i] = pr.center_m[i] + r;
                if (pr.normal[i] < 0.0f) b.lo[i] = pr.center_m[i] - r;
            }
            return padded(b);
        }
        case PrimitiveKind::TerrainLayer:
            assert(hf);
            return padded(Bounds{glm::vec3(-inf, -inf, hf->minHeight() - r),
                                 glm::vec3(inf, inf, hf->maxHeight() + pr.thickness_m + r)});
        case PrimitiveKind::TerrainSolid:
            assert(hf);
            return padded(Bounds{glm::vec3(-inf), glm::vec3(inf, inf, hf->maxHeight())});
        case PrimitiveKind::External: return Bounds::everything();
    }
    return Bounds::everything();
}

Bounds primitivePositiveBoundsIn(const Primitive& pr, const HeightField* hf, const Bounds& box) {
    if (!(pr.weight > 0.0f) || box.empty()) return Bounds{};
    Bounds b = intersect(primitiveBounds(pr, hf), box);
    if (b.empty()) return Bounds{};
    if (pr.kind == PrimitiveKind::TerrainLayer || pr.kind == PrimitiveKind::TerrainSolid) {
        assert(hf);
        const glm::vec2 range = hf->heightRange(glm::vec2(b.lo), glm::vec2(b.hi));
        // Bilinear interpolation may round a few ulps past its corners: padded() covers that.
        const float zlo = pr.kind == PrimitiveKind::TerrainLayer ? range.x - pr.radius_m
                                                                   : -std::numeric_limits<float>::infinity();
        const float zhi = pr.kind == PrimitiveKind::TerrainLayer ? range.y + pr.thickness_m + pr.radius_m : range.y;
        const Bounds local = padded(Bounds{glm::vec3(b.lo.x, b.lo.y, zlo), glm::vec3(b.hi.x, b.hi.y, zhi)});
        b = intersect(b, local);
        if (b.empty()) return Bounds{};
    }
    return b;
}

float primitiveValue(const Primitive& prim, const HeightField* height_field, glm::vec3 p_m) {
    return field_detail::evalPrimitive<false>(prim, height_field, p_m);
}

glm::vec4 primitiveValueAndGradient(const Primitive& prim, const HeightField* height_field, glm::vec3 p_m) {
    return field_detail::evalPrimitive<true>(prim, height_field, p_m);
}

}  // namespace ug
