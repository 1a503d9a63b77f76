// The seed corpus (tests/fuzz/corpus), written from tiny shapes defined here: `fuzz_inputs --make-corpus
// tests/fuzz/corpus` rewrites it. Seeds are small (a few KB) so a mutated input loads in milliseconds
// and CI runs thousands per target; each format gets its variants (ASCII and binary, both endiannesses,
// indexed and not, embedded and external buffers, 1- to 16-bit images, interlaced, palettes) plus a few
// near-valid files the reader must refuse with a message. Every file is deterministic.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "core/hash.h"
#include "fuzz.h"
#include "ghosttile/ghost_tile.h"
#include "ghosttile/ghost_tile_cache.h"
#include "io/gltf_mesh_io.h"
#include "mesh/triangle_mesh.h"

extern "C" {
unsigned char* stbi_zlib_compress(unsigned char* data, int data_len, int* out_len, int quality);
typedef void stbi_write_func(void* context, void* data, int size);
int stbi_write_bmp_to_func(stbi_write_func* func, void* context, int w, int h, int comp, const void* data);
int stbi_write_tga_to_func(stbi_write_func* func, void* context, int w, int h, int comp, const void* data);
}

namespace ug::fuzz {

namespace {

namespace fs = std::filesystem;

struct Shape {
    std::vector<glm::vec3> v;
    std::vector<std::vector<uint32_t>> faces;  // polygons, counter-clockwise seen from outside
};

Shape cube() {
    Shape s;
    for (int i = 0; i < 8; ++i) s.v.push_back({(i & 1) ? 0.05f : -0.05f, (i & 2) ? 0.05f : -0.05f, (i & 4) ? 0.05f : -0.05f});
    s.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    return s;
}

Shape tetra() {
    Shape s;
    s.v = {{0.04f, 0.04f, 0.04f}, {-0.04f, -0.04f, 0.04f}, {-0.04f, 0.04f, -0.04f}, {0.04f, -0.04f, -0.04f}};
    s.faces = {{0, 1, 3}, {0, 2, 1}, {0, 3, 2}, {1, 2, 3}};
    return s;
}

// A triangular prism: two triangles and three quads.
Shape wedge() {
    Shape s;
    s.v = {{-0.05f, -0.03f, 0}, {0.05f, -0.03f, 0}, {0, 0.04f, 0}, {-0.05f, -0.03f, 0.03f}, {0.05f, -0.03f, 0.03f},
           {0, 0.04f, 0.03f}};
    s.faces = {{0, 2, 1}, {3, 4, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};
    return s;
}

// An icosahedron: the "pebble".
Shape icosahedron() {
    Shape s;
    const float t = 0.5f * (1.0f + std::sqrt(5.0f)), k = 0.02f;
    const float raw[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                              {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (const auto& p : raw) s.v.push_back({p[0] * k, p[1] * k, p[2] * k * 0.6f});
    s.faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
               {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
               {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    return s;
}

std::vector<uint32_t> triangles(const Shape& s) {
    std::vector<uint32_t> idx;
    for (const auto& f : s.faces)
        for (size_t k = 1; k + 1 < f.size(); ++k) idx.insert(idx.end(), {f[0], f[k], f[k + 1]});
    return idx;
}

TriangleMesh mesh(const Shape& s) {
    TriangleMesh m;
    m.positions = s.v;
    m.indices = triangles(s);
    computeNormals(&m);
    return m;
}

std::string num(float f) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%g", double(f));
    return buf;
}

template <typename T>
void put(std::string* b, T v) {
    b->append(reinterpret_cast<const char*>(&v), sizeof(T));
}

template <typename T>
void putBigEndian(std::string* b, T v) {
    unsigned char p[sizeof(T)];
    std::memcpy(p, &v, sizeof(T));
    for (size_t k = 0; k < sizeof(T); ++k) b->push_back(char(p[sizeof(T) - 1 - k]));
}

// ---- OBJ / PLY / OFF / STL ----------------------------------------------------------------------------

std::string obj(const Shape& s, int style) {
    std::string o = "# fuzz seed\n";
    if (style == 1) o += "o tetra\ng part\ns off\nusemtl stone\n";
    for (const glm::vec3& p : s.v) o += "v " + num(p.x) + " " + num(p.y) + " " + num(p.z) + "\n";
    if (style == 2) {
        o += "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nvn 0 1 0\n";
    }
    const int n = int(s.v.size());
    int k = 0;
    for (const auto& f : s.faces) {
        o += "f";
        for (uint32_t i : f) {
            if (style == 1) o += " " + std::to_string(int(i) - n);  // negative: relative to the end
            else if (style == 2) o += (k % 2 ? " " + std::to_string(i + 1) + "//" + std::to_string(1 + k % 2)
                                             : " " + std::to_string(i + 1) + "/" + std::to_string(1 + (i % 4)) + "/1");
            else o += " " + std::to_string(i + 1);
        }
        o += "\n";
        ++k;
    }
    return o;
}

std::string plyAscii(const Shape& s) {
    std::string o = "ply\nformat ascii 1.0\ncomment fuzz seed\nelement vertex " + std::to_string(s.v.size()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
                    "property float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                    "element face " + std::to_string(s.faces.size()) + "\nproperty list uchar int vertex_indices\n"
                    "end_header\n";
    for (const glm::vec3& p : s.v) {
        const glm::vec3 n = glm::normalize(p);
        o += num(p.x) + " " + num(p.y) + " " + num(p.z) + " " + num(n.x) + " " + num(n.y) + " " + num(n.z) + " 200 180 90\n";
    }
    for (const auto& f : s.faces) {
        o += std::to_string(f.size());
        for (uint32_t i : f) o += " " + std::to_string(i);
        o += "\n";
    }
    return o;
}

// Binary PLY: little-endian float coordinates, or big-endian doubles with an extra element after the faces.
std::string plyBinary(const Shape& s, bool big) {
    std::string o = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\nelement vertex " + std::to_string(s.v.size()) + "\n" +
                    (big ? "property double x\nproperty double y\nproperty double z\n"
                         : "property float x\nproperty float y\nproperty float z\n") +
                    "element face " + std::to_string(s.faces.size()) + "\nproperty list uchar " +
                    (big ? "uint" : "int") + " vertex_indices\n" +
                    (big ? "element edge 1\nproperty int vertex1\nproperty int vertex2\n" : "") + "end_header\n";
    for (const glm::vec3& p : s.v)
        for (int a = 0; a < 3; ++a) {
            if (big) putBigEndian(&o, double(p[a]));
            else put(&o, p[a]);
        }
    for (const auto& f : s.faces) {
        o.push_back(char(f.size()));
        for (uint32_t i : f) {
            if (big) putBigEndian(&o, i);
            else put(&o, int32_t(i));
        }
    }
    if (big) {
        putBigEndian(&o, int32_t(0));
        putBigEndian(&o, int32_t(1));
    }
    return o;
}

std::string off(const Shape& s, int style) {
    std::string o = style == 1 ? "COFF\n" : "OFF\n";
    if (style == 3) o += "# OpenMesh reads no comments: a near-valid file\n";
    o += std::to_string(s.v.size()) + " " + std::to_string(s.faces.size()) + " 0\n";
    for (const glm::vec3& p : s.v) {
        o += num(p.x) + " " + num(p.y) + " " + num(p.z);
        if (style == 1) o += " 120 100 80 255";
        o += "\n";
    }
    for (const auto& f : s.faces) {
        o += std::to_string(f.size());
        for (uint32_t i : f) o += " " + std::to_string(i);
        if (style >= 2) o += " 0.5 0.4 0.3";  // a face colour
        o += "\n";
    }
    return o;
}

// "OFF BINARY": 32-bit counts, floats and indices. Geomview's format is big-endian, but OpenMesh reads
// host order (little-endian here); a big-endian file's counts read as ~67 million (a finding, see
// tests/fuzz/findings/off/), so the seed is written the way OpenMesh reads it.
std::string offBinary(const Shape& s) {
    std::string o = "OFF BINARY\n";
    put(&o, int32_t(s.v.size()));
    put(&o, int32_t(s.faces.size()));
    put(&o, int32_t(0));
    for (const glm::vec3& p : s.v)
        for (int a = 0; a < 3; ++a) put(&o, p[a]);
    for (const auto& f : s.faces) {
        put(&o, int32_t(f.size()));
        for (uint32_t i : f) put(&o, int32_t(i));
        put(&o, int32_t(0));  // no colour
    }
    return o;
}

std::string stlAscii(const Shape& s) {
    const std::vector<uint32_t> t = triangles(s);
    std::string o = "solid seed\n";
    for (size_t k = 0; k < t.size(); k += 3) {
        const glm::vec3 a = s.v[t[k]], b = s.v[t[k + 1]], c = s.v[t[k + 2]];
        const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        o += "  facet normal " + num(n.x) + " " + num(n.y) + " " + num(n.z) + "\n    outer loop\n";
        for (const glm::vec3& p : {a, b, c}) o += "      vertex " + num(p.x) + " " + num(p.y) + " " + num(p.z) + "\n";
        o += "    endloop\n  endfacet\n";
    }
    return o + "endsolid seed\n";
}

// Binary STL; header_text starting with "solid" is the classic ASCII/binary ambiguity. declared < 0: the
// real count.
std::string stlBinary(const Shape& s, const std::string& header_text, int declared = -1) {
    const std::vector<uint32_t> t = triangles(s);
    std::string o = header_text;
    o.resize(80, ' ');
    put(&o, uint32_t(declared < 0 ? t.size() / 3 : size_t(declared)));
    for (size_t k = 0; k < t.size(); k += 3) {
        const glm::vec3 a = s.v[t[k]], b = s.v[t[k + 1]], c = s.v[t[k + 2]];
        const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        for (const glm::vec3& p : {n, a, b, c})
            for (int x = 0; x < 3; ++x) put(&o, p[x]);
        put(&o, uint16_t(0));
    }
    return o;
}

// ---- glTF ----------------------------------------------------------------------------------------

std::string base64(const std::string& in) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < in.size(); i += 3) {
        uint32_t v = uint32_t(uint8_t(in[i])) << 16;
        if (i + 1 < in.size()) v |= uint32_t(uint8_t(in[i + 1])) << 8;
        if (i + 2 < in.size()) v |= uint32_t(uint8_t(in[i + 2]));
        out.push_back(k[(v >> 18) & 63]);
        out.push_back(k[(v >> 12) & 63]);
        out.push_back(i + 1 < in.size() ? k[(v >> 6) & 63] : '=');
        out.push_back(i + 2 < in.size() ? k[v & 63] : '=');
    }
    return out;
}

// A hand-made glTF: one buffer with positions and indices of the given width (1, 2 or 4 bytes; 0 = not
// indexed), a node hierarchy (a matrix on the root, TRS on the child), a second primitive in LINES mode
// the loader must skip. `uri`: "" for a GLB's BIN chunk, else a data URI or a file name.
struct HandGltf {
    std::string json;
    std::string bin;
};

HandGltf handGltf(const Shape& s, int index_bytes, bool with_scene, const std::string& uri_kind) {
    HandGltf g;
    const std::vector<uint32_t> t = triangles(s);
    std::vector<glm::vec3> pos;
    if (index_bytes == 0)
        for (uint32_t i : t) pos.push_back(s.v[i]);
    else
        pos = s.v;
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const glm::vec3& p : pos) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
        for (int a = 0; a < 3; ++a) put(&g.bin, p[a]);
    }
    const size_t pos_bytes = g.bin.size();
    if (index_bytes) {
        for (uint32_t i : t) {
            if (index_bytes == 1) g.bin.push_back(char(i));
            else if (index_bytes == 2) put(&g.bin, uint16_t(i));
            else put(&g.bin, i);
        }
    }
    const size_t idx_bytes = g.bin.size() - pos_bytes;
    while (g.bin.size() % 4) g.bin.push_back('\0');
    const int component = index_bytes == 1 ? 5121 : index_bytes == 2 ? 5123 : 5125;
    std::string uri;
    if (uri_kind == "data") uri = ", \"uri\": \"data:application/octet-stream;base64," + base64(g.bin) + "\"";
    else if (!uri_kind.empty()) uri = ", \"uri\": \"" + uri_kind + "\"";
    std::string j = "{\"asset\": {\"version\": \"2.0\", \"generator\": \"fuzz seed\"},\n";
    if (with_scene) j += " \"scene\": 0, \"scenes\": [{\"nodes\": [0]}],\n";
    j += " \"nodes\": [{\"matrix\": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0.01,0,0,1], \"children\": [1]},\n"
         "           {\"mesh\": 0, \"translation\": [0, 0.02, 0], \"rotation\": [0, 0.3826834, 0, 0.9238795],"
         " \"scale\": [1, 1.5, 1]}],\n";
    j += " \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0}" +
         std::string(index_bytes ? ", \"indices\": 1" : "") + ", \"material\": 0},\n"
         "                           {\"attributes\": {\"POSITION\": 0}, \"mode\": 1}]}],\n";
    j += " \"materials\": [{\"pbrMetallicRoughness\": {\"baseColorFactor\": [0.5, 0.4, 0.3, 1]}}],\n";
    j += " \"buffers\": [{\"byteLength\": " + std::to_string(g.bin.size()) + uri + "}],\n";
    j += " \"bufferViews\": [{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": " + std::to_string(pos_bytes) +
         ", \"byteStride\": 12}";
    if (index_bytes)
        j += ",\n                 {\"buffer\": 0, \"byteOffset\": " + std::to_string(pos_bytes) +
             ", \"byteLength\": " + std::to_string(idx_bytes) + "}";
    j += "],\n";
    j += " \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": " + std::to_string(pos.size()) +
         ", \"type\": \"VEC3\", \"min\": [" + num(lo.x) + ", " + num(lo.y) + ", " + num(lo.z) + "], \"max\": [" +
         num(hi.x) + ", " + num(hi.y) + ", " + num(hi.z) + "]}";
    if (index_bytes)
        j += ",\n               {\"bufferView\": 1, \"componentType\": " + std::to_string(component) +
             ", \"count\": " + std::to_string(t.size()) + ", \"type\": \"SCALAR\"}";
    j += "]}\n";
    g.json = j;
    return g;
}

std::string glb(const HandGltf& g) {
    std::string json = g.json;
    while (json.size() % 4) json.push_back(' ');
    std::string o = "glTF";
    put(&o, uint32_t(2));
    put(&o, uint32_t(12 + 8 + json.size() + 8 + g.bin.size()));
    put(&o, uint32_t(json.size()));
    o += "JSON" + json;
    put(&o, uint32_t(g.bin.size()));
    o += std::string("BIN\0", 4) + g.bin;
    return o;
}

std::string engineWritten(const fs::path& dir, const std::string& name,
                          const std::vector<std::pair<std::string, const TriangleMesh*>>& meshes) {
    fs::create_directories(dir);
    const std::string path = (dir / name).string();
    std::string error;
    if (!writeGltfMeshes(path, meshes, &error)) throw std::runtime_error(error);
    std::string bytes = readFile(path);
    fs::remove(path);
    return bytes;
}

// ---- images ----------------------------------------------------------------------------------------

uint32_t crc32(const std::string& s, size_t from) {
    uint32_t c = 0xffffffffu;
    for (size_t i = from; i < s.size(); ++i) {
        c ^= uint8_t(s[i]);
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return ~c;
}

void chunk(std::string* png, const char* type, const std::string& data) {
    putBigEndian(png, uint32_t(data.size()));
    const size_t from = png->size();
    *png += std::string(type, 4) + data;
    putBigEndian(png, crc32(*png, from));
}

uint8_t paeth(int a, int b, int c) {
    const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    return uint8_t(pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
}

// Filters rows of `row_bytes` bytes (bpp: bytes per complete pixel, at least 1), each with a different
// filter type so every unfilter path of the decoder is seeded.
std::string filterRows(const std::string& raw, size_t row_bytes, size_t bpp, int first_filter) {
    std::string out;
    const size_t rows = row_bytes ? raw.size() / row_bytes : 0;
    for (size_t y = 0; y < rows; ++y) {
        const int f = int((y + size_t(first_filter)) % 5);
        out.push_back(char(f));
        for (size_t x = 0; x < row_bytes; ++x) {
            const int cur = uint8_t(raw[y * row_bytes + x]);
            const int a = x >= bpp ? uint8_t(raw[y * row_bytes + x - bpp]) : 0;
            const int b = y ? uint8_t(raw[(y - 1) * row_bytes + x]) : 0;
            const int c = x >= bpp && y ? uint8_t(raw[(y - 1) * row_bytes + x - bpp]) : 0;
            int v = cur;
            if (f == 1) v = cur - a;
            else if (f == 2) v = cur - b;
            else if (f == 3) v = cur - (a + b) / 2;
            else if (f == 4) v = cur - paeth(a, b, c);
            out.push_back(char(uint8_t(v)));
        }
    }
    return out;
}

struct PngSpec {
    int w, h, depth, colour;
    bool interlaced = false;
    bool split_idat = false;  // two IDAT chunks
    bool extras = false;      // ancillary chunks the decoder must skip
};

int channels(int colour) { return colour == 2 ? 3 : colour == 4 ? 2 : colour == 6 ? 4 : 1; }

// Samples: a smooth slope with a bump, scaled to the depth (palette: indices into a 4-entry palette).
uint32_t sample(const PngSpec& s, int x, int y, int c) {
    const uint32_t max = s.colour == 3 ? 3u : (1u << s.depth) - 1u;
    const double v = 0.5 + 0.4 * std::sin(0.9 * x + 0.3 * c) * std::cos(0.7 * y);
    return std::min<uint32_t>(max, uint32_t(v * max + 0.5));
}

// Packs rows of the (sub)image of pixels (x0 + k dx, y0 + l dy) as PNG scanlines (samples MSB first).
std::string packed(const PngSpec& s, int x0, int y0, int dx, int dy, int* pw, int* ph) {
    const int nc = channels(s.colour);
    *pw = s.w > x0 ? (s.w - x0 + dx - 1) / dx : 0;
    *ph = s.h > y0 ? (s.h - y0 + dy - 1) / dy : 0;
    const size_t row_bits = size_t(*pw) * size_t(nc) * size_t(s.depth);
    const size_t row_bytes = (row_bits + 7) / 8;
    std::string raw(row_bytes * size_t(*ph), '\0');
    for (int l = 0; l < *ph; ++l) {
        size_t bit = 0;
        for (int k = 0; k < *pw; ++k)
            for (int c = 0; c < nc; ++c) {
                const uint32_t v = sample(s, x0 + k * dx, y0 + l * dy, c);
                unsigned char* row = reinterpret_cast<unsigned char*>(raw.data()) + size_t(l) * row_bytes;
                if (s.depth == 16) {
                    row[bit / 8] = uint8_t(v >> 8);
                    row[bit / 8 + 1] = uint8_t(v);
                } else if (s.depth == 8) {
                    row[bit / 8] = uint8_t(v);
                } else {
                    row[bit / 8] |= uint8_t(v << (8 - s.depth - bit % 8));
                }
                bit += size_t(s.depth);
            }
    }
    return raw;
}

std::string png(const PngSpec& s) {
    const int nc = channels(s.colour);
    const size_t bpp = std::max<size_t>(1, size_t(nc) * size_t(s.depth) / 8);
    std::string filtered;
    if (!s.interlaced) {
        int pw, ph;
        const std::string raw = packed(s, 0, 0, 1, 1, &pw, &ph);
        filtered = filterRows(raw, raw.size() / size_t(ph), bpp, 0);
    } else {
        static const int kPass[7][4] = {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4},
                                        {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}};
        for (int p = 0; p < 7; ++p) {
            int pw, ph;
            const std::string raw = packed(s, kPass[p][0], kPass[p][1], kPass[p][2], kPass[p][3], &pw, &ph);
            if (pw && ph) filtered += filterRows(raw, raw.size() / size_t(ph), bpp, p);
        }
    }
    int zlen = 0;
    unsigned char* z = stbi_zlib_compress(reinterpret_cast<unsigned char*>(filtered.data()), int(filtered.size()), &zlen, 8);
    const std::string zs(reinterpret_cast<char*>(z), size_t(zlen));
    std::free(z);
    std::string o = "\x89PNG\r\n\x1a\n";
    std::string ihdr;
    putBigEndian(&ihdr, uint32_t(s.w));
    putBigEndian(&ihdr, uint32_t(s.h));
    ihdr += {char(s.depth), char(s.colour), 0, 0, char(s.interlaced ? 1 : 0)};
    chunk(&o, "IHDR", ihdr);
    if (s.extras) {
        chunk(&o, "gAMA", std::string("\x00\x00\xb1\x8f", 4));
        chunk(&o, "tEXt", std::string("Comment\0fuzz seed", 17));
    }
    if (s.colour == 3) {
        chunk(&o, "PLTE", std::string("\x00\x00\x00\x40\x40\x40\x90\x90\x90\xff\xff\xff", 12));
        chunk(&o, "tRNS", std::string("\xff\x80", 2));
    }
    if (s.split_idat) {
        chunk(&o, "IDAT", zs.substr(0, zs.size() / 2));
        chunk(&o, "IDAT", zs.substr(zs.size() / 2));
    } else {
        chunk(&o, "IDAT", zs);
    }
    chunk(&o, "IEND", "");
    return o;
}

std::string pgm(int w, int h) {
    std::string o = "P5\n# fuzz seed\n" + std::to_string(w) + " " + std::to_string(h) + "\n255\n";
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) o.push_back(char(uint8_t(16 * x + 8 * y)));
    return o;
}

void appendBytes(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

std::string stbWritten(bool bmp) {
    unsigned char rgb[4 * 3 * 3];
    for (int i = 0; i < 36; ++i) rgb[i] = uint8_t(7 * i);
    std::string o;
    if (bmp) stbi_write_bmp_to_func(appendBytes, &o, 4, 3, 3, rgb);
    else stbi_write_tga_to_func(appendBytes, &o, 4, 3, 3, rgb);
    return o;
}

// ---- Ghost Tile caches -------------------------------------------------------------------------------

DetailModel sphereModel(const char* name, std::vector<Sphere> spheres) {
    DetailModel m;
    m.name = name;
    m.spheres = std::move(spheres);
    glm::vec3 c(0.0f);
    for (const Sphere& s : m.spheres) c += s.center;
    c /= float(m.spheres.size());
    float r = 0.0f;
    for (const Sphere& s : m.spheres) {
        r = std::max(r, glm::length(s.center - c) + s.radius);
        m.anchors.push_back(s.center);
    }
    m.bounds = {c, r};
    return m;
}

std::string cache(const fs::path& dir, std::vector<uint32_t> counts, uint64_t seed) {
    static const DetailModel models[] = {
        sphereModel("rod", {{{-0.03f, 0, 0}, 0.012f}, {{0, 0, 0}, 0.012f}, {{0.03f, 0, 0}, 0.012f}}),
        sphereModel("blob", {{{0, 0, 0}, 0.03f}, {{0.02f, 0.01f, 0}, 0.02f}}),
        sphereModel("chip", {{{0, 0, 0}, 0.015f}}),
    };
    GhostTileInput input;
    input.settings = {.tile_size_m = 0.3f, .delta_m = -0.001f, .seed = seed};
    for (size_t t = 0; t < counts.size(); ++t) {
        DetailTypeSettings d;
        d.name = models[t].name;
        d.candidate_count = counts[t];
        d.scale_min = 0.8f;
        d.scale_max = 1.2f;
        if (t == 1) {
            d.orientation.mode = OrientationMode::Tilt;
            d.orientation.tilt_ranges = {{0, 20, 1}};
        }
        input.types.push_back(d);
        input.models.push_back(&models[t]);
    }
    GhostTile tile;
    std::string error;
    if (!buildGhostTile(input, BuildOptions{.threads = 1}, &tile, &error)) throw std::runtime_error(error);
    if (tile.graph.encodedBytes().empty()) throw std::runtime_error("seed cache without pairs");
    fs::create_directories(dir);
    const std::string path = (dir / "tmp.ugt").string();
    if (!saveGhostTileCache(path, tile, &error)) throw std::runtime_error(error);
    std::string bytes = readFile(path);
    fs::remove(path);
    return bytes;
}

// ---- scenes ------------------------------------------------------------------------------------------

// Small sphere fits keep a scene load in milliseconds.
const char* kFit = "\"spheres\": {\"max_spheres\": 8, \"surface_samples\": 200}";

std::string sceneV1() {
    return std::string(R"({"format": "undergrowth-project", "format_version": 1, "name": "v1",
 "ghost_tile": {"tile_size_m": 0.3, "delta_m": -0.001, "seed": 3},
 "detail_types": [{"name": "pebble", "model": {"mesh": "data/pebble.glb", )") + kFit + R"(},
                   "candidates": {"count": 30, "scale": [0.8, 1.2]}}]}
)";
}

// Materials on the terrain and on two types (one a cut-out), every key of the material object used.
std::string sceneMaterials() {
    return R"({"format": "undergrowth-project", "format_version": 2, "name": "materials",
 "ghost_tile": {"tile_size_m": 0.3, "delta_m": -0.001, "seed": 7},
 "terrain": {"procedural": {"origin": [-2, -2], "cell_size_m": 0.5, "width": 9, "height": 9, "seed": 11,
                            "octaves": 3, "amplitude_m": 0.3, "feature_size_m": 2},
             "material": {"base_color": [0.33, 0.26, 0.18], "roughness": 1, "texture": "ground", "texture_scale_m": 0.5}},
 "instantiation": {"seed": 1, "chunk_size_m": 2},
 "detail_types": [
  {"name": "cube", "model": {"mesh": "data/cube.obj", "y_up": false, "spheres": {"max_spheres": 8, "surface_samples": 200}},
   "material": {"base_color": [0.36, 0.33, 0.29], "roughness": 0.85, "texture": "rock", "texture_scale_m": 0.12,
                "tint_variation": 0.35, "alpha_cutout": false},
   "candidates": {"count": 25, "scale": [0.8, 1.3]},
   "density": {"terrain_layer": {"thickness": 0.05, "radius": 0.1, "weight": 0.8}}},
  {"name": "tetra", "model": {"mesh": "data/tetra.ply", "y_up": false, "spheres": {"max_spheres": 8, "surface_samples": 200}},
   "material": {"texture": "leaf", "texture_scale_m": 0.1, "alpha_cutout": true},
   "candidates": {"count": 15, "position": "jittered"},
   "density": {"terrain_layer": {"thickness": 0.03, "radius": 0.05, "weight": 0.5}}}]}
)";
}

std::string sceneProcedural() {
    return std::string(R"({"format": "undergrowth-project", "format_version": 2, "name": "procedural",
 "ghost_tile": {"tile_size_m": 0.3, "delta_m": -0.001, "seed": 7},
 "terrain": {"procedural": {"origin": [-2, -2], "cell_size_m": 0.5, "width": 9, "height": 9, "seed": 11,
                            "octaves": 3, "base_height_m": 0, "amplitude_m": 0.3, "feature_size_m": 2,
                            "lacunarity": 2, "gain": 0.5}},
 "instantiation": {"seed": 1, "chunk_size_m": 2},
 "detail_types": [
  {"name": "cube", "model": {"mesh": "data/cube.obj", "y_up": false, )") + kFit + R"(},
   "candidates": {"count": 25, "scale": [0.8, 1.3], "orientation": {"mode": "tilt", "tilt_ranges": [[0, 20, 1], [40, 60, 0.5]]}},
   "density": {"blend": [{"terrain_layer": {"thickness": 0.05, "radius": 0.1, "weight": 0.8}},
                         {"intersection": [{"terrain_layer": {"thickness": 0.05, "radius": 0.1}},
                                           {"point": {"center": [0.5, 0.5, 0], "radius": 1}}]}]},
   "instancing": {"strategy": "random", "orientation": {"direction": [0, 0, 1], "max_angle_deg": 30}}},
  {"name": "tetra", "model": {"mesh": "data/tetra.ply", "y_up": false, "scale": 1.5, )" + kFit + R"(},
   "candidates": {"count": 15, "position": "jittered"},
   "density": {"terrain_layer": {"thickness": 0.03, "radius": 0.05, "weight": 0.5}},
   "subtract_terrain": false,
   "instancing": {"strategy": "elevation", "layer_m": 0.01, "orientation": {"direction": "gradient", "max_angle_deg": 45}}}]}
)";
}

