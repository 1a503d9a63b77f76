#include "scene/live_instancer.h"

#include <algorithm>
#include <iterator>

namespace ug {

namespace {

std::vector<uint64_t> tileKeys(const InstanceStore* store) {
    std::vector<uint64_t> keys;
    if (!store) return keys;
    keys.reserve(store->tileCount());
    for (size_t t = 0; t < store->tileCount(); ++t) keys.push_back(store->tileKey(t));
    return keys;
}

std::vector<uint64_t> sortedUnion(const std::vector<uint64_t>& a, const std::vector<uint64_t>& b) {
    std::vector<uint64_t> out;
    out.reserve(a.size() + b.size());
    std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
    return out;
}

}  // namespace

LiveInstancer::LiveInstancer(int threads) : threads_(threads), worker_([this] { run(); }) {}

LiveInstancer::~LiveInstancer() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
        cancel_.store(true);
    }
    wake_.notify_all();
    worker_.join();
}

uint64_t LiveInstancer::reset(InstancerInput input, SettleInput settle) {
    uint64_t generation = 0;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        generation = ++generation_;
        pending_ = Job{};
        pending_.valid = true;
        pending_.full = true;
        pending_.input = std::move(input);
        pending_.settle = std::move(settle);
        pending_.generation = generation;
        have_input_ = true;
        // The run in progress is stale: a full run stops early (an update is short and not cancellable).
        if (running_ && running_full_) cancel_.store(true);
    }
    wake_.notify_one();
    return generation;
}

uint64_t LiveInstancer::submit(std::vector<InstanceTypeSettings> types, std::vector<Bounds> dirty,
                              std::optional<SettleInput> support, bool support_moved) {
    uint64_t generation = 0;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!have_input_) return generation_;  // nothing to update (contract: reset() first)
        generation = ++generation_;
        if (pending_.valid && pending_.full) {
            pending_.input.types = std::move(types);  // the full run will cover this edit
            if (support) pending_.settle = std::move(*support);
        } else {
            if (support) {
                pending_.support = std::move(support);  // the newest support wins
                // Coalesced edits: a move in any of them moved the support since the worker's last run.
                pending_.support_moved = pending_.support_moved || support_moved;
            }
            pending_.valid = true;
            pending_.types = std::move(types);
            // Merged regions: the worker's state differs from the newest settings only inside the union
            // of every region submitted since its last run started.
            pending_.dirty.insert(pending_.dirty.end(), dirty.begin(), dirty.end());
            // A long stroke would otherwise pile up boxes; one box around them stays exact (a superset).
            if (pending_.dirty.size() > 256) {
                Bounds all;
                for (const Bounds& b : pending_.dirty) all = unite(all, b);
                pending_.dirty.assign(1, all);
            }
        }
        pending_.generation = generation;
    }
    wake_.notify_one();
    return generation;
}

bool LiveInstancer::poll(LiveResult* out) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!fresh_) return false;
    *out = published_;
    published_.changed_tiles.clear();
    published_.full = false;
    fresh_ = false;
    return true;
}

LiveResult LiveInstancer::latest() const {
    std::lock_guard<std::mutex> lock(mutex_);
    LiveResult r = published_;
    if (!r.store) r.store = std::make_shared<const InstanceStore>();
    r.changed_tiles.clear();
    r.full = false;
    return r;
}

bool LiveInstancer::pending() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return pending_.valid || running_;
}

void LiveInstancer::waitIdle() {
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [&] { return !pending_.valid && !running_; });
}

bool LiveInstancer::waitIdleFor(std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    return idle_.wait_for(lock, timeout, [&] { return !pending_.valid && !running_; });
}

uint64_t LiveInstancer::generation() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return generation_;
}

