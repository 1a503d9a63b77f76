// The instantiation result: which (tile, candidate) pairs are objects. Never transforms: an instance's
// frame is its Ghost Tile candidate's frame moved to its tile, rebuilt on demand (exporter, renderer).
//
// Storage: tiles sorted by packed key; per tile its selected candidate ids, ascending, delta-encoded as
// LEB128 varints. With hundreds of candidates per tile the gaps fit in one byte, so an instance costs about
// 1 byte plus the tile's 12-byte header shared by its instances (target: <= 4 bytes per instance).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace ug {

class InstanceStore {
public:
    // Appends a tile; tiles must come in ascending key order, ids ascending. Tiles with no ids are skipped.
    void appendTile(uint64_t tile_key, std::span<const uint32_t> candidate_ids);
    void clear();

    uint64_t instanceCount() const { return instance_count_; }
    size_t tileCount() const { return tile_keys_.size(); }
    uint64_t tileKey(size_t tile) const { return tile_keys_[tile]; }
    // Bytes held: tile keys + offsets + encoded ids (capacity slack excluded).
    uint64_t byteSize() const;

    // Decodes tile `tile`'s ids (ascending) into *out (cleared first).
    void tileIds(size_t tile, std::vector<uint32_t>* out) const;
    // Calls f(tile_key, candidate_id) for every instance in (tile key, id) order.
    template <typename F>
    void forEach(F&& f) const {
        std::vector<uint32_t> ids;
        for (size_t t = 0; t < tile_keys_.size(); ++t) {
            tileIds(t, &ids);
            for (uint32_t j : ids) f(tile_keys_[t], j);
        }
    }
    // The tile's index, or -1.
    int64_t findTile(uint64_t tile_key) const;

    bool operator==(const InstanceStore& o) const {
        return tile_keys_ == o.tile_keys_ && offsets_ == o.offsets_ && bytes_ == o.bytes_;
    }

private:
    std::vector<uint64_t> tile_keys_;
    std::vector<uint32_t> offsets_{0};  // tile t's bytes are [offsets_[t], offsets_[t + 1])
    std::vector<uint8_t> bytes_;
    uint64_t instance_count_ = 0;
};

}  // namespace ug