std::string sceneImage() {
    return std::string(R"({"format": "undergrowth-project", "format_version": 2, "name": "image",
 "ghost_tile": {"tile_size_m": 0.3, "delta_m": 0, "seed": 5},
 "terrain": {"image": {"path": "data/terrain.png", "origin": [-1, -1], "cell_size_m": 0.25, "min_height_m": -0.2, "max_height_m": 0.4}},
 "detail_types": [
  {"name": "wedge", "model": {"mesh": "data/wedge.stl", "y_up": false, )") + kFit + R"(},
   "candidates": {"count": 20, "scale": [0.9, 1.1]},
   "density": {"difference": [{"terrain_layer": {"thickness": 0.04, "radius": 0.08}},
                              {"terrain_solid": {"radius": 0.02}}]},
   "terrain_falloff_m": 0.02,
   "instancing": {"strategy": "distance_to_boundary", "size": {"target": {"field": {"point": {"center": [0, 0, 0], "radius": 1}},
                  "value_lo": 0, "value_hi": 1, "scale_lo": 0.8, "scale_hi": 1.2}, "tolerance": 0.3}}},
  {"name": "leaf", "model": {"mesh": "data/leaf.gltf", )" + kFit + R"(, "anchors": {"mode": "surface", "count": 4}},
   "candidates": {"count": 15},
   "density": {"terrain_layer": {"thickness": 0.02, "radius": 0.05, "weight": 0.6}},
   "instancing": {"size": {"target": 1.1, "tolerance": 0.2}}}]}
)";
}

