// The Sculpt tool (app/editor/tools.h) on a real Document, without a window: a held brush pours a cone at
// the type's angle of repose under the cursor's ground point whatever the view (the issue: from an oblique
// view it grew a leaning column towards the camera), as ONE primitive that one undo removes and that
// survives saving.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <utility>

#include "editor/tools.h"
#include "scene/document.h"
#include "scene/project.h"

namespace ug::editor {
namespace {

namespace fs = std::filesystem;

// By default no terrain: the ground is the plane z = 0. One rock type, no density of its own.
// `terrain`: a project "terrain" entry ending in a comma, or nothing for the plane z = 0.
std::string projectJson(float angle_deg, const std::string& terrain = "") {
    const std::string models = (fs::path(UG_SOURCE_DIR) / "assets" / "models").string();
    return R"({"format": "undergrowth-project", "format_version": 2, "name": "sculpt_test", )" + terrain + R"(
 "ghost_tile": {"tile_size_m": 0.5, "delta_m": -0.002, "seed": 7},
 "extent": {"min": [-6, -6, -0.5], "max": [6, 6, 4]},
 "detail_types": [{"name": "rock", "model": {"mesh": ")" +
           models + R"(/rock.glb"}, "candidates": {"count": 60, "scale": [0.8, 1.2]},
   "angle_of_repose_deg": )" +
           std::to_string(angle_deg) + R"(, "instancing": {"strategy": "elevation"}}]})";
}

class SculptTool : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        std::random_device rd;
        dir_ = new fs::path(fs::temp_directory_path() / ("ug_sculpt_test_" + std::to_string(rd())));
        fs::create_directories(*dir_);
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        fs::remove_all(*dir_, ec);
        delete dir_;
    }
    std::unique_ptr<Document> makeDoc(float angle_deg, const std::string& terrain = "") {
        Project p;
        std::string error;
        EXPECT_TRUE(parseProject(projectJson(angle_deg, terrain), "sculpt_test.json", &p, &error)) << error;
        p.base_dir = dir_->string();
        DocumentOptions options{.cache_dir = (*dir_ / "cache").string(), .config_dir = "", .threads = 2};
        std::unique_ptr<Document> doc = Document::create(std::move(p), "", options, &error);
        EXPECT_TRUE(doc) << error;
        return doc;
    }
    static fs::path* dir_;
};
fs::path* SculptTool::dir_ = nullptr;

// The ray the mouse over ground point g casts from an eye at `distance` from g, `pitch` above its horizon.
Ray viewRay(glm::vec3 g, float yaw_deg, float pitch_deg, float distance = 8.0f) {
    const float y = glm::radians(yaw_deg), p = glm::radians(pitch_deg);
    const glm::vec3 eye = g + distance * glm::vec3(std::cos(p) * std::cos(y), std::cos(p) * std::sin(y), std::sin(p));
    return Ray{eye, glm::normalize(g - eye)};
}

// Holds the brush still for `steps` hold intervals; returns the stroke's primitives.
std::vector<uint64_t> hold(Document* doc, const Ray& ray, int steps, float radius = 0.6f) {
    BrushSettings brush = defaultBrush(*doc);
    brush.radius_m = radius;
    BrushStroke stroke;
    std::string error;
    EXPECT_TRUE(stroke.begin(doc, ToolKind::Sculpt, brush, ray, 0.0, &error)) << error;
    for (int k = 1; k < steps; ++k) EXPECT_TRUE(stroke.drag(ray, k * kSculptHoldInterval_s, &error)) << error;
    EXPECT_EQ(stroke.stamps(), steps);
    const std::vector<uint64_t> ids = stroke.pileIds();
    stroke.end();
    return ids;
}

// Drags the sculpt brush (radius 0.6 m) from `from` to `to` in `moves` mouse moves, each through the ray
// ray_at gives for the ground point under the cursor; returns the stroke's cones.
std::vector<uint64_t> dragSculpt(Document* doc, glm::vec2 from, glm::vec2 to, int moves,
                                 const std::function<Ray(glm::vec3)>& ray_at) {
    BrushSettings brush = defaultBrush(*doc);
    brush.radius_m = 0.6f;
    BrushStroke stroke;
    std::string error;
    EXPECT_TRUE(stroke.begin(doc, ToolKind::Sculpt, brush, ray_at(glm::vec3(from, 0.0f)), 0.0, &error)) << error;
    for (int k = 1; k <= moves; ++k)
        EXPECT_TRUE(stroke.drag(ray_at(glm::vec3(from + (to - from) * (float(k) / float(moves)), 0.0f)), 0.01 * k,
                                &error))
            << error;
    const std::vector<uint64_t> cones = stroke.pileIds();
    stroke.end();
    return cones;
}

TEST_F(SculptTool, HeldBrushPoursTheSameVerticalConeFromAnyView) {
    const glm::vec3 g(1.0f, -0.5f, 0.0f);
    Primitive first;
    bool have_first = false;
    const std::pair<float, float> views[] = {{0.0f, 89.0f}, {-90.0f, 30.0f}, {45.0f, 8.0f}, {180.0f, 55.0f}};
    for (const auto& [yaw, pitch] : views) {
        SCOPED_TRACE("yaw " + std::to_string(yaw) + " pitch " + std::to_string(pitch));
        std::unique_ptr<Document> doc = makeDoc(35.0f);
        ASSERT_TRUE(doc);
        const std::vector<uint64_t> ids = hold(doc.get(), viewRay(g, yaw, pitch), 40);
        ASSERT_EQ(ids.size(), 1u);  // one primitive for the whole stroke
        ASSERT_EQ(doc->primitiveIds(0).size(), 1u);
        Primitive cone;
        ASSERT_TRUE(doc->findPrimitive(ids[0], nullptr, &cone));
        EXPECT_EQ(cone.kind, PrimitiveKind::Segment);
        EXPECT_NEAR(cone.end_m.x, cone.center_m.x, 1e-5f);  // the axis is vertical
        EXPECT_NEAR(cone.end_m.y, cone.center_m.y, 1e-5f);
        if (!have_first) {
            first = cone;
            have_first = true;
        }
        // The view only changes rounding in the ground point.
        EXPECT_LT(glm::length(cone.center_m - first.center_m), 1e-4f);
        EXPECT_NEAR(cone.end_m.z, first.end_m.z, 1e-4f);
        EXPECT_NEAR(cone.radius_m, first.radius_m, 1e-4f);
        const PileMeasure m = measureSculptedPile(*doc, 0, glm::vec2(g), 3.0f, 0.03f, 4.0f);
        ASSERT_TRUE(m.found);
        // Flat ground: nothing pulls the pile off the brush's ground point (the bound of the issue is 0.2 m).
        EXPECT_LT(glm::length(m.centroid_m - glm::vec2(g)), 0.05f);
        std::printf("view yaw %.0f pitch %.0f: centre %.3f m off, height %.3f m, radius %.3f m, h/r %.3f\n", yaw,
                    pitch, glm::length(m.centroid_m - glm::vec2(g)), m.height_m, m.radius_m, m.height_m / m.radius_m);
        EXPECT_NEAR(m.height_m / m.radius_m, std::tan(glm::radians(35.0f)), 0.25f * std::tan(glm::radians(35.0f)));
        // One undo step takes the whole stroke away.
        EXPECT_EQ(doc->undoName(), "Sculpt");
        EXPECT_TRUE(doc->undo());
        EXPECT_TRUE(doc->primitiveIds(0).empty());
        EXPECT_FALSE(doc->canUndo());
        doc->close();
    }
}

TEST_F(SculptTool, PileSteepnessFollowsTheTypesAngleOfRepose) {
    const glm::vec3 g(0.0f, 0.0f, 0.0f);
    for (float deg : {25.0f, 45.0f}) {
        SCOPED_TRACE(deg);
        std::unique_ptr<Document> doc = makeDoc(deg);
        ASSERT_TRUE(doc);
        hold(doc.get(), viewRay(g, -90.0f, 35.0f), 30);
        const PileMeasure m = measureSculptedPile(*doc, 0, glm::vec2(g), 3.0f, 0.03f, 4.0f);
        ASSERT_TRUE(m.found);
        EXPECT_NEAR(m.height_m / m.radius_m, std::tan(glm::radians(deg)), 0.25f * std::tan(glm::radians(deg)));
        doc->close();
    }
}

// A second stroke on top of a pile lands on the pile, straight under the brush's ground point.
TEST_F(SculptTool, StampOnAPileLandsOnItsTopUnderTheGroundPoint) {
    std::unique_ptr<Document> doc = makeDoc(35.0f);
    ASSERT_TRUE(doc);
    hold(doc.get(), viewRay(glm::vec3(0.0f), 0.0f, 89.0f), 30);
    const float top = measureSculptedPile(*doc, 0, glm::vec2(0.0f), 3.0f, 0.03f, 4.0f).height_m;
    // From a low, oblique view the ray passes the pile's side before it reaches the ground beyond it: the
    // landing is still above the ground point, on the pile's surface there.
    const glm::vec3 g(0.2f, 0.0f, 0.0f);
    const SurfaceHit h = sculptLanding(*doc, 0, viewRay(g, 180.0f, 20.0f));
    ASSERT_TRUE(h.hit && h.on_pile);
    EXPECT_NEAR(h.point_m.x, g.x, 1e-3f);
    EXPECT_NEAR(h.point_m.y, g.y, 1e-3f);
    EXPECT_GT(h.point_m.z, 0.5f * top);
    EXPECT_LT(h.point_m.z, top + 0.01f);
    doc->close();
}

// The stroke's cone is saved like any primitive and comes back the same, with the type's angle.
TEST_F(SculptTool, StrokeSurvivesSaving) {
    std::unique_ptr<Document> doc = makeDoc(40.0f);
    ASSERT_TRUE(doc);
    const std::vector<uint64_t> ids = hold(doc.get(), viewRay(glm::vec3(0.5f, 0.5f, 0.0f), -90.0f, 30.0f), 20);
    Primitive cone;
    ASSERT_TRUE(doc->findPrimitive(ids.at(0), nullptr, &cone));
    Project back;
    std::string error;
    ASSERT_TRUE(parseProject(projectToJson(doc->project()), "saved.json", &back, &error)) << error;
    EXPECT_EQ(back.detail_types[0].angle_of_repose_deg, 40.0f);
    const DensityField& f = back.detail_types[0].density;
    size_t segments = 0;
    for (const Primitive& p : f.primitives)
        if (p.kind == PrimitiveKind::Segment) {
            ++segments;
            EXPECT_EQ(p.center_m, cone.center_m);
            EXPECT_EQ(p.end_m, cone.end_m);
            EXPECT_EQ(p.radius_m, cone.radius_m);
            EXPECT_EQ(p.end_radius_m, cone.end_radius_m);
            EXPECT_EQ(p.weight, cone.weight);
            EXPECT_EQ(p.stroke, cone.stroke);
            EXPECT_NE(p.stroke, 0u);
        }
    EXPECT_EQ(segments, 1u);
    doc->close();
}

// A dragged stroke leaves a cone every radius / 3 of travel; they are one unit (issue 9: "a stroke is one
// edit object"): Select moves them all, the Inspector re-weights them all, Delete takes them all, each one
// undo step; a second stroke is another unit.
TEST_F(SculptTool, ADraggedStrokeIsOneUnitToMoveReweightAndDelete) {
    std::unique_ptr<Document> doc = makeDoc(35.0f);
    ASSERT_TRUE(doc);
    std::string error;
    const std::vector<uint64_t> cones =
        dragSculpt(doc.get(), {-2.0f, 0.0f}, {2.0f, 0.0f}, 20, [](glm::vec3 g) { return viewRay(g, -90.0f, 35.0f); });
    ASSERT_GE(cones.size(), 10u);
    const std::vector<uint64_t> other = hold(doc.get(), viewRay({0.0f, 2.5f, 0.0f}, 0.0f, 60.0f), 5);
    ASSERT_EQ(other.size(), 1u);
    EXPECT_EQ(doc->strokeMembers(cones[3]), cones);
    EXPECT_EQ(doc->strokeMembers(other[0]), other);
    auto centres = [&](const std::vector<uint64_t>& ids) {
        std::vector<Primitive> out;
        for (uint64_t id : ids) {
            Primitive p;
            EXPECT_TRUE(doc->findPrimitive(id, nullptr, &p));
            out.push_back(p);
        }
        return out;
    };
    const std::vector<Primitive> before = centres(cones);
    const Primitive other_before = centres(other)[0];

    // Select-drag the middle cone 1 m along +y: every cone of its stroke goes, the other pile stays.
    const glm::vec3 grab = before[5].center_m;
    MoveDrag move;
    ASSERT_TRUE(move.begin(doc.get(), cones[5], rayDownOnto(*doc, glm::vec2(grab))));
    for (int k = 1; k <= 4; ++k)
        ASSERT_TRUE(move.drag(rayDownOnto(*doc, glm::vec2(grab) + glm::vec2(0.0f, 0.25f * k)), false, &error)) << error;
    move.end();
    EXPECT_EQ(doc->undoName(), "Move stroke");
    const std::vector<Primitive> moved = centres(cones);
    for (size_t k = 0; k < cones.size(); ++k) {
        EXPECT_NEAR(moved[k].center_m.y - before[k].center_m.y, 1.0f, 1e-3f) << k;
        EXPECT_NEAR(moved[k].center_m.x, before[k].center_m.x, 1e-4f) << k;
        EXPECT_NEAR(moved[k].end_m.y - before[k].end_m.y, 1.0f, 1e-3f) << k;
    }
    EXPECT_EQ(centres(other)[0].center_m, other_before.center_m);

    // The Inspector halves the grabbed cone's weight: the stroke's weights all halve, one undo step.
    Primitive edited = moved[5];
    edited.weight *= 0.5f;
    ASSERT_TRUE(doc->setPrimitives(strokeEdit(*doc, cones[5], edited), "Edit stroke", &error)) << error;
    const std::vector<Primitive> reweighted = centres(cones);
    for (size_t k = 0; k < cones.size(); ++k) {
        EXPECT_FLOAT_EQ(reweighted[k].weight, 0.5f * moved[k].weight) << k;
        EXPECT_EQ(reweighted[k].center_m, moved[k].center_m) << k;
    }
    EXPECT_EQ(centres(other)[0].weight, other_before.weight);
    ASSERT_TRUE(doc->undo());
    EXPECT_EQ(centres(cones)[0].weight, moved[0].weight);

    // Delete through any cone takes the stroke, one undo step; undo brings every cone back.
    ASSERT_TRUE(doc->removePrimitives(doc->strokeMembers(cones[0]), "Delete stroke", &error)) << error;
    EXPECT_EQ(doc->primitiveIds(0), other);
    ASSERT_TRUE(doc->undo());
    EXPECT_EQ(doc->strokeMembers(cones[0]), cones);
    ASSERT_TRUE(doc->undo());  // the move
    EXPECT_EQ(centres(cones)[7].center_m, before[7].center_m);
    doc->close();
}

// A slow drag pours a ridge, not a ramp (issue 9: a 2 m drag with a 0.6 m brush used to stack each new cone
// on the flank of the last and climb 2.5 m, rocks in the air). Every cone stands on the ground; the ridge
// levels off at the height where each spot's material fills its stretch of the drag, its flanks at the
// angle of repose, and it is solid from the ground up. The same from above, the side and an oblique view.
TEST_F(SculptTool, ASlowDragPoursARidgeOfSteadyHeightOnTheGround) {
    const float slope = std::tan(glm::radians(35.0f));
    const std::pair<float, float> views[] = {{-90.0f, 35.0f}, {0.0f, 10.0f}, {0.0f, 89.0f}};
    for (const auto& [yaw, pitch] : views) {
        SCOPED_TRACE("yaw " + std::to_string(yaw) + " pitch " + std::to_string(pitch));
        std::unique_ptr<Document> doc = makeDoc(35.0f);
        ASSERT_TRUE(doc);
        // 2 m in 30 mouse moves of 6.7 cm along +x: a cone every 0.2 m.
        const std::vector<uint64_t> cones = dragSculpt(doc.get(), {-1.0f, 0.0f}, {1.0f, 0.0f}, 30,
                                                       [&](glm::vec3 g) { return viewRay(g, yaw, pitch); });
        ASSERT_GE(cones.size(), 9u);
        for (uint64_t id : cones) {
            Primitive p;
            ASSERT_TRUE(doc->findPrimitive(id, nullptr, &p));
            EXPECT_NEAR(p.center_m.z, 0.0f, 1e-5f);  // on the ground, not on the pile
        }
        // What the stroke poured: a stamp's volume per cone; the ridge between the cones stands at
        // h = sqrt(a·tanθ), a = V / spacing its cross-section.
        const float stamp_v = sculptStampVolume(0.6f, 1.0f, kSculptIso);
        const float steady_h = std::sqrt(stamp_v / 0.2f * slope);
        const DensityField& field = *doc->compiled().types[0].field;
        auto thickness = [&](glm::vec2 xy) { return pileThicknessOverPlane(field, kSculptIso, xy, 0.0f, 4.0f); };
        float start = 0.0f, end = 0.0f, top = 0.0f;
        for (int i = 0; i <= 40; ++i) {
            const float x = -1.0f + 2.0f * i / 40.0f;
            const float t = thickness({x, 0.0f});
            top = std::max(top, t);
            if (x <= -0.5f) start = std::max(start, t);
            if (x >= 0.5f) end = std::max(end, t);
            // Solid under the surface: no rocks in the air.
            for (float z = 0.02f; z < t - 0.02f; z += 0.02f)
                ASSERT_GE(evaluate(field, {x, 0.0f, z}), kSculptIso) << "x " << x << " z " << z;
        }
        // The flanks across the ridge's middle, at the angle of repose.
        float half_width = 0.0f;
        for (float y = 0.0f; y < 3.0f && thickness({0.0f, y}) > 0.02f; y += 0.01f) half_width = y;
        const float mid = thickness({0.0f, 0.0f});
        std::printf("ridge: start %.3f m, middle %.3f m, end %.3f m, top %.3f m (steady %.3f m), half width %.3f m, "
                    "h/w %.3f\n",
                    start, mid, end, top, steady_h, half_width, mid / half_width);
        EXPECT_LT(top, 1.4f * steady_h);
        EXPECT_LT(end, 1.25f * mid);  // levelled off, not still climbing
        EXPECT_NEAR(mid / half_width, slope, 0.3f * slope);
        doc->close();
    }
}

// A pile moved across sloping ground keeps standing on it (the issue: piles rest on something): dragged
// with the Select tool, each cone's base follows the ground's height under its new place, not the height it
// had where it was poured; its shape does not change. A dragged stroke's cones each follow the ground, and
// so does a copy (Ctrl+D).
TEST_F(SculptTool, APileMovedOverSlopingGroundKeepsItsBaseOnTheGround) {
    const std::string hills = R"("terrain": {"procedural": {"origin": [-6, -6], "cell_size_m": 0.25, "width": 49,
        "height": 49, "seed": 5, "octaves": 3, "base_height_m": 0, "amplitude_m": 0.8, "feature_size_m": 4,
        "lacunarity": 2, "gain": 0.5}},)";
    std::unique_ptr<Document> doc = makeDoc(35.0f, hills);
    ASSERT_TRUE(doc && doc->terrain());
    const std::vector<uint64_t> held = hold(doc.get(), viewRay({-1.0f, -1.0f, 0.0f}, -90.0f, 35.0f), 20);
    const std::vector<uint64_t> ridge = dragSculpt(doc.get(), {-2.0f, 1.5f}, {-0.5f, 1.5f}, 10,
                                                   [&](glm::vec3 g) { return rayDownOnto(*doc, glm::vec2(g)); });
    std::string error;
    ASSERT_EQ(held.size(), 1u);
    ASSERT_GE(ridge.size(), 5u);
    for (const std::vector<uint64_t>& ids : {held, ridge}) {
        std::vector<Primitive> before;
        for (uint64_t id : ids) {
            before.emplace_back();
            ASSERT_TRUE(doc->findPrimitive(id, nullptr, &before.back()));
            EXPECT_NEAR(before.back().center_m.z, groundHeightAt(*doc, glm::vec2(before.back().center_m)), 1e-5f);
        }
        MoveDrag move;
        const glm::vec2 grab(before[0].center_m);
        ASSERT_TRUE(move.begin(doc.get(), ids[0], rayDownOnto(*doc, grab)));
        for (int k = 1; k <= 5; ++k)
            ASSERT_TRUE(move.drag(rayDownOnto(*doc, grab + glm::vec2(0.5f * k, 0.4f * k)), false, &error)) << error;
        move.end();
        float climbed = 0.0f;
        for (size_t k = 0; k < ids.size(); ++k) {
            Primitive p;
            ASSERT_TRUE(doc->findPrimitive(ids[k], nullptr, &p));
            const glm::vec2 xy(p.center_m);
            EXPECT_NEAR(xy.x - before[k].center_m.x, 2.5f, 1e-3f);
            EXPECT_NEAR(xy.y - before[k].center_m.y, 2.0f, 1e-3f);
            EXPECT_NEAR(p.center_m.z, groundHeightAt(*doc, xy), 1e-4f) << k;  // on the ground where it is now
            EXPECT_NEAR(p.end_m.z - p.center_m.z, before[k].end_m.z - before[k].center_m.z, 1e-4f);  // same cone
            EXPECT_EQ(p.end_m.x, p.center_m.x);  // still vertical
            climbed = std::max(climbed, std::abs(p.center_m.z - before[k].center_m.z));
        }
        // The ground is not level between the two places, or the test proves nothing.
        EXPECT_GT(climbed, 0.05f);
    }
    // Ctrl+D copies the held pile one falloff radius along +x, onto the ground there, one undo step.
    Primitive original;
    ASSERT_TRUE(doc->findPrimitive(held[0], nullptr, &original));
    const std::vector<uint64_t> copy = duplicateStroke(doc.get(), held[0], &error);
    ASSERT_EQ(copy.size(), 1u) << error;
    Primitive c;
    ASSERT_TRUE(doc->findPrimitive(copy[0], nullptr, &c));
    EXPECT_NEAR(c.center_m.x - original.center_m.x, original.radius_m, 1e-4f);
    EXPECT_NEAR(c.center_m.z, groundHeightAt(*doc, glm::vec2(c.center_m)), 1e-4f);
    EXPECT_GT(std::abs(c.center_m.z - original.center_m.z), 0.01f);  // the ground differs there
    EXPECT_NE(c.stroke, original.stroke);
    EXPECT_EQ(doc->undoName(), "Duplicate primitive");
    doc->close();
}

}  // namespace
}  // namespace ug::editor
