// The particle tool in the viewport (app/editor/particle_tools.h) on a real Document: an attractor, a
// generator or a cutter is picked by its dot on screen, dragged on the horizontal plane (or up and down),
// each step a document edit and the whole drag one undo step.
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
          "cutters": [{"kind": "plane", "center_m": [-0.5, 0.5, 0], "threshold_m": 0.2, "action": {"kind": "stop"}}],
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
    const ParticleScene& scene() const { return (*doc_->particles())[0].scene; }
    glm::vec3 attractor(size_t i) const { return scene().attractors[i].a_m; }
    // Pixel of a world point looking straight down from 5 m over the origin, 800 x 600.
    static glm::mat4 topView() {
        return glm::perspective(glm::radians(60.0f), 800.0f / 600.0f, 0.1f, 100.0f) *
               glm::lookAt(glm::vec3(0, 0, 5), glm::vec3(0), glm::vec3(0, 1, 0));
    }
    static glm::vec2 pixel(glm::vec3 p) {
        const glm::vec4 clip = topView() * glm::vec4(p, 1.0f);
        return {(clip.x / clip.w * 0.5f + 0.5f) * 800.0f, (0.5f - clip.y / clip.w * 0.5f) * 600.0f};
    }
    static Ray down(glm::vec2 xy) { return Ray{glm::vec3(xy, 10.0f), glm::vec3(0.0f, 0.0f, -1.0f)}; }

    fs::path dir_;
    std::unique_ptr<Document> doc_;
};

TEST_F(ParticleTool, PicksTheHandleUnderTheCursor) {
    const glm::mat4 view_proj = topView();
    const glm::vec2 px = pixel(attractor(1));
    EXPECT_EQ(pickParticleHandle(*doc_, 0, view_proj, 800, 600, px + glm::vec2(5, -5), 20.0f),
              (ParticleHandle{ParticlePart::Attractor, 1}));
    EXPECT_FALSE(pickParticleHandle(*doc_, 0, view_proj, 800, 600, px + glm::vec2(60, 0), 20.0f));
    EXPECT_FALSE(pickParticleHandle(*doc_, 3, view_proj, 800, 600, px, 20.0f));  // no such system
    // The generator by its centre; the plane cutter by the point where it cuts (its centre + 0.2 m up).
    EXPECT_EQ(pickParticleHandle(*doc_, 0, view_proj, 800, 600, pixel(glm::vec3(0.0f)) + glm::vec2(3, 3), 20.0f),
              (ParticleHandle{ParticlePart::Generator, 0}));
    const std::vector<ParticleHandlePoint> dots = particleHandlePoints(scene());
    ASSERT_EQ(dots.size(), 6u);
    EXPECT_EQ(dots[3].handle, (ParticleHandle{ParticlePart::Cutter, 0}));
    EXPECT_EQ(dots[3].position_m, glm::vec3(-0.5f, 0.5f, 0.2f));
    EXPECT_EQ(pickParticleHandle(*doc_, 0, view_proj, 800, 600, pixel(dots[3].position_m), 20.0f), dots[3].handle);
    // The tilt dots last: the generator's at its normal's tip (its larger half side up), the plane's 0.1 m
    // along its normal from the cut point. Seen from above each covers its place (within 2 px): the place
    // is picked. Seen from the side, 2 m away, the plane's is 0.1 m above its cut point: picked on it.
    EXPECT_EQ(dots[4].handle, (ParticleHandle{ParticlePart::Generator, 0, true}));
    EXPECT_EQ(dots[4].position_m, glm::vec3(0.0f, 0.0f, 0.3f));
    EXPECT_EQ(dots[5].handle, (ParticleHandle{ParticlePart::Cutter, 0, true}));
    EXPECT_EQ(dots[5].position_m, glm::vec3(-0.5f, 0.5f, 0.3f));
    EXPECT_EQ(pickParticleHandle(*doc_, 0, view_proj, 800, 600, pixel(dots[5].position_m), 20.0f), dots[3].handle);
    const glm::mat4 side = glm::perspective(glm::radians(60.0f), 800.0f / 600.0f, 0.1f, 100.0f) *
                           glm::lookAt(glm::vec3(-0.5f, -1.5f, 0.25f), glm::vec3(-0.5f, 0.5f, 0.25f), glm::vec3(0, 0, 1));
    const auto side_px = [&](glm::vec3 p) {
        const glm::vec4 c = side * glm::vec4(p, 1.0f);
        return glm::vec2((c.x / c.w * 0.5f + 0.5f) * 800.0f, (0.5f - c.y / c.w * 0.5f) * 600.0f);
    };
    ASSERT_GT(glm::distance(side_px(dots[3].position_m), side_px(dots[5].position_m)), 20.0f);
    EXPECT_EQ(pickParticleHandle(*doc_, 0, side, 800, 600, side_px(dots[5].position_m), 20.0f), dots[5].handle);
    EXPECT_EQ(pickParticleHandle(*doc_, 0, side, 800, 600, side_px(dots[3].position_m), 20.0f), dots[3].handle);
}

