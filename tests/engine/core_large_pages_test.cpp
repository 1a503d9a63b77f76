#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <utility>

#include "core/large_pages.h"

namespace ug {

// Growing across the threshold moves the elements from an ordinary block into a huge-page one (and a
// copy or a move keeps them): what a growth's point store does as it fills.
TEST(LargePages, AVectorKeepsItsElementsAcrossTheThreshold) {
    const size_t small = large_pages::kThreshold / sizeof(uint32_t) / 4;
    LargeVector<uint32_t> v(small);
    std::iota(v.begin(), v.end(), 7u);
    v.resize(large_pages::kThreshold / sizeof(uint32_t) * 3 + 5);  // past the threshold: a huge-page block
    for (size_t i = 0; i < small; ++i) ASSERT_EQ(v[i], uint32_t(7 + i)) << i;
    for (size_t i = small; i < v.size(); ++i) ASSERT_EQ(v[i], 0u) << i;
    v.back() = 42;

    const LargeVector<uint32_t> copy = v;
    EXPECT_EQ(copy, v);
    LargeVector<uint32_t> moved = std::move(v);
    EXPECT_EQ(moved, copy);
    moved.resize(3);
    moved.shrink_to_fit();  // back below the threshold: an ordinary block again
    EXPECT_EQ(moved, (LargeVector<uint32_t>{7, 8, 9}));
}

// A large block starts on a huge page boundary and spans whole huge pages: the kernel can back it with
// 2 MiB pages only then.
TEST(LargePages, ALargeBlockIsAlignedToAHugePage) {
    LargePageAllocator<uint64_t> allocator;
    const size_t n = large_pages::kThreshold / sizeof(uint64_t) + 1;
    uint64_t* block = allocator.allocate(n);
    EXPECT_EQ(reinterpret_cast<uintptr_t>(block) % large_pages::kHugePage, 0u);
    // Under AddressSanitizer (CI's second stage) a block shorter than n elements fails here.
    block[0] = 1;
    block[n - 1] = 2;
    allocator.deallocate(block, n);
}

TEST(LargePages, AnImpossibleSizeIsRefused) {
    LargePageAllocator<uint64_t> allocator;
    EXPECT_THROW(allocator.allocate(size_t(-1) / 4), std::bad_array_new_length);
}

}  // namespace ug
