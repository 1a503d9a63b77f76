#include "core/hash.h"

#include <algorithm>
#include <cstdio>

namespace ug {

namespace {
inline uint64_t rotl(uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }
inline uint64_t load64(const unsigned char* p) {
    uint64_t v;
    std::memcpy(&v, p, 8);
    return v;
}
constexpr uint64_t kPrime1 = 0x9e3779b185ebca87ull;
constexpr uint64_t kPrime2 = 0xc2b2ae3d27d4eb4full;
}  // namespace

// Four independent lanes over 32-byte blocks (the xxHash64 layout), so checksumming a multi-megabyte
// cache file costs well under a millisecond per megabyte.
void Hasher::block(const unsigned char* p) {
    for (int lane = 0; lane < 4; ++lane) {
        uint64_t v = state_[lane] + load64(p + 8 * lane) * kPrime2;
        state_[lane] = rotl(v, 31) * kPrime1;
    }
}

void Hasher::addBytes(const void* data, size_t size) {
    // Nothing to add; an empty vector's data() may be null, which memcpy must never be given.
    if (size == 0) return;
    const unsigned char* p = static_cast<const unsigned char*>(data);
    total_ += size;
    if (tail_size_ > 0) {
        size_t take = std::min(size, sizeof(tail_) - tail_size_);
        std::memcpy(tail_ + tail_size_, p, take);
        tail_size_ += take;
        p += take;
        size -= take;
        if (tail_size_ < sizeof(tail_)) return;
        block(tail_);
        tail_size_ = 0;
    }
    while (size >= 32) {
        block(p);
        p += 32;
        size -= 32;
    }
    std::memcpy(tail_, p, size);
    tail_size_ = size;
}

uint64_t Hasher::value() const {
    uint64_t h = rotl(state_[0], 1) + rotl(state_[1], 7) + rotl(state_[2], 12) + rotl(state_[3], 18);
    h = mix64(h ^ total_);
    for (size_t i = 0; i < tail_size_; ++i) h = mix64(h ^ (uint64_t(tail_[i]) << ((i % 8) * 8)) ^ i);
    return mix64(h);
}

uint64_t hashBytes(const void* data, size_t size) {
    Hasher h;
    h.addBytes(data, size);
    return h.value();
}

std::string hex64(uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

}  // namespace ug
