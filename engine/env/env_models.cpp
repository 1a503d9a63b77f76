// The env starter set's registry and writer; the generators are in env_models_*.cpp.
#include "env/env_models.h"


#include "env/env_model_makers.h"
#include "io/gltf_mesh_io.h"

namespace ug {

const std::vector<std::string>& envStarterNames() {
    static const std::vector<std::string> names = {
        "bench",        "lamppost", "trash_can", "bus_shelter", "fence_segment", "pavement_slab",
        "road_segment", "tree",     "fountain",  "facade",      "steps",         "fountain_water"};
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
                                                           {"steps", envmodels::makeSteps},
                                                           {"fountain_water", envmodels::makeFountainWater}};
    for (const auto& [n, make] : makers)
        if (name == n) {
            *out = make(seed);
            return true;
        }
    return false;
}

bool writeEnvStarterModels(const std::string& dir, std::string* error) {
    return writeModelFolder(
        dir, envStarterNames(), [](const std::string& name, TriangleMesh* mesh) { makeEnvStarterModel(name, kEnvStarterSeed, mesh); }, error);
}

}  // namespace ug
