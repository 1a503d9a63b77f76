#include "editor/scene_loader.h"

#include <algorithm>

#include "mesh/terrain_mesh.h"

namespace ug::editor {

SceneLoader::SceneLoader(LoadRequest request) : request_(std::move(request)), data_(std::make_unique<SceneData>()) {
    thread_ = std::thread([this] { work(); });
}

SceneLoader::~SceneLoader() {
    cancel_.store(true);
    if (thread_.joinable()) thread_.join();
}

void SceneLoader::work() {
    SceneData& d = *data_;
    std::string error;
    auto failWith = [&](const std::string& message) {
        error_ = message;
        phase_.store(LoadPhase::Failed, std::memory_order_release);
    };
    if (!cli::loadSceneJob(request_.scene_path, request_.cache_dir, request_.threads, request_.quiet, &d.job, &error))
        return failWith(error);
    if (d.job.compiled.terrain) {
        // 512 cells a side at most: the meadow's 80 x 80 samples stay exact, a large image is decimated.
        if (!heightFieldMesh(*d.job.compiled.terrain, d.job.compiled.extent, 512, &d.terrain, &error))
            return failWith(request_.scene_path + ": terrain mesh: " + error);
        d.has_terrain = true;
    }
    const CandidateSet& candidates = d.job.tile.candidates;
    for (size_t i = 0; i < d.job.models.size(); ++i) {
        float scale_max = 1.0f;
        if (i < candidates.typeCount())
            for (uint32_t c = candidates.type_begin[i]; c < candidates.type_begin[i + 1]; ++c)
                scale_max = std::max(scale_max, candidates.scale[c]);
        d.meshes.push_back(buildDetailLods(d.job.models[i], scale_max));
    }
    phase_.store(LoadPhase::Instantiating, std::memory_order_release);

    InstanceOptions options;
    options.threads = request_.threads;
    options.cancel = &cancel_;
    options.progress = [this](float f) { progress_.store(f, std::memory_order_relaxed); };
    if (!d.instantiator.setInput(cli::instancerInput(d.job, d.job.project.instantiation_seed), &error) ||
        !d.instantiator.instantiateAll(options, &d.stats, &error))
        return failWith(request_.scene_path + ": " + (cancel_.load() ? std::string("cancelled") : error));
    if (!buildRenderInstances(d.instantiator.store(), candidates, d.job.tile.settings.tile_size_m, &d.instances, &error))
        return failWith(request_.scene_path + ": " + error);
    progress_.store(1.0f);
    phase_.store(LoadPhase::Ready, std::memory_order_release);
}

}  // namespace ug::editor
