// The editor's live loop (issue 4, "Live loop"): edits go in from the UI thread, a background worker runs
// the incremental instantiator, and finished results come out at a frame boundary. The UI never waits
// for the worker (except waitIdle(), for tests and scripts).
//
//   LiveInstancer live;
//   live.reset(input);                            // full instantiation in the background
//   ... every stamp of a stroke:
//   live.submit(types, {old_bounds, new_bounds}); // queued; coalesced with edits not yet started
//   ... every frame:
//   LiveResult r;
//   if (live.poll(&r)) renderer.upload(*r.store, r.changed_tiles);
//   ui.busy(live.pending());
//
// Coalescing: while the worker runs one job, later submissions merge into one pending job (the newest
// settings, the union of the dirty regions), so a fast stroke never builds a backlog: the worker always
// starts from the newest state. Correctness does not depend on timing: the instantiator's update() is
// exact (docs/architecture.md "incremental = full"), and its starting state differs from the pending settings
// only inside the merged dirty region. A pending reset() (new extent, seed or strategy) supersedes
// everything queued, and a full run in progress is cancelled by a newer reset() (updates are short and
// are not cancelled; a stroke never starves behind a reset because updates never cancel a full run).
//
// Thread-safety: all public calls are for one thread (the UI's). The Instantiator is touched only by the
// worker. A result is a snapshot (shared, immutable), so the UI may keep it across frames.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "field/bounds.h"
#include "instancer/instance_store.h"
#include "instancer/instantiator.h"
#include "instancer/instancing_settings.h"
#include "instancer/settling.h"

namespace ug {

struct LiveResult {
    // The submission this result reflects: every submit()/reset() up to this number is in it.
    uint64_t generation = 0;
    std::shared_ptr<const InstanceStore> store;  // never null after a successful poll
    // The store's settled drops (instancer/settling.h), or null when the input does not settle. Tiles
    // whose drops changed are in changed_tiles too.
    std::shared_ptr<const SettledDrops> drops;
    // Packed keys (tile_coord.h) of every tile whose selected set changed since the previous poll,
    // ascending; accumulated over every run in between, so re-uploading these tiles is always enough.
    std::vector<uint64_t> changed_tiles;
    bool full = false;    // a full run happened since the previous poll (changed_tiles covers it too)
    InstanceStats stats;  // of the latest run
    // The latest run failed (bad settings: the message says which); store is the last good one.
    bool ok = true;
    std::string error;
};

class LiveInstancer {
public:
    // threads: the instantiator's (0 = all hardware threads).
    explicit LiveInstancer(int threads = 0);
    ~LiveInstancer();  // cancels a full run in progress and joins the worker
    LiveInstancer(const LiveInstancer&) = delete;
    LiveInstancer& operator=(const LiveInstancer&) = delete;

    // A new input (first open, new extent, seed, strategy): instantiates everything. The input's tile and
    // models must outlive this object (or the next reset()). An input with an empty extent (no density
    // anywhere) gives an empty result. Returns the generation.
    // `settle` (optional; its tile and models must outlive this object too): settle every result.
    uint64_t reset(InstancerInput input, SettleInput settle = {});
    // An edit: `types` replaces the settings; their fields changed only inside `dirty`. Requires a
    // previous reset(). Returns the generation.
    // `support` (optional; a new environment): the new settling input (its tile and models as for reset()).
    // `support_moved`: what the instances rest on changed (an environmental object moved), so every result
    // is settled again with it; otherwise (an edit of fields only) the input only replaces the old one,
    // which the caller may then free, and only the edited region is settled.
    uint64_t submit(std::vector<InstanceTypeSettings> types, std::vector<Bounds> dirty,
                    std::optional<SettleInput> support = std::nullopt, bool support_moved = true);

    // Non-blocking: true and *out filled when a result newer than the previous poll is ready.
    bool poll(LiveResult* out);
    // The newest published result without taking it (changed_tiles and full stay for the next poll()).
    // Before the first result: generation 0 and an empty store.
    LiveResult latest() const;
    // Work queued or running.
    bool pending() const;
    // Blocks until nothing is queued or running (tests, scripted runs, closing).
    void waitIdle();
    // The same for at most `timeout`: true when nothing is queued or running (a frame that waits for its
    // own edit's result within a budget, woken when the result is published).
    bool waitIdleFor(std::chrono::milliseconds timeout);
    uint64_t generation() const;  // of the latest submission
    // The latest full run's progress in [0, 1] (instantiating 90 %, settling the rest): 0 when it starts,
    // 1 once it is done (a UI's progress bar while a big scene's first result is computed).
    float fullRunProgress() const;

private:
    struct Job {
        bool valid = false;
        bool full = false;
        InstancerInput input;  // full
        SettleInput settle;    // full
        std::vector<InstanceTypeSettings> types;
        std::vector<Bounds> dirty;
        std::optional<SettleInput> support;  // update: settle with this from now on
        bool support_moved = false;          // ... and settle everything again
        uint64_t generation = 0;
    };
    void run();
    bool runJob(Job& job, InstanceStats* stats, std::vector<uint64_t>* changed, bool* full, std::string* error);
    // After a run changed the store: the drops, fully or in the window around `changed` (which grows by
    // the tiles whose drops were rewritten).
    void settle(bool full, std::vector<uint64_t>* changed);

    const int threads_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;  // worker: a job or stop
    std::condition_variable idle_;  // waitIdle
    Job pending_;
    bool running_ = false;
    bool running_full_ = false;
    bool stop_ = false;
    bool have_input_ = false;
    uint64_t generation_ = 0;
    std::atomic<bool> cancel_{false};
    std::atomic<float> full_instantiated_{0.0f};  // InstanceOptions::fraction of the full run
    std::atomic<float> full_settled_{0.0f};       // 0 or 1
    // Published, under mutex_.
    LiveResult published_;
    bool fresh_ = false;

    // Worker only.
    Instantiator instantiator_;
    bool instantiated_ = false;
    InstancerInput base_;  // the last reset()'s input with the newest types: a failed update restarts from it
    std::shared_ptr<const InstanceStore> last_store_ = std::make_shared<const InstanceStore>();
    SettleInput settle_;  // the last reset()'s
    std::shared_ptr<const SettledDrops> last_drops_;
    SettleHistory history_;  // last_drops_'s after each pass: lets an edit settle only what it reaches

    std::thread worker_;  // last: starts after everything above is constructed
};

}  // namespace ug
