// A background worker that always works on the newest submission (the editor's live jobs: strands,
// environmental effects). submit() replaces a submission not yet started, so a fast drag never builds a
// backlog; poll(), at a frame boundary, hands over the newest finished result. GL-free; every public call
// is for one thread (the UI's), and the work function runs on the worker's own thread only.
//
//   LatestWorker<Input, Result> worker([this](const Input& in) { return compute(in); });
//   worker.submit(input);  ...  Result r; if (worker.poll(&r)) show(r);
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

namespace ug::editor {

template <class Input, class Result>
class LatestWorker {
public:
    using Work = std::function<Result(const Input&)>;

    // The work function may use state of its owner that only it touches (it is never run twice at once).
    explicit LatestWorker(Work work) : work_(std::move(work)), thread_([this] { loop(); }) {}
    ~LatestWorker() {  // waits for the work in progress; a submission not started is dropped
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stop_ = true;
        }
        wake_.notify_all();
        thread_.join();
    }
    LatestWorker(const LatestWorker&) = delete;
    LatestWorker& operator=(const LatestWorker&) = delete;

    void submit(Input input) {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            pending_ = std::move(input);
        }
        wake_.notify_all();
    }
    // The newest finished result not handed over yet.
    bool poll(Result* out) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!done_) return false;
        *out = std::move(*done_);
        done_.reset();
        return true;
    }
    // A submission waiting or being worked on.
    bool busy() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return working_ || pending_.has_value();
    }
    // Blocks until a finished result waits to be polled, nothing is waiting or being worked on, or `budget`
    // has passed; whether a result waits. (The editor lets a fresh edit's result catch the next frame.)
    template <class Rep, class Period>
    bool waitForResult(std::chrono::duration<Rep, Period> budget) {
        std::unique_lock<std::mutex> lock(mutex_);
        idle_.wait_for(lock, budget, [this] { return done_.has_value() || (!working_ && !pending_); });
        return done_.has_value();
    }
    // Blocks until nothing is waiting or being worked on (tests, scripted runs).
    void waitIdle() {
        std::unique_lock<std::mutex> lock(mutex_);
        idle_.wait(lock, [this] { return !working_ && !pending_; });
    }

private:
    void loop() {
        std::unique_lock<std::mutex> lock(mutex_);
        for (;;) {
            wake_.wait(lock, [this] { return stop_ || pending_.has_value(); });
            if (stop_) return;
            Input input = std::move(*pending_);
            pending_.reset();
            working_ = true;
            lock.unlock();
            Result result = work_(input);
            lock.lock();
            working_ = false;
            // A newer finished result replaces an older one the UI has not taken: only the newest is shown.
            done_ = std::move(result);
            idle_.notify_all();  // waitIdle re-checks that nothing is pending; waitForResult takes the result
        }
    }

    Work work_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::condition_variable idle_;  // a result finished (and maybe nothing is left to do)
    std::optional<Input> pending_;
    bool working_ = false;
    bool stop_ = false;
    std::optional<Result> done_;
    std::thread thread_;  // last: started once the rest is ready
};

}  // namespace ug::editor
