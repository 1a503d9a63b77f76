// The fuzz targets: which reader each one drives, what an accepted result must satisfy (the promises in
// the reader's header), and the format-aware mutations that know where each format keeps its counts.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>

#include "core/hash.h"
#include "field/height_field.h"
#include "fuzz.h"
#include "ghosttile/ghost_tile.h"
#include "ghosttile/ghost_tile_cache.h"
#include "mesh/mesh_loader.h"
#include "particles/particle_json.h"
#include "particles/strand_growth.h"
#include "particles/strand_mesh.h"
#include "scene/project.h"
#include "scene/scene_compile.h"
#include "scene/scene_particles.h"

// stb's zlib codec (the library is linked anyway): the PNG mutation that rewrites pixel data behind a
// valid zlib stream inflates and deflates with it.
extern "C" {
char* stbi_zlib_decode_malloc(const char* buffer, int len, int* outlen);
unsigned char* stbi_zlib_compress(unsigned char* data, int data_len, int* out_len, int quality);
}

namespace ug::fuzz {

namespace {

Outcome rejected(std::string message) {
    Outcome o;
    o.message = std::move(message);
    return o;
}

// ---- scene: the load path of the CLI's loadSceneJob (app/cli/scene_job.cpp) ----------------------

// The Ghost Tile build is part of loading a scene, but its cost grows with the candidate count; above
// this many candidates in all a mutated count would only measure the build's speed (a 10 s "hang" that
// is just work), so larger tiles are validated but not built.
constexpr uint64_t kMaxBuiltCandidates = 1500;

Outcome runScene(const std::string& path) {
    Outcome o;
    Project project;
    std::string error;
    if (!loadProject(path, &project, &error)) return rejected(error);
    // project.h promises parseProject(projectToJson(p)) gives p back: a loaded scene must save to a file
    // that loads again, to the same text.
    const std::string saved = projectToJson(project);
    Project again;
    std::string again_error;
    if (!parseProject(saved, path, &again, &again_error))
        o.violation = "the saved form of an accepted scene does not load: " + again_error;
    else if (projectToJson(again) != saved)
        o.violation = "projectToJson(parseProject(projectToJson(p))) differs from projectToJson(p)";

    std::vector<DetailModel> models;
    if (!loadProjectModels(project, &models, &error)) return rejected(error);
    GhostTileInput input = ghostTileInput(project, models);
    // loadSceneJob prefixes the scene's path to the Ghost Tile's errors, which name only the type.
    if (!validateGhostTileInput(input, &error)) return rejected(path + ": " + error);
    uint64_t candidates = 0;
    for (const DetailTypeSettings& t : input.types) candidates += t.candidate_count;
    if (candidates <= kMaxBuiltCandidates) {
        GhostTile tile;
        if (!buildGhostTile(input, BuildOptions{.threads = 1}, &tile, &error)) return rejected(path + ": " + error);
        if (tile.candidates.size() != candidates && o.violation.empty())
            o.violation = "the tile has " + std::to_string(tile.candidates.size()) + " candidates, the types ask for " +
                          std::to_string(candidates);
    }
    std::shared_ptr<const HeightField> terrain;
    if (!loadTerrain(project, &terrain, &error)) return rejected(error);
    std::vector<ParticleSystemFile> particles;
    if (!loadSceneParticles(project, terrain, nullptr, &particles, &error)) return rejected(error);
    CompiledScene compiled;
    if (!compileScene(project, terrain, &compiled, &error)) return rejected(error);
    o.accepted = true;
    const Bounds& e = compiled.extent;
    bool extent_ok = compiled.types.size() == project.detail_types.size();
    for (int a = 0; a < 3; ++a)
        extent_ok = extent_ok && std::isfinite(e.lo[a]) && std::isfinite(e.hi[a]) && e.lo[a] < e.hi[a];
    if (!extent_ok && o.violation.empty())
        o.violation = "compileScene accepted a scene whose extent is not finite with min < max, or lost a type";
    return o;
}

// ---- meshes: loadMeshFile, one target per extension -----------------------------------------------

TriangleMesh sentinelMesh() {
    TriangleMesh m;
    m.positions = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
    m.indices = {0, 1, 2};
    return m;
}

Outcome runMesh(const std::string& path) {
    Outcome o;
    TriangleMesh mesh = sentinelMesh();
    std::string error;
    if (!loadMeshFile(path, &mesh, &error)) {
        o.message = error;
        if (mesh.positions != sentinelMesh().positions || mesh.indices != sentinelMesh().indices)
            o.violation = "loadMeshFile failed but changed its output (the header says it is untouched)";
        return o;
    }
    o.accepted = true;
    std::string why;
    if (!validateMesh(mesh, &why)) o.violation = "accepted a mesh that fails validateMesh: " + why;
    else if (mesh.normals.size() != mesh.positions.size()) o.violation = "accepted a mesh without one normal per vertex";
    return o;
}

// ---- particle systems: undergrowth grow's path (particle_json.h, strand_growth.h, strand_mesh.h) ------

// Growth is bounded by the file's own limits, which allow minutes of work: above this many particle-steps
// a mutated count would only measure the walk's speed, so larger systems are read but not grown.
constexpr uint64_t kMaxGrownParticleSteps = 20'000;

Outcome runParticles(const std::string& path) {
    Outcome o;
    ParticleSystemFile system;
    system.name = "untouched";
    std::string error;
    if (!loadParticleSystem(path, &system, &error)) {
        o.message = error;
        if (system.name != "untouched") o.violation = "loadParticleSystem failed but changed its output";
        return o;
    }
    o.accepted = true;
    // particle_json.h promises the written form reads back to the same system.
    ParticleSystemFile again;
    const nlohmann::json saved = nlohmann::json::parse(particleSystemToJson(system).dump());
    if (!parseParticleSystem(saved, path, &again, &error))
        return o.violation = "the written form of an accepted particle system does not read: " + error, o;
    if (particleSystemToJson(again) != saved) return o.violation = "the written form does not read back the same", o;
    uint64_t particles = 0;
    for (const ParticleGenerator& g : system.scene.generators) particles += g.count;
    if (particles * system.scene.walk.steps > kMaxGrownParticleSteps) return o;
    Strands strands;
    if (!growStrands(system.scene, {.threads = 1}, &strands, &error)) return o;  // refused at a step: fine
    StrandMeshSettings mesh = system.mesh;
    mesh.max_triangles = std::min<uint64_t>(mesh.max_triangles, 2'000'000);
    TriangleMesh tubes;
    if (strands.size() > 0 && strandMesh(strands, mesh, &tubes, &error) && !validateMesh(tubes, &error))
        o.violation = "the strands' tubes fail validateMesh: " + error;
    return o;
}

// ---- the Ghost Tile cache ------------------------------------------------------------------------

constexpr size_t kCacheHeaderBytes = 40;  // magic, version, header bytes, key, payload bytes, checksum

Outcome runCache(const std::string& path) {
    Outcome o;
    GhostTile tile;
    tile.key = 0x5e5e5e5e5e5e5e5eull;
    std::string error;
    if (!loadGhostTileCache(path, 0, &tile, &error)) {
        o.message = error;
        if (tile.key != 0x5e5e5e5e5e5e5e5eull) o.violation = "a refused cache changed the output tile";
        return o;
    }
    o.accepted = true;
    // "every array is bounds-checked and the graph stream is fully validated": walking every edge of an
    // accepted tile must stay inside it, and saving it again must give back the very same bytes.
    const uint32_t n = tile.candidates.size();
    uint64_t edges = 0;
    for (uint32_t i = 0; i < n; ++i)
        tile.graph.forEachNeighbor(i, [&](uint32_t j, uint32_t) {
            if (j >= n && o.violation.empty()) o.violation = "an edge names candidate " + std::to_string(j);
            ++edges;
        });
    if (o.violation.empty() && edges != tile.graph.edgeCount())
        o.violation = "the graph has " + std::to_string(edges) + " edges, it says " + std::to_string(tile.graph.edgeCount());
    const std::string again = path + ".resaved";
    if (o.violation.empty() && saveGhostTileCache(again, tile, &error) && readFile(again) != readFile(path))
        o.violation = "an accepted cache saved again differs from the file it was read from";
    std::filesystem::remove(again);
    return o;
}

// The forger's repair: the payload size and checksum in the header match the (mutated) payload, as
// saveGhostTileCache would have written them. Everything after the checksum is then up to the reader's
// own validation, which is what this target is for.
void forgeCacheChecksum(std::string* b) {
    if (b->size() < kCacheHeaderBytes) return;
    const uint64_t payload = b->size() - kCacheHeaderBytes;
    const uint64_t sum = hashBytes(b->data() + kCacheHeaderBytes, payload);
    std::memcpy(b->data() + 24, &payload, 8);
    std::memcpy(b->data() + 32, &sum, 8);
}

// The payload's arrays (ghost_tile_cache.cpp's save order): u64 count, then count elements of this size.
constexpr size_t kCacheArrayElement[] = {4 /*type_begin*/, 2 /*type*/,        12 /*position*/, 16 /*rotation*/,
                                         4 /*scale*/,      4 /*row_offsets*/, 1 /*graph stream*/};
constexpr size_t kCacheSettingsBytes = 4 + 4 + 8;  // tile_size_m, delta_m, seed

struct CacheArray {
    size_t at;  // offset of the count
    size_t element;
    uint64_t count;
};

std::vector<CacheArray> cacheArrays(const std::string& b, size_t payload_at) {
    std::vector<CacheArray> arrays;
    size_t at = payload_at + kCacheSettingsBytes;
    for (size_t element : kCacheArrayElement) {
        if (at + 8 > b.size()) break;
        uint64_t count;
        std::memcpy(&count, b.data() + at, 8);
        arrays.push_back({at, element, count});
        if (count > (b.size() - at - 8) / element) break;
        at += 8 + count * element;
    }
    return arrays;
}

// Bumps one array's count; half the time the array's bytes follow (elements dropped, or copies of the
// last one appended), so the layout stays consistent and the reader's semantic checks are reached.
bool mutateCacheCount(std::string* b, Rng& rng, size_t payload_at) {
    std::vector<CacheArray> arrays = cacheArrays(*b, payload_at);
    if (arrays.empty()) return false;
    const CacheArray a = arrays[rng.below(arrays.size())];
    const uint64_t count = interestingCount(a.count, rng);
    std::memcpy(b->data() + a.at, &count, 8);
    if (rng.oneIn(2) && count <= (1u << 16) && a.count <= (b->size() - a.at - 8) / a.element) {
        const size_t data = a.at + 8;
        if (count < a.count) {
            b->erase(data + count * a.element, (a.count - count) * a.element);
        } else if (count > a.count) {
            std::string extra((count - a.count) * a.element, '\0');
            if (a.count) {
                const std::string last = b->substr(data + (a.count - 1) * a.element, a.element);
                for (size_t k = 0; k < extra.size(); ++k) extra[k] = last[k % a.element];
            }
            b->insert(data + a.count * a.element, extra);
        }
    }
    return true;
}

// One element of an index array (type ranges, type ids, row offsets) set to an edge value.
bool mutateCacheElement(std::string* b, Rng& rng, size_t payload_at) {
    std::vector<CacheArray> arrays = cacheArrays(*b, payload_at);
    std::vector<CacheArray> index_arrays;
    for (const CacheArray& a : arrays)
        if ((a.element == 4 || a.element == 2) && a.count && a.count <= (b->size() - a.at - 8) / a.element &&
            &a - arrays.data() != 4 /*scale*/)
            index_arrays.push_back(a);
    if (index_arrays.empty()) return false;
    const CacheArray a = index_arrays[rng.below(index_arrays.size())];
    const size_t at = a.at + 8 + rng.below(a.count) * a.element;
    uint64_t old = 0;
    std::memcpy(&old, b->data() + at, a.element);
    const uint64_t v = rng.oneIn(4) ? old - 1 : interestingCount(old, rng);
    std::memcpy(b->data() + at, &v, a.element);
    return true;
}

bool cacheCountRaw(std::string* b, Rng& rng) { return mutateCacheCount(b, rng, kCacheHeaderBytes); }
bool cacheElementRaw(std::string* b, Rng& rng) { return mutateCacheElement(b, rng, kCacheHeaderBytes); }
bool cacheCountForged(std::string* b, Rng& rng) { return mutateCacheCount(b, rng, 0); }
bool cacheElementForged(std::string* b, Rng& rng) { return mutateCacheElement(b, rng, 0); }

// The header's own fields: version, header size, payload size (a truncated file that says so).
bool cacheHeaderField(std::string* b, Rng& rng) {
    static const size_t kAt[] = {8, 12, 24};
    static const size_t kWidth[] = {4, 4, 8};
    if (b->size() < kCacheHeaderBytes) return false;
    const size_t k = rng.below(3);
    uint64_t old = 0;
    std::memcpy(&old, b->data() + kAt[k], kWidth[k]);
    const uint64_t v = interestingCount(old, rng);
    std::memcpy(b->data() + kAt[k], &v, kWidth[k]);
    return true;
}

// ---- the PNG height field -----------------------------------------------------------------------------

Outcome runPng(const std::string& path) {
    Outcome o;
    const HeightFieldImageDesc desc{.origin_m = {-1.0f, 2.0f}, .cell_size_m = 0.25f, .min_height_m = -1.0f,
                                    .max_height_m = 3.0f};
    HeightField hf;
    std::string error;
    if (!loadHeightFieldPng(path, desc, &hf, &error)) {
        o.message = error;
        if (!hf.empty()) o.violation = "a refused image changed the output field";
        return o;
    }
    o.accepted = true;
    if (hf.width() < 1 || hf.height() < 1 || hf.width() > kMaxHeightFieldSide || hf.height() > kMaxHeightFieldSide ||
        hf.heights().size() != size_t(hf.width()) * size_t(hf.height()))
        o.violation = "accepted a field of impossible size";
    else if (hf.minHeight() < desc.min_height_m || hf.maxHeight() > desc.max_height_m || !std::isfinite(hf.minHeight()))
        o.violation = "heights outside [min_height_m, max_height_m]";
    return o;
}

uint32_t readBigEndian32(const std::string& b, size_t at) {
    return uint32_t(uint8_t(b[at])) << 24 | uint32_t(uint8_t(b[at + 1])) << 16 | uint32_t(uint8_t(b[at + 2])) << 8 |
           uint32_t(uint8_t(b[at + 3]));
}

void writeBigEndian32(std::string* b, size_t at, uint32_t v) {
    for (int k = 0; k < 4; ++k) (*b)[at + size_t(k)] = char(v >> (24 - 8 * k));
}

uint32_t crc32(const char* p, size_t n) {
    uint32_t c = 0xffffffffu;
    for (size_t i = 0; i < n; ++i) {
        c ^= uint8_t(p[i]);
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return ~c;
}

struct PngChunk {
    size_t at;  // offset of the length field
    uint32_t length;
    std::string type;
};

std::vector<PngChunk> pngChunks(const std::string& b) {
    std::vector<PngChunk> chunks;
    if (b.size() < 8 || b.compare(1, 3, "PNG") != 0) return chunks;
    size_t at = 8;
    while (at + 12 <= b.size()) {
        const uint32_t len = readBigEndian32(b, at);
        chunks.push_back({at, len, b.substr(at + 4, 4)});
        if (len > b.size() - at - 12) break;
        at += 12 + len;
    }
    return chunks;
}

// IHDR: width, height, bit depth, colour type, compression, filter, interlace.
bool pngHeaderField(std::string* b, Rng& rng) {
    if (b->size() < 33 || b->compare(12, 4, "IHDR") != 0) return false;
    switch (rng.below(4)) {
        case 0: writeBigEndian32(b, 16, uint32_t(interestingCount(readBigEndian32(*b, 16), rng))); break;
        case 1: writeBigEndian32(b, 20, uint32_t(interestingCount(readBigEndian32(*b, 20), rng))); break;
        case 2: {
            static const uint8_t kDepths[] = {0, 1, 2, 4, 8, 16, 3, 32, 255};
            (*b)[24] = char(kDepths[rng.below(std::size(kDepths))]);
            break;
        }
        default: {
            static const uint8_t kColour[] = {0, 2, 3, 4, 6, 1, 5, 7, 255};
            (*b)[25 + rng.below(4)] = char(rng.oneIn(2) ? kColour[rng.below(std::size(kColour))] : uint8_t(rng.below(3)));
            break;
        }
    }
    writeBigEndian32(b, 29, crc32(b->data() + 12, 17));
    return true;
}

bool pngChunkLength(std::string* b, Rng& rng) {
    const auto chunks = pngChunks(*b);
    if (chunks.empty()) return false;
    const PngChunk& c = chunks[rng.below(chunks.size())];
    writeBigEndian32(b, c.at, uint32_t(interestingCount(c.length, rng)));
    return true;
}

// The pixel data behind a valid zlib stream: inflate every IDAT, mutate the filtered scanlines (filter
// bytes, a short or long stream), deflate into one IDAT with a correct CRC. Without this nearly every
// pixel mutation dies in zlib and the unfiltering and deinterlacing code is never reached.
bool pngPixels(std::string* b, Rng& rng) {
    const auto chunks = pngChunks(*b);
    std::string z;
    size_t first = 0, end = 0;
    for (const PngChunk& c : chunks) {
        if (c.type != "IDAT" || c.length > b->size() - c.at - 12) continue;
        if (z.empty()) first = c.at;
        z.append(*b, c.at + 8, c.length);
        end = c.at + 12 + c.length;
    }
    if (z.empty()) return false;
    int raw_len = 0;
    char* raw = stbi_zlib_decode_malloc(z.data(), int(z.size()), &raw_len);
    if (!raw) return false;
    std::string pixels(raw, size_t(raw_len));
    std::free(raw);
    const int edits = 1 + int(rng.below(3));
    for (int k = 0; k < edits; ++k) mutateGeneric(&pixels, rng, nullptr, 0);
    if (pixels.empty()) pixels.push_back('\0');
    int zlen = 0;
    unsigned char* packed =
        stbi_zlib_compress(reinterpret_cast<unsigned char*>(pixels.data()), int(pixels.size()), &zlen, 8);
    if (!packed) return false;
    std::string idat(8, '\0');
    writeBigEndian32(&idat, 0, uint32_t(zlen));
    idat.replace(4, 4, "IDAT");
    idat.append(reinterpret_cast<char*>(packed), size_t(zlen));
    std::free(packed);
    idat.append(4, '\0');
    writeBigEndian32(&idat, idat.size() - 4, crc32(idat.data() + 4, idat.size() - 8));
    // Everything between the first and the last IDAT (ancillary chunks between them are rare) is replaced.
    b->replace(first, end - first, idat);
    return true;
}

// ---- text mesh formats ------------------------------------------------------------------------------

// One word replaced by another of the same family (a type, a format, an enumerant).
bool swapWord(std::string* b, Rng& rng, const std::vector<std::string>& words) {
    std::vector<std::pair<size_t, size_t>> hits;  // offset, word
    for (size_t w = 0; w < words.size(); ++w)
        for (size_t p = b->find(words[w]); p != std::string::npos && hits.size() < 4096; p = b->find(words[w], p + 1))
            hits.emplace_back(p, w);
    if (hits.empty()) return false;
    const auto [at, w] = hits[rng.below(hits.size())];
    b->replace(at, words[w].size(), words[rng.below(words.size())]);
    return true;
}

bool plyCount(std::string* b, Rng& rng) { return bumpCountAfter(b, rng, {"element vertex", "element face", "element "}); }
bool plyType(std::string* b, Rng& rng) {
    return swapWord(b, rng, {" float ", " double ", " uchar ", " char ", " int ", " uint ", " short ", " ushort ",
                             " int8 ", " uint8 ", " int32 ", " uint32 ", " float32 ", " float64 ", " list "});
}
bool plyFormat(std::string* b, Rng& rng) {
    return swapWord(b, rng, {"ascii", "binary_little_endian", "binary_big_endian"});
}
// A header that never ends: the reader must give up at the end of the file.
bool plyNoEndHeader(std::string* b, Rng& rng) {
    const size_t p = b->find("end_header");
    if (p == std::string::npos) return false;
    b->replace(p, 10, rng.oneIn(2) ? "end_headex" : "");
    return true;
}

bool objIndex(std::string* b, Rng& rng) { return bumpCountAfter(b, rng, {"\nf ", "/"}); }
bool objKeyword(std::string* b, Rng& rng) { return swapWord(b, rng, {"\nv ", "\nvt ", "\nvn ", "\nf ", "\nl ", "\np "}); }

bool offCount(std::string* b, Rng& rng) { return bumpCountAfter(b, rng, {"OFF\n", "OFF\r\n", "OFF\n\n"}); }
bool offHeader(std::string* b, Rng& rng) {
    return swapWord(b, rng, {"OFF", "COFF", "NOFF", "CNOFF", "STOFF", "4OFF", "nOFF", "OFF BINARY"});
}

// Binary STL: the triangle count after the 80-byte header; and the "solid" that makes a file ASCII.
bool stlCount(std::string* b, Rng& rng) {
    if (b->size() < 84) return false;
    uint32_t old;
    std::memcpy(&old, b->data() + 80, 4);
    const uint32_t v = uint32_t(interestingCount(old, rng));
    std::memcpy(b->data() + 80, &v, 4);
    return true;
}
bool stlSolid(std::string* b, Rng& rng) {
    if (b->size() < 5) return false;
    b->replace(0, 5, rng.oneIn(2) ? "solid" : "SOLID");
    return true;
}

// ---- glTF ----------------------------------------------------------------------------------------

const std::vector<std::string>& gltfCountKeys() {
    static const std::vector<std::string> keys = {
        "\"count\"",  "\"byteLength\"",    "\"byteOffset\"", "\"byteStride\"", "\"bufferView\"", "\"buffer\"",
        "\"indices\"", "\"POSITION\"", "\"mesh\"", "\"componentType\"", "\"mode\"", "\"scene\"", "\"nodes\"",
        "\"children\""};
    return keys;
}

bool gltfCount(std::string* b, Rng& rng) { return bumpCountAfter(b, rng, gltfCountKeys()); }
bool gltfType(std::string* b, Rng& rng) {
    return swapWord(b, rng, {"\"VEC3\"", "\"VEC2\"", "\"VEC4\"", "\"SCALAR\"", "\"MAT4\""});
}
// A node made its own child: node transforms are applied recursively.
bool gltfCycle(std::string* b, Rng& rng) {
    // The top-level "nodes" array holds objects; a scene's "nodes" holds numbers. Find an object.
    for (size_t p = b->find("\"nodes\""); p != std::string::npos; p = b->find("\"nodes\"", p + 1)) {
        const size_t open = b->find_first_of("[", p);
        if (open == std::string::npos) return false;
        const size_t next = b->find_first_not_of(" \n\r\t", open + 1);
        if (next != std::string::npos && (*b)[next] == '{') {
            b->insert(next + 1, "\"children\": [" + std::to_string(rng.below(3)) + "], ");
            return true;
        }
    }
    return false;
}

// A GLB's JSON chunk mutated as text, then the container's lengths repaired, so the mutation reaches the
// glTF reader instead of dying on a chunk length. Sometimes the BIN chunk is cut instead.
bool glbRepack(std::string* b, Rng& rng) {
    if (b->size() < 28 || b->compare(0, 4, "glTF") != 0) return false;
    uint32_t json_len;
    std::memcpy(&json_len, b->data() + 12, 4);
    if (b->compare(16, 4, "JSON") != 0 || json_len > b->size() - 20) return false;
    std::string json = b->substr(20, json_len);
    std::string rest = b->substr(20 + json_len);  // the BIN chunk (header included), if any
    if (rest.size() >= 8 && rng.oneIn(4)) {
        uint32_t bin_len;
        std::memcpy(&bin_len, rest.data(), 4);
        const uint32_t cut = bin_len ? uint32_t(rng.below(bin_len)) & ~3u : 0;
        std::memcpy(rest.data(), &cut, 4);
        rest.resize(std::min<size_t>(rest.size(), 8 + cut));
    } else {
        switch (rng.below(4)) {
            case 0: if (!replaceNumberToken(&json, rng)) return false; break;
            case 1: if (!gltfCount(&json, rng)) return false; break;
            case 2: if (!gltfType(&json, rng) && !gltfCycle(&json, rng)) return false; break;
            default: mutateGeneric(&json, rng, nullptr, 0); break;
        }
        while (json.size() % 4) json.push_back(' ');
    }
    const uint32_t new_json_len = uint32_t(json.size());
    const uint32_t total = uint32_t(20 + json.size() + rest.size());
    std::string out = b->substr(0, 20);
    std::memcpy(out.data() + 8, &total, 4);
    std::memcpy(out.data() + 12, &new_json_len, 4);
    *b = out + json + rest;
    return true;
}

// The GLB container's own words: total length, chunk lengths and types.
bool glbHeader(std::string* b, Rng& rng) {
    if (b->size() < 20 || b->compare(0, 4, "glTF") != 0) return false;
    static const size_t kAt[] = {4, 8, 12};
    const size_t at = kAt[rng.below(3)];
    uint32_t old;
    std::memcpy(&old, b->data() + at, 4);
    const uint32_t v = uint32_t(interestingCount(old, rng));
    std::memcpy(b->data() + at, &v, 4);
    return true;
}

// ---- scene JSON ------------------------------------------------------------------------------------

bool sceneCount(std::string* b, Rng& rng) {
    return bumpCountAfter(b, rng, {"\"count\"", "\"width\"", "\"height\"", "\"max_spheres\"", "\"surface_samples\"",
                                   "\"format_version\"", "\"octaves\"", "\"seed\""});
}
bool sceneWord(std::string* b, Rng& rng) {
    static const std::vector<std::vector<std::string>> families = {
        {"\"point\"", "\"segment\"", "\"disc\"", "\"box\"", "\"half_space\"", "\"terrain_layer\"", "\"terrain_solid\"",
         "\"polyline\"", "\"blend\"", "\"union\"", "\"intersection\"", "\"difference\""},
        {"\"random\"", "\"elevation\"", "\"distance_to_boundary\"", "\"gradient\""},
        {"\"uniform\"", "\"tilt\"", "\"jittered\""},
        {"\"authored\"", "\"center\"", "\"sphere_centers\"", "\"surface\""},
        {"\"procedural\"", "\"image\""},
        {"true", "false", "null", "[]", "{}", "\"\""},
    };
    return swapWord(b, rng, families[rng.below(families.size())]);
}
// A density node wrapped in many one-child unions: the reader's depth limit (kMaxFieldDepth = 64) must
// hold, and a deep document must not exhaust the stack on the way there.
bool sceneDeep(std::string* b, Rng& rng) {
    const size_t at = b->find("{\"point\"");
    if (at == std::string::npos) return false;
    size_t end = at, depth = 0;
    for (; end < b->size(); ++end) {
        if ((*b)[end] == '{') ++depth;
        else if ((*b)[end] == '}' && --depth == 0) break;
    }
    if (end >= b->size()) return false;
    static const size_t kLevels[] = {62, 63, 64, 65, 1000, 100000};
    const size_t levels = kLevels[rng.below(std::size(kLevels))];
    std::string open, close;
    for (size_t k = 0; k < levels; ++k) {
        open += "{\"union\": [";
        close += "]}";
    }
    b->insert(end + 1, close);
    b->insert(at, open);
    return true;
}
// A referenced file swapped for another: a mesh of another format, an image as a mesh, a folder, nothing.
bool scenePath(std::string* b, Rng& rng) {
    return swapWord(b, rng, {"\"data/cube.obj\"", "\"data/tetra.ply\"", "\"data/wedge.stl\"", "\"data/cube.off\"",
                             "\"data/pebble.glb\"", "\"data/leaf.gltf\"", "\"data/terrain.png\"",
                             "\"data/terrain16.png\"", "\"data\"", "\"data/missing.obj\"", "\"data/cube.OBJ\"",
                             "\"data/strands.json\"",
                             "\"\"", "\"data/\""});
}

bool particleCount(std::string* b, Rng& rng) {
    return bumpCountAfter(b, rng, {"\"count\"", "\"steps\"", "\"trials\"", "\"split_count\"", "\"sides\"",
                                   "\"countdown_steps\"", "\"max_split_depth\"", "\"format_version\""});
}
bool particleWord(std::string* b, Rng& rng) {
    return swapWord(b, rng, {"\"point\"", "\"segment\"", "\"sphere\"", "\"rectangle\"", "\"box\"", "\"plane\"",
                             "\"above\"", "\"below\"", "\"stop\"", "\"kill\"", "\"split\"", "\"countdown\"",
                             "\"mesh\"", "\"data/cube.obj\"", "\"data\"", "\"\"",
                             "true", "false", "null", "[]", "{}", "0", "-1", "1e9"});
}

const std::vector<Target> kTargets = {
    {"scene", ".json", "scene files: loadProject, models, Ghost Tile build, terrain, compileScene", runScene,
     {sceneCount, sceneWord, sceneDeep, scenePath}},
    {"obj", ".obj", "Wavefront OBJ via loadMeshFile (OpenMesh)", runMesh, {objIndex, objKeyword}},
    {"ply", ".ply", "PLY via loadMeshFile (OpenMesh)", runMesh, {plyCount, plyType, plyFormat, plyNoEndHeader}},
    {"stl", ".stl", "STL, ASCII and binary, via loadMeshFile (OpenMesh)", runMesh, {stlCount, stlSolid}},
    {"off", ".off", "OFF via loadMeshFile (OpenMesh)", runMesh, {offCount, offHeader}},
    {"glb", ".glb", "binary glTF via loadMeshFile (tinygltf + our checks)", runMesh,
     {glbRepack, glbRepack, glbHeader, gltfCount}},
    {"gltf", ".gltf", "JSON glTF, embedded and external buffers, via loadMeshFile", runMesh,
     {gltfCount, gltfType, gltfCycle}},
    {"ghosttile", ".ugt", "Ghost Tile cache as found on disk (checksum not repaired)", runCache,
     {cacheHeaderField, cacheCountRaw, cacheElementRaw}},
    {"ghosttile-forged", ".ugt", "Ghost Tile cache with payload size and checksum forged after mutating", runCache,
     {cacheCountForged, cacheCountForged, cacheElementForged}, kCacheHeaderBytes, forgeCacheChecksum, "ghosttile"},
    {"png", ".png", "height-field images via loadHeightFieldPng (stb_image)", runPng,
     {pngHeaderField, pngChunkLength, pngPixels, pngPixels}},
    {"particles", ".json", "particle system files: loadParticleSystem, growStrands, strandTubeMesh", runParticles,
     {particleCount, particleWord}},
};

}  // namespace

const std::vector<Target>& targets() { return kTargets; }

const Target* findTarget(const std::string& name) {
    for (const Target& t : kTargets)
        if (name == t.name) return &t;
    return nullptr;
}

std::string checkMessage(const Target& target, const std::string& input_path, const std::string& message) {
    if (message.empty()) return "rejected with an empty message";
    if (message.find(input_path) != std::string::npos) return "";
    if (std::string(target.name) == "scene") {
        const std::string folder = std::filesystem::path(input_path).parent_path().string() + "/";
        if (message.find(folder) != std::string::npos) return "";
    }
    return "the message does not name the file";
}

}  // namespace ug::fuzz
