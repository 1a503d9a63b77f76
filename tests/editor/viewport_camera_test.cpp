// The viewport fixes of issue 10 that need no window: the camera kept above the ground, zoom toward the
// point under the cursor, the window title, and the live instancer's full-run progress (the Statistics
// window's bar while a big scene's first result is computed).
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "editor/orbit_camera.h"
#include "editor/window_title.h"
#include "instancer/instantiator.h"
#include "scene/document.h"

namespace ug::editor {
namespace {

namespace fs = std::filesystem;

// A tilted plane z = 0.3 x - 0.2 y + 1: the eye's ground changes as the camera swings.
float slope(glm::vec2 p) { return 0.3f * p.x - 0.2f * p.y + 1.0f; }

TEST(EyeAboveGround, AViewBelowTheHorizonIsLiftedAboveTheGround) {
    for (const float pitch_deg : {-80.0f, -30.0f, -5.0f, 2.0f}) {
        for (const float yaw_deg : {-90.0f, 0.0f, 45.0f, 170.0f}) {
            OrbitCamera c;
            c.target = glm::vec3(2.0f, -1.0f, slope({2.0f, -1.0f}));
            c.distance_m = 10.0f;
            c.pitch_rad = glm::radians(pitch_deg);
            c.yaw_rad = glm::radians(yaw_deg);
            const glm::vec3 target = c.target;
            keepEyeAboveGround(&c, slope);
            const glm::vec3 eye = c.eye();
            EXPECT_GE(eye.z, slope(glm::vec2(eye)) + kEyeGroundMargin_m - 1e-4f) << pitch_deg << " " << yaw_deg;
            // The view stays on the target (only the pitch changed) where the pitch alone can do it.
            EXPECT_EQ(c.target, target) << pitch_deg << " " << yaw_deg;
            EXPECT_FLOAT_EQ(c.distance_m, 10.0f);
        }
    }
}

TEST(EyeAboveGround, AnEyeAboveTheGroundIsLeftAlone) {
    OrbitCamera c;
    c.target = glm::vec3(0.0f, 0.0f, 1.0f);
    c.pitch_rad = glm::radians(30.0f);
    const OrbitCamera before = c;
    EXPECT_FALSE(keepEyeAboveGround(&c, slope));
    EXPECT_EQ(c.target, before.target);
    EXPECT_EQ(c.pitch_rad, before.pitch_rad);
}

TEST(EyeAboveGround, ATargetUnderGroundIsLifted) {
    // Even looking straight down the eye would be under a ground 50 m up: the target comes up with it.
    OrbitCamera c;
    c.target = glm::vec3(0.0f);
    c.distance_m = 5.0f;
    keepEyeAboveGround(&c, [](glm::vec2) { return 50.0f; });
    EXPECT_GE(c.eye().z, 50.0f + kEyeGroundMargin_m - 1e-4f);
}

// Where a world point lands in normalized device coordinates.
glm::vec2 ndc(const OrbitCamera& c, glm::vec3 p) {
    const glm::vec4 q = c.viewProjection() * glm::vec4(p, 1.0f);
    return glm::vec2(q) / q.w;
}

TEST(ZoomToward, ThePivotStaysOnItsPixelAndTheTargetMovesTowardIt) {
    OrbitCamera c;
    c.target = glm::vec3(0.0f);
    c.distance_m = 20.0f;
    c.pitch_rad = glm::radians(40.0f);
    c.yaw_rad = glm::radians(-100.0f);
    const glm::vec3 pivot(6.0f, -3.0f, 0.0f);
    const glm::vec2 before = ndc(c, pivot);
    ASSERT_LT(std::abs(before.x), 1.0f);  // on screen, off centre
    ASSERT_GT(glm::length(before), 0.1f);
    zoomToward(&c, 3.0f, pivot);
    EXPECT_NEAR(c.distance_m, 20.0f / std::pow(1.2f, 3.0f), 1e-3f);
    const glm::vec2 after = ndc(c, pivot);
    EXPECT_NEAR(after.x, before.x, 1e-4f);
    EXPECT_NEAR(after.y, before.y, 1e-4f);
    EXPECT_NEAR(glm::length(c.target - pivot), glm::length(pivot) / std::pow(1.2f, 3.0f), 1e-3f);
    // Zooming out by as much comes back.
    zoomToward(&c, -3.0f, pivot);
    EXPECT_NEAR(c.distance_m, 20.0f, 1e-3f);
    EXPECT_NEAR(glm::length(c.target), 0.0f, 1e-3f);
}

TEST(WindowTitle, FileNameUnsavedMarkAndApp) {
    EXPECT_EQ(windowTitle("/a/b/meadow.json", false), "meadow.json \xE2\x80\x94 Undergrowth");
    EXPECT_EQ(windowTitle("/a/b/meadow.json", true), "meadow.json \xE2\x80\xA2 \xE2\x80\x94 Undergrowth");
    EXPECT_EQ(windowTitle("", true), "untitled \xE2\x80\xA2 \xE2\x80\x94 Undergrowth");
    EXPECT_EQ(windowTitle("", false, false), "Undergrowth");
}

TEST(LoadProgress, TheFirstFullRunReportsProgressUpToOne) {
    std::random_device rd;
    const fs::path dir = fs::temp_directory_path() / ("ug_load_progress_" + std::to_string(rd()));
    std::string error;
    DocumentOptions options{.cache_dir = (dir / "cache").string(), .config_dir = "", .threads = 2};
    std::unique_ptr<Document> doc =
        Document::open((fs::path(UG_SOURCE_DIR) / "assets" / "scenes" / "rock_pile.json").string(), options, &error);
    ASSERT_TRUE(doc) << error;
    // Sampled while the run goes: never decreasing, 1 once it is done.
    std::vector<float> seen;
    while (doc->live().pending()) {
        seen.push_back(doc->live().fullRunProgress());
        std::this_thread::yield();
    }
    doc->live().waitIdle();
    seen.push_back(doc->live().fullRunProgress());
    for (size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i], seen[i - 1]) << i;
    EXPECT_GE(seen.front(), 0.0f);
    EXPECT_FLOAT_EQ(seen.back(), 1.0f);

    // The instantiator's own fraction, read where its calling-thread callback says the tiles are all
    // computed (0.5) and all resolved (1.0): exactly the computing share, then 1.
    Instantiator instantiator;
    ASSERT_TRUE(instantiator.setInput(doc->instancerInput(), &error)) << error;
    std::atomic<float> fraction{0.0f};
    std::vector<float> at_callback;
    InstanceOptions o;
    o.threads = 2;
    o.progress = [&](float) { at_callback.push_back(fraction.load()); };
    o.fraction = &fraction;
    InstanceStats stats;
    ASSERT_TRUE(instantiator.instantiateAll(o, &stats, &error)) << error;
    ASSERT_GT(stats.instances, 0u);
    ASSERT_EQ(at_callback.size(), 2u);
    EXPECT_FLOAT_EQ(at_callback[0], 0.6f);
    EXPECT_GT(at_callback[1], 0.6f);
    EXPECT_FLOAT_EQ(fraction.load(), 1.0f);
    doc.reset();
    std::error_code ec;
    fs::remove_all(dir, ec);
}

}  // namespace
}  // namespace ug::editor
