// Format dispatch. glTF goes through our checked tinygltf path; the classic interchange formats go
// through our own bounded readers, which work on the file's bytes in memory.
#include "mesh/mesh_loader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <vector>

#include "io/gltf_mesh_io.h"
#include "mesh/mesh_readers.h"

namespace ug {

bool loadMeshFile(const std::string& path, TriangleMesh* out, std::string* error) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".glb" || ext == ".gltf") return loadGltfMesh(path, out, error);
    using Reader = bool (*)(std::string_view, const std::string&, TriangleMesh*, std::string*);
    Reader reader = ext == ".obj"   ? &readObj
                    : ext == ".ply" ? &readPly
                    : ext == ".off" ? &readOff
                    : ext == ".stl" ? &readStl
                                    : nullptr;
    if (!reader) {
        std::error_code ec;
        if (!std::filesystem::exists(path, ec)) {
            if (error) *error = path + ": no such file";
            return false;
        }
        if (error)
            *error =
                path + ": unsupported mesh format '" + ext + "' (want .glb, .gltf, .obj, .ply, .off or .stl)";
        return false;
    }
    std::vector<unsigned char> bytes;
    if (!readMeshFileBytes(path, &bytes, error)) return false;
    return reader(asText(bytes), path, out, error);
}

}  // namespace ug
