#include "editor/charge_curve.h"

#include <algorithm>
#include <cmath>

namespace ug::editor {

void chargeCurveRange(const std::vector<ChargeKey>& keys, float* lo, float* hi) {
    float m = 0.0f;
    for (const ChargeKey& k : keys) m = std::max(m, std::abs(k.charge));
    // Room above the largest key to drag it further, and a sensible plot for a curve of zeros.
    const float half = std::min(kMaxChargeMagnitude, std::max(1.0f, 1.25f * m));
    *lo = -half;
    *hi = half;
}

glm::vec2 chargeKeyPixel(const ChargeCurveFrame& f, ChargeKey key) {
    const float s = float(key.step) / float(std::max<uint32_t>(1, f.steps));
    const float c = (key.charge - f.lo) / std::max(1e-6f, f.hi - f.lo);
    return {f.min_px.x + s * (f.max_px.x - f.min_px.x), f.max_px.y - c * (f.max_px.y - f.min_px.y)};
}

ChargeKey chargeKeyAtPixel(const ChargeCurveFrame& f, glm::vec2 px) {
    const float s = std::clamp((px.x - f.min_px.x) / std::max(1e-6f, f.max_px.x - f.min_px.x), 0.0f, 1.0f);
    const float c = std::clamp((f.max_px.y - px.y) / std::max(1e-6f, f.max_px.y - f.min_px.y), 0.0f, 1.0f);
    const float charge = std::clamp(f.lo + c * (f.hi - f.lo), -kMaxChargeMagnitude, kMaxChargeMagnitude);
    return {uint32_t(std::lround(s * float(f.steps))), charge};
}

size_t nearestChargeKey(const std::vector<ChargeKey>& keys, const ChargeCurveFrame& frame, glm::vec2 px, float max_px) {
    size_t best = kNoChargeKey;
    float best_d = max_px;
    for (size_t k = 0; k < keys.size(); ++k) {
        const float d = glm::length(chargeKeyPixel(frame, keys[k]) - px);
        if (d <= best_d) {
            best = k;
            best_d = d;
        }
    }
    return best;
}

bool moveChargeKey(std::vector<ChargeKey>* keys, size_t k, ChargeKey to) {
    if (k >= keys->size()) return false;
    // Strictly between the neighbours: a key never passes another, so its index stays the one dragged.
    uint32_t lo = 0, hi = UINT32_MAX;
    if (k > 0) lo = (*keys)[k - 1].step + 1;
    if (k + 1 < keys->size()) hi = (*keys)[k + 1].step - 1;
    const ChargeKey moved{std::clamp(to.step, lo, hi),
                          std::clamp(to.charge, -kMaxChargeMagnitude, kMaxChargeMagnitude)};
    if (moved == (*keys)[k]) return false;
    (*keys)[k] = moved;
    return true;
}

size_t insertChargeKey(std::vector<ChargeKey>* keys, ChargeKey key) {
    const auto at = std::lower_bound(keys->begin(), keys->end(), key.step,
                                     [](const ChargeKey& k, uint32_t step) { return k.step < step; });
    if (at != keys->end() && at->step == key.step) return kNoChargeKey;
    key.charge = std::clamp(key.charge, -kMaxChargeMagnitude, kMaxChargeMagnitude);
    const size_t index = size_t(at - keys->begin());  // before the insertion, which may reallocate
    keys->insert(at, key);
    return index;
}

bool removeChargeKey(std::vector<ChargeKey>* keys, size_t k) {
    if (k >= keys->size() || keys->size() < 2) return false;
    keys->erase(keys->begin() + std::ptrdiff_t(k));
    return true;
}

}  // namespace ug::editor
