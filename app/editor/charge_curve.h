// The Particles window's a(t) curve editor (issue 14), the part without ImGui: an attractor's charge keys
// drawn as a plot over the walk's steps, and edited on it. A key is dragged (sideways: its step, kept
// strictly between its neighbours' so the keys stay ordered; up and down: its charge), a double click adds
// a key on the curve where it is clicked, a right click removes one (never the last).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "particles/particle_scene.h"

namespace ug::editor {

constexpr size_t kNoChargeKey = SIZE_MAX;
constexpr float kMaxChargeMagnitude = 100.0f;  // the curve's and the charge field's range

// The plot's rectangle on screen (pixels, y down) and what it spans: steps 0..steps across, charges
// lo..hi up.
struct ChargeCurveFrame {
    glm::vec2 min_px{0.0f}, max_px{1.0f};
    uint32_t steps = 1;
    float lo = -1.0f, hi = 1.0f;
};

// A range that holds every key and 0 with a margin, symmetric about 0 so the zero line stays in the
// middle (attract above, repel below).
void chargeCurveRange(const std::vector<ChargeKey>& keys, float* lo, float* hi);

glm::vec2 chargeKeyPixel(const ChargeCurveFrame& frame, ChargeKey key);
// The key at a pixel: the step rounded and clamped to [0, steps], the charge clamped to the range.
ChargeKey chargeKeyAtPixel(const ChargeCurveFrame& frame, glm::vec2 px);

// The key whose point is nearest `px` within max_px; kNoChargeKey for none.
size_t nearestChargeKey(const std::vector<ChargeKey>& keys, const ChargeCurveFrame& frame, glm::vec2 px, float max_px);

// Key k moved to `to`: its step clamped strictly between its neighbours', its charge to ±kMaxChargeMagnitude.
// False (nothing changed) when k is out of range or the key would not move.
bool moveChargeKey(std::vector<ChargeKey>* keys, size_t k, ChargeKey to);
// A key added in step order; kNoChargeKey when a key already has that step (the keys stay strictly
// increasing), else its index.
size_t insertChargeKey(std::vector<ChargeKey>* keys, ChargeKey key);
// False when k is out of range or the last key (a charge needs one).
bool removeChargeKey(std::vector<ChargeKey>* keys, size_t k);

}  // namespace ug::editor
