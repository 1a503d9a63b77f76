// Atomic writes: leftovers of interrupted writes are cleaned up by the next write of the same target.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cctype>
#include <chrono>
#include <filesystem>
#include <fstream>

#include "core/atomic_file.h"

namespace ug {
namespace {

namespace fs = std::filesystem;

std::string sanitizedHost() {
    char name[256] = {};
    gethostname(name, sizeof name - 1);
    std::string out;
    for (const char* c = name; *c; ++c) out += std::isalnum(static_cast<unsigned char>(*c)) ? *c : '_';
    return out.empty() ? "host" : out;
}

struct AtomicFileCleanup : ::testing::Test {
    fs::path dir = fs::temp_directory_path() / "ug_atomic_cleanup_test";
    void SetUp() override {
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    fs::path leftover(const std::string& name, std::chrono::hours age = std::chrono::hours(0)) {
        const fs::path p = dir / name;
        std::ofstream(p) << std::string(4096, 'x');
        if (age.count() > 0) fs::last_write_time(p, fs::file_time_type::clock::now() - age);
        return p;
    }
};

TEST_F(AtomicFileCleanup, RemovesTemporariesOfDeadWritersAndKeepsLiveOnes) {
    const std::string host = sanitizedHost();
    // pid_max is at most 2^22 on Linux: this pid cannot exist.
    const fs::path dead = leftover(".out.glb.tmp-" + host + "-999999999-Ab3dEf");
    const fs::path live = leftover(".out.glb.tmp-" + host + "-" + std::to_string(getppid()) + "-Zz9yX8");
    const fs::path other_target = leftover(".other.glb.tmp-" + host + "-999999999-Ab3dEf");
    const fs::path foreign_fresh = leftover(".out.glb.tmp-farm07-1234-Qw12er");
    const fs::path foreign_old = leftover(".out.glb.tmp-farm07-1234-Rt34yu", std::chrono::hours(2));
    const fs::path legacy_old = leftover(".out.glb.tmp-Xy12Zw", std::chrono::hours(2));
    const fs::path legacy_fresh = leftover(".out.glb.tmp-Ab12Cd");
    std::string error;
    ASSERT_TRUE(writeTextFileAtomically((dir / "out.glb").string(), "new", &error)) << error;
    EXPECT_FALSE(fs::exists(dead));
    EXPECT_FALSE(fs::exists(foreign_old));
    EXPECT_FALSE(fs::exists(legacy_old));
    EXPECT_TRUE(fs::exists(live)) << "a running writer's file is never touched";
    EXPECT_TRUE(fs::exists(foreign_fresh)) << "another host's writer may still be running";
    EXPECT_TRUE(fs::exists(legacy_fresh));
    EXPECT_TRUE(fs::exists(other_target)) << "only the target's own temporaries are cleaned";
    // Nothing of this write is left beside the target.
    size_t own = 0;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().find("-" + std::to_string(getpid()) + "-") != std::string::npos) ++own;
    EXPECT_EQ(own, 0u);
    std::string text;
    ASSERT_TRUE(readTextFile((dir / "out.glb").string(), &text, &error)) << error;
    EXPECT_EQ(text, "new");
}

}  // namespace
}  // namespace ug
