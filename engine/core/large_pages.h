// Arrays of tens of megabytes backed by 2 MiB pages where the system lends them (Linux transparent huge
// pages in "madvise" mode, Debian's default).
//
// Why: a growth of a fur ball (100,000 strands, 64 steps) files six million points and segments, about
// 250 MB written once. With 4 KiB pages that is 60,000 page faults, and a fault costs ~10 µs on the
// virtual machines CI and users run on: half a second of a 3.5 s growth went to faulting memory in
// (docs/particles.md, "Performance"). A 2 MiB page is one fault for 512 of those, and one TLB entry for the
// grid's random reads. Smaller arrays take the ordinary allocator: rounding them up to 2 MiB would waste
// more than it saves.
//
// Nothing here changes a result: the pages hold the same bytes either way, and a system without huge
// pages (or that refuses the advice) simply faults 4 KiB pages as before.
#pragma once

#include <cstddef>
#include <new>
#include <vector>

namespace ug {

namespace large_pages {

constexpr size_t kHugePage = size_t(2) << 20;
// Arrays from this size up are given their own huge-page-aligned block.
constexpr size_t kThreshold = size_t(4) << 20;

// An aligned block of at least `bytes` (rounded up to whole huge pages), advised to be backed by huge
// pages; throws std::bad_alloc when the system has no memory for it.
void* allocate(size_t bytes);
void release(void* block);

}  // namespace large_pages

template <typename T>
struct LargePageAllocator {
    using value_type = T;

    LargePageAllocator() = default;
    template <typename U>
    LargePageAllocator(const LargePageAllocator<U>&) {}

    T* allocate(size_t n) {
        if (n > size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
        const size_t bytes = n * sizeof(T);
        if (bytes < large_pages::kThreshold) return static_cast<T*>(::operator new(bytes));
        return static_cast<T*>(large_pages::allocate(bytes));
    }
    // `n` is the allocation's own count, so the branch taken is allocate()'s.
    void deallocate(T* p, size_t n) {
        if (n * sizeof(T) < large_pages::kThreshold)
            ::operator delete(p);
        else
            large_pages::release(p);
    }

    template <typename U>
    bool operator==(const LargePageAllocator<U>&) const { return true; }
};

template <typename T>
using LargeVector = std::vector<T, LargePageAllocator<T>>;

}  // namespace ug
