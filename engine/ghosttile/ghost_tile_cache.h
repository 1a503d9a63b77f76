// The Ghost Tile cache: a binary file so the editor and batch jobs start without rebuilding.
//
// Layout (little-endian):
//   magic "UGGHOST\0" | u32 format version | u32 header bytes | u64 key | u64 payload bytes |
//   u64 payload checksum | payload
// The payload holds the settings, candidate frames, the collision graph stream and the statistics.
// A file is used only if every check passes: magic, version, key (the inputs' hash), size and checksum;
// otherwise the caller rebuilds. A cache is never trusted: loadOrBuildGhostTile also checks every payload
// value of a loaded tile against the scene's inputs (ghost_tile_verify.h) before it uses it.
#pragma once

#include <cstdint>
#include <string>

#include "ghosttile/ghost_tile.h"

namespace ug {

// 2: GhostTileSettings::variants after the seed. A file of another version is refused as stale and rebuilt.
constexpr uint32_t kGhostTileCacheVersion = 2;

// Writes atomically: a temporary file in the same folder, flushed, then renamed over `path`.
bool saveGhostTileCache(const std::string& path, const GhostTile& tile, std::string* error);

// Reads and verifies. expected_key: the key of the current inputs (0 accepts any key, for inspection).
// Errors say why the file was refused ("checksum mismatch", "truncated: 1200 of 5344 bytes", ...).
bool loadGhostTileCache(const std::string& path, uint64_t expected_key, GhostTile* out, std::string* error);

enum class CacheOutcome : uint8_t { Loaded, BuiltMissing, BuiltStale, BuiltCorrupt };
const char* cacheOutcomeName(CacheOutcome outcome);

// The cache file name for a key inside `cache_dir`: "<dir>/ghosttile-<16 hex digits>.ugt".
std::string ghostTileCachePath(const std::string& cache_dir, uint64_t key);

// Loads the tile for `input` from cache_dir when a valid file exists and agrees with `input`
// (verifyGhostTileAgainstInput), else builds it and writes the cache; a refused file is named in *note
// with the reason ("disagrees with the scene: candidate 12: position differs ..."). A failure to write
// the cache is reported in *note too, not as an error: the tile is still good.
bool loadOrBuildGhostTile(const std::string& cache_dir, const GhostTileInput& input, const BuildOptions& options,
                          GhostTile* out, CacheOutcome* outcome, std::string* note, std::string* error);

}  // namespace ug
