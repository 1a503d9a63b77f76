#include "editor/live_environment.h"

#include <chrono>

#include "env/env_outputs.h"

namespace ug::editor {

LiveEnvironment::LiveEnvironment(int threads, std::shared_ptr<const EnvScene> scene,
                                 std::shared_ptr<const EnvEffects> effects)
    : threads_(threads),
      base_scene_(std::move(scene)),
      base_effects_(std::move(effects)),
      worker_([this](const Submission& s) { return compute(s); }) {}

LiveEnvironmentResult LiveEnvironment::compute(const Submission& s) {
    const auto t0 = std::chrono::steady_clock::now();
    LiveEnvironmentResult out;
    out.generation = s.generation;
    auto fx = std::make_shared<EnvEffects>();
    const EnvEffectsOptions options{.threads = threads_};
    bool ok = false;
    if (base_scene_ && base_effects_) {
        const std::vector<Bounds> dirty = envDirtyRegion(*base_scene_, *s.scene);
        out.dirty_boxes = dirty.size();
        ok = updateEnvEffects(*s.scene, *base_effects_, dirty, options, fx.get(), &out.error);
    } else {
        ok = computeEnvEffects(*s.scene, options, fx.get(), &out.error);
    }
    if (ok) {
        out.meshes = envMeshInstances(*s.scene, *fx);
        out.effects = fx;
        out.scene = s.scene;
        base_scene_ = s.scene;
        base_effects_ = std::move(fx);
    } else {
        out.error = "environmental effects: " + out.error;
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace ug::editor
