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
    // Files segment `id` (ids are the caller's, dense from 0) under the cell of midpoint.
    void insert(uint32_t id, glm::vec3 midpoint);
    size_t size() const { return count_; }

    // Calls visit(id) for every segment filed in the 27 cells around midpoint's cell (and any sharing
    // their slots); stops early when visit returns true, and returns whether one did.
    template <typename Visit>
    bool anyNear(glm::vec3 midpoint, Visit&& visit) const {
        if (heads_.empty()) return false;
        const glm::ivec3 c = cellOf(midpoint);
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const uint32_t slot = cellHash(c + glm::ivec3(dx, dy, dz)) & mask_;
                    for (uint32_t id = heads_[slot]; id != kNone; id = next_[id])
                        if (visit(id)) return true;
                }
        return false;
    }

private:
    glm::ivec3 cellOf(glm::vec3 p) const {
        return glm::ivec3(glm::floor(p * inv_cell_));
    }
    static uint32_t cellHash(glm::ivec3 c) {
        return uint32_t(c.x) * 73856093u ^ uint32_t(c.y) * 19349663u ^ uint32_t(c.z) * 83492791u;
    }
    void rehash(size_t slots);

    float cell_, inv_cell_;
    uint32_t mask_ = 0;
    size_t count_ = 0;
    std::vector<uint32_t> heads_;
    std::vector<uint32_t> next_;   // by id
    std::vector<uint32_t> hash_;   // by id: its cell's hash, kept for rehashing
    std::vector<uint32_t> ids_;    // filed ids in insertion order (rehash keeps their order)
};

// Squared distance between segments p0p1 and q0q1 (either may be a point).
float segmentSegmentDistance2(glm::vec3 p0, glm::vec3 p1, glm::vec3 q0, glm::vec3 q1);

}  // namespace ug
