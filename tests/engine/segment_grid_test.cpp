// The segment grids of particle sculpting (segment_grid.h): a step's moves built at once visit exactly
// what brute force finds, and a batch filed on several threads leaves the lists serial filing leaves.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <vector>

#include "core/hash.h"
#include "particles/segment_grid.h"

namespace ug {
namespace {

glm::vec3 randomPoint(uint64_t seed, uint32_t i, float size) {
    const uint64_t h = hashWords(seed, i);
    return (glm::vec3(unitFloat(h), unitFloat(mix64(h)), unitFloat(mix64(mix64(h)))) - 0.5f) * size;
}

std::vector<SegmentGrid::Filed> scatteredBatch(uint32_t count, float size) {
    std::vector<SegmentGrid::Filed> batch;
    for (uint32_t i = 0; i < count; ++i) batch.push_back({5 * i + 2, i * 3, randomPoint(1, i, size)});
    return batch;
}

std::set<uint32_t> withinReach(const std::vector<SegmentGrid::Filed>& batch, glm::vec3 q, float reach) {
    std::set<uint32_t> ids;
    for (const SegmentGrid::Filed& f : batch)
        if (glm::dot(f.midpoint - q, f.midpoint - q) <= reach * reach) ids.insert(f.id);
    return ids;
}

std::set<uint32_t> visited(const StepSegmentGrid& grid, glm::vec3 q) {
    std::set<uint32_t> ids;
    EXPECT_FALSE(grid.anyNear(q, [&](uint32_t id, uint32_t tag) {
        EXPECT_EQ(tag * 5, (id - 2) * 3) << "the tag filed beside id " << id;
        ids.insert(id);
        return false;
    }));
    return ids;
}

TEST(StepSegmentGrid, VisitsExactlyTheSegmentsWithinReach) {
    // Across the origin (negative cells), ids that are not dense, on 1 and 3 threads.
    const float reach = 0.05f;
    const std::vector<SegmentGrid::Filed> batch = scatteredBatch(4000, 0.6f);
    for (int threads : {1, 3}) {
        StepSegmentGrid grid(reach);
        grid.build(batch, threads);
        size_t seen = 0;
        for (uint32_t q = 0; q < 1500; ++q) {
            const glm::vec3 p = randomPoint(2, q, 0.7f);
            const std::set<uint32_t> ids = visited(grid, p);
            ASSERT_EQ(ids, withinReach(batch, p, reach)) << "query " << q << ", " << threads << " threads";
            seen += ids.size();
        }
        EXPECT_GT(seen, 1500u * 4u);  // about 6 a query: the sets are not trivially empty
    }
}

TEST(StepSegmentGrid, AQueryBelowAnIdVisitsOnlyTheLowerIdsWithinReach) {
    // The scan of a slot stops at the first id not below when the batch's ids ascend; when they do not,
    // it must go on.
    const float reach = 0.05f;
    std::vector<SegmentGrid::Filed> batch = scatteredBatch(4000, 0.6f);
    for (bool ascending : {true, false}) {
        if (!ascending) std::reverse(batch.begin(), batch.end());
        StepSegmentGrid grid(reach);
        grid.build(batch, 2);
        size_t seen = 0;
        for (uint32_t q = 0; q < 1000; ++q) {
            const glm::vec3 p = randomPoint(8, q, 0.7f);
            const uint32_t below = 5 * (4 * q) + 2;  // ids are 5i + 2
            std::set<uint32_t> ids, expected;
            grid.anyNear(p, [&](uint32_t id, uint32_t) {
                ids.insert(id);
                return false;
            }, below);
            for (uint32_t id : withinReach(batch, p, reach))
                if (id < below) expected.insert(id);
            ASSERT_EQ(ids, expected) << "query " << q << (ascending ? ", ascending" : ", descending");
            seen += ids.size();
        }
        EXPECT_GT(seen, 1000u * 2u);
    }
}

TEST(StepSegmentGrid, AQueryWhoseCellsWrapAroundTheTableSeesThemAll) {
    // A block whose two cells along x take the table's last slot and its first: 1,000 segments make a
    // table of 2,048 slots. Find a query in such a block's second cell, then put segments all around it.
    const float reach = 0.05f;
    const GridCells cells(reach);
    const uint32_t last_slot = 2047;
    glm::vec3 q(0.0f);
    bool found = false;
    for (uint32_t i = 0; i < 1'000'000 && !found; ++i) {
        q = randomPoint(3, i, 50.0f);
        // q in the block's upper cell along x, the one in the first slot, with most of its neighbours.
        found = (GridCells::hash(cells.blockOf(q)) & last_slot) == last_slot && cells.cellOf(q).x == cells.blockOf(q).x + 1;
    }
    ASSERT_TRUE(found);
    std::vector<SegmentGrid::Filed> batch = scatteredBatch(900, 0.6f);
    for (uint32_t i = 0; i < 100; ++i) batch.push_back({5 * (900 + i) + 2, (900 + i) * 3, q + randomPoint(4, i, 0.1f)});
    StepSegmentGrid grid(reach);
    grid.build(batch, 1);
    const std::set<uint32_t> expected = withinReach(batch, q, reach);
    EXPECT_GT(expected.size(), 10u);
    EXPECT_EQ(visited(grid, q), expected);
}

TEST(StepSegmentGrid, RebuildingForgetsTheLastStep) {
    const std::vector<SegmentGrid::Filed> first = scatteredBatch(2000, 0.6f);
    const std::vector<SegmentGrid::Filed> second(first.begin(), first.begin() + 50);
    StepSegmentGrid grid(0.05f);
    grid.build(first, 2);
    grid.build(second, 2);
    for (uint32_t q = 0; q < 200; ++q) {
        const glm::vec3 p = randomPoint(5, q, 0.7f);
        ASSERT_EQ(visited(grid, p), withinReach(second, p, 0.05f));
    }
    grid.build({}, 2);
    EXPECT_FALSE(grid.anyNear(glm::vec3(0.0f), [](uint32_t, uint32_t) { return true; }));
}

// The ids a query visits, in the order it visits them.
std::vector<uint32_t> visitOrder(const SegmentGrid& grid, glm::vec3 q) {
    std::vector<uint32_t> ids;
    grid.anyNear(q, [&](uint32_t id, uint32_t) {
        ids.push_back(id);
        return false;
    });
    return ids;
}

TEST(SegmentGrid, ABatchFiledOnManyThreadsLeavesTheListsOfSerialFiling) {
    // Ids dense from 0 as a growth files them: the first steps one by one, then a step in a batch, with
    // room reserved (the batch links into the table) and without (the batch makes it grow).
    const float reach = 0.05f;
    std::vector<SegmentGrid::Filed> segments;
    for (uint32_t i = 0; i < 6000; ++i) segments.push_back({i, i / 7, randomPoint(6, i, 0.6f)});
    for (bool reserved : {true, false}) {
        SegmentGrid serial(reach);
        if (reserved) serial.reserve(segments.size());
        for (const SegmentGrid::Filed& f : segments) serial.insert(f.id, f.midpoint, f.tag);
        for (int threads : {1, 2, 8}) {
            SegmentGrid batched(reach);
            if (reserved) batched.reserve(segments.size());
            for (uint32_t i = 0; i < 2000; ++i) batched.insert(segments[i].id, segments[i].midpoint, segments[i].tag);
            batched.insert(std::vector<SegmentGrid::Filed>(segments.begin() + 2000, segments.end()), threads);
            ASSERT_EQ(batched.size(), serial.size());
            size_t seen = 0;
            for (uint32_t q = 0; q < 800; ++q) {
                const glm::vec3 p = randomPoint(7, q, 0.7f);
                const std::vector<uint32_t> order = visitOrder(serial, p);
                ASSERT_EQ(visitOrder(batched, p), order) << "query " << q << ", " << threads << " threads";
                seen += order.size();
            }
            EXPECT_GT(seen, 800u * 4u);
        }
    }
}

}  // namespace
}  // namespace ug
