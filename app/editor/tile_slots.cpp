#include "editor/tile_slots.h"

#include <algorithm>
#include <bit>
#include <cassert>

namespace ug::editor {

namespace {

int sizeClass(uint32_t capacity) { return int(std::bit_width(capacity)) - 1; }  // floor(log2)

}  // namespace

uint32_t TileSlotAllocator::roundedCapacity(uint32_t count) { return std::bit_ceil(std::max<uint32_t>(count, 1)); }

TileSlot TileSlotAllocator::allocate(uint32_t count, SlotFit fit) {
    assert(count > 0);
    const uint32_t want = fit == SlotFit::Exact ? count : roundedCapacity(count);
    // Reuse a released slot when one is large enough: any slot of want's class or the next holds `want`
    // once it is at least `want` (class k holds capacities in [2^k, 2^(k+1))).
    for (int c = sizeClass(want); c < kClasses && c <= sizeClass(want) + 1; ++c) {
        std::vector<TileSlot>& list = free_[size_t(c)];
        for (size_t i = list.size(); i-- > 0;) {
            if (list[i].capacity < want) continue;
            const TileSlot s = list[i];
            list[i] = list.back();
            list.pop_back();
            used_ += s.capacity;
            return s;
        }
    }
    // Else the end of the array; grow it (doubling, so a stroke that keeps adding tiles reallocates
    // O(log n) times, not at every stamp).
    const TileSlot s{end_, want};
    end_ += want;
    used_ += want;
    if (end_ > capacity_) capacity_ = std::max(end_, capacity_ * 2);
    return s;
}

void TileSlotAllocator::release(TileSlot slot) {
    if (slot.capacity == 0) return;
    assert(slot.offset + slot.capacity <= end_ && used_ >= slot.capacity);
    used_ -= slot.capacity;
    free_[size_t(sizeClass(slot.capacity))].push_back(slot);
}

void TileSlotAllocator::reset() {
    for (auto& list : free_) list.clear();
    capacity_ = end_ = used_ = 0;
}

}  // namespace ug::editor
