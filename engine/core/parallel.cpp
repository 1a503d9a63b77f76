#include "core/parallel.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace ug {

int resolveThreadCount(int requested) {
    if (requested > 0) return requested;
    unsigned hw = std::thread::hardware_concurrency();
    return hw == 0 ? 1 : int(hw);
}

namespace {

// Set on a thread while it runs a loop's chunks: a loop started from inside one takes threads of its own
// (the pool is busy with the outer loop).
thread_local bool t_in_loop = false;

// Spins until ready() holds or about `micros` microseconds have passed; returns ready().
template <typename Ready>
bool spinFor(int micros, Ready&& ready) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(micros);
    for (;;) {
        for (int i = 0; i < 64; ++i) {
            if (ready()) return true;
            std::this_thread::yield();
        }
        if (std::chrono::steady_clock::now() >= until) return ready();
    }
}

// Threads kept between loops. Starting and joining threads cost ~100 µs a loop, which a growth of
// 10,000 strands pays ~150 times (several loops a step); a kept thread waits on a condition instead.
// One loop at a time: a caller that finds the pool busy (another thread's loop) starts threads of its own.
//
// Waking a thread asleep on a condition takes tens of microseconds on the virtual machines we run on,
// as long as many of a growth's loops (a step of a 10,000-strand patch runs seven, most under 200 µs):
// the caller ran them nearly alone, and two threads re-grew the patch barely faster than one. So a
// worker that finishes a loop, and a caller that waits for its workers, first spin briefly (yielding)
// on the generation and the pending count, and sleep only when nothing came.
class WorkerPool {
public:
    static WorkerPool& instance() {
        static WorkerPool pool;
        return pool;
    }

    ~WorkerPool() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stop_ = true;
        }
        wake_.notify_all();
        for (std::thread& t : threads_) t.join();
    }

    // Runs run(w) for w in [1, workers) on kept threads and run(0) on the caller; false (nothing run)
    // when the pool is busy.
    bool tryRun(int workers, const std::function<void(int)>& run) {
        std::unique_lock<std::mutex> busy(busy_, std::try_to_lock);
        if (!busy.owns_lock()) return false;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            while (int(threads_.size()) < workers - 1) {
                const int id = int(threads_.size()) + 1;
                threads_.emplace_back([this, id] { serve(id); });
            }
            job_ = &run;
            wanted_ = workers;
            pending_.store(workers - 1, std::memory_order_relaxed);
            generation_.fetch_add(1, std::memory_order_release);
        }
        wake_.notify_all();
        run(0);
        if (!spinFor(kSpinMicros, [this] { return pending_.load(std::memory_order_acquire) == 0; })) {
            std::unique_lock<std::mutex> lock(mutex_);
            done_.wait(lock, [this] { return pending_.load(std::memory_order_acquire) == 0; });
        }
        std::lock_guard<std::mutex> lock(mutex_);
        job_ = nullptr;
        return true;
    }

private:
    static constexpr int kSpinMicros = 200;

    WorkerPool() = default;

    void serve(int id) {
        uint64_t seen = 0;
        for (;;) {
            spinFor(kSpinMicros, [&] { return generation_.load(std::memory_order_acquire) != seen; });
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || (generation_.load(std::memory_order_relaxed) != seen && id < wanted_); });
            if (stop_) return;
            seen = generation_.load(std::memory_order_relaxed);
            const std::function<void(int)>* job = job_;
            lock.unlock();
            (*job)(id);
            // The last worker to finish wakes the caller if it went to sleep; the lock orders that
            // notification after the caller's check of the count.
            if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
                std::lock_guard<std::mutex> done_lock(mutex_);
                done_.notify_one();
            }
        }
    }

    std::mutex busy_;   // held by the caller whose loop the pool runs
    std::mutex mutex_;  // guards what follows (the atomics are written under it too, but read without)
    std::condition_variable wake_, done_;
    std::vector<std::thread> threads_;  // thread i serves worker i + 1
    const std::function<void(int)>* job_ = nullptr;
    int wanted_ = 0;                     // workers 1 .. wanted_ - 1 take part in the current loop
    std::atomic<int> pending_{0};        // of those, the ones not finished
    std::atomic<uint64_t> generation_{0};
    bool stop_ = false;
};

}  // namespace

void parallelFor(size_t count, int threads, size_t chunk_size,
                 const std::function<void(size_t, size_t, int)>& body) {
    if (count == 0) return;
    chunk_size = std::max<size_t>(1, chunk_size);
    size_t chunks = (count + chunk_size - 1) / chunk_size;
    int workers = int(std::min<size_t>(size_t(resolveThreadCount(threads)), chunks));
    if (workers <= 1) {
        body(0, count, 0);
        return;
    }
    std::atomic<size_t> next{0};
    const std::function<void(int)> run = [&](int worker) {
        const bool nested = t_in_loop;
        t_in_loop = true;
        for (;;) {
            size_t c = next.fetch_add(1, std::memory_order_relaxed);
            if (c >= chunks) break;
            size_t begin = c * chunk_size;
            body(begin, std::min(count, begin + chunk_size), worker);
        }
        t_in_loop = nested;
    };
    if (!t_in_loop && WorkerPool::instance().tryRun(workers, run)) return;
    std::vector<std::thread> pool;
    pool.reserve(size_t(workers - 1));
    for (int w = 1; w < workers; ++w) pool.emplace_back(run, w);
    run(0);
    for (auto& t : pool) t.join();
}

}  // namespace ug
