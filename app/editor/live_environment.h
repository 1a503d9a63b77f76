// The environmental objects' effects (snow cover, icicles) computed again as the Environment window and
// the weather brushes edit them (issue 13), off the UI thread and GL-free. The session submits the
// document's compiled environment after every edit, undo and redo; the worker takes the newest, reuses
// the effects of the previous one outside the region the edit changed (env_effects.h updateEnvEffects:
// equal to a full computation) and makes the meshes every output takes (env_outputs.h). poll(), at a frame
// boundary, hands over the newest: the session swaps them into the scene's static meshes.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "editor/latest_worker.h"
#include "env/env_effects.h"
#include "io/mesh_instances.h"

namespace ug::editor {

struct LiveEnvironmentResult {
    uint64_t generation = 0;            // the document's environmentGeneration() it was computed for
    std::vector<MeshInstances> meshes;  // "env/...", "snow/...", "icicles/..." (envMeshInstances)
    std::shared_ptr<const EnvEffects> effects;  // null when it failed
    std::shared_ptr<const EnvScene> scene;      // what `effects` were computed for
    std::string error;                  // why it failed (the previous meshes stay on screen)
    double seconds = 0.0;
    size_t dirty_boxes = 0;             // the edit's region (0: computed in full)
};

class LiveEnvironment {
public:
    // `scene` and `effects`: what is on screen already (the loader computed it), the base of the first
    // edit's update. threads: the effects' (0 = all hardware threads).
    LiveEnvironment(int threads, std::shared_ptr<const EnvScene> scene, std::shared_ptr<const EnvEffects> effects);
    ~LiveEnvironment() = default;  // waits for a computation in progress
    LiveEnvironment(const LiveEnvironment&) = delete;
    LiveEnvironment& operator=(const LiveEnvironment&) = delete;

    void submit(std::shared_ptr<const EnvScene> scene, uint64_t generation) { worker_.submit({std::move(scene), generation}); }
    bool poll(LiveEnvironmentResult* out) { return worker_.poll(out); }
    bool busy() const { return worker_.busy(); }
    // Waits up to `budget` for a result to poll (LatestWorker::waitForResult).
    bool waitForResult(std::chrono::milliseconds budget) { return worker_.waitForResult(budget); }
    void waitIdle() { worker_.waitIdle(); }

private:
    struct Submission {
        std::shared_ptr<const EnvScene> scene;
        uint64_t generation = 0;
    };
    LiveEnvironmentResult compute(const Submission& s);

    const int threads_;
    // Worker only (after construction): the last scene computed and its effects.
    std::shared_ptr<const EnvScene> base_scene_;
    std::shared_ptr<const EnvEffects> base_effects_;
    LatestWorker<Submission, LiveEnvironmentResult> worker_;  // last: started once the rest is ready
};

}  // namespace ug::editor