// Every density node kind, authored spheres and anchors, an explicit extent.
std::string sceneAllNodes() {
    return R"({"format": "undergrowth-project", "format_version": 2, "name": "nodes",
 "ghost_tile": {"tile_size_m": 0.3, "delta_m": -0.002, "seed": 9},
 "extent": {"min": [-1, -1, -0.5], "max": [1, 1, 0.5]},
 "detail_types": [
  {"name": "cube", "model": {"mesh": "data/cube.off", "y_up": false,
                             "spheres": [[0, 0, 0, 0.06], [0.03, 0, 0, 0.03]],
                             "anchors": {"mode": "authored", "points": [[0, 0, 0], [0.02, 0.02, 0]]}},
   "candidates": {"count": 20},
   "density": {"difference": [
     {"blend": [{"point": {"center": [0, 0, 0], "radius": 0.6, "weight": 2}},
                {"segment": {"a": [-0.5, 0, 0], "b": [0.5, 0.1, 0], "radius": 0.2, "end_radius": 0.1, "weight": 1.5}},
                {"disc": {"center": [0, 0, 0], "normal": [0, 0, 1], "disc_radius": 0.3, "radius": 0.1}},
                {"box": {"center": [0.2, -0.2, 0], "half_extents": [0.1, 0.2, 0.05], "radius": 0.05, "weight": 0.5}},
                {"polyline": {"vertices": [[-0.6, -0.6, 0, 0.1], [0, -0.3, 0, 0.15], [0.6, -0.6, 0, 0.1]], "weight": 0.7}}]},
     {"union": [{"half_space": {"point": [0, 0, -0.05], "normal": [0, 0, 1], "radius": 0.02, "weight": 10000}},
                {"intersection": [{"point": {"center": [0.4, 0.4, 0], "radius": 0.2}},
                                  {"box": {"center": [0.4, 0.4, 0], "half_extents": [0.1, 0.1, 0.1], "radius": 0.05}}]}]}]}},
  {"name": "chip", "model": {"mesh": "data/tetra.ply", "y_up": false, "spheres": [[0, 0, 0, 0.05]],
                             "anchors": {"mode": "center"}},
   "candidates": {"count": 10, "orientation": {"mode": "uniform"}},
   "density": {"point": {"center": [0, 0, 0], "radius": 0.5}}}]}
)";
}

