#include "core/parallel.h"

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace ug {

int resolveThreadCount(int requested) {
    if (requested > 0) return requested;
    unsigned hw = std::thread::hardware_concurrency();
    return hw == 0 ? 1 : int(hw);
}

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
    auto run = [&](int worker) {
        for (;;) {
            size_t c = next.fetch_add(1, std::memory_order_relaxed);
            if (c >= chunks) return;
            size_t begin = c * chunk_size;
            body(begin, std::min(count, begin + chunk_size), worker);
        }
    };
    std::vector<std::thread> pool;
    pool.reserve(size_t(workers - 1));
    for (int w = 1; w < workers; ++w) pool.emplace_back(run, w);
    run(0);
    for (auto& t : pool) t.join();
}

}  // namespace ug
