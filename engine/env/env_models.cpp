// The env starter set's registry and writer; the generators are in env_models_*.cpp.
#include "env/env_models.h"

#include <filesystem>

#include "env/env_model_makers.h"
#include "io/gltf_mesh_io.h"

namespace ug {

const std::vector<std::string>& envStarterNames() {
    static const std::vector<std::string> names = {
        "bench",        "lamppost", "trash_can", "bus_shelter", "fence_segment", "pavement_slab",
        "road_segment", "tree",     "fountain",  "facade",      "steps"};
    return names;
}

bool makeEnvStarterModel(const std::string& name, uint64_t seed, TriangleMesh* out) {
    using Maker = TriangleMesh (*)(uint64_t);
    static const std::pair<const char*, Maker> makers[] = {{"bench", envmodels::makeBench},
                                                           {"lamppost", envmodels::makeLamppost},
                                                           {"trash_can", envmodels::makeTrashCan},
                                                           {"bus_shelter", envmodels::makeBusShelter},
                                                           {"fence_segment", envmodels::makeFenceSegment},
                                                           {"pavement_slab", envmodels::makePavementSlab},
                                                           {"road_segment", envmodels::makeRoadSegment},
                                                           {"tree", envmodels::makeTree},
                                                           {"fountain", envmodels::makeFountain},
                                                           {"facade", envmodels::makeFacade},
                                                           {"steps", envmodels::makeSteps}};
    for (const auto& [n, make] : makers)
        if (name == n) {
            *out = make(seed);
            return true;
        }
    return false;
}

bool writeEnvStarterModels(const std::string& dir, std::string* error) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) {
        if (error) *error = dir + ": cannot create the folder: " + ec.message();
        return false;
    }
    for (const std::string& name : envStarterNames()) {
        TriangleMesh mesh;
        makeEnvStarterModel(name, kEnvStarterSeed, &mesh);
        const std::string path = (std::filesystem::path(dir) / (name + ".glb")).string();
        if (!writeGltfMeshes(path, {{name, &mesh}}, error)) return false;
    }
    return true;
}

}  // namespace ug
