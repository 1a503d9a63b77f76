// Direction and size fields: the control fields of the orientation and size constraints (Ghost Tile
// §5.3 "Control": a candidate is kept when z(F) · u(p) exceeds a threshold, with u constant (u = z) or
// the gradient of the density, u = ∇f_i; Figure 22 uses a size field around the openings).
//
//   DirectionField up;                                              // constant +Z
//   DirectionField normal{.kind = DirectionFieldKind::Gradient, .field = grass_field};
//   glm::vec3 u = evaluateDirection(normal, nullptr, p);            // unit length, always
//   SizeField s{.kind = SizeFieldKind::Ramp, .field = f, .value_lo = 0, .value_hi = 1,
//               .scale_lo = 0.5f, .scale_hi = 1.5f};
//   float scale = evaluateSize(s, nullptr, p);                      // in [scale_lo, scale_hi]
//
// The density field is shared and read-only (a detail type's own field can be passed, as the paper
// does). The optional TileFieldList must have been built from that same field, for a box holding p; the
// result is then bit-identical to the full evaluation.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "field/density_field.h"

namespace ug {

enum class DirectionFieldKind : uint8_t { Constant, Gradient };

// Below this gradient length (value units per metre) the direction falls back to +Z.
constexpr float kMinDirectionGradient = 1e-6f;

struct DirectionField {
    DirectionFieldKind kind = DirectionFieldKind::Constant;
    glm::vec3 direction{0.0f, 0.0f, 1.0f};    // Constant: unit length
    std::shared_ptr<const DensityField> field;  // Gradient: non-null, valid
};

// A unit vector: the constant, or ∇f / |∇f| (+Z where |∇f| < kMinDirectionGradient).
glm::vec3 evaluateDirection(const DirectionField& d, const TileFieldList* list, glm::vec3 p_m);
// *error names the setting and the reason.
bool validate(const DirectionField& d, std::string* error);

enum class SizeFieldKind : uint8_t { Constant, Ramp };

struct SizeField {
    SizeFieldKind kind = SizeFieldKind::Constant;
    float scale = 1.0f;                         // Constant: the scale factor, finite, > 0
    std::shared_ptr<const DensityField> field;  // Ramp: non-null, valid
    float value_lo = 0.0f;                      // Ramp: field values mapped to scale_lo / scale_hi,
    float value_hi = 1.0f;                      //       finite, value_lo < value_hi
    float scale_lo = 1.0f;                      // Ramp: finite, > 0 (either may be the larger)
    float scale_hi = 1.0f;
};

// Constant: scale. Ramp: lerp(scale_lo, scale_hi, clamp((f(p) - value_lo) / (value_hi - value_lo), 0, 1)).
float evaluateSize(const SizeField& s, const TileFieldList* list, glm::vec3 p_m);
bool validate(const SizeField& s, std::string* error);

}  // namespace ug
