// The particle tool in the viewport (app/editor/particle_tools.h) on a real Document: an attractor is
// picked by its dot on screen, dragged on the horizontal plane (or up and down), each step a document edit
// and the whole drag one undo step.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "editor/particle_tools.h"
#include "scene/project.h"

namespace ug::editor {
namespace {

namespace fs = std::filesystem;

class ParticleTool : public ::testing::Test {
protected:
    void SetUp() override {
        std::random_device rd;
        dir_ = fs::temp_directory_path() / ("ug_particle_tool_" + std::to_string(rd()));
        fs::create_directories(dir_);
        std::ofstream(dir_ / "grass.json") << R"({"format": "undergrowth-particles", "format_version": 1,
          "generators": [{"kind": "rectangle", "axis_u_m": [0.3, 0, 0], "axis_v_m": [0, 0.3, 0], "count": 50}],
          "attractors": [{"kind": "point", "a_m": [0, 0, 3], "charge": 1},
                         {"kind": "point", "a_m": [0.5, 0, 0.3], "influence_m": 0.3, "charge": 2}],
          "walk": {"steps": 6, "step_length_m": 0.01, "strand_radius_m": 0.001}})";
        const std::string models = (fs::path(UG_SOURCE_DIR) / "assets" / "models").string();
        const std::string json = R"({"format": "undergrowth-project", "format_version": 4, "name": "tool_test",
          "ghost_tile": {"tile_size_m": 0.5, "delta_m": -0.002, "seed": 7},
          "extent": {"min": [-2, -2, -0.5], "max": [2, 2, 2]},
          "detail_types": [{"name": "rock", "model": {"mesh": ")" + models + R"(/rock.glb"},
            "candidates": {"count": 20, "scale": [0.8, 1.2]}}],
          "particles": [{"file": "grass.json"}]})";
        Project p;
        std::string error;
        ASSERT_TRUE(parseProject(json, (dir_ / "scene.json").string(), &p, &error)) << error;
        p.base_dir = dir_.string();
        doc_ = Document::create(std::move(p), "", {.cache_dir = (dir_ / "cache").string(), .threads = 2}, &error);
        ASSERT_TRUE(doc_) << error;
    }
    void TearDown() override {
        doc_.reset();
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    glm::vec3 attractor(size_t i) const { return (*doc_->particles())[0].scene.attractors[i].a_m; }
    static Ray down(glm::vec2 xy) { return Ray{glm::vec3(xy, 10.0f), glm::vec3(0.0f, 0.0f, -1.0f)}; }

    fs::path dir_;
    std::unique_ptr<Document> doc_;
};

TEST_F(ParticleTool, PicksTheAttractorUnderTheCursor) {
    // Looking straight down from 5 m over the origin, 800 x 600.
    const glm::mat4 view_proj = glm::perspective(glm::radians(60.0f), 800.0f / 600.0f, 0.1f, 100.0f) *
                                glm::lookAt(glm::vec3(0, 0, 5), glm::vec3(0), glm::vec3(0, 1, 0));
    const glm::vec4 clip = view_proj * glm::vec4(attractor(1), 1.0f);
    const glm::vec2 px((clip.x / clip.w * 0.5f + 0.5f) * 800.0f, (0.5f - clip.y / clip.w * 0.5f) * 600.0f);
    EXPECT_EQ(pickAttractor(*doc_, 0, view_proj, 800, 600, px + glm::vec2(5, -5), 20.0f), 1u);
    EXPECT_EQ(pickAttractor(*doc_, 0, view_proj, 800, 600, px + glm::vec2(60, 0), 20.0f), kNoAttractor);
    EXPECT_EQ(pickAttractor(*doc_, 3, view_proj, 800, 600, px, 20.0f), kNoAttractor);  // no such system
}

TEST_F(ParticleTool, ADragMovesTheAttractorAndIsOneUndoStep) {
    const glm::vec3 start = attractor(1);
    const uint64_t generation = doc_->particlesGeneration();
    AttractorDrag drag;
    ASSERT_TRUE(drag.begin(doc_.get(), 0, 1, down(glm::vec2(start))));
    std::string error;
    for (int k = 1; k <= 5; ++k) ASSERT_TRUE(drag.drag(down(glm::vec2(start) + 0.04f * float(k) * glm::vec2(1, 0.5f)), false, &error)) << error;
    // Horizontal: the height is kept, the place follows the ray's point on the plane through the grab.
    EXPECT_NEAR(attractor(1).x, start.x + 0.2f, 1e-5f);
    EXPECT_NEAR(attractor(1).y, start.y + 0.1f, 1e-5f);
    EXPECT_EQ(attractor(1).z, start.z);
    // Shift: up and down only, on the upright plane facing a slanted ray.
    const glm::vec3 eye(start.x + 0.2f, start.y - 3.0f, start.z + 0.5f);
    const glm::vec3 target(start.x + 0.2f, start.y + 0.1f, start.z + 0.2f);
    ASSERT_TRUE(drag.drag(Ray{eye, glm::normalize(target - eye)}, true, &error)) << error;
    EXPECT_NEAR(attractor(1).x, start.x + 0.2f, 1e-5f);
    EXPECT_GT(attractor(1).z, start.z + 0.05f);
    EXPECT_EQ(attractor(0), glm::vec3(0, 0, 3));  // the others stay
    drag.end();
    EXPECT_EQ(drag.moves(), 6);
    EXPECT_NE(doc_->particlesGeneration(), generation);
    EXPECT_EQ(doc_->undoName(), "Move attractor");
    ASSERT_TRUE(doc_->undo());
    EXPECT_EQ(attractor(1), start);
    EXPECT_FALSE(doc_->canUndo());
    // No such attractor: nothing begins.
    EXPECT_FALSE(drag.begin(doc_.get(), 0, 2, down(glm::vec2(0))));
    EXPECT_FALSE(drag.active());
}

}  // namespace
}  // namespace ug::editor
