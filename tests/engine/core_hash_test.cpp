#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "core/hash.h"
#include "core/parallel.h"

namespace ug {

TEST(Hash, StreamingEqualsOneShot) {
    std::vector<unsigned char> data(1000);
    for (size_t i = 0; i < data.size(); ++i) data[i] = static_cast<unsigned char>(i * 31 + 7);
    uint64_t whole = hashBytes(data.data(), data.size());
    for (size_t split : {0, 1, 31, 32, 33, 500, 999}) {
        Hasher h;
        h.addBytes(data.data(), split);
        h.addBytes(data.data() + split, data.size() - split);
        EXPECT_EQ(h.value(), whole) << "split at " << split;
    }
}

TEST(Hash, OneBitChangesTheHash) {
    std::vector<unsigned char> data(100, 0);
    uint64_t base = hashBytes(data.data(), data.size());
    for (size_t i = 0; i < data.size(); ++i) {
        data[i] ^= 1;
        EXPECT_NE(hashBytes(data.data(), data.size()), base) << "byte " << i;
        data[i] ^= 1;
    }
    // Length is part of the content: trailing zero bytes are not ignored.
    EXPECT_NE(hashBytes(data.data(), 99), base);
}

TEST(Hash, UnitFloatStaysInHalfOpenRange) {
    EXPECT_EQ(unitFloat(0), 0.0f);
    EXPECT_LT(unitFloat(~0ull), 1.0f);
    EXPECT_LT(unitDouble(~0ull), 1.0);
}

TEST(Parallel, CoversEveryIndexOnceForAnyThreadCount) {
    for (int threads : {1, 2, 3, 8}) {
        std::vector<std::atomic<int>> hits(1037);
        parallelFor(hits.size(), threads, 10, [&](size_t b, size_t e, int worker) {
            EXPECT_GE(worker, 0);
            EXPECT_LT(worker, threads);
            for (size_t i = b; i < e; ++i) hits[i]++;
        });
        for (size_t i = 0; i < hits.size(); ++i) ASSERT_EQ(hits[i].load(), 1) << i;
    }
}

}  // namespace ug
