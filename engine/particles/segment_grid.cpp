#include "particles/segment_grid.h"

#include <algorithm>

#include "core/parallel.h"

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
        const uint32_t slot = GridCells::hash(cells_.cellOf(entries_[id].mid)) & mask_;
        entries_[id].next = heads_[slot];
        heads_[slot] = id;
    }
}

void SegmentGrid::reserve(size_t segments) {
    // Capacity only: store() sizes the arrays as ids arrive, so each page is written once, not zeroed first.
    entries_.reserve(segments);
    tags_.reserve(segments);
    ids_.reserve(segments);
    size_t slots = 1024;
    while (slots < segments * 2) slots *= 2;
    if (slots > heads_.size()) rehash(slots);
}

void SegmentGrid::sizeFor(uint32_t id) {
    if (id < entries_.size()) return;
    // Within the reserved capacity, or grown geometrically by the vectors themselves.
    entries_.resize(size_t(id) + 1);
    tags_.resize(size_t(id) + 1);
}

void SegmentGrid::store(uint32_t id, glm::vec3 midpoint, uint32_t tag) {
    sizeFor(id);
    entries_[id] = Entry{midpoint, kNone};
    tags_[id] = tag;
    ids_.push_back(id);
    ++count_;
}

void SegmentGrid::insert(uint32_t id, glm::vec3 midpoint, uint32_t tag) {
    store(id, midpoint, tag);
    if (heads_.empty() || count_ * 2 > heads_.size()) {
        rehash(std::max<size_t>(1024, heads_.size() * 4));
        return;
    }
    link(id, GridCells::hash(cells_.cellOf(midpoint)) & mask_);
}

void SegmentGrid::insert(const std::vector<Filed>& batch, int threads) {
    // Stored as store() would, on every thread: sized once, each segment at its own id.
    uint32_t top = 0;
    for (const Filed& f : batch) top = std::max(top, f.id);
    if (!batch.empty()) sizeFor(top);
    const size_t first = ids_.size();
    ids_.resize(first + batch.size());
    count_ += batch.size();
    parallelFor(batch.size(), threads, 4096, [&](size_t begin, size_t end, int) {
        for (size_t i = begin; i < end; ++i) {
            entries_[batch[i].id] = Entry{batch[i].midpoint, kNone};
            tags_[batch[i].id] = batch[i].tag;
            ids_[first + i] = batch[i].id;
        }
    });
    if (heads_.empty() || count_ * 2 > heads_.size()) {
        // The size serial filing would reach (it quadruples the table whenever it is half full).
        size_t slots = std::max<size_t>(1024, heads_.size() * 4);
        while (count_ * 2 > slots) slots *= 4;
        rehash(slots);  // files the batch too
        return;
    }
    std::vector<uint32_t>& slot = slot_;
    slot.resize(batch.size());
    parallelFor(batch.size(), threads, 4096, [&](size_t begin, size_t end, int) {
        for (size_t i = begin; i < end; ++i) slot[i] = GridCells::hash(cells_.cellOf(batch[i].midpoint)) & mask_;
    });
    // Each share of the table is linked by one worker, in the batch's order: the lists are those of
    // serial insertion, for any thread count.
    const size_t shares = size_t(resolveThreadCount(threads));
    const uint64_t slots = uint64_t(mask_) + 1;
    parallelFor(shares, threads, 1, [&](size_t begin, size_t end, int) {
        for (size_t share = begin; share < end; ++share) {
            const uint64_t lo = slots * share / shares, hi = slots * (share + 1) / shares;
            for (size_t i = 0; i < batch.size(); ++i)
                if (slot[i] >= lo && slot[i] < hi) link(batch[i].id, slot[i]);
        }
    });
}

void StepSegmentGrid::build(const std::vector<SegmentGrid::Filed>& batch, int threads) {
    size_t slots = 1024;
    while (slots < batch.size() * 2) slots *= 2;
    mask_ = uint32_t(slots - 1);
    ascending_ = std::is_sorted(batch.begin(), batch.end(),
                                [](const SegmentGrid::Filed& a, const SegmentGrid::Filed& b) { return a.id < b.id; });
    slot_.resize(batch.size());
    parallelFor(batch.size(), threads, 4096, [&](size_t begin, size_t end, int) {
        for (size_t i = begin; i < end; ++i) slot_[i] = GridCells::hash(cells_.cellOf(batch[i].midpoint)) & mask_;
    });
    // A counting sort by slot, stable: start_[s + 1] counts slot s, the running sum makes it slot s + 1's
    // start, and placing the segments advances each slot's start to its end.
    start_.assign(slots + 1, 0);
    for (uint32_t s : slot_) ++start_[s + 1];
    for (size_t s = 0; s < slots; ++s) start_[s + 1] += start_[s];
    entries_.resize(batch.size());
    tags_.resize(batch.size());
    for (size_t i = 0; i < batch.size(); ++i) {
        const uint32_t at = start_[slot_[i]]++;
        entries_[at] = Entry{batch[i].midpoint, batch[i].id};
        tags_[at] = batch[i].tag;
    }
    // The increments moved every start to its slot's end, the next slot's start: shift them back.
    for (size_t s = slots; s > 0; --s) start_[s] = start_[s - 1];
    start_[0] = 0;
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
