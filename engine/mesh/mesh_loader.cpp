// Format dispatch. glTF goes through our own checked reader; the classic interchange formats go
// through OpenMesh, whose TriMesh kernel triangulates polygons as they are added.
#include "mesh/mesh_loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include "io/gltf_mesh_io.h"

namespace ug {
namespace {

using OmMesh = OpenMesh::TriMesh_ArrayKernelT<>;

bool fail(std::string* error, const std::string& path, const std::string& why) {
    if (error) *error = path + ": " + why;
    return false;
}

bool loadWithOpenMesh(const std::string& path, TriangleMesh* out, std::string* error) {
    OmMesh om;
    OpenMesh::IO::Options options;
    // note: OpenMesh reports parse problems on its own log stream (omerr); the caller only gets our
    // message, which is the one that names the file.
    if (!OpenMesh::IO::read_mesh(om, path, options))
        return fail(error, path, "OpenMesh could not read the file (corrupt or unsupported content)");
    TriangleMesh mesh;
    mesh.positions.reserve(om.n_vertices());
    for (const auto& vh : om.vertices()) {
        const auto& p = om.point(vh);
        mesh.positions.emplace_back(float(p[0]), float(p[1]), float(p[2]));
    }
    mesh.indices.reserve(om.n_faces() * 3);
    for (const auto& fh : om.faces()) {
        uint32_t corner[3];
        int k = 0;
        for (const auto& vh : om.fv_range(fh)) {
            if (k < 3) corner[k] = uint32_t(vh.idx());
            ++k;
        }
        if (k != 3) continue;  // TriMesh guarantees triangles; be defensive anyway
        mesh.indices.insert(mesh.indices.end(), corner, corner + 3);
    }
    if (mesh.indices.empty()) return fail(error, path, "no triangles");
    std::string why;
    if (!validateMesh(mesh, &why)) return fail(error, path, why);
    computeNormals(&mesh);
    *out = std::move(mesh);
    return true;
}

}  // namespace

bool loadMeshFile(const std::string& path, TriangleMesh* out, std::string* error) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return fail(error, path, "no such file");
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".glb" || ext == ".gltf") return loadGltfMesh(path, out, error);
    if (ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".stl") return loadWithOpenMesh(path, out, error);
    return fail(error, path, "unsupported mesh format '" + ext + "' (want .glb, .gltf, .obj, .ply, .off or .stl)");
}

}  // namespace ug
