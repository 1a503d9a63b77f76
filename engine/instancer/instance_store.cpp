#include "instancer/instance_store.h"

#include <algorithm>
#include <cassert>

namespace ug {

void InstanceStore::appendTile(uint64_t tile_key, std::span<const uint32_t> ids) {
    if (ids.empty()) return;
    assert(tile_keys_.empty() || tile_keys_.back() < tile_key);
    uint32_t previous = 0;
    for (size_t k = 0; k < ids.size(); ++k) {
        assert(k == 0 || ids[k] > ids[k - 1]);
        uint32_t v = ids[k] - previous;  // the first id is stored as itself
        previous = ids[k];
        while (v >= 0x80) {
            bytes_.push_back(uint8_t(v | 0x80));
            v >>= 7;
        }
        bytes_.push_back(uint8_t(v));
    }
    tile_keys_.push_back(tile_key);
    offsets_.push_back(uint32_t(bytes_.size()));
    instance_count_ += ids.size();
}

void InstanceStore::clear() {
    tile_keys_.clear();
    offsets_.assign(1, 0);
    bytes_.clear();
    instance_count_ = 0;
}

uint64_t InstanceStore::byteSize() const {
    return tile_keys_.size() * sizeof(uint64_t) + offsets_.size() * sizeof(uint32_t) + bytes_.size();
}

void InstanceStore::tileIds(size_t tile, std::vector<uint32_t>* out) const {
    out->clear();
    const uint8_t* p = bytes_.data() + offsets_[tile];
    const uint8_t* end = bytes_.data() + offsets_[tile + 1];
    uint32_t id = 0;
    while (p < end) {
        uint32_t v = 0;
        int shift = 0;
        while (*p & 0x80) {
            v |= uint32_t(*p++ & 0x7f) << shift;
            shift += 7;
        }
        v |= uint32_t(*p++) << shift;
        id += v;
        out->push_back(id);
    }
}

int64_t InstanceStore::findTile(uint64_t tile_key) const {
    auto it = std::lower_bound(tile_keys_.begin(), tile_keys_.end(), tile_key);
    if (it == tile_keys_.end() || *it != tile_key) return -1;
    return it - tile_keys_.begin();
}

}  // namespace ug
