#include "io/gltf_scene_export.h"

namespace ug {

bool writeSceneGltf(const std::string& path, const SceneExport&, std::string* error) {
    if (error) *error = path + ": scene export is not implemented yet";
    return false;
}

}  // namespace ug
