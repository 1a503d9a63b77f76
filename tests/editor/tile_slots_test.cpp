// The resident tiles' slot allocator (app/editor/tile_slots.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "editor/tile_slots.h"

namespace ug::editor {
namespace {

TEST(TileSlots, ExactSlotsPackTightlyInOrder) {
    TileSlotAllocator a;
    // [3][5][1]: offsets 0, 3, 8 and nothing between them.
    const TileSlot s0 = a.allocate(3, SlotFit::Exact), s1 = a.allocate(5, SlotFit::Exact),
                   s2 = a.allocate(1, SlotFit::Exact);
    EXPECT_EQ(s0.offset, 0u);
    EXPECT_EQ(s0.capacity, 3u);
    EXPECT_EQ(s1.offset, 3u);
    EXPECT_EQ(s1.capacity, 5u);
    EXPECT_EQ(s2.offset, 8u);
    EXPECT_EQ(a.end(), 9u);
    EXPECT_EQ(a.used(), 9u);
    EXPECT_GE(a.capacity(), 9u);
}

TEST(TileSlots, RoundedSlotsArePowersOfTwo) {
    EXPECT_EQ(TileSlotAllocator::roundedCapacity(1), 1u);
    EXPECT_EQ(TileSlotAllocator::roundedCapacity(5), 8u);
    EXPECT_EQ(TileSlotAllocator::roundedCapacity(8), 8u);
    EXPECT_EQ(TileSlotAllocator::roundedCapacity(9), 16u);
    TileSlotAllocator a;
    EXPECT_EQ(a.allocate(37, SlotFit::Rounded).capacity, 64u);
}

TEST(TileSlots, ReleasedSlotIsReusedBySameClass) {
    TileSlotAllocator a;
    const TileSlot s0 = a.allocate(6, SlotFit::Rounded);  // 8
    a.allocate(2, SlotFit::Rounded);                      // 2, after it
    a.release(s0);
    EXPECT_EQ(a.used(), 2u);
    const TileSlot again = a.allocate(7, SlotFit::Rounded);  // 8 fits in the freed 8
    EXPECT_EQ(again.offset, s0.offset);
    EXPECT_EQ(again.capacity, 8u);
    EXPECT_EQ(a.end(), 10u);  // no growth
}

TEST(TileSlots, FreedExactSlotTooSmallIsNotReused) {
    TileSlotAllocator a;
    const TileSlot s0 = a.allocate(5, SlotFit::Exact);  // class 2 (4..7) but only 5 long
    a.release(s0);
    const TileSlot s1 = a.allocate(6, SlotFit::Exact);
    EXPECT_NE(s1.offset, s0.offset);  // 6 does not fit in 5
    EXPECT_EQ(s1.offset, 5u);
}

TEST(TileSlots, GrowthKeepsLiveSlotsAndDoubles) {
    TileSlotAllocator a;
    a.allocate(4, SlotFit::Exact);
    EXPECT_EQ(a.capacity(), 4u);
    a.allocate(1, SlotFit::Exact);
    EXPECT_EQ(a.capacity(), 8u);  // doubled, not 5
    a.allocate(20, SlotFit::Exact);
    EXPECT_EQ(a.capacity(), 25u);  // a request larger than doubling: to fit
    a.reset();
    EXPECT_EQ(a.capacity(), 0u);
    EXPECT_EQ(a.allocate(2, SlotFit::Exact).offset, 0u);
}

// Random allocate/release: live slots never overlap, lie inside capacity(), hold what was asked.
TEST(TileSlots, RandomChurnNeverOverlaps) {
    TileSlotAllocator a;
    std::mt19937 rng(5);
    std::vector<std::pair<TileSlot, uint32_t>> live;
    for (int step = 0; step < 4000; ++step) {
        if (!live.empty() && rng() % 3 == 0) {
            const size_t i = rng() % live.size();
            a.release(live[i].first);
            live[i] = live.back();
            live.pop_back();
        } else {
            const uint32_t n = 1 + rng() % 40;
            live.push_back({a.allocate(n, rng() % 2 ? SlotFit::Exact : SlotFit::Rounded), n});
        }
        if (step % 97 != 0) continue;
        std::vector<TileSlot> sorted;
        uint32_t used = 0;
        for (const auto& [s, n] : live) {
            ASSERT_GE(s.capacity, n);
            ASSERT_LE(s.offset + s.capacity, a.capacity());
            sorted.push_back(s);
            used += s.capacity;
        }
        EXPECT_EQ(used, a.used());
        std::sort(sorted.begin(), sorted.end(), [](TileSlot x, TileSlot y) { return x.offset < y.offset; });
        for (size_t i = 1; i < sorted.size(); ++i)
            ASSERT_LE(sorted[i - 1].offset + sorted[i - 1].capacity, sorted[i].offset) << "step " << step;
    }
}

}  // namespace
}  // namespace ug::editor
