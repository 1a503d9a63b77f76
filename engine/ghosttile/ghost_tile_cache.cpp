#include "ghosttile/ghost_tile_cache.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <type_traits>
#include <vector>

#include <unistd.h>

#include "core/atomic_file.h"
#include "core/hash.h"
#include "ghosttile/ghost_tile_verify.h"

namespace ug {

namespace {

constexpr char kMagic[8] = {'U', 'G', 'G', 'H', 'O', 'S', 'T', '\0'};
constexpr uint32_t kHeaderBytes = 8 + 4 + 4 + 8 + 8 + 8;

class Writer {
public:
    template <typename T>
    void put(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        const auto* p = reinterpret_cast<const unsigned char*>(&v);
        bytes.insert(bytes.end(), p, p + sizeof(T));
    }
    template <typename T>
    void putArray(const std::vector<T>& v) {
        put(uint64_t(v.size()));
        if (v.empty()) return;
        const auto* p = reinterpret_cast<const unsigned char*>(v.data());
        bytes.insert(bytes.end(), p, p + v.size() * sizeof(T));
    }
    std::vector<unsigned char> bytes;
};

class Reader {
public:
    Reader(const unsigned char* p, size_t n) : p_(p), end_(p + n) {}
    template <typename T>
    bool get(T* v) {
        if (size_t(end_ - p_) < sizeof(T)) return false;
        std::memcpy(v, p_, sizeof(T));
        p_ += sizeof(T);
        return true;
    }
    template <typename T>
    bool getArray(std::vector<T>* v, uint64_t max_count) {
        uint64_t count;
        if (!get(&count) || count > max_count || count > size_t(end_ - p_) / sizeof(T)) return false;
        v->resize(count);
        // An empty array is legal (a tile without colliding pairs writes one); memcpy must not see the
        // null data() of an empty vector.
        if (count > 0) std::memcpy(v->data(), p_, count * sizeof(T));
        p_ += count * sizeof(T);
        return true;
    }
    bool atEnd() const { return p_ == end_; }

private:
    const unsigned char* p_;
    const unsigned char* end_;
};

}  // namespace

const char* cacheOutcomeName(CacheOutcome outcome) {
    switch (outcome) {
        case CacheOutcome::Loaded: return "loaded";
        case CacheOutcome::BuiltMissing: return "built (no cache)";
        case CacheOutcome::BuiltStale: return "built (stale cache)";
        case CacheOutcome::BuiltCorrupt: return "built (corrupt cache)";
    }
    return "?";
}

std::string ghostTileCachePath(const std::string& cache_dir, uint64_t key) {
    return (std::filesystem::path(cache_dir) / ("ghosttile-" + hex64(key) + ".ugt")).string();
}

bool saveGhostTileCache(const std::string& path, const GhostTile& tile, std::string* error) {
    Writer w;
    w.put(tile.settings.tile_size_m);
    w.put(tile.settings.delta_m);
    w.put(tile.settings.seed);
    w.put(tile.settings.variants);
    const CandidateSet& c = tile.candidates;
    w.putArray(c.type_begin);
    w.putArray(c.type);
    w.putArray(c.position);
    w.putArray(c.rotation);
    w.putArray(c.scale);
    w.putArray(tile.graph.rowOffsets());
    w.putArray(tile.graph.encodedBytes());
    w.put(tile.stats.build_seconds);

    Writer header;
    for (char ch : kMagic) header.put(ch);
    header.put(kGhostTileCacheVersion);
    header.put(kHeaderBytes);
    header.put(tile.key);
    header.put(uint64_t(w.bytes.size()));
    header.put(hashBytes(w.bytes.data(), w.bytes.size()));
    header.bytes.insert(header.bytes.end(), w.bytes.begin(), w.bytes.end());
    return writeFileAtomically(path, header.bytes.data(), header.bytes.size(), error);
}

bool loadGhostTileCache(const std::string& path, uint64_t expected_key, GhostTile* out, std::string* error) {
    std::vector<unsigned char> data;
    if (!readWholeFile(path, &data, error)) return false;
    auto fail = [&](const std::string& why) {
        *error = path + ": " + why;
        return false;
    };
    if (data.size() < kHeaderBytes) {
        return fail("truncated: " + std::to_string(data.size()) + " bytes, shorter than the " +
                    std::to_string(kHeaderBytes) + "-byte header");
    }
    if (std::memcmp(data.data(), kMagic, 8) != 0) return fail("not a Ghost Tile cache (bad magic)");
    Reader h(data.data() + 8, kHeaderBytes - 8);
    uint32_t version = 0, header_bytes = 0;
    uint64_t key = 0, payload_bytes = 0, checksum = 0;
    h.get(&version);
    h.get(&header_bytes);
    h.get(&key);
    h.get(&payload_bytes);
    h.get(&checksum);
    if (version != kGhostTileCacheVersion) {
        // Another version's file is not damaged, only out of date: "stale" makes it a stale rebuild.
        return fail("stale format version " + std::to_string(version) + ", expected " +
                    std::to_string(kGhostTileCacheVersion));
    }
    if (header_bytes != kHeaderBytes) return fail("unexpected header size " + std::to_string(header_bytes));
    if (expected_key != 0 && key != expected_key) {
        return fail("stale: built for inputs " + hex64(key) + ", current inputs are " + hex64(expected_key));
    }
    if (payload_bytes != data.size() - kHeaderBytes) {
        return fail("truncated or padded: payload is " + std::to_string(data.size() - kHeaderBytes) +
                    " bytes, header says " + std::to_string(payload_bytes));
    }
    const unsigned char* payload = data.data() + kHeaderBytes;
    if (hashBytes(payload, payload_bytes) != checksum) return fail("checksum mismatch (corrupt file)");

    // The checksum passed, but a file written by a buggy or hostile writer must still not crash us:
    // every array is bounds-checked and the graph stream is fully validated.
    Reader r(payload, payload_bytes);
    GhostTile tile;
    tile.key = key;
    CandidateSet& c = tile.candidates;
    const uint64_t max_n = kMaxCandidatesPerTile;
    std::vector<uint32_t> row_offsets;
    std::vector<uint8_t> stream;
    bool ok = r.get(&tile.settings.tile_size_m) && r.get(&tile.settings.delta_m) && r.get(&tile.settings.seed) &&
              r.get(&tile.settings.variants) &&
              r.getArray(&c.type_begin, 65536) && r.getArray(&c.type, max_n) && r.getArray(&c.position, max_n) &&
              r.getArray(&c.rotation, max_n) && r.getArray(&c.scale, max_n) &&
              r.getArray(&row_offsets, max_n + 1) && r.getArray(&stream, kMaxGraphBytes) &&
              r.get(&tile.stats.build_seconds) && r.atEnd();
    if (!ok) return fail("payload does not match its declared layout");
    if (tile.settings.variants < 1 || tile.settings.variants > kMaxTileVariants)
        return fail("variants " + std::to_string(tile.settings.variants) + " out of range [1, " +
                    std::to_string(kMaxTileVariants) + "]");
    c.variants = tile.settings.variants;
    const uint32_t n = c.size();
    if (c.type_begin.size() < 2 || c.type_begin.front() != 0 || c.type_begin.back() != n ||
        c.position.size() != n || c.rotation.size() != n || c.scale.size() != n) {
        return fail("candidate arrays disagree in size");
    }
    // Order first, over every entry: with the ends fixed at 0 and n, ordered entries all lie in [0, n],
    // so the walk below stays inside the arrays.
    for (size_t t = 0; t + 1 < c.type_begin.size(); ++t)
        if (c.type_begin[t] > c.type_begin[t + 1]) return fail("candidate type ranges are not ordered");
    // The instantiator cuts every type range into `variants` equal parts.
    for (size_t t = 0; t + 1 < c.type_begin.size(); ++t)
        if ((c.type_begin[t + 1] - c.type_begin[t]) % c.variants != 0)
            return fail("candidate type " + std::to_string(t) + " does not split into " + std::to_string(c.variants) +
                        " variants");
    for (size_t t = 0; t + 1 < c.type_begin.size(); ++t) {
        for (uint32_t i = c.type_begin[t]; i < c.type_begin[t + 1]; ++i)
            if (c.type[i] != t) return fail("candidate " + std::to_string(i) + " is filed under the wrong type");
    }
    std::string graph_error;
    if (!CollisionGraph::fromEncoded(n, std::move(row_offsets), std::move(stream), &tile.graph, &graph_error))
        return fail(graph_error);
    GhostTileStats& st = tile.stats;
    st.candidate_count = n;
    st.pair_count = tile.graph.edgeCount() / 2;
    st.rho = n ? double(st.pair_count) / double(n) : 0.0;
    st.graph_bytes = tile.graph.byteSize();
    st.total_bytes = st.graph_bytes + uint64_t(n) * (sizeof(uint16_t) + sizeof(glm::vec3) + sizeof(glm::quat) +
                                                     sizeof(float));
    st.bytes_per_pair = st.pair_count ? double(st.graph_bytes) / double(st.pair_count) : 0.0;
    *out = std::move(tile);
    return true;
}

bool loadOrBuildGhostTile(const std::string& cache_dir, const GhostTileInput& input, const BuildOptions& options,
                          GhostTile* out, CacheOutcome* outcome, std::string* note, std::string* error) {
    if (!validateGhostTileInput(input, error)) return false;
    const uint64_t key = ghostTileKey(input);
    const std::string path = ghostTileCachePath(cache_dir, key);
    note->clear();
    std::string load_error;
    *outcome = CacheOutcome::BuiltMissing;
    if (std::filesystem::exists(path)) {
        GhostTile loaded;
        std::string why;
        if (loadGhostTileCache(path, key, &loaded, &load_error)) {
            // The checksum only proves the file is what its writer wrote, not that the writer was right.
            if (verifyGhostTileAgainstInput(loaded, input, &why)) {
                *out = std::move(loaded);
                *outcome = CacheOutcome::Loaded;
                return true;
            }
            load_error = path + ": disagrees with the scene: " + why;
        }
        *outcome = load_error.find("stale") != std::string::npos ? CacheOutcome::BuiltStale
                                                                  : CacheOutcome::BuiltCorrupt;
        *note = "cache refused, rebuilding: " + load_error;
    }
    if (!buildGhostTile(input, options, out, error)) return false;
    std::error_code ec;
    std::filesystem::create_directories(cache_dir, ec);
    std::string save_error;
    if (!saveGhostTileCache(path, *out, &save_error)) {
        *note += (note->empty() ? "" : "; ") + std::string("could not write the cache: ") + save_error;
    }
    return true;
}

}  // namespace ug
