#include "io/instance_list_file.h"

#include <cstring>
#include <vector>

#include "core/atomic_file.h"
#include "core/hash.h"

namespace ug {

namespace {

constexpr char kMagic[4] = {'U', 'G', 'I', 'L'};
constexpr uint32_t kVersion = 1;
constexpr uint32_t kMaxHeaderBytes = 1u << 20;  // a header is a few hundred bytes; more is corruption

template <typename T>
void put(std::vector<unsigned char>* out, T v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));  // the formats we run on are little-endian (x86-64, aarch64)
    out->insert(out->end(), b, b + sizeof(T));
}

// A bounds-checked cursor over the file's bytes: every read says where it failed.
struct Reader {
    const unsigned char* data;
    size_t size;
    size_t at = 0;
    std::string problem;

    bool need(size_t n, const char* what) {
        if (size - at >= n) return true;
        problem = "truncated at byte " + std::to_string(at) + " (reading " + what + ")";
        return false;
    }
    template <typename T>
    bool get(T* v, const char* what) {
        if (!need(sizeof(T), what)) return false;
        std::memcpy(v, data + at, sizeof(T));
        at += sizeof(T);
        return true;
    }
};

bool readHeader(Reader* r, uint64_t* key, std::string* header) {
    if (!r->need(4, "the magic") || std::memcmp(r->data, kMagic, 4) != 0) {
        r->problem = "not an Undergrowth instance list (no UGIL magic)";
        return false;
    }
    r->at = 4;
    uint32_t version = 0, header_bytes = 0;
    if (!r->get(&version, "the version")) return false;
    if (version != kVersion) {
        r->problem = "version " + std::to_string(version) + " is not supported (this build reads " +
                     std::to_string(kVersion) + ")";
        return false;
    }
    if (!r->get(key, "the Ghost Tile key") || !r->get(&header_bytes, "the header size")) return false;
    if (header_bytes > kMaxHeaderBytes) {
        r->problem = "header of " + std::to_string(header_bytes) + " bytes is absurd";
        return false;
    }
    if (!r->need(header_bytes, "the header")) return false;
    header->assign(reinterpret_cast<const char*>(r->data + r->at), header_bytes);
    r->at += header_bytes;
    return true;
}

}  // namespace

bool writeInstanceListFile(const std::string& path, uint64_t ghost_tile_key, const std::string& header_json,
                           const InstanceStore& store, const SettledDrops* drops, std::string* error) {
    if (header_json.size() > kMaxHeaderBytes) {
        if (error) *error = path + ": the header is too large";
        return false;
    }
    std::vector<unsigned char> bytes;
    bytes.reserve(64 + header_json.size() + store.instanceCount() * 6 + store.tileCount() * 12);
    bytes.insert(bytes.end(), kMagic, kMagic + 4);
    put(&bytes, kVersion);
    put(&bytes, ghost_tile_key);
    put(&bytes, uint32_t(header_json.size()));
    bytes.insert(bytes.end(), header_json.begin(), header_json.end());
    put(&bytes, uint64_t(store.tileCount()));
    put(&bytes, store.instanceCount());
    put(&bytes, uint8_t(drops ? 1 : 0));
    std::vector<uint32_t> ids;
    for (size_t t = 0; t < store.tileCount(); ++t) {
        const uint64_t key = store.tileKey(t);
        store.tileIds(t, &ids);
        put(&bytes, key);
        put(&bytes, uint32_t(ids.size()));
        for (uint32_t id : ids) put(&bytes, id);
        if (drops) {
            const std::span<const uint16_t> d = drops->tile(key);
            if (d.size() != ids.size()) {
                if (error) *error = path + ": the drops do not match the instances (tile " + hex64(key) + ")";
                return false;
            }
            for (uint16_t v : d) put(&bytes, v);
        }
    }
    put(&bytes, hashBytes(bytes.data(), bytes.size()));
    return writeFileAtomically(path, bytes.data(), bytes.size(), error);
}

bool readInstanceListFile(const std::string& path, InstanceListFile* out, std::string* error) {
    std::vector<unsigned char> bytes;
    if (!readWholeFile(path, &bytes, error)) return false;
    Reader r{bytes.data(), bytes.size()};
    auto fail = [&](const std::string& why) {
        if (error) *error = path + ": " + why;
        return false;
    };
    *out = InstanceListFile{};
    if (!readHeader(&r, &out->ghost_tile_key, &out->header_json)) return fail(r.problem);
    if (bytes.size() < r.at + 8) return fail("truncated (no checksum)");
    uint64_t stored = 0;
    std::memcpy(&stored, bytes.data() + bytes.size() - 8, 8);
    if (stored != hashBytes(bytes.data(), bytes.size() - 8))
        return fail("checksum mismatch (corrupt or truncated)");
    r.size = bytes.size() - 8;
    uint64_t tiles = 0, instances = 0;
    uint8_t has_drops = 0;
    if (!r.get(&tiles, "the tile count") || !r.get(&instances, "the instance count") ||
        !r.get(&has_drops, "the drops flag"))
        return fail(r.problem);
    const size_t per_instance = has_drops ? 6 : 4;
    // Counts are checked against the bytes left before anything is sized by them.
    if (has_drops > 1 || tiles > (r.size - r.at) / 12 || instances > (r.size - r.at) / per_instance)
        return fail("the counts (" + std::to_string(tiles) + " tiles, " + std::to_string(instances) +
                    " instances) do not fit the file's " + std::to_string(bytes.size()) + " bytes");
    out->has_drops = has_drops == 1;
    std::vector<uint32_t> ids;
    std::vector<uint16_t> drops;
    uint64_t seen = 0, previous = 0;
    for (uint64_t t = 0; t < tiles; ++t) {
        uint64_t key = 0;
        uint32_t n = 0;
        if (!r.get(&key, "a tile key") || !r.get(&n, "a tile's count")) return fail(r.problem);
        if (t > 0 && key <= previous) return fail("tile keys are not ascending at tile " + std::to_string(t));
        if (n == 0 || !r.need(size_t(n) * per_instance, "a tile's instances")) {
            return fail(n == 0 ? "tile " + std::to_string(t) + " is empty" : r.problem);
        }
        previous = key;
        ids.resize(n);
        std::memcpy(ids.data(), bytes.data() + r.at, size_t(n) * 4);
        r.at += size_t(n) * 4;
        for (uint32_t i = 1; i < n; ++i)
            if (ids[i] <= ids[i - 1])
                return fail("candidate ids are not ascending in tile " + std::to_string(t));
        out->store.appendTile(key, ids);
        if (out->has_drops) {
            drops.resize(n);
            std::memcpy(drops.data(), bytes.data() + r.at, size_t(n) * 2);
            r.at += size_t(n) * 2;
            out->drops.append(key, drops);
        }
        seen += n;
    }
    if (seen != instances)
        return fail("holds " + std::to_string(seen) + " instances, its count says " +
                    std::to_string(instances));
    if (r.at != r.size) return fail(std::to_string(r.size - r.at) + " bytes after the last tile");
    return true;
}

}  // namespace ug
