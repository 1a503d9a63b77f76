// Integer tile coordinates of the infinite Ghost Tile grid, anchored at the world origin: tile t covers
// [t * s, (t + 1) * s) on every axis. A tile is packed into 64 bits (21 bits per axis, biased) so it can key
// hash maps and order ties; the packed order is the tie-break order of instantiation keys.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

namespace ug {

constexpr int32_t kTileCoordLimit = (1 << 20) - 1;  // |coordinate| <= this: ±524 km with 0.5 m tiles

inline uint64_t packTile(const glm::ivec3& t) {
    const uint64_t bias = uint64_t(1) << 20;
    return ((uint64_t(int64_t(t.x) + int64_t(bias)) & 0x1fffff) << 42) |
           ((uint64_t(int64_t(t.y) + int64_t(bias)) & 0x1fffff) << 21) |
           (uint64_t(int64_t(t.z) + int64_t(bias)) & 0x1fffff);
}

inline glm::ivec3 unpackTile(uint64_t key) {
    const int64_t bias = int64_t(1) << 20;
    return glm::ivec3(int32_t(int64_t((key >> 42) & 0x1fffff) - bias), int32_t(int64_t((key >> 21) & 0x1fffff) - bias),
                      int32_t(int64_t(key & 0x1fffff) - bias));
}

// The tile whose half-open cell holds p.
inline glm::ivec3 tileOf(glm::vec3 p_m, float tile_size_m) {
    return glm::ivec3(int32_t(std::floor(p_m.x / tile_size_m)), int32_t(std::floor(p_m.y / tile_size_m)),
                      int32_t(std::floor(p_m.z / tile_size_m)));
}

// The world position of a tile's corner. Every world position of a candidate is tileOrigin + tile-space
// position, computed by this one expression, so all code paths agree to the bit.
inline glm::vec3 tileOrigin(const glm::ivec3& t, float tile_size_m) { return glm::vec3(t) * tile_size_m; }

}  // namespace ug
