#include <gtest/gtest.h>

#include <atomic>
#include <thread>
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

TEST(Hash, NoBytesFromANullPointerHashAsNoBytes) {
    // An empty vector's data() may be null (the renderer hashes an entry's empty instance list): adding no
    // bytes from it is allowed (UndefinedBehaviorSanitizer checks the memcpy) and changes nothing, even
    // between other bytes.
    const std::vector<unsigned char> none;
    const unsigned char empty[1] = {0};
    EXPECT_EQ(hashBytes(nullptr, 0), hashBytes(empty, 0));
    const unsigned char data[5] = {1, 2, 3, 4, 5};
    Hasher h;
    h.addBytes(data, 3);
    h.addBytes(none.data(), 0);
    h.addBytes(nullptr, 0);
    h.addBytes(data + 3, 2);
    EXPECT_EQ(h.value(), hashBytes(data, 5));
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

TEST(Parallel, LoopsFromSeveralThreadsAndNestedLoopsEachCoverTheirIndicesOnce) {
    // The kept threads run one loop at a time: loops started together from other threads, and loops
    // started inside a loop's body, take threads of their own; every one still covers its range once.
    constexpr int kCallers = 4;
    std::vector<std::vector<std::atomic<int>>> hits(kCallers);
    for (auto& h : hits) h = std::vector<std::atomic<int>>(3001);
    std::vector<std::atomic<int>> nested(64 * 50);
    std::vector<std::thread> callers;
    for (int c = 0; c < kCallers; ++c)
        callers.emplace_back([&, c] {
            for (int round = 0; round < 20; ++round)
                parallelFor(hits[size_t(c)].size(), 3, 7, [&](size_t b, size_t e, int worker) {
                    EXPECT_LT(worker, 3);
                    for (size_t i = b; i < e; ++i) hits[size_t(c)][i]++;
                });
        });
    parallelFor(64, 2, 1, [&](size_t b, size_t e, int) {
        for (size_t i = b; i < e; ++i)
            parallelFor(50, 2, 3, [&](size_t nb, size_t ne, int worker) {
                EXPECT_LT(worker, 2);
                for (size_t j = nb; j < ne; ++j) nested[i * 50 + j]++;
            });
    });
    for (std::thread& t : callers) t.join();
    for (int c = 0; c < kCallers; ++c)
        for (size_t i = 0; i < hits[size_t(c)].size(); ++i) ASSERT_EQ(hits[size_t(c)][i].load(), 20) << c << " " << i;
    for (size_t i = 0; i < nested.size(); ++i) ASSERT_EQ(nested[i].load(), 1) << i;
}

}  // namespace ug
