// The region jobs' instance lists (io/instance_list_file.h) and the planner's footprint
// (measureRegionFootprint): a list reads back to the very store and drops, a damaged one is refused with
// its reason, and the footprint is exactly what the region job's memory check counts.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/atomic_file.h"
#include "core/hash.h"
#include "instancer/settling.h"
#include "instancer_test_util.h"
#include "io/instance_list_file.h"

namespace ug {
namespace {

using test::InstancerFixture;
namespace fs = std::filesystem;

void setFields(InstancerFixture& fx) {
    fx.input.types[0].field = InstancerFixture::field({makePoint({0.0f, 0.0f, 0.0f}, 1.2f, 3.0f)});
    fx.input.types[1].field = InstancerFixture::field({makeSegment({-1.2f, -0.8f, 0.0f}, {0.8f, 0.9f, 0.2f}, 0.5f, 2.5f)});
}

struct ListFixture : ::testing::Test {
    InstancerFixture fx;
    InstanceStore store;
    SettledDrops drops;
    std::string dir;

    void SetUp() override {
        setFields(fx);
        Instantiator inst;
        std::string error;
        ASSERT_TRUE(inst.setInput(fx.input, &error)) << error;
        ASSERT_TRUE(inst.instantiateAll({.threads = 2}, nullptr, &error)) << error;
        store = inst.store();
        ASSERT_GT(store.instanceCount(), 50u);
        // Drops that differ per instance, so that a swap or a shift would show.
        uint16_t next = 1;
        std::vector<uint32_t> ids;
        for (size_t t = 0; t < store.tileCount(); ++t) {
            store.tileIds(t, &ids);
            std::vector<uint16_t> d;
            for (size_t k = 0; k < ids.size(); ++k) d.push_back(next++);
            drops.append(store.tileKey(t), d);
        }
        dir = (fs::temp_directory_path() / ("ug_list_" + std::to_string(::getpid()))).string();
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    std::vector<unsigned char> bytesOf(const std::string& path) {
        std::vector<unsigned char> b;
        std::string error;
        EXPECT_TRUE(readWholeFile(path, &b, &error)) << error;
        return b;
    }
    void write(const std::string& path, const std::vector<unsigned char>& b) {
        std::string error;
        ASSERT_TRUE(writeFileAtomically(path, b.data(), b.size(), &error)) << error;
    }
    // Re-seals a hand-edited file, so that the reader's other checks (not the checksum) are what refuse it.
    void reseal(std::vector<unsigned char>* b) {
        const uint64_t h = hashBytes(b->data(), b->size() - 8);
        std::memcpy(b->data() + b->size() - 8, &h, 8);
    }
};

TEST_F(ListFixture, ReadsBackTheSameInstancesDropsAndHeader) {
    const std::string path = dir + "/a.ugi";
    std::string error;
    ASSERT_TRUE(writeInstanceListFile(path, 0x1234abcdull, R"({"plan":"0x9","task":3})", store, &drops, &error)) << error;
    InstanceListFile back;
    ASSERT_TRUE(readInstanceListFile(path, &back, &error)) << error;
    EXPECT_EQ(back.ghost_tile_key, 0x1234abcdull);
    EXPECT_EQ(back.header_json, R"({"plan":"0x9","task":3})");
    EXPECT_TRUE(back.has_drops);
    EXPECT_TRUE(back.store == store);
    EXPECT_TRUE(back.drops == drops);
    // The size is the layout's: 4 + 4 + 8 + 4 + header + 8 + 8 + 1, 12 per tile, 6 per instance, 8.
    const uint64_t header = std::strlen(R"({"plan":"0x9","task":3})");
    EXPECT_EQ(fs::file_size(path), 20 + header + 17 + 12 * store.tileCount() + 6 * store.instanceCount() + 8);

    ASSERT_TRUE(writeInstanceListFile(path, 7, "{}", store, nullptr, &error)) << error;
    ASSERT_TRUE(readInstanceListFile(path, &back, &error)) << error;
    EXPECT_FALSE(back.has_drops);
    EXPECT_TRUE(back.store == store);
    EXPECT_EQ(back.drops.instanceCount(), 0u);
}

TEST_F(ListFixture, RefusesDamagedFilesWithTheirReason) {
    const std::string path = dir + "/a.ugi";
    std::string error;
    ASSERT_TRUE(writeInstanceListFile(path, 1, "{}", store, &drops, &error)) << error;
    const std::vector<unsigned char> good = bytesOf(path);
    InstanceListFile back;

    std::vector<unsigned char> b = good;
    b[b.size() / 2] ^= 0x40;  // one flipped bit in the instances
    write(path, b);
    EXPECT_FALSE(readInstanceListFile(path, &back, &error));
    EXPECT_NE(error.find("checksum mismatch"), std::string::npos) << error;
    EXPECT_NE(error.find(path), std::string::npos) << error;

    b.assign(good.begin(), good.begin() + long(good.size() / 3));  // a writer killed half way (not atomic)
    write(path, b);
    EXPECT_FALSE(readInstanceListFile(path, &back, &error));

    b = good;
    b[0] = 'X';
    write(path, b);
    EXPECT_FALSE(readInstanceListFile(path, &back, &error));
    EXPECT_NE(error.find("UGIL"), std::string::npos) << error;

    // An absurd instance count with a valid checksum: refused from the file's size, before allocating.
    b = good;
    const uint64_t absurd = uint64_t(1) << 60;
    std::memcpy(b.data() + 20 + 2 + 8, &absurd, 8);  // after magic, version, key, size, "{}" and the tile count
    reseal(&b);
    write(path, b);
    EXPECT_FALSE(readInstanceListFile(path, &back, &error));
    EXPECT_NE(error.find("do not fit"), std::string::npos) << error;

    // Two tiles swapped (keys no longer ascending), resealed.
    ASSERT_GE(store.tileCount(), 2u);
    b = good;
    const uint64_t first_key = store.tileKey(0), second_key = store.tileKey(1);
    const size_t at = 20 + 2 + 17;  // the first tile's key
    std::memcpy(b.data() + at, &second_key, 8);
    std::vector<uint32_t> ids;
    store.tileIds(0, &ids);
    std::memcpy(b.data() + at + 12 + ids.size() * 6, &first_key, 8);
    reseal(&b);
    write(path, b);
    EXPECT_FALSE(readInstanceListFile(path, &back, &error));
    EXPECT_NE(error.find("not ascending"), std::string::npos) << error;

    EXPECT_FALSE(readInstanceListFile(dir + "/missing.ugi", &back, &error));
    EXPECT_NE(error.find("missing.ugi"), std::string::npos) << error;
}

TEST(RegionFootprint, IsExactlyWhatTheRegionJobsMemoryCheckCounts) {
    InstancerFixture fx;
    setFields(fx);
    const Bounds region{glm::vec3(-2.0f, -2.0f, -1.0f), glm::vec3(0.3f, 2.0f, 1.0f)};
    RegionFootprint f;
    std::string error;
    ASSERT_TRUE(measureRegionFootprint(fx.input, region, {.threads = 2}, &f, &error)) << error;
    ASSERT_GT(f.tiles, 0u);
    ASSERT_GT(f.bytes_per_tile, 0u);
    // The planned tiles are among the tiles the clipped region touches (0.5 m: at most 5 x 9 x 5).
    EXPECT_LE(f.tiles, 5u * 9u * 5u);
    InstanceStore part;
    EXPECT_TRUE(instantiateRegion(fx.input, region, {.threads = 2, .max_memory_bytes = f.bytes()}, &part, nullptr, &error))
        << error;
    EXPECT_GT(part.instanceCount(), 0u);
    // One byte less and the job is refused up front: the planner's figure is the check's, not a guess.
    EXPECT_FALSE(
        instantiateRegion(fx.input, region, {.threads = 2, .max_memory_bytes = f.bytes() - 1}, &part, nullptr, &error));
    EXPECT_NE(error.find("--region jobs"), std::string::npos) << error;
    RegionFootprint small;
    EXPECT_FALSE(measureRegionFootprint(fx.input, region, {.threads = 2, .max_memory_bytes = f.bytes() - 1}, &small, &error));
    EXPECT_EQ(small.bytes_per_tile, f.bytes_per_tile);

    // A region away from every field plans nothing.
    const Bounds empty_region{glm::vec3(1.6f, 1.6f, 0.6f), glm::vec3(2.0f, 2.0f, 1.0f)};
    ASSERT_TRUE(measureRegionFootprint(fx.input, empty_region, {.threads = 2}, &f, &error)) << error;
    EXPECT_EQ(f.tiles, 0u);
}

}  // namespace
}  // namespace ug
