// A GL-free allocator of ranges ("slots") in one growable array, used for the renderer's resident
// per-tile instance buffers (render_data.h "ResidentTiles"): each (tile, detail type) owns a slot of the
// type's GPU instance buffer, so a live result rewrites only the slots of the tiles it changed.
//
//   TileSlotAllocator a;
//   TileSlot s = a.allocate(37, SlotFit::Rounded);  // capacity 64, offset 0
//   if (a.capacity() > gpu_capacity) { ...reallocate the buffer to a.capacity() and copy... }
//   a.release(s);                                   // its range is reused by a later allocate()
//
// Units are elements (instances), not bytes. Released slots go to a free list by size class (the
// power of two at or below their capacity); a rounded request of 2^k takes any free slot of class k
// (capacity >= 2^k) whole. note: free slots are never merged or split: the arena is rebuilt from scratch
// on every full result, which bounds the fragmentation a long editing session can pile up.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace ug::editor {

struct TileSlot {
    uint32_t offset = 0;    // first element
    uint32_t capacity = 0;  // elements reserved; 0 = no slot
};

enum class SlotFit {
    Exact,    // capacity = count: a full rebuild packs tiles tightly, in order (neighbours stay contiguous)
    Rounded,  // capacity = count rounded up to a power of two: a tile that grows a little keeps its slot
};

class TileSlotAllocator {
public:
    // A slot of at least `count` elements (count > 0). May grow capacity() (doubling, or to fit): the
    // caller then reallocates its buffer and copies the old content.
    TileSlot allocate(uint32_t count, SlotFit fit);
    // Contract: `slot` came from allocate() since the last reset() and was not released already.
    void release(TileSlot slot);
    // Forgets every slot; capacity() drops to 0.
    void reset();

    uint32_t capacity() const { return capacity_; }  // the array must hold this many elements
    uint32_t used() const { return used_; }          // elements in live slots
    uint32_t end() const { return end_; }            // one past the highest element ever handed out

    static uint32_t roundedCapacity(uint32_t count);  // the next power of two >= count (>= 1)

private:
    static constexpr int kClasses = 33;
    std::array<std::vector<TileSlot>, kClasses> free_;  // by floor(log2(capacity))
    uint32_t capacity_ = 0;
    uint32_t end_ = 0;
    uint32_t used_ = 0;
};

}  // namespace ug::editor
