// Hashing for two jobs: content keys (cache files, scene fingerprints) and counter-based random numbers.
//
// Random numbers in Undergrowth never come from a generator's state: a value is a pure function of
// (seed, a, b, c), so the same candidate in the same tile gets the same number whatever thread, batch or
// order computed it (docs/architecture.md "Instantiation as a pure function").
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>

namespace ug {

// SplitMix64's finalizer: a bijective 64-bit mix with full avalanche.
inline uint64_t mix64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// A hash of up to four 64-bit words; order matters.
inline uint64_t hashWords(uint64_t a, uint64_t b = 0, uint64_t c = 0, uint64_t d = 0) {
    uint64_t h = mix64(a ^ 0x243f6a8885a308d3ull);
    h = mix64(h ^ b);
    h = mix64(h ^ c);
    return mix64(h ^ d);
}

// hashWords(a, b, c, d) for many d (the trials of one move): the state after a, b and c is mixed once,
// then hashLastWord(state, d) is exactly hashWords(a, b, c, d).
inline uint64_t hashFirstWords(uint64_t a, uint64_t b, uint64_t c) {
    return mix64(mix64(mix64(a ^ 0x243f6a8885a308d3ull) ^ b) ^ c);
}
inline uint64_t hashLastWord(uint64_t first_words, uint64_t d) { return mix64(first_words ^ d); }

// Uniform float in [0, 1) from the top 24 bits of a hash: exact, never 1.
inline float unitFloat(uint64_t h) { return float(h >> 40) * (1.0f / 16777216.0f); }
// Uniform double in [0, 1) from the top 53 bits.
inline double unitDouble(uint64_t h) { return double(h >> 11) * (1.0 / 9007199254740992.0); }

// Streaming 64-bit content hash (not cryptographic). Used for cache keys and file checksums; both the
// writer and the reader run the same code, so any change to the algorithm must bump the cache version.
class Hasher {
public:
    void addBytes(const void* data, size_t size);
    template <typename T>
    void add(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>, "hash plain values only");
        addBytes(&value, sizeof(T));
    }
    void addString(std::string_view s) {
        add(uint64_t(s.size()));
        addBytes(s.data(), s.size());
    }
    uint64_t value() const;

private:
    uint64_t state_[4] = {0x6a09e667f3bcc908ull, 0xbb67ae8584caa73bull, 0x3c6ef372fe94f82bull,
                          0xa54ff53a5f1d36f1ull};
    uint64_t total_ = 0;
    unsigned char tail_[32] = {};
    size_t tail_size_ = 0;
    void block(const unsigned char* p);
};

uint64_t hashBytes(const void* data, size_t size);

// "0x0123456789abcdef"-style fixed-width hex, for file names and messages.
std::string hex64(uint64_t v);

}  // namespace ug
