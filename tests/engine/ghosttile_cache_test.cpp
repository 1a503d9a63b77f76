// The Ghost Tile cache: round trip, and refusal of every damaged file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>

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
    EXPECT_EQ(a.settings.variants, b.settings.variants);
    EXPECT_EQ(a.candidates.variants, b.candidates.variants);
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

// A forger rewrites the payload and recomputes the checksum (saveGhostTileCache does exactly that): the
// file then passes every structural check, so only the comparison with the scene's inputs can refuse it.
struct ForgedCache : CacheFixture {
    GhostTile good;
    void SetUp() override {
        CacheFixture::SetUp();
        std::string error;
        ASSERT_TRUE(buildGhostTile(input, {}, &good, &error)) << error;
        ASSERT_GT(good.stats.pair_count, 0u);
    }
    std::vector<std::vector<uint32_t>> rowsOf(const GhostTile& t) {
        std::vector<std::vector<uint32_t>> rows(t.candidates.size());
        for (uint32_t i = 0; i < t.candidates.size(); ++i)
            t.graph.forEachNeighbor(i, [&](uint32_t j, uint32_t v) { rows[i].push_back(j * kOffsetCount + v); });
        return rows;
    }
    void setRows(GhostTile* t, const std::vector<std::vector<uint32_t>>& rows) {
        std::string error;
        ASSERT_TRUE(CollisionGraph::fromRows(t->candidates.size(), rows, &t->graph, &error)) << error;
    }
    // Writes the forged tile where loadOrBuild looks, loads: it must be refused with `reason` and rebuilt.
    void expectRefused(const GhostTile& forged, const std::string& reason) {
        std::string error, note;
        const std::string path = ghostTileCachePath(dir.string(), ghostTileKey(input));
        ASSERT_TRUE(saveGhostTileCache(path, forged, &error)) << error;
        GhostTile raw;
        ASSERT_TRUE(loadGhostTileCache(path, ghostTileKey(input), &raw, &error)) << "structurally valid: " << error;
        GhostTile used;
        CacheOutcome outcome;
        ASSERT_TRUE(loadOrBuildGhostTile(dir.string(), input, {}, &used, &outcome, &note, &error)) << error;
        EXPECT_EQ(outcome, CacheOutcome::BuiltCorrupt) << reason;
        EXPECT_NE(note.find("disagrees with the scene"), std::string::npos) << note;
        EXPECT_NE(note.find(reason), std::string::npos) << note;
        EXPECT_NE(note.find(path), std::string::npos) << note;
        expectSameTile(good, used);
        // The rebuilt file is the honest one.
        ASSERT_TRUE(loadOrBuildGhostTile(dir.string(), input, {}, &used, &outcome, &note, &error)) << error;
        EXPECT_EQ(outcome, CacheOutcome::Loaded);
    }
};

TEST_F(ForgedCache, HonestTileIsLoaded) {
    std::string error, note;
    ASSERT_TRUE(saveGhostTileCache(ghostTileCachePath(dir.string(), ghostTileKey(input)), good, &error)) << error;
    GhostTile used;
    CacheOutcome outcome;
    ASSERT_TRUE(loadOrBuildGhostTile(dir.string(), input, {}, &used, &outcome, &note, &error)) << error;
    EXPECT_EQ(outcome, CacheOutcome::Loaded) << note;
    expectSameTile(good, used);
}

TEST_F(ForgedCache, OtherTileSizeIsRefused) {
    GhostTile forged = good;
    forged.settings.tile_size_m = 0.25f;
    expectRefused(forged, "tile size");
}

TEST_F(ForgedCache, OtherDeltaIsRefused) {
    GhostTile forged = good;
    forged.settings.delta_m = -0.01f;
    expectRefused(forged, "delta");
}

TEST_F(ForgedCache, NanPositionIsRefused) {
    GhostTile forged = good;
    forged.candidates.position[7].y = std::numeric_limits<float>::quiet_NaN();
    expectRefused(forged, "candidate 7: position");
}

TEST_F(ForgedCache, ZeroScaleIsRefused) {
    GhostTile forged = good;
    forged.candidates.scale[3] = 0.0f;
    expectRefused(forged, "candidate 3: scale");
}

TEST_F(ForgedCache, NonUnitRotationIsRefused) {
    GhostTile forged = good;
    forged.candidates.rotation[11] *= 2.0f;
    expectRefused(forged, "candidate 11: rotation");
}

TEST_F(ForgedCache, FewerCandidatesAreRefused) {
    // Drop the last candidate everywhere, graph included, so the file is consistent in itself.
    GhostTile forged = good;
    CandidateSet& c = forged.candidates;
    const uint32_t n = c.size() - 1;
    c.type.resize(n);
    c.position.resize(n);
    c.rotation.resize(n);
    c.scale.resize(n);
    c.type_begin.back() = n;
    auto rows = rowsOf(good);
    rows.resize(n);
    for (auto& row : rows) std::erase_if(row, [&](uint32_t k) { return k / kOffsetCount >= n; });
    setRows(&forged, rows);
    expectRefused(forged, "candidate counts");
}

TEST_F(ForgedCache, OneSidedEdgeIsRefused) {
    GhostTile forged = good;
    auto rows = rowsOf(good);
    rows[0].clear();  // row 0 forgets its edges, its neighbours still list it
    setRows(&forged, rows);
    expectRefused(forged, "not symmetric");
}

