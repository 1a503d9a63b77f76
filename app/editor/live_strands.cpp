#include "editor/live_strands.h"

#include <chrono>

#include "particles/particle_output.h"

namespace ug::editor {

LiveStrands::LiveStrands(int threads) : threads_(threads), thread_([this] { work(); }) {}

LiveStrands::~LiveStrands() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

void LiveStrands::submit(ParticleSystems systems, uint64_t generation) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        pending_ = std::move(systems);
        pending_generation_ = generation;
    }
    wake_.notify_all();
}

bool LiveStrands::poll(LiveStrandsResult* out) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!done_) return false;
    *out = std::move(*done_);
    done_.reset();
    return true;
}

bool LiveStrands::busy() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return growing_ || pending_ != nullptr;
}

void LiveStrands::waitIdle() {
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [this] { return !growing_ && pending_ == nullptr; });
}

void LiveStrands::work() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
        wake_.wait(lock, [this] { return stop_ || pending_ != nullptr; });
        if (stop_) return;
        const ParticleSystems systems = std::move(pending_);
        const uint64_t generation = pending_generation_;
        pending_.reset();
        growing_ = true;
        lock.unlock();
        LiveStrandsResult result = grow(*systems, generation);
        lock.lock();
        growing_ = false;
        // A newer finished result replaces an older one the UI has not taken: only the newest is shown.
        done_ = std::move(result);
        if (pending_ == nullptr) idle_.notify_all();
    }
}

LiveStrandsResult LiveStrands::grow(const std::vector<ParticleSystemFile>& systems, uint64_t generation) {
    const auto t0 = std::chrono::steady_clock::now();
    LiveStrandsResult out;
    out.generation = generation;
    out.report.incremental = !systems.empty();
    // A system's regrower keeps its record across edits; a different number of systems (another document)
    // starts every one afresh.
    if (regrowers_.size() != systems.size()) {
        regrowers_.clear();
        for (size_t i = 0; i < systems.size(); ++i) regrowers_.push_back(std::make_unique<StrandRegrower>());
    }
    for (size_t i = 0; i < systems.size(); ++i) {
        const ParticleSystemFile& system = systems[i];
        Strands strands;
        MeshInstances mesh;
        std::string why;
        if (!regrowers_[i]->grow(system.scene, {.threads = threads_}, &strands, &why) ||
            !meshParticleStrands(system, strands, &mesh, &why)) {
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
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace ug::editor
