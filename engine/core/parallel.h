// A minimal fork-join parallel loop over std::thread. Work is split into contiguous chunks taken from an
// atomic counter, so uneven chunks balance themselves; results must never depend on which worker ran a
// chunk (callers write into per-index slots or per-worker scratch that is merged in a fixed order).
// Threads are kept between loops (a growth runs hundreds of short ones) and spin for up to 200 µs,
// yielding, before they sleep; a loop started while the kept threads run another (from another thread,
// or nested in a loop's body) starts threads of its own.
#pragma once

#include <cstddef>
#include <functional>

namespace ug {

// 0 means "all hardware threads"; the result is always >= 1.
int resolveThreadCount(int requested);

// Calls body(begin, end, worker) over [0, count) in chunks of at most chunk_size indices, on up to
// `threads` workers (worker in [0, threads)). Runs inline when threads == 1 or count is small.
void parallelFor(size_t count, int threads, size_t chunk_size,
                 const std::function<void(size_t begin, size_t end, int worker)>& body);

}  // namespace ug