// The sphere fit's own defaults (3000 samples), a derived extent, a 16-bit terrain.
std::string sceneFit() {
    return R"({"format": "undergrowth-project", "format_version": 2, "name": "fit",
 "terrain": {"image": {"path": "data/terrain16.png", "cell_size_m": 0.5, "max_height_m": 0.5}},
 "ghost_tile": {"tile_size_m": 0.4, "seed": 2},
 "detail_types": [
  {"name": "pebble", "model": {"mesh": "data/pebble.glb", "anchors": {"mode": "sphere_centers", "count": 3}},
   "candidates": {"count": 12},
   "density": {"intersection": [{"terrain_layer": {"thickness": 0.05, "radius": 0.05}},
                                {"point": {"center": [1, 1, 0], "radius": 0.8}}]}}]}
)";
}

// Near-valid: must be refused with the place named.
std::string sceneUnknownKey() {
    std::string s = sceneV1();
    s.replace(s.find("\"seed\": 3"), 9, "\"seed\": 3, \"sede\": 4");
    return s;
}

std::string sceneMissingModel() {
    std::string s = sceneAllNodes();
    s.replace(s.find("data/tetra.ply"), 14, "data/nothing.ply");
    return s;
}

// ---- particle systems ------------------------------------------------------------------------------

// Few particles and steps: a mutated seed grows in milliseconds unless its counts were raised.
std::string particlesGrass() {
    return R"({"format": "undergrowth-particles", "format_version": 1, "name": "grass",
 "generators": [{"kind": "rectangle", "center_m": [0, 0, 0], "axis_u_m": [0.2, 0, 0], "axis_v_m": [0, 0.2, 0],
                 "count": 24, "heading_cone_deg": 10}],
 "attractors": [{"kind": "point", "a_m": [0, 0, 2], "charge": 1}],
 "cutters": [{"kind": "plane", "center_m": [0, 0, 0.05], "normal": [0, 0, 1], "threshold_m": 0, "side": "above",
              "action": {"kind": "split", "split_count": 2, "split_angle_deg": 30}}],
 "walk": {"seed": 3, "steps": 12, "trials": 4, "cone_deg": 20, "step_length_m": 0.01, "strand_radius_m": 0.002,
          "collisions": true, "on_collision": {"kind": "stop"}, "max_split_depth": 1},
 "mesh": {"sides": 4}, "material": {"base_color": [0.2, 0.4, 0.1], "roughness": 0.8}}
)";
}

