// Wavefront OBJ reader (contract in mesh_readers.h). One pass over the text: `v` and `f` statements
// are parsed in place from the buffer, every other statement is skipped to its line end.
#include <cmath>
#include <vector>

#include "mesh/mesh_reader_detail.h"
#include "mesh/mesh_readers.h"

namespace ug {

namespace {

using namespace mesh_reader;

// Splits a face corner "v", "v/vt", "v/vt/vn" or "v//vn" and returns the vertex reference. The texture
// and normal references are not used, but must be integers (or empty) so garbage is not mistaken for
// a corner.
bool cornerVertex(std::string_view corner, int64_t* vertex) {
    const size_t slash = corner.find('/');
    if (!parseInteger(corner.substr(0, slash), vertex)) return false;
    if (slash == std::string_view::npos) return true;
    std::string_view rest = corner.substr(slash + 1);
    const size_t slash2 = rest.find('/');
    int64_t unused = 0;
    const std::string_view vt = rest.substr(0, slash2);
    if (!vt.empty() && !parseInteger(vt, &unused)) return false;
    if (slash2 == std::string_view::npos) return true;
    const std::string_view vn = rest.substr(slash2 + 1);
    // "v/vt/" is not a form the spec has, and "v//" (no vt, no vn) neither.
    if (vn.empty() || !parseInteger(vn, &unused)) return false;
    return true;
}

}  // namespace

bool readObj(std::string_view bytes, const std::string& name, TriangleMesh* out, std::string* error) {
    TriangleMesh mesh;
    TextScanner scan(withoutBom(bytes), '#', /*continuation=*/true);
    uint64_t face_count = 0;
    // A positive index may point past the vertices read so far (a later `v`); the largest such
    // reference is checked against the final count once the file has been read.
    int64_t forward_index = 0;
    size_t forward_line = 0;
    uint64_t forward_face = 0;
    std::vector<uint32_t> corners;  // reused for every face
    auto where = [&](size_t line) { return "line " + std::to_string(line) + ": "; };

    while (scan.nextContentLine()) {
        const size_t line = scan.line();
        const std::string_view keyword = scan.lineToken();
        if (keyword == "v") {
            const uint64_t number = mesh.positions.size() + 1;
            if (mesh.positions.size() >= kMaxMeshVertices)
                return fail(error, name,
                            where(line) + "vertex " + std::to_string(number) + ": more than " +
                                std::to_string(kMaxMeshVertices) + " vertices (kMaxMeshVertices)");
            float xyz[3];
            for (int k = 0; k < 3; ++k) {
                const std::string_view token = scan.lineToken();
                if (token.empty())
                    return fail(error, name,
                                where(line) + "vertex " + std::to_string(number) + " has only " +
                                    std::to_string(k) + " coordinates (needs x y z)");
                double value = 0.0;
                if (!parseReal(token, &value))
                    return fail(error, name,
                                where(line) + "vertex " + std::to_string(number) + ": " + shown(token) +
                                    " is not a number");
                xyz[k] = float(value);
                // The float test also catches finite doubles beyond float range (1e39 -> inf).
                if (!std::isfinite(xyz[k]))
                    return fail(error, name,
                                where(line) + "vertex " + std::to_string(number) + " has a non-finite " +
                                    axisName(k) + " coordinate (" + std::string(token.substr(0, 40)) + ")");
            }
            mesh.positions.emplace_back(xyz[0], xyz[1], xyz[2]);
        } else if (keyword == "f") {
            ++face_count;
            // Built only for a message: no allocation per face on the good path.
            auto face = [&] { return "face " + std::to_string(face_count); };
            corners.clear();
            const int64_t defined = int64_t(mesh.positions.size());
            for (std::string_view token = scan.lineToken(); !token.empty(); token = scan.lineToken()) {
                int64_t index = 0;
                if (!cornerVertex(token, &index))
                    return fail(error, name,
                                where(line) + face() + ": " + shown(token) +
                                    " is not a corner (want v, v/vt, v/vt/vn or v//vn)");
                if (index == 0)
                    return fail(error, name,
                                where(line) + face() + " refers to vertex 0 (OBJ indices start at 1)");
                int64_t resolved = 0;
                if (index < 0) {
                    // Relative: -1 is the latest vertex. Only vertices before the face can be meant.
                    if (-index > defined)
                        return fail(error, name,
                                    where(line) + face() + " refers to vertex " + std::to_string(index) +
                                        " but only " + std::to_string(defined) + " vertices precede it");
                    resolved = defined + index;
                } else {
                    if (index > defined && index > forward_index) {
                        forward_index = index;
                        forward_line = line;
                        forward_face = face_count;
                    }
                    // An index beyond any possible count fails below anyway; keep the stored value small.
                    resolved = index > int64_t(kMaxMeshVertices) ? 0 : index - 1;
                }
                // Checked per corner so one absurdly long face cannot grow `corners` past the limit.
                if (mesh.triangleCount() + corners.size() >= kMaxMeshTriangles + 2)
                    return fail(error, name,
                                where(line) + face() + ": more than " + std::to_string(kMaxMeshTriangles) +
                                    " triangles (kMaxMeshTriangles)");
                corners.push_back(uint32_t(resolved));
            }
            if (corners.size() < 3)
                return fail(error, name,
                            where(line) + face() + " has " + std::to_string(corners.size()) +
                                " vertices (a face needs at least 3)");
            for (size_t i = 1; i + 1 < corners.size(); ++i) {
                mesh.indices.push_back(corners[0]);
                mesh.indices.push_back(corners[i]);
                mesh.indices.push_back(corners[i + 1]);
            }
        }
        // Everything else (vt, vn, o, g, s, usemtl, mtllib, l, p, curves) carries nothing we use.
        scan.nextLine();
    }

    if (forward_index > int64_t(mesh.positions.size()))
        return fail(error, name,
                    where(forward_line) + "face " + std::to_string(forward_face) + " refers to vertex " +
                        std::to_string(forward_index) + " but the file has " +
                        std::to_string(mesh.positions.size()) + " vertices");
    if (face_count == 0)
        return fail(error, name,
                    "no triangles (the file has " + std::to_string(mesh.positions.size()) +
                        " vertices and no faces)");
    return finish(&mesh, name, out, error);
}

}  // namespace ug
