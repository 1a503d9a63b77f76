// STL reader, binary and ASCII (contract in mesh_readers.h). STL has no shared vertices; corners are
// welded through a small open-addressing hash so the result is an indexed mesh in linear time.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

#include "mesh/mesh_reader_detail.h"
#include "mesh/mesh_readers.h"

namespace ug {

namespace {

using namespace mesh_reader;

constexpr size_t kBinaryHeaderBytes = 84;  // 80-byte comment + u32 triangle count
constexpr size_t kBinaryFacetBytes = 50;   // normal, 3 corners (12 floats), u16 attribute
// Maps each distinct position to one vertex of `mesh`. The table keeps at most half its slots full,
// so probes stay short; it grows with the number of distinct positions, not the number of corners.
class Welder {
  public:
    explicit Welder(TriangleMesh* mesh) : mesh_(mesh) { slots_.assign(1024, 0); }

    // The vertex for `p` (finite), adding it when new; false past kMaxMeshVertices.
    bool add(glm::vec3 p, uint32_t* vertex) {
        // -0 and 0 are the same point; make them the same bits before hashing.
        for (int k = 0; k < 3; ++k)
            if (p[k] == 0.0f) p[k] = 0.0f;
        const size_t mask = slots_.size() - 1;
        for (size_t slot = hash(p) & mask;; slot = (slot + 1) & mask) {
            const uint32_t entry = slots_[slot];
            if (entry == 0) break;
            if (mesh_->positions[entry - 1] == p) {
                *vertex = entry - 1;
                return true;
            }
        }
        if (mesh_->positions.size() >= kMaxMeshVertices) return false;
        mesh_->positions.push_back(p);
        *vertex = uint32_t(mesh_->positions.size() - 1);
        if (2 * mesh_->positions.size() > slots_.size())
            rebuild(slots_.size() * 2);
        else
            insert(*vertex);
        return true;
    }

  private:
    static size_t hash(const glm::vec3& p) {
        uint64_t h = uint64_t(std::bit_cast<uint32_t>(p.x)) * 0x9E3779B97F4A7C15ull;
        h ^= uint64_t(std::bit_cast<uint32_t>(p.y)) * 0xC2B2AE3D27D4EB4Full;
        h ^= uint64_t(std::bit_cast<uint32_t>(p.z)) * 0x165667B19E3779F9ull;
        return size_t(h ^ (h >> 31));
    }
    void insert(uint32_t vertex) {
        const size_t mask = slots_.size() - 1;
        size_t slot = hash(mesh_->positions[vertex]) & mask;
        while (slots_[slot] != 0) slot = (slot + 1) & mask;
        slots_[slot] = vertex + 1;
    }
    void rebuild(size_t size) {
        slots_.assign(size, 0);
        for (uint32_t v = 0; v < mesh_->positions.size(); ++v) insert(v);
    }

    TriangleMesh* mesh_;
    std::vector<uint32_t> slots_;  // vertex + 1; 0 = empty
};

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i) {
        const char x = (a[i] >= 'A' && a[i] <= 'Z') ? char(a[i] - 'A' + 'a') : a[i];
        if (x != b[i]) return false;  // b is lower case
    }
    return true;
}