std::string particlesEveryKind() {
    return R"({"format": "undergrowth-particles", "format_version": 1, "name": "every_kind",
 "generators": [{"kind": "sphere", "center_m": [0, 0, 0], "radius_m": 0.05, "count": 12, "heading_cone_deg": 20},
                {"kind": "box", "center_m": [1, 0, 0], "half_extents_m": [0.1, 0.1, 0.1], "count": 12}],
 "attractors": [{"kind": "segment", "a_m": [0, 0, 1], "b_m": [1, 0, 1], "influence_m": 0.5,
                 "charge": [[0, 1], [5, -0.5]]},
                {"kind": "sphere", "a_m": [0.5, 0, 0.5], "radius_m": 0.2, "charge": -1}],
 "cutters": [{"kind": "sphere", "center_m": [0.5, 0, 0.5], "radius_m": 0.3, "threshold_m": 0, "side": "below",
              "action": {"kind": "countdown", "countdown_steps": 2}},
             {"kind": "box", "center_m": [0, 0, 0], "half_extents_m": [2, 2, 2], "threshold_m": 0,
              "action": {"kind": "kill"}}],
 "walk": {"seed": 9, "steps": 10, "trials": 3, "cone_deg": 40, "step_length_m": 0.02, "strand_radius_m": 0.001,
          "max_age_steps": 6, "on_age": {"kind": "split", "split_count": 2}, "max_split_depth": 2}}
)";
}

