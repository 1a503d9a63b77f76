// The project's particle systems grown again as the Particles panel edits them (issue 14), off the UI
// thread and GL-free. The session submits the document's systems after every edit, undo and redo; the
// worker grows the newest submission (those that came while it grew are coalesced into it) with one
// StrandRegrower per system, so moving an attractor re-grows only the strands it reaches, and meshes
// them as every output does (particles/particle_output.h). poll(), at a frame boundary, hands over the
// newest finished meshes: the session swaps them into the scene's static meshes.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "editor/latest_worker.h"
#include "io/mesh_instances.h"
#include "particles/strand_growth.h"
#include "scene/edit_commands.h"

namespace ug::editor {

struct LiveStrandsResult {
    uint64_t generation = 0;            // the document's particlesGeneration() it was grown for
    std::vector<MeshInstances> meshes;  // every system's "strands/<name>", then its generator surfaces
    std::string error;                  // a system that did not grow (its name and why); the others are there
    double seconds = 0.0;
    uint64_t strands = 0;
    RegrowReport report;                // summed over the systems
    bool cancelled = false;             // stopped by cancel(): no meshes, the strands shown stay
};

class LiveStrands {
public:
    explicit LiveStrands(int threads);
    ~LiveStrands() = default;  // waits for a growth in progress
    LiveStrands(const LiveStrands&) = delete;
    LiveStrands& operator=(const LiveStrands&) = delete;

    // Grow `systems` (the document's, never changed in place) next; replaces a submission not yet started.
    void submit(ParticleSystems systems, uint64_t generation) { worker_.submit({std::move(systems), generation}); }
    // The newest finished result not handed over yet.
    bool poll(LiveStrandsResult* out) { return worker_.poll(out); }
    // Whether a submission is waiting or growing.
    bool busy() const { return worker_.busy(); }
    // Waits up to `budget` for a result to poll (LatestWorker::waitForResult).
    bool waitForResult(std::chrono::milliseconds budget) { return worker_.waitForResult(budget); }
    // Blocks until nothing is waiting or growing (tests, scripted runs).
    void waitIdle() { worker_.waitIdle(); }
    // Stops the growth of `generation` (or of an older one) before its next step: its result comes back
    // cancelled. The regrowers keep the records of their last finished growths, so growing the systems
    // from before the edit again (the edit undone) reuses every move.
    void cancel(uint64_t generation) {
        cancel_through_.store(generation);
        cancel_.store(true);
    }
    // How far the growth in progress is, in [0, 1]: systems done and the current one's steps.
    float progress() const;

private:
    struct Submission {
        ParticleSystems systems;
        uint64_t generation = 0;
    };
    LiveStrandsResult grow(const std::vector<ParticleSystemFile>& systems, uint64_t generation);

    const int threads_;
    std::vector<std::unique_ptr<StrandRegrower>> regrowers_;  // worker only: one per system index
    std::atomic<bool> cancel_{false};          // the growth in progress stops (GrowOptions::cancel)
    std::atomic<uint64_t> cancel_through_{0};  // generations up to this one are cancelled
    std::atomic<uint32_t> steps_done_{0};      // progress: the current system's steps done,
    std::atomic<uint32_t> system_steps_{1};    // of its steps,
    std::atomic<uint32_t> system_{0}, systems_{0};  // the current system of how many
    LatestWorker<Submission, LiveStrandsResult> worker_;       // last: started once the rest is ready
};

}  // namespace ug::editor