TEST_F(ParticleTool, TiltDotsTurnAFlatGeneratorAndAPlaneCutterOneUndoStepEach) {
    const ParticleScene before = scene();
    ParticleHandleDrag drag;
    std::string error;
    // The generator's dot (0, 0, 0.3) pulled towards +x, seen from the side (-y): rays through the points
    // of the sphere of 0.3 around the centre at 30 and 60 degrees from up, in the xz plane.
    const glm::vec3 eye(0.0f, -4.0f, 0.3f);
    const auto through = [&](glm::vec3 p) { return Ray{eye, glm::normalize(p - eye)}; };
    ASSERT_TRUE(drag.begin(doc_.get(), 0, {ParticlePart::Generator, 0, true}, through({0.0f, 0.0f, 0.3f})));
    for (float deg : {30.0f, 60.0f}) {
        const float a = glm::radians(deg);
        ASSERT_TRUE(drag.drag(through(0.3f * glm::vec3(std::sin(a), 0.0f, std::cos(a))), false, &error)) << error;
    }
    drag.end();
    EXPECT_EQ(doc_->undoName(), "Tilt generator");
    const ParticleGenerator& g = scene().generators[0];
    const glm::vec3 n = glm::normalize(glm::cross(g.axis_u_m, g.axis_v_m));
    // The ray meets the sphere at its front (y < 0): the normal leans 60 degrees to +x, a little towards -y.
    EXPECT_NEAR(glm::degrees(std::acos(n.z)), 60.0f, 3.0f);
    EXPECT_GT(n.x, 0.8f);
    EXPECT_NEAR(glm::length(g.axis_u_m), 0.3f, 1e-5f);  // turned, not stretched, still at right angles
    EXPECT_NEAR(glm::dot(g.axis_u_m, g.axis_v_m), 0.0f, 1e-5f);
    EXPECT_EQ(g.center_m, before.generators[0].center_m);
    // The plane cutter's dot pulled sideways: the normal follows, the cut point stays under it.
    const glm::vec3 cut(-0.5f, 0.5f, 0.2f);
    const glm::vec3 side_eye = cut + glm::vec3(0.0f, -4.0f, 0.0f);
    ASSERT_TRUE(drag.begin(doc_.get(), 0, {ParticlePart::Cutter, 0, true},
                           Ray{side_eye, glm::normalize(cut + glm::vec3(0, 0, 0.1f) - side_eye)}));
    ASSERT_TRUE(drag.drag(Ray{side_eye, glm::normalize(cut + glm::vec3(0.1f, 0, 0) - side_eye)}, false, &error)) << error;
    drag.end();
    EXPECT_EQ(doc_->undoName(), "Tilt cutter");
    const Cutter& c = scene().cutters[0];
    EXPECT_NEAR(c.normal.x, 1.0f, 0.02f);
    EXPECT_NEAR(glm::length(c.normal), 1.0f, 1e-5f);
    const glm::vec3 cut_after = c.center_m + c.normal * c.threshold_m;
    EXPECT_NEAR(glm::distance(cut_after, cut), 0.0f, 1e-5f);
    EXPECT_EQ(c.threshold_m, before.cutters[0].threshold_m);
    // One undo step each.
    ASSERT_TRUE(doc_->undo());
    EXPECT_EQ(scene().cutters, before.cutters);
    ASSERT_TRUE(doc_->undo());
    EXPECT_EQ(scene().generators, before.generators);
    EXPECT_FALSE(doc_->canUndo());
    // No tilt for a generator on the terrain or a sphere cutter.
    ParticleScene s = before;
    s.generators[0].on_terrain = true;
    EXPECT_FALSE(tiltParticleHandle(&s, {ParticlePart::Generator, 0, true}, glm::vec3(1, 0, 0)));
    s.cutters[0].kind = CutterKind::Sphere;
    EXPECT_FALSE(tiltParticleHandle(&s, {ParticlePart::Cutter, 0, true}, glm::vec3(1, 0, 0)));
}