// A mesh generator on the corpus's cube (data/cube.obj, beside the input), solids on, a countdown that
// ends in a stop.
std::string particlesMesh() {
    return R"({"format": "undergrowth-particles", "format_version": 1, "name": "moss",
 "generators": [{"kind": "mesh", "mesh": "data/cube.obj", "scale": 2, "center_m": [0, 0, 0.1], "count": 20,
                 "heading_cone_deg": 30}],
 "attractors": [{"kind": "point", "a_m": [0, 0, 0.1], "charge": [[0, -1], [4, 1]]}],
 "cutters": [{"kind": "sphere", "center_m": [0, 0, 0.1], "radius_m": 0.2, "threshold_m": 0, "side": "above",
              "action": {"kind": "countdown", "countdown_steps": 2, "countdown_then": "stop"}}],
 "walk": {"seed": 4, "steps": 8, "trials": 4, "cone_deg": 40, "step_length_m": 0.01, "strand_radius_m": 0.001,
          "solids": true}}
)";
}

// The procedural scene with two particle systems (format 4): one on its terrain, one moved and renamed.
std::string sceneParticles() {
    std::string s = sceneProcedural();
    s.replace(s.find("\"format_version\": 2"), 19, "\"format_version\": 4");
    s.insert(s.rfind('}'), R"(,
 "particles": [{"file": "data/strands.json"},
               {"file": "data/strands.json", "name": "strands_2", "offset_m": [0.5, 0.5, 0]}])");
    return s;
}

