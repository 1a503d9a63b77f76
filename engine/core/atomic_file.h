// Files that are never half-written: write to a temporary file in the same folder, flush it to disk,
// then rename it over the target (atomic on POSIX file systems). Used for every save: projects, caches,
// exports, statistics.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace ug {

// Errors name the path and the system's reason (e.g. "out/x.glb: cannot create temporary file:
// Permission denied"). On failure the target is untouched and the temporary file is removed.
// The temporary file is ".<name>.tmp-<host>-<pid>-XXXXXX" beside the target; one left by a writer that
// was killed (same host, process gone; or over an hour old) is removed by the next write of the target.
bool writeFileAtomically(const std::string& path, const void* data, size_t size, std::string* error);
bool writeTextFileAtomically(const std::string& path, const std::string& text, std::string* error);

// The same for a file made of several pieces written back to back (a GLB header, its JSON and its binary
// chunk), so large outputs need not be copied into one contiguous block first.
struct ByteSpan {
    const void* data = nullptr;
    size_t size = 0;
};
bool writeFileAtomically(const std::string& path, const std::vector<ByteSpan>& parts, std::string* error);

// Reads a whole file; errors name the path and the reason. Refuses files larger than max_bytes.
bool readWholeFile(const std::string& path, std::vector<unsigned char>* out, std::string* error,
                   size_t max_bytes = size_t(4) << 30);
bool readTextFile(const std::string& path, std::string* out, std::string* error, size_t max_bytes = size_t(1) << 30);

}  // namespace ug
