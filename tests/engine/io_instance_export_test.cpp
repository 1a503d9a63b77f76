// exportInstancedScene's progress hook (the editor's background export): fractions rise within [0, 1),
// a false return stops the export before anything is written, and without a hook nothing changes.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "io/instance_export.h"
#include "scene/document.h"

namespace ug {
namespace {

namespace fs = std::filesystem;

// One document for the suite: opening builds the Ghost Tile (seconds), the exports only read it.
class ExportProgress : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        std::random_device rd;
        suite_dir_ =
            fs::temp_directory_path() / ("ug_export_progress_" + std::to_string(rd()) + std::to_string(rd()));
        std::string error;
        // The default scene: 9 types, a few thousand instances, a terrain (so every stage runs).
        doc_ = Document::open((fs::path(UG_SOURCE_DIR) / "assets/scenes/default.json").string(),
                              DocumentOptions{.cache_dir = (suite_dir_ / "cache").string(), .threads = 2},
                              &error);
        ASSERT_TRUE(doc_) << error;
        const LiveResult r = doc_->waitForResult();
        ASSERT_TRUE(r.ok) << r.error;
        store_ = r.store;
    }
    static void TearDownTestSuite() {
        doc_.reset();
        std::error_code ec;
        fs::remove_all(suite_dir_, ec);
    }
    void SetUp() override {
        ASSERT_TRUE(doc_ && store_ && store_->instanceCount() > 0);
        dir_ = suite_dir_ / ::testing::UnitTest::GetInstance()->current_test_info()->name();
        fs::create_directories(dir_);
    }
    bool exportWith(const std::string& path, const InstanceExportOptions& options, std::string* error) {
        return exportInstancedScene(path, doc_->ghostTile(), doc_->models(), *store_, doc_->terrain().get(),
                                    doc_->compiled().extent, options, "{}", error);
    }

    fs::path dir_;
    static inline fs::path suite_dir_;
    static inline std::unique_ptr<Document> doc_;
    static inline std::shared_ptr<const InstanceStore> store_;
};

TEST_F(ExportProgress, FractionsRiseBelowOneAndTheFileIsWritten) {
    std::vector<float> seen;
    InstanceExportOptions options;
    options.progress = [&](float f) {
        seen.push_back(f);
        return true;
    };
    const std::string path = (dir_ / "scene.glb").string();
    std::string error;
    ASSERT_TRUE(exportWith(path, options, &error)) << error;
    EXPECT_TRUE(fs::exists(path));
    ASSERT_GE(seen.size(), 2u);  // after gathering, before the write
    for (size_t i = 0; i < seen.size(); ++i) {
        EXPECT_GE(seen[i], 0.0f);
        EXPECT_LT(seen[i], 1.0f);
        if (i > 0) {
            EXPECT_GE(seen[i], seen[i - 1]);
        }
    }
}

TEST_F(ExportProgress, FalseFromTheHookStopsBeforeAnythingIsWritten) {
    for (int stop_at_call = 1; stop_at_call <= 2; ++stop_at_call) {
        int calls = 0;
        InstanceExportOptions options;
        options.progress = [&](float) { return ++calls < stop_at_call; };
        const std::string path = (dir_ / ("cancelled" + std::to_string(stop_at_call) + ".gltf")).string();
        std::string error;
        EXPECT_FALSE(exportWith(path, options, &error));
        EXPECT_EQ(error, path + ": cancelled");
        EXPECT_EQ(calls, stop_at_call);
        EXPECT_FALSE(fs::exists(path));
    }
    // Nothing was left in the folder either (no temporary file).
    size_t files = 0;
    for (const auto& e : fs::directory_iterator(dir_))
        if (e.is_regular_file()) ++files;
    EXPECT_EQ(files, 0u);
}

TEST_F(ExportProgress, WithoutAHookTheOutputIsTheSameBytes) {
    std::string error;
    const std::string a = (dir_ / "a.glb").string(), b = (dir_ / "b.glb").string();
    ASSERT_TRUE(exportWith(a, InstanceExportOptions{}, &error)) << error;
    InstanceExportOptions with_hook;
    with_hook.progress = [](float) { return true; };
    ASSERT_TRUE(exportWith(b, with_hook, &error)) << error;
    EXPECT_EQ(fs::file_size(a), fs::file_size(b));
    std::string ta, tb;
    ASSERT_TRUE(readTextFile(a, &ta, &error) && readTextFile(b, &tb, &error)) << error;
    EXPECT_TRUE(ta == tb);
}

}  // namespace
}  // namespace ug