std::string particlesOnTerrain() {
    return R"({"format": "undergrowth-particles", "format_version": 1, "name": "strands",
 "generators": [{"kind": "rectangle", "axis_u_m": [0.2, 0, 0], "axis_v_m": [0, 0.2, 0], "count": 16,
                 "on_terrain": true}],
 "walk": {"seed": 2, "steps": 6, "trials": 4, "cone_deg": 20, "step_length_m": 0.01, "strand_radius_m": 0.001}}
)";
}

void write(const fs::path& dir, const std::string& name, const std::string& bytes) {
    fs::create_directories(dir);
    writeFile((dir / name).string(), bytes);
}

}  // namespace

int makeCorpus(const std::string& root_arg) {
    const fs::path root(root_arg);
    const Shape cu = cube(), te = tetra(), we = wedge(), ico = icosahedron();

    const fs::path o = root / "obj";
    write(o, "cube_quads.obj", obj(cu, 0));
    write(o, "tetra_negative_indices.obj", obj(te, 1));
    write(o, "wedge_vt_vn.obj", obj(we, 2));
    write(o, "pentagon_fan.obj", "v 0 0 0\nv 0.04 0 0\nv 0.05 0.03 0\nv 0.02 0.05 0\nv -0.01 0.03 0\nf 1 2 3 4 5\n");
    write(o, "near_index_out_of_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    write(o, "near_nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
    write(o, "near_no_faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");

    const fs::path p = root / "ply";
    write(p, "cube_ascii.ply", plyAscii(cu));
    write(p, "tetra_binary_le.ply", plyBinary(te, false));
    write(p, "wedge_binary_be.ply", plyBinary(we, true));
    std::string short_ply = plyAscii(te);
    short_ply.replace(short_ply.find("element vertex 4"), 16, "element vertex 5");
    write(p, "near_vertex_count.ply", short_ply);

    const fs::path s = root / "stl";
    write(s, "tetra_ascii.stl", stlAscii(te));
    write(s, "cube_binary.stl", stlBinary(cu, "binary seed"));
    write(s, "wedge_binary_solid_header.stl", stlBinary(we, "solid but binary"));
    write(s, "near_count.stl", stlBinary(te, "binary seed", 5));

    const fs::path f = root / "off";
    write(f, "cube.off", off(cu, 0));
    write(f, "tetra_coff.off", off(te, 1));
    write(f, "wedge_face_colours.off", off(we, 2));
    write(f, "near_comment.off", off(we, 3));
    write(f, "tetra_binary.off", offBinary(te));
    std::string short_off = off(te, 0);
    short_off.replace(short_off.find("4 4 0"), 5, "4 6 0");
    write(f, "near_face_count.off", short_off);

    const TriangleMesh cu_m = mesh(cu), te_m = mesh(te), ico_m = mesh(ico), we_m = mesh(we);
    const fs::path g = root / "glb";
    write(g, "pebble_engine.glb", engineWritten(g, "x.glb", {{"pebble", &ico_m}}));
    write(g, "two_meshes_engine.glb", engineWritten(g, "x.glb", {{"cube", &cu_m}, {"tetra", &te_m}}));
    write(g, "wedge_ushort_nodes.glb", glb(handGltf(we, 2, true, "")));
    write(g, "tetra_not_indexed_no_scene.glb", glb(handGltf(te, 0, false, "")));

    const fs::path t = root / "gltf";
    write(t, "leaf_engine.gltf", engineWritten(t, "x.gltf", {{"leaf", &we_m}}));
    write(t, "cube_ubyte_embedded.gltf", handGltf(cu, 1, true, "data").json);
    const HandGltf ext = handGltf(we, 4, true, "data/wedge.bin");
    write(t, "wedge_external_buffer.gltf", ext.json);
    write(t / "data", "wedge.bin", ext.bin);
    write(t, "near_missing_buffer.gltf", handGltf(te, 2, false, "data/missing.bin").json);

    const fs::path c = root / "ghosttile";
    write(c, "two_types.ugt", cache(c, {40, 12}, 7));
    write(c, "three_types.ugt", cache(c, {20, 8, 30}, 11));
    write(c, "one_type.ugt", cache(c, {60}, 3));

    const fs::path i = root / "png";
    write(i, "gray8_5x4.png", png({5, 4, 8, 0}));
    write(i, "gray16_4x3.png", png({4, 3, 16, 0}));
    write(i, "rgb8_3x3_extras.png", png({3, 3, 8, 2, false, false, true}));
    write(i, "rgba8_2x2_split_idat.png", png({2, 2, 8, 6, false, true}));
    write(i, "palette4_5x3.png", png({5, 3, 4, 3}));
    write(i, "gray1_9x2.png", png({9, 2, 1, 0}));
    write(i, "gray8_9x9_interlaced.png", png({9, 9, 8, 0, true}));
    write(i, "graya16_3x2.png", png({3, 2, 16, 4}));
    write(i, "gray8_4x3.pgm", pgm(4, 3));
    write(i, "rgb_4x3.bmp", stbWritten(true));
    write(i, "rgb_4x3.tga", stbWritten(false));

    const fs::path sc = root / "scene", data = sc / "data";
    write(data, "cube.obj", obj(cu, 0));
    write(data, "cube.off", off(cu, 0));
    write(data, "tetra.ply", plyBinary(te, false));
    write(data, "wedge.stl", stlBinary(we, "binary seed"));
    write(data, "pebble.glb", engineWritten(data, "x.glb", {{"pebble", &ico_m}}));
    write(data, "leaf.gltf", engineWritten(data, "x.gltf", {{"leaf", &we_m}}));
    write(data, "terrain.png", png({9, 9, 8, 0}));
    write(data, "terrain16.png", png({5, 5, 16, 0}));
    write(sc, "v1_minimal.json", sceneV1());
    write(sc, "procedural_terrain.json", sceneProcedural());
    write(sc, "materials.json", sceneMaterials());
    write(sc, "image_terrain_size_ramp.json", sceneImage());
    write(sc, "all_nodes_authored.json", sceneAllNodes());
    write(sc, "default_fit_derived_extent.json", sceneFit());
    write(sc, "near_unknown_key.json", sceneUnknownKey());
    write(sc, "near_missing_model.json", sceneMissingModel());
    write(data, "strands.json", particlesOnTerrain());
    write(sc, "particle_systems.json", sceneParticles());
    const fs::path pa = root / "particles";
    write(pa, "grass_split.json", particlesGrass());
    write(pa, "every_kind.json", particlesEveryKind());
    write(pa / "data", "cube.obj", obj(cu, 0));
    write(pa, "mesh_generator.json", particlesMesh());
    std::printf("corpus written under %s\n", root.string().c_str());
    return 0;
}

}  // namespace ug::fuzz