void LiveInstancer::run() {
    for (;;) {
        Job job;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || pending_.valid; });
            if (stop_) return;
            job = std::move(pending_);
            pending_ = Job{};
            running_ = true;
            running_full_ = job.full || !instantiated_;
            cancel_.store(false);
        }
        InstanceStats stats;
        std::vector<uint64_t> changed;
        bool full = false;
        std::string error;
        const bool ok = runJob(job, &stats, &changed, &full, &error);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            running_ = false;
            running_full_ = false;
            // A cancelled run was superseded by a newer reset(), already pending: nothing to publish.
            const bool cancelled = !ok && cancel_.load();
            if (stop_) return;
            if (!cancelled) {
                published_.generation = job.generation;
                published_.store = last_store_;
                published_.drops = last_drops_;
                published_.changed_tiles = sortedUnion(published_.changed_tiles, changed);
                published_.full = published_.full || full;
                published_.stats = stats;
                published_.ok = ok;
                published_.error = ok ? std::string() : error;
                fresh_ = true;
            }
        }
        idle_.notify_all();
    }
}

bool LiveInstancer::runJob(Job& job, InstanceStats* stats, std::vector<uint64_t>* changed, bool* full,
                           std::string* error) {
    if (job.full) {
        base_ = std::move(job.input);
        settle_ = std::move(job.settle);
    } else {
        base_.types = job.types;
    }
    if (!job.full && job.support) settle_ = std::move(*job.support);
    const bool support_moved = !job.full && job.support_moved;
    const InstanceOptions options{.threads = threads_, .cancel = &cancel_};
    if (!job.full && instantiated_) {
        if (!instantiator_.update(std::move(job.types), job.dirty, options, stats, changed, error)) {
            instantiated_ = false;  // start over from base_ next time
            return false;
        }
        last_store_ = std::make_shared<const InstanceStore>(instantiator_.store());
        if (support_moved) {
            // The support moved: any drop may change, so every tile is settled again and re-uploaded.
            *changed = sortedUnion(*changed, tileKeys(last_store_.get()));
            settle(true, changed);
        } else {
            settle(false, changed);
        }
        return true;
    }
    // Full: a reset, or an edit after a failed run. Every tile of the old and new result changed.
    instantiated_ = false;
    *full = true;
    full_instantiated_.store(0.0f);
    full_settled_.store(0.0f);
    InstanceOptions full_options = options;
    full_options.fraction = &full_instantiated_;
    std::vector<uint64_t> old_keys = tileKeys(last_store_.get());
    if (base_.extent.empty()) {  // no density anywhere: nothing to instantiate
        last_store_ = std::make_shared<const InstanceStore>();
        *changed = std::move(old_keys);
        settle(true, changed);
        full_instantiated_.store(1.0f);
        full_settled_.store(1.0f);
        return true;
    }
    if (!instantiator_.setInput(base_, error) || !instantiator_.instantiateAll(full_options, stats, error))
        return false;
    instantiated_ = true;
    last_store_ = std::make_shared<const InstanceStore>(instantiator_.store());
    *changed = sortedUnion(old_keys, tileKeys(last_store_.get()));
    settle(true, changed);
    full_settled_.store(1.0f);
    return true;
}

void LiveInstancer::settle(bool full, std::vector<uint64_t>* changed) {
    if (!settle_.settings.enabled) {
        last_drops_.reset();
        history_.clear();
        return;
    }
    auto drops = std::make_shared<SettledDrops>();
    if (full || !last_drops_) {
        settleAll(settle_, *last_store_, threads_, drops.get(), &history_);
    } else {
        *drops = *last_drops_;
        std::vector<uint64_t> touched;
        settleUpdate(settle_, *last_store_, *changed, threads_, drops.get(), &touched, &history_);
        *changed = sortedUnion(*changed, touched);
    }
    last_drops_ = std::move(drops);
}

float LiveInstancer::fullRunProgress() const {
    return 0.9f * full_instantiated_.load() + 0.1f * full_settled_.load();
}

}  // namespace ug
