// A spatial hash of strand segments for the collision test of particle sculpting: each segment is filed
// under the cell of its midpoint, cells are hashed into a power-of-two table of list heads, and a query
// visits the 3 × 3 × 3 cells around a midpoint. With cells at least as wide as the longest segment plus
// the distance looked for, every segment that can come that close to the query is visited.
//
// Cells that hash to the same slot share a list: a query sees a few extra segments, never fewer, so the
// table needs no keys. Insertion is serial (the caller files segments in a fixed order); queries are
// read-only and may run on any number of threads.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace ug {

class SegmentGrid {
public:
    static constexpr uint32_t kNone = 0xffffffffu;

    explicit SegmentGrid(float cell_m = 1.0f) : cell_(cell_m), inv_cell_(1.0f / cell_m) {}

    // Forgets every segment; keeps the cell size and the memory.
    void clear();
    // Files segment `id` (ids are the caller's, dense from 0) with its midpoint and a tag of the caller's
    // (the strand) kept beside it, so a query rejects most segments without touching the caller's data.
    void insert(uint32_t id, glm::vec3 midpoint, uint32_t tag);
    // Sizes the table for `segments` segments with ids below that, so filing them never rehashes.
    void reserve(size_t segments);
    size_t size() const { return count_; }

    // Calls visit(id, tag) for every segment filed in the 27 cells around midpoint's cell (and any sharing
    // their slots) whose midpoint lies within `reach` of it; stops early when visit returns true, and
    // returns whether one did. reach must not exceed the cell size.
    template <typename Visit>
    bool anyNear(glm::vec3 midpoint, float reach, Visit&& visit) const {
        if (heads_.empty()) return false;
        const float reach2 = reach * reach;
        const glm::ivec3 c = cellOf(midpoint);
        // x innermost: the three cells of a row are adjacent slots (cellHash is linear in x).
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const uint32_t slot = (cellHash(glm::ivec3(c.x, c.y + dy, c.z + dz)) + uint32_t(dx)) & mask_;
                    for (uint32_t id = heads_[slot]; id != kNone;) {
                        const Entry& e = entries_[id];
                        const glm::vec3 d = e.mid - midpoint;
                        if (glm::dot(d, d) <= reach2 && visit(id, tags_[id])) return true;
                        id = e.next;
                    }
                }
        return false;
    }

private:
    // 16 bytes, what a query reads for every segment it visits; the tag is read only for the few
    // within reach.
    struct Entry {
        glm::vec3 mid;
        uint32_t next;
    };

    glm::ivec3 cellOf(glm::vec3 p) const {
        return glm::ivec3(glm::floor(p * inv_cell_));
    }
    // Linear in the cell's coordinates, so neighbouring cells along x share cache lines and the queries
    // of neighbouring strands (close ids, close places) touch the same lines: a scrambling hash made
    // every one of the 27 lookups a cache miss. Distinct cells that alias only lengthen a list.
    static uint32_t cellHash(glm::ivec3 c) {
        return uint32_t(c.x) + uint32_t(c.y) * 4099u + uint32_t(c.z) * 16'851'989u;
    }
    void rehash(size_t slots);

    float cell_, inv_cell_;
    uint32_t mask_ = 0;
    size_t count_ = 0;
    std::vector<uint32_t> heads_;
    std::vector<Entry> entries_;  // by id
    std::vector<uint32_t> tags_;  // by id
    std::vector<uint32_t> ids_;   // filed ids in insertion order (rehash keeps their order)
};

// Squared distance between segments p0p1 and q0q1 (either may be a point).
float segmentSegmentDistance2(glm::vec3 p0, glm::vec3 p1, glm::vec3 q0, glm::vec3 q1);

}  // namespace ug
