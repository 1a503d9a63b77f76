// A region job's instances as a compact binary file, for the join step to merge exactly: the selected
// (tile, candidate) ids and their settled drops, with a JSON header naming the plan and the region they
// belong to. glTF holds transforms as floats; this holds the ids, so a join rebuilds the very instances
// the single-process run would, and can tell a region of another plan from one of this plan.
//
// Layout (little-endian):
//   "UGIL" | u32 version (1) | u64 Ghost Tile key | u32 header bytes | header (JSON text)
//   | u64 tile count | u64 instance count | u8 has_drops
//   | per tile: u64 key | u32 n | n x u32 ids (ascending) | n x u16 drops (when has_drops)
//   | u64 hashBytes(everything before)
// Tiles come in ascending key order. The reader checks every count against the file's size before it
// allocates, the order, and the checksum, so a truncated or corrupt file is refused with its reason.
#pragma once

#include <cstdint>
#include <string>

#include "instancer/instance_store.h"
#include "instancer/settling.h"

namespace ug {

struct InstanceListFile {
    uint64_t ghost_tile_key = 0;
    std::string header_json;  // a JSON object (the plan's hash and the task, for region jobs)
    InstanceStore store;
    bool has_drops = false;
    SettledDrops drops;  // one per instance of store when has_drops
};

// Written atomically (core/atomic_file.h). `drops` may be null (no settling).
bool writeInstanceListFile(const std::string& path, uint64_t ghost_tile_key, const std::string& header_json,
                           const InstanceStore& store, const SettledDrops* drops, std::string* error);

// Errors name the path and the reason ("truncated at byte N", "checksum mismatch", ...).
bool readInstanceListFile(const std::string& path, InstanceListFile* out, std::string* error);

}  // namespace ug
