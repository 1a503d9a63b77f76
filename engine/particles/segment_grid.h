// Spatial hashes of strand segments for the collision tests of particle sculpting: each segment is filed
// under the cell of its midpoint, cells are hashed into a power-of-two table of slots, and a query for the
// segments whose midpoints lie within `reach` of a point visits the 2 x 2 x 2 cells around it. Cells are
// twice the reach (padded against rounding), so the reach's cube lies in the cell and its neighbours on
// the nearer side along each axis; with reach = the longest segment plus the distance looked for, every
// segment that can come that close to the query is visited. Eight lookups of cells twice as wide took a
// quarter less CPU time than 27 of cells as wide as the reach (a 20k-strand fur ball), though they visit
// more segments.
//
// Cells that hash to the same slot share it: a query sees a few extra segments, never fewer, so the
// tables need no keys. Queries are read-only and may run on any number of threads.
//
// SegmentGrid grows step by step (the segments of earlier steps): a list per slot, linked through the
// segments. StepSegmentGrid holds one step's moves, built at once: a slot's segments lie together (a
// counting sort), so a query reads a few contiguous runs instead of chasing a list through memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/large_pages.h"

namespace ug {

// The cells and slots both grids share.
class GridCells {
public:
    explicit GridCells(float reach_m) : reach_(reach_m), cell_(2.0f * reach_m * 1.001f), inv_cell_(1.0f / cell_) {}

    float reach() const { return reach_; }
    glm::ivec3 cellOf(glm::vec3 p) const { return glm::ivec3(glm::floor(p * inv_cell_)); }
    // The lowest cell of the 2 x 2 x 2 block whose cells hold every midpoint within the reach of p: the
    // reach's cube around p lies in p's cell and its neighbours on the sides p is nearer to.
    glm::ivec3 blockOf(glm::vec3 p) const {
        const glm::vec3 f = p * inv_cell_;
        const glm::ivec3 c(glm::floor(f));
        const glm::vec3 frac = f - glm::vec3(c);
        return {c.x - (frac.x < 0.5f), c.y - (frac.y < 0.5f), c.z - (frac.z < 0.5f)};
    }
    // Linear in the cell's coordinates, so neighbouring cells along x take neighbouring slots (a query's
    // two cells along x are one run) and the queries of neighbouring strands (close ids, close places)
    // touch the same cache lines, where a scrambling hash sends each lookup somewhere new. Distinct cells
    // that alias only lengthen a slot.
    static uint32_t hash(glm::ivec3 c) { return uint32_t(c.x) + uint32_t(c.y) * 4099u + uint32_t(c.z) * 16'851'989u; }

    // Calls scan(slot) for the slots (of a table of mask + 1) of the 2 x 2 x 2 cells around p, until one
    // returns true; returns whether one did. The block's two cells along x take neighbouring slots.
    template <typename Scan>
    bool anySlotAround(glm::vec3 p, uint32_t mask, Scan&& scan) const {
        const glm::ivec3 lo = blockOf(p);
        for (int dz = 0; dz <= 1; ++dz)
            for (int dy = 0; dy <= 1; ++dy) {
                const uint32_t row = hash(glm::ivec3(lo.x, lo.y + dy, lo.z + dz));
                if (scan(row & mask) || scan((row + 1u) & mask)) return true;
            }
        return false;
    }

private:
    float reach_, cell_, inv_cell_;
};

class SegmentGrid {
public:
    static constexpr uint32_t kNone = 0xffffffffu;

    // reach_m > 0: the distance between midpoints that queries look for.
    explicit SegmentGrid(float reach_m = 1.0f) : cells_(reach_m) {}

    // Forgets every segment; keeps the cell size and the memory.
    void clear();
    // Forgets every segment and takes a new reach; keeps the memory.
    void reset(float reach_m) {
        cells_ = GridCells(reach_m);
        clear();
    }
    // Files segment `id` (ids are the caller's, dense from 0) with its midpoint and a tag of the caller's
    // (the strand) kept beside it, so a query rejects most segments without touching the caller's data.
    void insert(uint32_t id, glm::vec3 midpoint, uint32_t tag);
    // insert() for each segment of a batch (of distinct ids), in its order, on up to `threads` threads:
    // each links the slots of its own share of the table in the batch's order, so every list comes out as
    // serial insertion leaves it (a growth files each step's segments at once; serially, that took a
    // fifth of a fur ball's growth).
    struct Filed {
        uint32_t id;
        uint32_t tag;
        glm::vec3 midpoint;
    };
    void insert(const std::vector<Filed>& batch, int threads);
    // Sizes the table for `segments` segments with ids below that, so filing them never rehashes.
    void reserve(size_t segments);
    size_t size() const { return count_; }

