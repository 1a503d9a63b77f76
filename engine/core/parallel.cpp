#include "core/parallel.h"

#include <algorithm>
#include <atomic>
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

// Threads kept between loops. Starting and joining threads cost ~100 µs a loop, which a growth of
// 10,000 strands pays ~150 times (several loops a step); a kept thread waits on a condition instead.
// One loop at a time: a caller that finds the pool busy (another thread's loop) starts threads of its own.
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
            pending_ = workers - 1;
            ++generation_;
        }
        wake_.notify_all();
        run(0);
        std::unique_lock<std::mutex> lock(mutex_);
        done_.wait(lock, [this] { return pending_ == 0; });
        job_ = nullptr;
        return true;
    }

private:
    WorkerPool() = default;

    void serve(int id) {
        uint64_t seen = 0;
        std::unique_lock<std::mutex> lock(mutex_);
        for (;;) {
            wake_.wait(lock, [&] { return stop_ || (generation_ != seen && id < wanted_); });
            if (stop_) return;
            seen = generation_;
            const std::function<void(int)>* job = job_;
            lock.unlock();
            (*job)(id);
            lock.lock();
            if (--pending_ == 0) done_.notify_one();
        }
    }

    std::mutex busy_;   // held by the caller whose loop the pool runs
    std::mutex mutex_;  // guards what follows
    std::condition_variable wake_, done_;
    std::vector<std::thread> threads_;  // thread i serves worker i + 1
    const std::function<void(int)>* job_ = nullptr;
    int wanted_ = 0;   // workers 1 .. wanted_ - 1 take part in the current loop
    int pending_ = 0;  // of those, the ones not finished
    uint64_t generation_ = 0;
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
