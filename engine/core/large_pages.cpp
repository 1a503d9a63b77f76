#include "core/large_pages.h"

#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace ug::large_pages {

void* allocate(size_t bytes) {
    const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* block = std::aligned_alloc(kHugePage, rounded);
    if (!block) throw std::bad_alloc();
#if defined(MADV_HUGEPAGE)
    // Advice only: refused (no transparent huge pages, "never" mode) the block faults in 4 KiB pages.
    madvise(block, rounded, MADV_HUGEPAGE);
#endif
    return block;
}

void release(void* block) { std::free(block); }

}  // namespace ug::large_pages