    // Calls visit(id, tag) for every segment filed in the 2 x 2 x 2 cells around midpoint (and any sharing
    // their slots) whose midpoint lies within the reach of it, and for no other; stops early when visit
    // returns true, and returns whether one did.
    template <typename Visit>
    bool anyNear(glm::vec3 midpoint, Visit&& visit) const {
        if (heads_.empty()) return false;
        const float reach2 = cells_.reach() * cells_.reach();
        return cells_.anySlotAround(midpoint, mask_, [&](uint32_t slot) {
            for (uint32_t id = heads_[slot]; id != kNone;) {
                const Entry& e = entries_[id];
                const glm::vec3 d = e.mid - midpoint;
                if (glm::dot(d, d) <= reach2 && visit(id, tags_[id])) return true;
                id = e.next;
            }
            return false;
        });
    }

private:
    // 16 bytes, what a query reads for every segment it visits; the tag is read only for the few
    // within reach.
    struct Entry {
        glm::vec3 mid;
        uint32_t next;
    };

    void rehash(size_t slots);
    void sizeFor(uint32_t id);  // entries_ and tags_ reach id
    void store(uint32_t id, glm::vec3 midpoint, uint32_t tag);
    void link(uint32_t id, uint32_t slot) {
        entries_[id].next = heads_[slot];
        heads_[slot] = id;
    }

    GridCells cells_;
    uint32_t mask_ = 0;
    size_t count_ = 0;
    // A fur ball's are tens of megabytes each (large_pages.h).
    LargeVector<uint32_t> heads_;
    LargeVector<Entry> entries_;  // by id
    LargeVector<uint32_t> tags_;  // by id
    LargeVector<uint32_t> ids_;   // filed ids in insertion order (rehash keeps their order)
    std::vector<uint32_t> slot_;  // scratch: each batch segment's slot (a growth files a batch a step)
};

class StepSegmentGrid {
public:
    explicit StepSegmentGrid(float reach_m = 1.0f) : cells_(reach_m) {}
    // Takes a new reach for the next build.
    void reset(float reach_m) { cells_ = GridCells(reach_m); }

    // Replaces the grid's segments by the batch's (ids need not be dense), on up to `threads` threads;
    // keeps the memory.
    void build(const std::vector<SegmentGrid::Filed>& batch, int threads);

    // As SegmentGrid::anyNear, for the segments with ids below `below` only (the test of a move against
    // the moves of lower ids): a slot keeps the batch's order, so when the batch's ids ascend, the scan of
    // a slot stops at the first id that does not qualify.
    template <typename Visit>
    bool anyNear(glm::vec3 midpoint, Visit&& visit, uint32_t below = SegmentGrid::kNone) const {
        if (entries_.empty()) return false;
        const float reach2 = cells_.reach() * cells_.reach();
        return cells_.anySlotAround(midpoint, mask_, [&](uint32_t slot) {
            for (uint32_t i = start_[slot]; i < start_[slot + 1]; ++i) {
                if (entries_[i].id >= below) {
                    if (ascending_) break;
                    continue;
                }
                const glm::vec3 d = entries_[i].mid - midpoint;
                if (glm::dot(d, d) <= reach2 && visit(entries_[i].id, tags_[i])) return true;
            }
            return false;
        });
    }

private:
    struct Entry {
        glm::vec3 mid;
        uint32_t id;
    };

    GridCells cells_;
    uint32_t mask_ = 0;
    bool ascending_ = true;        // the batch's ids ascend
    std::vector<uint32_t> start_;  // per slot, where its segments begin in entries_; one more at the end
    std::vector<Entry> entries_;   // by slot, in the batch's order within one
    std::vector<uint32_t> tags_;   // beside entries_
    std::vector<uint32_t> slot_;   // scratch: each batch segment's slot
};

// Squared distance between segments p0p1 and q0q1 (either may be a point).
float segmentSegmentDistance2(glm::vec3 p0, glm::vec3 p1, glm::vec3 q0, glm::vec3 q1);

}  // namespace ug
