// Loading and instantiating a scene off the UI thread. The worker loads the project, its models and Ghost
// Tile (cli::loadSceneJob), builds the terrain mesh and the detail LODs, publishes them (phase Instantiating:
// the viewport can show the terrain), runs Instantiator::instantiateAll, packs the instances for the GPU
// and publishes them (phase Ready). The UI thread polls phase() every frame and never waits, except in
// the destructor (which cancels the instantiation first).
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "cli/scene_job.h"
#include "editor/render_data.h"
#include "instancer/instantiator.h"
#include "mesh/triangle_mesh.h"

namespace ug::editor {

enum class LoadPhase : int { Loading, Instantiating, Ready, Failed };

// What the worker produced. The static part (job, terrain, meshes) is complete once the phase is past
// Loading; the instances once it is Ready. The worker never touches a part after publishing it.
struct SceneData {
    cli::SceneJob job;
    bool has_terrain = false;
    TriangleMesh terrain;                     // world space; empty without terrain
    std::vector<DetailLodMesh> meshes;        // one per detail type
    Instantiator instantiator;
    InstanceStats stats;
    RenderInstances instances;
};

struct LoadRequest {
    std::string scene_path;
    std::string cache_dir = "out/cache";
    int threads = 0;
    bool quiet = false;
};

class SceneLoader {
public:
    explicit SceneLoader(LoadRequest request);
    ~SceneLoader();
    SceneLoader(const SceneLoader&) = delete;
    SceneLoader& operator=(const SceneLoader&) = delete;

    LoadPhase phase() const { return phase_.load(std::memory_order_acquire); }
    float progress() const { return progress_.load(std::memory_order_relaxed); }  // instantiation, [0, 1]
    // Valid when phase() is Instantiating or Ready (static part) — see SceneData.
    const SceneData& data() const { return *data_; }
    // Valid when phase() is Failed.
    const std::string& error() const { return error_; }

private:
    void work();

    LoadRequest request_;
    std::unique_ptr<SceneData> data_;
    std::string error_;
    std::atomic<LoadPhase> phase_{LoadPhase::Loading};
    std::atomic<float> progress_{0.0f};
    std::atomic<bool> cancel_{false};
    std::thread thread_;
};

}  // namespace ug::editor
