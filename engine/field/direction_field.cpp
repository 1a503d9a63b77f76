// Direction and size control fields (Ghost Tile §5.3 "Control", Figures 17 and 22). They evaluate the
// density field through evaluateBatch*, so a tile-list evaluation stays bit-identical to a full one and
// the constraint decisions never depend on who evaluated them.
#include "field/direction_field.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace ug {

glm::vec3 evaluateDirection(const DirectionField& d, const TileFieldList* list, glm::vec3 p_m) {
    if (d.kind == DirectionFieldKind::Constant) return d.direction;
    assert(d.field);
    glm::vec4 s;
    evaluateBatchWithGradient(*d.field, list, &p_m, 1, &s);
    const glm::vec3 g(s);
    const float len = glm::length(g);
    // note: a flat field (inside a box, a blob's centre, outside every support) has no direction;
    // +Z is what an artist expects of ground details there.
    if (!(len >= kMinDirectionGradient)) return glm::vec3(0.0f, 0.0f, 1.0f);
    return g / len;
}

float evaluateSize(const SizeField& s, const TileFieldList* list, glm::vec3 p_m) {
    if (s.kind == SizeFieldKind::Constant) return s.scale;
    assert(s.field);
    float v;
    evaluateBatch(*s.field, list, &p_m, 1, &v);
    const float t = std::clamp((v - s.value_lo) / (s.value_hi - s.value_lo), 0.0f, 1.0f);
    return s.scale_lo + (s.scale_hi - s.scale_lo) * t;
}

namespace {

bool fail(std::string* error, const std::string& what) {
    if (error) *error = what;
    return false;
}

bool positiveFinite(float v) { return std::isfinite(v) && v > 0.0f; }

}  // namespace

bool validate(const DirectionField& d, std::string* error) {
    switch (d.kind) {
        case DirectionFieldKind::Constant: {
            const glm::vec3 v = d.direction;
            if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
                return fail(error, "direction field: direction is not finite");
            if (std::abs(glm::length(v) - 1.0f) > 1e-4f)
                return fail(error, "direction field: direction must be unit length");
            return true;
        }
        case DirectionFieldKind::Gradient: {
            if (!d.field) return fail(error, "direction field: gradient kind needs a density field");
            std::string inner;
            if (!validate(*d.field, &inner)) return fail(error, "direction field: " + inner);
            return true;
        }
    }
    return fail(error, "direction field: unknown kind");
}

bool validate(const SizeField& s, std::string* error) {
    switch (s.kind) {
        case SizeFieldKind::Constant:
            if (!positiveFinite(s.scale)) return fail(error, "size field: scale must be finite and > 0");
            return true;
        case SizeFieldKind::Ramp: {
            if (!s.field) return fail(error, "size field: ramp kind needs a density field");
            if (!std::isfinite(s.value_lo) || !std::isfinite(s.value_hi) || !(s.value_lo < s.value_hi))
                return fail(error, "size field: value_lo and value_hi must be finite with value_lo < value_hi");
            if (!positiveFinite(s.scale_lo) || !positiveFinite(s.scale_hi))
                return fail(error, "size field: scale_lo and scale_hi must be finite and > 0");
            std::string inner;
            if (!validate(*s.field, &inner)) return fail(error, "size field: " + inner);
            return true;
        }
    }
    return fail(error, "size field: unknown kind");
}

}  // namespace ug
