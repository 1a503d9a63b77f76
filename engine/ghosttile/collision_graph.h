// The Ghost Tile's collision graph (Guérin et al. 2016, §4.1): directed edges (i, j, v) meaning
// "candidate i in this tile collides with candidate j in the tile at integer offset v ∈ {-1,0,1}^3".
// Every edge has its mirror (j, i, -v).
//
// Storage (compressed sparse rows): row i lists its edges as keys k = j * 27 + offsetIndex(v), sorted
// ascending, delta-encoded as LEB128 varints. Rows of a dense tile hold thousands of keys spread over
// 27 #N possible values, so most deltas fit in one byte: both directions of a colliding pair cost about
// 2 bytes, against the paper's ≈4.8 bytes per pair and our target, ≤ 4 (docs/architecture.md "Quality bars").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace ug {

constexpr uint32_t kOffsetCount = 27;
constexpr uint32_t kCenterOffset = 13;  // offsetIndex({0,0,0})

inline uint32_t offsetIndex(const glm::ivec3& v) { return uint32_t((v.x + 1) * 9 + (v.y + 1) * 3 + (v.z + 1)); }
inline glm::ivec3 offsetVector(uint32_t index) {
    return glm::ivec3(int(index / 9) - 1, int(index / 3 % 3) - 1, int(index % 3) - 1);
}
inline uint32_t mirrorOffset(uint32_t index) { return kOffsetCount - 1 - index; }

class CollisionGraph {
public:
    CollisionGraph() = default;

    // Builds from rows of keys (j * 27 + offset), each row sorted ascending without duplicates.
    // Returns false (with the reason) when a row is unsorted or a key is out of range.
    static bool fromRows(uint32_t node_count, const std::vector<std::vector<uint32_t>>& rows,
                         CollisionGraph* out, std::string* error);

    // Adopts an already encoded stream (from the builder or the cache) after checking it decodes:
    // every row ends exactly at its offset, keys are ascending and < 27 * node_count.
    static bool fromEncoded(uint32_t node_count, std::vector<uint32_t> row_offsets,
                            std::vector<uint8_t> bytes, CollisionGraph* out, std::string* error);

    uint32_t nodeCount() const { return row_offsets_.empty() ? 0 : uint32_t(row_offsets_.size() - 1); }
    uint64_t edgeCount() const { return edge_count_; }  // directed edges = 2 x colliding pairs
    uint64_t byteSize() const { return row_offsets_.size() * sizeof(uint32_t) + bytes_.size(); }

    // Calls f(j, offset_index) for every edge of row i, in ascending key order. No allocation.
    template <typename F>
    void forEachNeighbor(uint32_t i, F&& f) const {
        anyNeighbor(i, [&](uint32_t j, uint32_t offset) {
            f(j, offset);
            return false;
        });
    }

    // As forEachNeighbor, stopping at the first edge for which f returns true; returns whether it stopped.
    // The resolver stops a row at the first selected higher-key neighbour: most rows end early.
    template <typename F>
    bool anyNeighbor(uint32_t i, F&& f) const {
        const uint8_t* p = bytes_.data() + row_offsets_[i];
        const uint8_t* end = bytes_.data() + row_offsets_[i + 1];
        uint32_t key = 0;
        while (p < end) {
            key += decodeVarint(p);
            if (f(key / kOffsetCount, key % kOffsetCount)) return true;
        }
        return false;
    }

    uint32_t degree(uint32_t i) const;
    bool hasEdge(uint32_t i, uint32_t j, uint32_t offset_index) const;

    const std::vector<uint32_t>& rowOffsets() const { return row_offsets_; }
    const std::vector<uint8_t>& encodedBytes() const { return bytes_; }

    // Appends the varint encoding of a sorted row to `bytes` (used by the builder's workers).
    static void encodeRow(const uint32_t* keys, size_t count, std::vector<uint8_t>* bytes);

private:
    static uint32_t decodeVarint(const uint8_t*& p) {
        uint32_t v = *p & 0x7f;
        int shift = 7;
        while (*p++ & 0x80) {
            v |= uint32_t(*p & 0x7f) << shift;
            shift += 7;
        }
        return v;
    }

    std::vector<uint32_t> row_offsets_;  // byte offset of each row; node_count + 1 entries
    std::vector<uint8_t> bytes_;
    uint64_t edge_count_ = 0;
};

}  // namespace ug
