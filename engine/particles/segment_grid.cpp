#include "particles/segment_grid.h"

#include <algorithm>

namespace ug {

void SegmentGrid::clear() {
    std::fill(heads_.begin(), heads_.end(), kNone);
    ids_.clear();
    count_ = 0;
}

void SegmentGrid::rehash(size_t slots) {
    heads_.assign(slots, kNone);
    mask_ = uint32_t(slots - 1);
    // Refiled in insertion order so every list keeps the order a table of this size from the start
    // would have (queries only ask "any?", but the order is cheap to keep fixed).
    for (uint32_t id : ids_) {
        const uint32_t slot = cellHash(cellOf(entries_[id].mid)) & mask_;
        entries_[id].next = heads_[slot];
        heads_[slot] = id;
    }
}

void SegmentGrid::reserve(size_t segments) {
    if (segments > entries_.size()) {
        entries_.resize(segments);
        tags_.resize(segments);
    }
    ids_.reserve(segments);
    size_t slots = 1024;
    while (slots < segments * 2) slots *= 2;
    if (slots > heads_.size()) rehash(slots);
}

void SegmentGrid::insert(uint32_t id, glm::vec3 midpoint, uint32_t tag) {
    if (id >= entries_.size()) {
        entries_.resize(std::max<size_t>(size_t(id) + 1, entries_.size() * 2));
        tags_.resize(entries_.size());
    }
    entries_[id] = Entry{midpoint, kNone};
    tags_[id] = tag;
    ids_.push_back(id);
    ++count_;
    if (heads_.empty() || count_ * 2 > heads_.size()) {
        rehash(std::max<size_t>(1024, heads_.size() * 4));
        return;
    }
    const uint32_t slot = cellHash(cellOf(midpoint)) & mask_;
    entries_[id].next = heads_[slot];
    heads_[slot] = id;
}

float segmentSegmentDistance2(glm::vec3 p0, glm::vec3 p1, glm::vec3 q0, glm::vec3 q1) {
    // Closest points of two segments: minimise |p(s) - q(u)|² over [0, 1]², clamping s, then u, then s
    // again (the standard construction for segments; the degenerate cases are points).
    const glm::vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const float a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
    float s = 0.0f, u = 0.0f;
    if (a <= 1e-20f && e <= 1e-20f) {
        return glm::dot(r, r);
    } else if (a <= 1e-20f) {
        u = std::clamp(f / e, 0.0f, 1.0f);
    } else {
        const float c = glm::dot(d1, r);
        if (e <= 1e-20f) {
            s = std::clamp(-c / a, 0.0f, 1.0f);
        } else {
            const float b = glm::dot(d1, d2), denom = a * e - b * b;
            s = denom > 1e-20f * a * e ? std::clamp((b * f - c * e) / denom, 0.0f, 1.0f) : 0.0f;
            u = (b * s + f) / e;
            if (u < 0.0f) {
                u = 0.0f;
                s = std::clamp(-c / a, 0.0f, 1.0f);
            } else if (u > 1.0f) {
                u = 1.0f;
                s = std::clamp((b - c) / a, 0.0f, 1.0f);
            }
        }
    }
    const glm::vec3 d = (p0 + s * d1) - (q0 + u * d2);
    return glm::dot(d, d);
}

}  // namespace ug