TEST_F(ParticleTool, ADragMovesTheAttractorAndIsOneUndoStep) {
    const glm::vec3 start = attractor(1);
    const uint64_t generation = doc_->particlesGeneration();
    ParticleHandleDrag drag;
    ASSERT_TRUE(drag.begin(doc_.get(), 0, {ParticlePart::Attractor, 1}, down(glm::vec2(start))));
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
    EXPECT_FALSE(drag.begin(doc_.get(), 0, {ParticlePart::Attractor, 2}, down(glm::vec2(0))));
    EXPECT_FALSE(drag.begin(doc_.get(), 0, {ParticlePart::Cutter, 1}, down(glm::vec2(0))));
    EXPECT_FALSE(drag.begin(doc_.get(), 0, {}, down(glm::vec2(0))));
    EXPECT_FALSE(drag.active());
}

TEST_F(ParticleTool, GeneratorsAndCuttersDragLikeAttractors) {
    const ParticleScene before = scene();
    ParticleHandleDrag drag;
    std::string error;
    // The generator: its centre moves, the strands' seeds with it; nothing else changes.
    ASSERT_TRUE(drag.begin(doc_.get(), 0, {ParticlePart::Generator, 0}, down(glm::vec2(0.0f))));
    for (int k = 1; k <= 4; ++k) ASSERT_TRUE(drag.drag(down(glm::vec2(0.05f * float(k), -0.02f * float(k))), false, &error)) << error;
    drag.end();
    EXPECT_EQ(doc_->undoName(), "Move generator");
    EXPECT_NEAR(scene().generators[0].center_m.x, 0.2f, 1e-5f);
    EXPECT_NEAR(scene().generators[0].center_m.y, -0.08f, 1e-5f);
    EXPECT_EQ(scene().generators[0].center_m.z, 0.0f);
    EXPECT_EQ(scene().generators[0].axis_u_m, before.generators[0].axis_u_m);
    EXPECT_EQ(scene().attractors, before.attractors);
    EXPECT_EQ(scene().cutters, before.cutters);
    // The cutter, grabbed at the point where it cuts: moved up by 0.1 m (Shift), its threshold kept.
    const glm::vec3 cut = before.cutters[0].center_m + glm::vec3(0, 0, 0.2f);
    ASSERT_TRUE(drag.begin(doc_.get(), 0, {ParticlePart::Cutter, 0}, Ray{cut + glm::vec3(0, -3, 0), glm::vec3(0, 1, 0)}));
    const glm::vec3 eye = cut + glm::vec3(0, -3, 0);
    ASSERT_TRUE(drag.drag(Ray{eye, glm::normalize(cut + glm::vec3(0, 0, 0.1f) - eye)}, true, &error)) << error;
    drag.end();
    EXPECT_EQ(doc_->undoName(), "Move cutter");
    EXPECT_NEAR(scene().cutters[0].center_m.z, 0.1f, 1e-4f);
    EXPECT_EQ(scene().cutters[0].center_m.x, before.cutters[0].center_m.x);
    EXPECT_EQ(scene().cutters[0].threshold_m, before.cutters[0].threshold_m);
    // Two undo steps, one a drag, back to the file's system.
    ASSERT_TRUE(doc_->undo());
    ASSERT_TRUE(doc_->undo());
    EXPECT_EQ(scene().generators, before.generators);
    EXPECT_EQ(scene().cutters, before.cutters);
    EXPECT_FALSE(doc_->canUndo());
}

