#include "ghosttile/collision_graph.h"

namespace ug {

void CollisionGraph::encodeRow(const uint32_t* keys, size_t count, std::vector<uint8_t>* bytes) {
    uint32_t previous = 0;
    for (size_t k = 0; k < count; ++k) {
        uint32_t delta = keys[k] - previous;
        previous = keys[k];
        while (delta >= 0x80) {
            bytes->push_back(uint8_t(delta | 0x80));
            delta >>= 7;
        }
        bytes->push_back(uint8_t(delta));
    }
}

bool CollisionGraph::fromRows(uint32_t node_count, const std::vector<std::vector<uint32_t>>& rows,
                              CollisionGraph* out, std::string* error) {
    if (rows.size() != node_count) {
        *error = "collision graph: " + std::to_string(rows.size()) + " rows for " + std::to_string(node_count) +
                 " nodes";
        return false;
    }
    std::vector<uint32_t> offsets(size_t(node_count) + 1, 0);
    std::vector<uint8_t> bytes;
    for (uint32_t i = 0; i < node_count; ++i) {
        const auto& row = rows[i];
        for (size_t k = 0; k < row.size(); ++k) {
            if (row[k] >= uint64_t(node_count) * kOffsetCount || (k > 0 && row[k] <= row[k - 1])) {
                *error = "collision graph: row " + std::to_string(i) + " is unsorted or has key " +
                         std::to_string(row[k]) + " out of range";
                return false;
            }
        }
        encodeRow(row.data(), row.size(), &bytes);
        offsets[i + 1] = uint32_t(bytes.size());
    }
    return fromEncoded(node_count, std::move(offsets), std::move(bytes), out, error);
}

bool CollisionGraph::fromEncoded(uint32_t node_count, std::vector<uint32_t> row_offsets,
                                 std::vector<uint8_t> bytes, CollisionGraph* out, std::string* error) {
    if (row_offsets.size() != size_t(node_count) + 1 || row_offsets[0] != 0 ||
        row_offsets.back() != bytes.size()) {
        *error = "collision graph: row offsets do not match the edge stream";
        return false;
    }
    const uint64_t key_limit = uint64_t(node_count) * kOffsetCount;
    uint64_t edges = 0;
    for (uint32_t i = 0; i < node_count; ++i) {
        uint32_t begin = row_offsets[i], end = row_offsets[i + 1];
        if (end < begin) {
            *error = "collision graph: row " + std::to_string(i) + " has a negative length";
            return false;
        }
        // Only the last offset was checked against the stream: a middle one may point past it.
        if (end > bytes.size()) {
            *error = "collision graph: row " + std::to_string(i) + " ends past the edge stream";
            return false;
        }
        uint64_t key = 0;
        bool first = true;
        uint32_t p = begin;
        while (p < end) {
            // Decode defensively here (the stream may come from a file); forEachNeighbor then trusts it.
            uint64_t delta = 0;
            int shift = 0;
            for (;;) {
                if (p >= end || shift > 28) {
                    *error = "collision graph: row " + std::to_string(i) + " has a truncated edge";
                    return false;
                }
                uint8_t b = bytes[p++];
                delta |= uint64_t(b & 0x7f) << shift;
                shift += 7;
                if (!(b & 0x80)) break;
            }
            if (!first && delta == 0) {
                *error = "collision graph: row " + std::to_string(i) + " repeats an edge";
                return false;
            }
            key += delta;
            first = false;
            if (key >= key_limit) {
                *error = "collision graph: row " + std::to_string(i) + " names a candidate out of range";
                return false;
            }
            ++edges;
        }
    }
    out->row_offsets_ = std::move(row_offsets);
    out->bytes_ = std::move(bytes);
    out->edge_count_ = edges;
    return true;
}

uint32_t CollisionGraph::degree(uint32_t i) const {
    uint32_t n = 0;
    forEachNeighbor(i, [&](uint32_t, uint32_t) { ++n; });
    return n;
}

bool CollisionGraph::hasEdge(uint32_t i, uint32_t j, uint32_t offset_index) const {
    const uint32_t wanted = j * kOffsetCount + offset_index;
    bool found = false;
    forEachNeighbor(i, [&](uint32_t nj, uint32_t no) { found |= (nj * kOffsetCount + no) == wanted; });
    return found;
}

}  // namespace ug
