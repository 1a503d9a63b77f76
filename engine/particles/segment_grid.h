// A spatial hash of strand segments for the collision test of particle sculpting: each segment is filed
// under the cell of its midpoint, cells are hashed into a power-of-two table of list heads, and a query
// for the segments whose midpoints lie within `reach` of a point visits the 2 x 2 x 2 cells around it.
// Cells are twice the reach (padded against rounding), so the reach's cube lies in the cell and its
// neighbours on the nearer side along each axis; with reach = the longest segment plus the distance looked
// for, every segment that can come that close to the query is visited. Eight lookups of cells twice as
// wide took a quarter less CPU time than 27 of cells as wide as the reach (a 20k-strand fur ball), though
// they visit more segments.
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

    // reach_m > 0: the distance between midpoints that queries look for.
    explicit SegmentGrid(float reach_m = 1.0f)
        : reach_(reach_m), cell_(2.0f * reach_m * 1.001f), inv_cell_(1.0f / cell_) {}

    // Forgets every segment; keeps the cell size and the memory.
    void clear();
    // Files segment `id` (ids are the caller's, dense from 0) with its midpoint and a tag of the caller's
    // (the strand) kept beside it, so a query rejects most segments without touching the caller's data.
    void insert(uint32_t id, glm::vec3 midpoint, uint32_t tag);
    // Sizes the table for `segments` segments with ids below that, so filing them never rehashes.
    void reserve(size_t segments);
    size_t size() const { return count_; }

    // Calls visit(id, tag) for every segment filed in the 2 x 2 x 2 cells around midpoint (and any sharing
    // their slots) whose midpoint lies within the reach of it, and for no other; stops early when visit
    // returns true, and returns whether one did.
    template <typename Visit>
    bool anyNear(glm::vec3 midpoint, Visit&& visit) const {
        if (heads_.empty()) return false;
        const float reach2 = reach_ * reach_;
        // Cells are twice the reach, so the reach's cube around midpoint lies in the 2 x 2 x 2 cells
        // on the sides of its cell that midpoint is nearer to.
        const glm::vec3 f = midpoint * inv_cell_;
        const glm::ivec3 c(glm::floor(f));
        const glm::vec3 frac = f - glm::vec3(c);
        const glm::ivec3 lo(c.x - (frac.x < 0.5f), c.y - (frac.y < 0.5f), c.z - (frac.z < 0.5f));
        for (int dz = 0; dz <= 1; ++dz)
            for (int dy = 0; dy <= 1; ++dy)
                for (int dx = 0; dx <= 1; ++dx) {
                    const uint32_t slot = (cellHash(glm::ivec3(lo.x, lo.y + dy, lo.z + dz)) + uint32_t(dx)) & mask_;
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
    // of neighbouring strands (close ids, close places) touch the same lines, where a scrambling hash
    // sends each lookup somewhere new. Distinct cells that alias only lengthen a list.
    static uint32_t cellHash(glm::ivec3 c) {
        return uint32_t(c.x) + uint32_t(c.y) * 4099u + uint32_t(c.z) * 16'851'989u;
    }
    void rehash(size_t slots);

    float reach_, cell_, inv_cell_;
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