TEST(ParticleHandles, MoveOnlyTheirOwnPart) {
    ParticleScene s;
    s.attractors.resize(2);
    s.attractors[1].kind = AttractorKind::Segment;
    s.attractors[1].b_m = {1, 0, 0};
    s.generators.resize(1);
    s.cutters.resize(1);
    const ParticleScene before = s;
    const glm::vec3 d(0.1f, 0.2f, 0.3f);
    ASSERT_TRUE(moveParticleHandle(&s, {ParticlePart::Attractor, 1}, d));
    EXPECT_EQ(s.attractors[1].a_m, d);  // a segment moves whole
    EXPECT_EQ(s.attractors[1].b_m, glm::vec3(1, 0, 0) + d);
    EXPECT_EQ(s.attractors[0], before.attractors[0]);
    ASSERT_TRUE(moveParticleHandle(&s, {ParticlePart::Cutter, 0}, d));
    EXPECT_EQ(s.cutters[0].center_m, d);
    EXPECT_EQ(s.generators, before.generators);
    EXPECT_FALSE(moveParticleHandle(&s, {ParticlePart::Generator, 1}, d));
    EXPECT_FALSE(moveParticleHandle(&s, {}, d));
    EXPECT_EQ(s.generators, before.generators);
}

}  // namespace
}  // namespace ug::editor

namespace ug::editor {
namespace {

// The window's "acts by": one action becomes a table of one and back, what the state does kept; weights
// go back to 1 outside a random table; the result always validates.
TEST(ParticleActionModes, ATableOfOneAndBackKeepsTheAction) {
    StrandAction split;
    split.kind = StrandActionKind::Split;
    split.split_count = 3;
    split.split_angle_deg = 25.0f;
    StrandAction a = split;
    EXPECT_EQ(actionMode(a), ActionMode::Single);
    setActionMode(&a, ActionMode::Random);
    EXPECT_EQ(actionMode(a), ActionMode::Random);
    ASSERT_EQ(a.table.size(), 1u);
    EXPECT_EQ(a.table[0], split);
    StrandAction turn;
    turn.kind = StrandActionKind::Turn;
    turn.weight = 3.0f;
    a.table.push_back(turn);
    ParticleScene scene;
    scene.generators.push_back(groundPatch(glm::vec3(0.0f), 0.1f, 4, 5.0f, false));
    scene.walk.on_collision = a;
    std::string error;
    EXPECT_TRUE(validateParticleScene(scene, &error)) << error;
    setActionMode(&a, ActionMode::Priority);
    EXPECT_EQ(a.choice, ActionChoice::Priority);
    ASSERT_EQ(a.table.size(), 2u);
    EXPECT_EQ(a.table[1].weight, 1.0f) << "a priority table keeps no weights";
    setActionMode(&a, ActionMode::Single);
    EXPECT_EQ(a, split) << "the table's first action, alone again";
    scene.walk.on_collision = a;
    EXPECT_TRUE(validateParticleScene(scene, &error)) << error;
}

}  // namespace
}  // namespace ug::editor
