#include "particles/growth_record.h"

#include <cmath>

namespace ug {

AttractorEdit::AttractorEdit(const std::vector<Attractor>& before, const std::vector<Attractor>& after,
                             float step_length_m)
    : before_(before), after_(after), margin_m_(step_length_m * 1.01f + 1e-6f) {
    for (uint32_t a = 0; a < after.size(); ++a) {
        const Attractor& b = before[a];
        const Attractor& n = after[a];
        const bool same_place = sameAttractorPlace(b, n);
        if (same_place && b.influence_m == n.influence_m) continue;  // only the charge may differ: everywhereAt
        if (b.influence_m == n.influence_m && n.influence_m > 0.0f)
            moved_.push_back(a);
        else
            global_.push_back(a);
    }
}

bool AttractorEdit::everywhereAt(uint32_t step) const {
    if (!global_.empty()) return true;
    for (size_t a = 0; a < after_.size(); ++a)
        if (chargeAt(before_[a].charge, step) != chargeAt(after_[a].charge, step)) return true;
    return false;
}

bool AttractorEdit::reaches(glm::vec3 p0) const {
    // The distance is 1-Lipschitz: a trial within one step of p0 is beyond the radius wherever p0 is
    // beyond the radius plus a step.
    for (uint32_t a : moved_) {
        const float reach = after_[a].influence_m + margin_m_;
        if (attractorDistance(before_[a], p0) <= reach || attractorDistance(after_[a], p0) <= reach) return true;
    }
    return false;
}

CutterEdit::CutterEdit(const std::vector<Cutter>& before, const std::vector<Cutter>& after, float step_length_m)
    : before_(before), after_(after), changed_(after.size(), 0), margin_m_(step_length_m * 1.01f + 1e-6f) {
    for (uint32_t c = 0; c < after.size(); ++c)
        if (!(before[c] == after[c])) {
            changed_[c] = 1;
            list_.push_back(c);
        }
}

bool CutterEdit::reaches(glm::vec3 p0) const {
    for (uint32_t c : list_)
        for (const Cutter* cut : {&before_[c], &after_[c]}) {
            // Rounding of g grows with the coordinates' size.
            const float slack = margin_m_ + 1e-6f * (glm::length(p0) + glm::length(cut->center_m));
            if (std::abs(cutterValue(*cut, p0) - cut->threshold_m) <= slack) return true;
        }
    return false;
}

bool regrowable(const ParticleScene& before, const ParticleScene& after) {
    return before.generators == after.generators && before.terrain == after.terrain &&
           before.cutters.size() == after.cutters.size() && before.walk == after.walk && before.obstacles == after.obstacles &&
           before.detail_obstacles == after.detail_obstacles &&
           before.attractors.size() == after.attractors.size();
}

}  // namespace ug