TEST_F(ForgedCache, EmptiedGraphIsRefused) {
    // Symmetric, structurally perfect, and wrong: every sampled row misses its edges.
    GhostTile forged = good;
    setRows(&forged, std::vector<std::vector<uint32_t>>(good.candidates.size()));
    expectRefused(forged, "collision graph row");
}

TEST_F(ForgedCache, InventedPairsAreRefused) {
    // Every candidate claims to collide with every other one in the home tile (both directions): symmetric
    // and structurally valid, but most of these pairs are far apart.
    GhostTile forged = good;
    const uint32_t n = good.candidates.size();
    std::vector<std::vector<uint32_t>> rows(n);
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; j < n; ++j)
            if (j != i) rows[i].push_back(j * kOffsetCount + kCenterOffset);
    setRows(&forged, rows);
    expectRefused(forged, "collision graph");
}

TEST_F(CacheFixture, VariantsRoundTripAndAreVerified) {
    input.settings.variants = 3;
    GhostTile tile, back;
    std::string error, note;
    ASSERT_TRUE(buildGhostTile(input, {}, &tile, &error)) << error;
    ASSERT_EQ(tile.candidates.size(), 450u);
    const std::string path = (dir / "v.ugt").string();
    ASSERT_TRUE(saveGhostTileCache(path, tile, &error)) << error;
    ASSERT_TRUE(loadGhostTileCache(path, tile.key, &back, &error)) << error;
    expectSameTile(tile, back);
    // Through loadOrBuild: built, then loaded after passing the check against the scene (graph rows with
    // the variant rule included).
    CacheOutcome outcome;
    ASSERT_TRUE(loadOrBuildGhostTile(dir.string(), input, {}, &back, &outcome, &note, &error)) << error;
    EXPECT_EQ(outcome, CacheOutcome::BuiltMissing);
    ASSERT_TRUE(loadOrBuildGhostTile(dir.string(), input, {}, &back, &outcome, &note, &error)) << error;
    EXPECT_EQ(outcome, CacheOutcome::Loaded) << note;
    expectSameTile(tile, back);
    // A variant count the type ranges do not divide into is refused by the loader itself.
    GhostTile forged = tile;
    forged.settings.variants = 4;  // 450 candidates: not 4 equal parts
    ASSERT_TRUE(saveGhostTileCache(path, forged, &error)) << error;
    EXPECT_FALSE(loadGhostTileCache(path, tile.key, &back, &error));
    EXPECT_NE(error.find("variants"), std::string::npos) << error;
    forged.settings.variants = 0;
    ASSERT_TRUE(saveGhostTileCache(path, forged, &error)) << error;
    EXPECT_FALSE(loadGhostTileCache(path, tile.key, &back, &error));
    EXPECT_NE(error.find("variants"), std::string::npos) << error;
}

TEST_F(CacheFixture, OtherFormatVersionIsAStaleRebuild) {
    GhostTile first, second;
    CacheOutcome outcome;
    std::string note, error;
    ASSERT_TRUE(loadOrBuildGhostTile(dir.string(), input, {}, &first, &outcome, &note, &error)) << error;
    const fs::path path = ghostTileCachePath(dir.string(), ghostTileKey(input));
    auto bytes = bytesOf(path);
    bytes[8] = uint8_t(kGhostTileCacheVersion - 1);  // what the build before variants wrote
    writeBytes(path, bytes);
    ASSERT_TRUE(loadOrBuildGhostTile(dir.string(), input, {}, &second, &outcome, &note, &error)) << error;
    EXPECT_EQ(outcome, CacheOutcome::BuiltStale) << note;
    EXPECT_NE(note.find("format version"), std::string::npos) << note;
    expectSameTile(first, second);
}

TEST_F(ForgedCache, OtherVariantCountIsRefused) {
    GhostTile forged = good;
    forged.settings.variants = 2;  // 150 candidates split in two: structurally fine, not the scene's tile
    expectRefused(forged, "variants");
}

TEST_F(CacheFixture, TileWithoutCollidingPairsRoundTrips) {
    // One small candidate in a large tile: no pairs, so the graph's stream is an empty array on disk.
    input.settings.tile_size_m = 5.0f;
    input.types = {{.name = "rock", .candidate_count = 1}};
    GhostTile tile, back;
    std::string error;
    ASSERT_TRUE(buildGhostTile(input, {}, &tile, &error)) << error;
    ASSERT_EQ(tile.stats.pair_count, 0u);
    const std::string path = (dir / "empty.ugt").string();
    ASSERT_TRUE(saveGhostTileCache(path, tile, &error)) << error;
    ASSERT_TRUE(loadGhostTileCache(path, tile.key, &back, &error)) << error;
    expectSameTile(tile, back);
    EXPECT_TRUE(back.graph.encodedBytes().empty());
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
    changed = input;
    changed.settings.variants = 2;
    EXPECT_NE(ghostTileKey(changed), base);
}

TEST(AtomicFile, FailureLeavesTargetUntouchedAndSaysWhy) {
    std::string error;
    EXPECT_FALSE(writeTextFileAtomically("/nonexistent-dir/x.txt", "hello", &error));
    EXPECT_NE(error.find("/nonexistent-dir/x.txt"), std::string::npos) << error;
}

}  // namespace
}  // namespace ug
