#include "editor/live_strands.h"

#include <algorithm>
#include <chrono>

#include "particles/particle_output.h"

namespace ug::editor {

LiveStrands::LiveStrands(int threads)
    : threads_(threads), worker_([this](const Submission& s) { return grow(*s.systems, s.generation); }) {}

LiveStrandsResult LiveStrands::grow(const std::vector<ParticleSystemFile>& systems, uint64_t generation) {
    const auto t0 = std::chrono::steady_clock::now();
    LiveStrandsResult out;
    out.generation = generation;
    out.report.incremental = !systems.empty();
    // A cancel that came before this growth started, for it, still counts; one for an older growth not.
    cancel_.store(cancel_through_.load() >= generation);
    systems_.store(uint32_t(systems.size()));
    // A system's regrower keeps its record across edits. Systems are only ever added or taken away at the
    // end (New system and its undo); another document gets another LiveStrands.
    regrowers_.resize(systems.size());
    for (std::unique_ptr<StrandRegrower>& r : regrowers_)
        if (!r) r = std::make_unique<StrandRegrower>();
    for (size_t i = 0; i < systems.size(); ++i) {
        const ParticleSystemFile& system = systems[i];
        Strands strands;
        MeshInstances mesh;
        std::string why;
        system_.store(uint32_t(i));
        system_steps_.store(std::max<uint32_t>(1, system.scene.walk.steps));
        steps_done_.store(0);
        const GrowOptions options{.threads = threads_, .cancel = &cancel_, .steps_done = &steps_done_};
        if (!regrowers_[i]->grow(system.scene, options, &strands, &why) && why == kGrowthCancelled) {
            out.cancelled = true;
            out.meshes.clear();
            break;
        }
        if (!why.empty() || !meshParticleStrands(system, strands, &mesh, &why)) {
            if (out.error.empty()) out.error = "particle system '" + system.name + "': " + why;
            continue;
        }
        const RegrowReport& r = regrowers_[i]->lastReport();
        out.report.incremental = out.report.incremental && r.incremental;
        out.report.recomputed += r.recomputed;
        out.report.reused += r.reused;
        out.strands += strands.size();
        out.meshes.push_back(std::move(mesh));
        for (MeshInstances& surface : generatorSurfaces(system)) out.meshes.push_back(std::move(surface));
    }
    systems_.store(0);
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

float LiveStrands::progress() const {
    const uint32_t systems = systems_.load();
    if (systems == 0) return 0.0f;
    const float step = std::min(1.0f, float(steps_done_.load()) / float(system_steps_.load()));
    return std::min(1.0f, (float(system_.load()) + step) / float(systems));
}

}  // namespace ug::editor
