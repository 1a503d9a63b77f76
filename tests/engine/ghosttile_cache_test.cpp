// The Ghost Tile cache: round trip, and refusal of every damaged file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/atomic_file.h"
#include "ghosttile/ghost_tile_cache.h"
#include "ghosttile_test_util.h"

namespace ug {
namespace {

namespace fs = std::filesystem;

struct CacheFixture : ::testing::Test {
    fs::path dir;
    DetailModel model = test::blobModel(5, 0.1f, 9);
    GhostTileInput input;
    void SetUp() override {
        dir = fs::temp_directory_path() /
              ("ug_cache_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir);
        fs::create_directories(dir);
        input.settings = {.tile_size_m = 0.5f, .delta_m = 0.002f, .seed = 5};
        input.types = {{.name = "rock", .candidate_count = 150}};
        input.models = {&model};
    }
    void TearDown() override { fs::remove_all(dir); }
    std::vector<unsigned char> bytesOf(const fs::path& p) {
        std::vector<unsigned char> b;
        std::string error;
        EXPECT_TRUE(readWholeFile(p.string(), &b, &error)) << error;
        return b;
    }
    void writeBytes(const fs::path& p, const std::vector<unsigned char>& b) {
        std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
    }
};

void expectSameTile(const GhostTile& a, const GhostTile& b) {
    EXPECT_EQ(a.key, b.key);
    EXPECT_EQ(a.settings.tile_size_m, b.settings.tile_size_m);
    EXPECT_EQ(a.settings.delta_m, b.settings.delta_m);
    EXPECT_EQ(a.candidates.type_begin, b.candidates.type_begin);
    EXPECT_EQ(a.candidates.type, b.candidates.type);
    EXPECT_EQ(a.candidates.position, b.candidates.position);
    EXPECT_EQ(a.candidates.rotation, b.candidates.rotation);
    EXPECT_EQ(a.candidates.scale, b.candidates.scale);
    EXPECT_EQ(a.graph.rowOffsets(), b.graph.rowOffsets());
    EXPECT_EQ(a.graph.encodedBytes(), b.graph.encodedBytes());
    EXPECT_EQ(a.stats.pair_count, b.stats.pair_count);
}

TEST_F(CacheFixture, RoundTripsBitForBit) {
    GhostTile tile, back;
    std::string error;
    ASSERT_TRUE(buildGhostTile(input, {}, &tile, &error)) << error;
    ASSERT_GT(tile.stats.pair_count, 0u);
    const std::string path = (dir / "t.ugt").string();
    ASSERT_TRUE(saveGhostTileCache(path, tile, &error)) << error;
    ASSERT_TRUE(loadGhostTileCache(path, tile.key, &back, &error)) << error;
    expectSameTile(tile, back);
}

TEST_F(CacheFixture, RejectsEveryTruncation) {
    GhostTile tile, back;
    std::string error;
    ASSERT_TRUE(buildGhostTile(input, {}, &tile, &error)) << error;
    const fs::path path = dir / "t.ugt";
    ASSERT_TRUE(saveGhostTileCache(path.string(), tile, &error)) << error;
    std::vector<unsigned char> good = bytesOf(path);
    const fs::path cut = dir / "cut.ugt";
    // Every length below 200 bytes, then a stride through the rest.
    for (size_t len = 0; len < good.size(); len += (len < 200 ? 1 : 97)) {
        writeBytes(cut, std::vector<unsigned char>(good.begin(), good.begin() + long(len)));
        EXPECT_FALSE(loadGhostTileCache(cut.string(), tile.key, &back, &error)) << len;
        EXPECT_NE(error.find(cut.string()), std::string::npos) << error;
    }
}

TEST_F(CacheFixture, RejectsCorruptionStalenessAndForeignFiles) {
    GhostTile tile, back;
    std::string error;
    ASSERT_TRUE(buildGhostTile(input, {}, &tile, &error)) << error;
    const fs::path path = dir / "t.ugt";
    ASSERT_TRUE(saveGhostTileCache(path.string(), tile, &error)) << error;
    std::vector<unsigned char> good = bytesOf(path);

    auto flipped = good;
    flipped[good.size() / 2] ^= 0x10;
    writeBytes(path, flipped);
    EXPECT_FALSE(loadGhostTileCache(path.string(), tile.key, &back, &error));
    EXPECT_NE(error.find("checksum"), std::string::npos) << error;

    writeBytes(path, good);
    EXPECT_FALSE(loadGhostTileCache(path.string(), tile.key + 1, &back, &error));
    EXPECT_NE(error.find("stale"), std::string::npos) << error;

    auto magic = good;
    magic[0] = 'X';
    writeBytes(path, magic);
    EXPECT_FALSE(loadGhostTileCache(path.string(), tile.key, &back, &error));
    EXPECT_NE(error.find("magic"), std::string::npos) << error;

    auto version = good;
    version[8] = 99;
    writeBytes(path, version);
    EXPECT_FALSE(loadGhostTileCache(path.string(), tile.key, &back, &error));
    EXPECT_NE(error.find("version"), std::string::npos) << error;

    EXPECT_FALSE(loadGhostTileCache((dir / "missing.ugt").string(), tile.key, &back, &error));
    EXPECT_NE(error.find("missing.ugt"), std::string::npos) << error;
}

TEST_F(CacheFixture, LoadOrBuildRebuildsWhatItCannotTrust) {
    GhostTile first, second, third;
    CacheOutcome outcome;
    std::string note, error;
    ASSERT_TRUE(loadOrBuildGhostTile(dir.string(), input, {}, &first, &outcome, &note, &error)) << error;
    EXPECT_EQ(outcome, CacheOutcome::BuiltMissing);
    ASSERT_TRUE(loadOrBuildGhostTile(dir.string(), input, {}, &second, &outcome, &note, &error)) << error;
    EXPECT_EQ(outcome, CacheOutcome::Loaded);
    expectSameTile(first, second);

    const fs::path path = ghostTileCachePath(dir.string(), ghostTileKey(input));
    auto bytes = bytesOf(path);
    bytes.resize(bytes.size() - 5);
    writeBytes(path, bytes);
    ASSERT_TRUE(loadOrBuildGhostTile(dir.string(), input, {}, &third, &outcome, &note, &error)) << error;
    EXPECT_EQ(outcome, CacheOutcome::BuiltCorrupt);
    EXPECT_NE(note.find("truncated"), std::string::npos) << note;
    expectSameTile(first, third);
    // And the rebuilt cache is good again.
    ASSERT_TRUE(loadOrBuildGhostTile(dir.string(), input, {}, &third, &outcome, &note, &error)) << error;
    EXPECT_EQ(outcome, CacheOutcome::Loaded);
}

TEST_F(CacheFixture, ChangedInputsChangeTheKey) {
    const uint64_t base = ghostTileKey(input);
    GhostTileInput changed = input;
    changed.settings.delta_m = 0.003f;
    EXPECT_NE(ghostTileKey(changed), base);
    DetailModel bigger = model;
    bigger.spheres[0].radius *= 1.01f;
    changed = input;
    changed.models = {&bigger};
    EXPECT_NE(ghostTileKey(changed), base);
    changed = input;
    changed.types[0].candidate_count++;
    EXPECT_NE(ghostTileKey(changed), base);
}

TEST(AtomicFile, FailureLeavesTargetUntouchedAndSaysWhy) {
    std::string error;
    EXPECT_FALSE(writeTextFileAtomically("/nonexistent-dir/x.txt", "hello", &error));
    EXPECT_NE(error.find("/nonexistent-dir/x.txt"), std::string::npos) << error;
}

}  // namespace
}  // namespace ug