// ASCII only when the file starts with "solid" AND its first bytes are text: binary exporters often
// put "solid" in the 80-byte comment, but their count and float bytes soon hit control characters.
bool looksAscii(std::string_view bytes) {
    size_t start = 0;
    while (start < bytes.size() &&
           (bytes[start] == ' ' || bytes[start] == '\t' || bytes[start] == '\r' || bytes[start] == '\n'))
        ++start;
    if (bytes.size() - start < 5 || !equalsIgnoringCase(bytes.substr(start, 5), "solid")) return false;
    const size_t probe = std::min<size_t>(bytes.size(), 1024);
    for (size_t i = 0; i < probe; ++i) {
        const unsigned char c = static_cast<unsigned char>(bytes[i]);
        if (c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\v' && c != '\f') return false;
        if (c == 0x7f) return false;
    }
    return true;
}

float loadFloatLE(const char* p) {
    uint32_t bits;
    std::memcpy(&bits, p, 4);
    if constexpr (std::endian::native == std::endian::big) bits = __builtin_bswap32(bits);
    return std::bit_cast<float>(bits);
}

std::string nonFinite(uint64_t facet, int corner, int axis, double value) {
    return "facet " + std::to_string(facet) + ": vertex " + std::to_string(corner) + " has a non-finite " +
           axisName(axis) + " coordinate (" + valueText(value) + ")";
}

bool readBinary(std::string_view bytes, const std::string& name, TriangleMesh* out, std::string* error) {
    if (bytes.size() < kBinaryHeaderBytes)
        return fail(
            error, name,
            "not an ASCII STL (it does not start with \"solid\" and text) and too short for a binary STL (" +
                std::to_string(bytes.size()) + " bytes, the binary header alone is 84)");
    uint32_t count;
    std::memcpy(&count, bytes.data() + 80, 4);
    if constexpr (std::endian::native == std::endian::big) count = __builtin_bswap32(count);
    std::string why = countExceedsFile(count, kBinaryFacetBytes, bytes.size() - kBinaryHeaderBytes,
                                       "triangles", bytes.size());
    if (!why.empty())
        return fail(error, name,
                    "binary STL header " + why + " (" +
                        std::to_string(kBinaryHeaderBytes + uint64_t(count) * kBinaryFacetBytes) +
                        " needed)");
    if (count > kMaxMeshTriangles)
        return fail(error, name, "binary STL header declares " + triangleLimitExceeded(count));
    if (count == 0) return fail(error, name, "binary STL with no triangles");

    TriangleMesh mesh;
    mesh.indices.reserve(size_t(count) * 3);
    Welder welder(&mesh);
    for (uint64_t f = 0; f < count; ++f) {
        const char* facet =
            bytes.data() + kBinaryHeaderBytes + f * kBinaryFacetBytes + 12;  // skip the normal
        for (int c = 0; c < 3; ++c) {
            glm::vec3 p;
            for (int k = 0; k < 3; ++k) {
                p[k] = loadFloatLE(facet + 12 * c + 4 * k);
                if (!std::isfinite(p[k])) return fail(error, name, nonFinite(f, c, k, p[k]));
            }
            uint32_t vertex = 0;
            if (!welder.add(p, &vertex))
                return fail(error, name,
                            "facet " + std::to_string(f) + ": the model has " +
                                vertexLimitExceeded(kMaxMeshVertices + 1));
            mesh.indices.push_back(vertex);
        }
    }
    return finish(&mesh, name, out, error);
}

bool readAscii(std::string_view bytes, const std::string& name, TriangleMesh* out, std::string* error) {
    TextScanner scan(bytes, 0, false);
    TriangleMesh mesh;
    Welder welder(&mesh);
    uint64_t facet = 0;
    std::string_view token;
    auto where = [&] { return "line " + std::to_string(scan.line()) + ": "; };
    // The next token must be `keyword` (lower case here, any case in the file).
    auto expect = [&](std::string_view keyword) {
        token = scan.token();
        if (token.empty())
            return fail(error, name,
                        "truncated in facet " + std::to_string(facet) + " (the file ends before '" +
                            std::string(keyword) + "')");
        if (!equalsIgnoringCase(token, keyword))
            return fail(error, name,
                        where() + "facet " + std::to_string(facet) + ": expected '" + std::string(keyword) +
                            "', found " + shown(token));
        return true;
    };
    auto number = [&](const char* what, double* value) {
        token = scan.token();
        if (token.empty())
            return fail(
                error, name,
                "truncated in facet " + std::to_string(facet) + " (the file ends inside its " + what + ")");
        if (!parseReal(token, value))
            return fail(
                error, name,
                where() + "facet " + std::to_string(facet) + ": " + shown(token) + " is not a number");
        return true;
    };

    if (!expect("solid")) return false;
    scan.nextLine();  // the solid's name
    for (;;) {
        token = scan.token();
        if (token.empty())
            return fail(
                error, name,
                "truncated after facet " + std::to_string(facet) + " (the file ends without 'endsolid')");
        if (equalsIgnoringCase(token, "endsolid")) {
            scan.nextLine();  // its name
            token = scan.token();
            if (token.empty()) break;
            // Some tools concatenate several solids into one file.
            if (!equalsIgnoringCase(token, "solid"))
                return fail(error, name,
                            where() + "expected 'solid' or the end after 'endsolid', found " + shown(token));
            scan.nextLine();
            continue;
        }
        if (!equalsIgnoringCase(token, "facet"))
            return fail(error, name,
                        where() + "expected 'facet' or 'endsolid' after facet " + std::to_string(facet) +
                            ", found " + shown(token));
        if (!expect("normal")) return false;
        double unused = 0.0;
        for (int k = 0; k < 3; ++k)
            if (!number("normal", &unused)) return false;  // recomputed anyway; NaN normals are common
        if (!expect("outer") || !expect("loop")) return false;
        if (mesh.triangleCount() >= kMaxMeshTriangles)
            return fail(error, name,
                        where() + "facet " + std::to_string(facet) + ": more than " +
                            std::to_string(kMaxMeshTriangles) + " triangles (kMaxMeshTriangles)");
        int corners = 0;
        for (;;) {
            token = scan.token();
            if (token.empty())
                return fail(
                    error, name,
                    "truncated in facet " + std::to_string(facet) + " (the file ends before 'endloop')");
            if (equalsIgnoringCase(token, "endloop")) break;
            if (!equalsIgnoringCase(token, "vertex"))
                return fail(error, name,
                            where() + "facet " + std::to_string(facet) +
                                ": expected 'vertex' or 'endloop', found " + shown(token));
            if (corners == 3)
                return fail(error, name,
                            where() + "facet " + std::to_string(facet) +
                                " has more than 3 vertices (STL facets are triangles)");
            glm::vec3 p;
            for (int k = 0; k < 3; ++k) {
                double value = 0.0;
                if (!number("vertex", &value)) return false;
                p[k] = float(value);
                if (!std::isfinite(p[k]))
                    return fail(error, name,
                                where() + "facet " + std::to_string(facet) + ": vertex " +
                                    std::to_string(corners) + " has a non-finite " + axisName(k) +
                                    " coordinate (" + std::string(token.substr(0, 40)) + ")");
            }
            uint32_t vertex = 0;
            if (!welder.add(p, &vertex))
                return fail(error, name,
                            where() + "the model has " + vertexLimitExceeded(kMaxMeshVertices + 1));
            mesh.indices.push_back(vertex);
            ++corners;
        }
        if (corners < 3)
            return fail(error, name,
                        where() + "facet " + std::to_string(facet) + " has " + std::to_string(corners) +
                            " vertices (a facet needs 3)");
        if (!expect("endfacet")) return false;
        ++facet;
    }
    return finish(&mesh, name, out, error);
}

}  // namespace

bool readStl(std::string_view bytes, const std::string& name, TriangleMesh* out, std::string* error) {
    // An exact binary size match wins: such a file can still start with "solid" in its comment. Text
    // cannot match, since text bytes at offsets 80..83 make a count beyond any allowed file size.
    if (bytes.size() >= kBinaryHeaderBytes) {
        uint32_t count;
        std::memcpy(&count, bytes.data() + 80, 4);
        if constexpr (std::endian::native == std::endian::big) count = __builtin_bswap32(count);
        if (kBinaryHeaderBytes + uint64_t(count) * kBinaryFacetBytes == bytes.size())
            return readBinary(bytes, name, out, error);
    }
    if (looksAscii(withoutBom(bytes))) return readAscii(withoutBom(bytes), name, out, error);
    return readBinary(bytes, name, out, error);
}

}  // namespace ug
