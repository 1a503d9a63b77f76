// OFF reader (contract in mesh_readers.h). Line-based: a vertex or face record is one line, so the
// optional extras the OFF variants append (normals, colours, texture coordinates) are skipped without
// knowing the variant.
#include <cmath>
#include <vector>

#include "mesh/mesh_reader_detail.h"
#include "mesh/mesh_readers.h"

namespace ug {

namespace {

using namespace mesh_reader;

// The shortest records: "0 0 0\n" and "3 0 1 2\n"; used to check the declared counts against the file.
constexpr uint64_t kMinVertexBytes = 6;
constexpr uint64_t kMinFaceBytes = 8;

// "OFF" with optional variant letters before it: ST (texture), C (colour), N (normal). 4OFF and nOFF
// change the vertex dimension, which this reader does not support.
bool checkKeyword(std::string_view keyword, std::string* why) {
    if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF") {
        *why = "not an OFF file (the first word is " + shown(keyword) + ", want OFF)";
        return false;
    }
    for (const char c : keyword.substr(0, keyword.size() - 3)) {
        if (c == '4' || c == 'n') {
            *why = shown(keyword) + " (vertices that are not 3D) is not supported";
            return false;
        }
        if (c != 'S' && c != 'T' && c != 'C' && c != 'N') {
            *why = "not an OFF file (the first word is " + shown(keyword) + ", want OFF)";
            return false;
        }
    }
    return true;
}

}  // namespace

bool readOff(std::string_view bytes, const std::string& name, TriangleMesh* out, std::string* error) {
    TextScanner scan(withoutBom(bytes), '#', /*continuation=*/false);
    auto where = [&](size_t line) { return "line " + std::to_string(line) + ": "; };
    if (!scan.nextContentLine()) return fail(error, name, "empty file (no OFF header)");
    std::string why;
    if (!checkKeyword(scan.lineToken(), &why)) return fail(error, name, why);

    // The counts follow on the OFF line itself or on the next content line.
    std::string_view token = scan.lineToken();
    if (token == "BINARY") return fail(error, name, "binary OFF is not supported");
    if (token.empty()) {
        scan.nextLine();
        if (!scan.nextContentLine()) return fail(error, name, "truncated before the vertex and face counts");
        token = scan.lineToken();
    }
    const size_t count_line = scan.line();
    int64_t counts[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
        if (k == 1) token = scan.lineToken();
        if (!parseInteger(token, &counts[k]) || counts[k] < 0)
            return fail(error, name,
                        where(count_line) + "bad " + (k == 0 ? "vertex" : "face") + " count " + shown(token) +
                            " (want \"<vertices> <faces> [<edges>]\", counts >= 0)");
    }
    // The edge count is optional and unused.
    const uint64_t vertex_count = uint64_t(counts[0]), face_count = uint64_t(counts[1]);
    scan.nextLine();

    // Counts against the bytes that are left, then the limits, before allocating anything.
    uint64_t budget = scan.remaining() + 1;  // the last line needs no line end
    why = countExceedsFile(vertex_count, kMinVertexBytes, budget, "vertices", bytes.size());
    if (why.empty()) {
        budget -= vertex_count * kMinVertexBytes;
        why = countExceedsFile(face_count, kMinFaceBytes, budget, "faces", bytes.size());
    }
    if (!why.empty()) return fail(error, name, where(count_line) + why);
    if (vertex_count > kMaxMeshVertices)
        return fail(error, name, where(count_line) + "declares " + vertexLimitExceeded(vertex_count));
    if (face_count > kMaxMeshTriangles)
        return fail(error, name,
                    where(count_line) + "declares " + std::to_string(face_count) +
                        " faces; models are limited to " + std::to_string(kMaxMeshTriangles) +
                        " triangles (kMaxMeshTriangles)");

    TriangleMesh mesh;
    mesh.positions.reserve(size_t(vertex_count));
    mesh.indices.reserve(size_t(face_count) * 3);
    for (uint64_t v = 0; v < vertex_count; ++v) {
        if (!scan.nextContentLine())
            return fail(error, name,
                        "truncated in the vertex list at vertex " + std::to_string(v) + " of " +
                            std::to_string(vertex_count));
        const size_t line = scan.line();
        float xyz[3];
        for (int k = 0; k < 3; ++k) {
            token = scan.lineToken();
            double value = 0.0;
            if (token.empty())
                return fail(error, name,
                            where(line) + "vertex " + std::to_string(v) + " has only " + std::to_string(k) +
                                " coordinates (needs x y z)");
            if (!parseReal(token, &value))
                return fail(
                    error, name,
                    where(line) + "vertex " + std::to_string(v) + ": " + shown(token) + " is not a number");
            xyz[k] = float(value);
            if (!std::isfinite(xyz[k]))
                return fail(error, name,
                            where(line) + "vertex " + std::to_string(v) + " has a non-finite " + axisName(k) +
                                " coordinate (" + std::string(token.substr(0, 40)) + ")");
        }
        mesh.positions.emplace_back(xyz[0], xyz[1], xyz[2]);
        scan.nextLine();
    }

    std::vector<uint32_t> corners;
    for (uint64_t f = 0; f < face_count; ++f) {
        if (!scan.nextContentLine())
            return fail(error, name,
                        "truncated in the face list at face " + std::to_string(f) + " of " +
                            std::to_string(face_count));
        const size_t line = scan.line();
        auto face = [&] { return where(line) + "face " + std::to_string(f); };
        token = scan.lineToken();
        int64_t n = 0;
        if (!parseInteger(token, &n))
            return fail(error, name, face() + ": " + shown(token) + " is not a vertex count");
        if (n < 3)
            return fail(error, name,
                        face() + " has " + std::to_string(n) + " vertices (a face needs at least 3)");
        if (mesh.triangleCount() + uint64_t(n - 2) > kMaxMeshTriangles)
            return fail(error, name,
                        face() + ": more than " + std::to_string(kMaxMeshTriangles) +
                            " triangles (kMaxMeshTriangles)");
        corners.clear();
        for (int64_t k = 0; k < n; ++k) {
            token = scan.lineToken();
            int64_t index = 0;
            if (token.empty())
                return fail(
                    error, name,
                    face() + " lists " + std::to_string(k) + " of its " + std::to_string(n) + " vertices");
            if (!parseInteger(token, &index))
                return fail(error, name, face() + ": " + shown(token) + " is not a vertex index");
            if (index < 0 || uint64_t(index) >= vertex_count)
                return fail(error, name,
                            face() + " refers to vertex " + std::to_string(index) + " but the file has " +
                                std::to_string(vertex_count) + " vertices");
            corners.push_back(uint32_t(index));
        }
        for (size_t k = 1; k + 1 < corners.size(); ++k)
            mesh.indices.insert(mesh.indices.end(), {corners[0], corners[k], corners[k + 1]});
        scan.nextLine();  // a face colour may follow the indices
    }
    return finish(&mesh, name, out, error);
}

}  // namespace ug
