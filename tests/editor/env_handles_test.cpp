// The environmental objects' handles in the view (app/editor/env_handles.h) and picking (env_tools.h) on a
// real document: the turn handle dragged a quarter round the ring turns the node 90 degrees about its
// origin, the scale handle dragged out to 1.5 times its distance scales it by 1.5 (snapped and clamped
// as documented); each drag is one undo step; a node inside a turned, scaled group turns and scales in the
// world, its object compiled where the drag put it; a click picks the object's top-level node, Ctrl + click
// its own.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "editor/env_handles.h"
#include "editor/env_tools.h"
#include "editor_test_util.h"

namespace ug::editor {
namespace {

// Drags `handle` of `path` from its point to `to` (XY) in `steps` vertical rays, as the replay does.
int dragHandle(Document* doc, const EnvPath& path, EnvHandle handle, glm::vec2 to, int steps, bool snap) {
    EnvHandleFrame frame;
    EXPECT_TRUE(envHandleFrame(*doc, path, &frame));
    const glm::vec2 from(envHandlePoint(frame, handle));
    EnvHandleDrag drag;
    EXPECT_TRUE(drag.begin(doc, path, handle, rayDownOnto(*doc, from)));
    std::string error;
    for (int k = 1; k <= steps; ++k)
        EXPECT_TRUE(drag.drag(rayDownOnto(*doc, glm::mix(from, to, float(k) / float(steps))), snap, &error)) << error;
    drag.end();
    return drag.moves();
}

glm::vec2 onRing(const EnvHandleFrame& f, float deg, float radius_factor = 1.0f) {
    const float rad = deg * 3.14159265f / 180.0f;
    return glm::vec2(f.origin) + radius_factor * f.radius_m * glm::vec2(std::cos(rad), std::sin(rad));
}

TEST(EnvHandles, TheTurnHandleTurnsTheNodeAboutItsOriginAsOneUndoStep) {
    test::OpenEnvDocument o;
    ASSERT_TRUE(o.doc);
    Document& doc = *o.doc;
    const EnvTransform start = doc.project().environment.roots[0].transform;  // the bench
    EnvHandleFrame f;
    ASSERT_TRUE(envHandleFrame(doc, {0}, &f));
    EXPECT_EQ(f.origin, start.translation);
    EXPECT_GT(f.radius_m, 0.8f) << "the ring goes round the 1.6 m bench";
    // A quarter round, along the ring's chord in 6 steps.
    EXPECT_GT(dragHandle(&doc, {0}, EnvHandle::Turn, onRing(f, start.yaw_deg + 90.0f), 6, false), 0);
    const EnvTransform turned = doc.project().environment.roots[0].transform;
    EXPECT_NEAR(turned.yaw_deg, start.yaw_deg + 90.0f, 1e-3f);
    EXPECT_EQ(turned.translation, start.translation);
    EXPECT_EQ(turned.scale, start.scale);
    EXPECT_EQ(doc.undoName(), "Turn object");
    ASSERT_TRUE(doc.undo());
    EXPECT_EQ(doc.project().environment.roots[0].transform.yaw_deg, start.yaw_deg);
    EXPECT_FALSE(doc.canUndo()) << "the whole drag was one step";
    // Snapped: 50 degrees becomes 45.
    dragHandle(&doc, {0}, EnvHandle::Turn, onRing(f, start.yaw_deg + 50.0f), 3, true);
    EXPECT_NEAR(doc.project().environment.roots[0].transform.yaw_deg, 45.0f, 1e-4f);
}

TEST(EnvHandles, TheScaleHandleScalesByTheRatioOfDistancesSnappedAndClamped) {
    test::OpenEnvDocument o;
    ASSERT_TRUE(o.doc);
    Document& doc = *o.doc;
    EnvHandleFrame f;
    ASSERT_TRUE(envHandleFrame(doc, {1}, &f));  // the bus shelter
    const float yaw = f.yaw_deg + 180.0f;       // the scale handle's side
    dragHandle(&doc, {1}, EnvHandle::Scale, onRing(f, yaw, 1.5f), 4, false);
    EXPECT_NEAR(doc.project().environment.roots[1].transform.scale, 1.5f, 1e-4f);
    EXPECT_EQ(doc.undoName(), "Scale object");
    ASSERT_TRUE(doc.undo());
    dragHandle(&doc, {1}, EnvHandle::Scale, onRing(f, yaw, 1.23f), 2, true);
    EXPECT_NEAR(doc.project().environment.roots[1].transform.scale, 1.25f, 1e-5f);
    ASSERT_TRUE(doc.undo());
    dragHandle(&doc, {1}, EnvHandle::Scale, onRing(f, yaw, 0.01f), 2, false);
    EXPECT_EQ(doc.project().environment.roots[1].transform.scale, kEnvHandleMinScale);
}

TEST(EnvHandles, ANestedNodeTurnsAndScalesInTheWorld) {
    test::OpenEnvDocument o;
    ASSERT_TRUE(o.doc);
    Document& doc = *o.doc;
    // The bench inside a group turned 30 degrees and scaled 1.2 about a point beside it.
    EnvironmentDesc env = doc.project().environment;
    std::string error;
    ASSERT_TRUE(groupEnvNode(&env, {0}, &error)) << error;
    EnvNode& group = env.roots[0];
    const EnvTransform world_bench = envWorldTransform(env, {0, 0});
    group.transform = EnvTransform{{0.5f, 0.5f, 0.0f}, 30.0f, 1.2f};
    ASSERT_TRUE(setEnvWorldTransform(&env, {0, 0}, world_bench));  // the bench stays where it was
    ASSERT_TRUE(doc.setEnvironment(env, "Group", &error)) << error;
    EnvHandleFrame f;
    ASSERT_TRUE(envHandleFrame(doc, {0, 0}, &f));
    EXPECT_NEAR(glm::distance(f.origin, world_bench.translation), 0.0f, 1e-5f);
    dragHandle(&doc, {0, 0}, EnvHandle::Turn, onRing(f, f.yaw_deg - 90.0f), 6, false);
    dragHandle(&doc, {0, 0}, EnvHandle::Scale, onRing(f, f.yaw_deg - 90.0f + 180.0f, 2.0f), 4, false);
    const EnvTransform world = envWorldTransform(doc.project().environment, {0, 0});
    EXPECT_NEAR(world.yaw_deg, world_bench.yaw_deg - 90.0f, 1e-3f);
    EXPECT_NEAR(world.scale, 2.0f * world_bench.scale, 1e-4f);
    EXPECT_EQ(doc.project().environment.roots[0].transform.yaw_deg, 30.0f) << "the group did not turn";
    // The compiled bench: its origin unmoved, its x axis turned -90 degrees and 2 m long.
    const EnvPlacement& p = doc.environment()->objects()[0].placement;
    EXPECT_NEAR(glm::distance(p.toWorld(glm::vec3(0.0f)), world_bench.translation), 0.0f, 1e-4f);
    const glm::vec3 x = p.toWorld(glm::vec3(1.0f, 0.0f, 0.0f)) - p.toWorld(glm::vec3(0.0f));
    EXPECT_NEAR(glm::length(x), 2.0f * world_bench.scale, 1e-4f);
    EXPECT_NEAR(std::atan2(x.y, x.x) * 180.0f / 3.14159265f, world_bench.yaw_deg - 90.0f, 1e-2f);
}

TEST(EnvHandles, AClickPicksTheTopLevelNodeACtrlClickTheNestedOne) {
    test::OpenEnvDocument o;
    ASSERT_TRUE(o.doc);
    Document& doc = *o.doc;
    EnvironmentDesc env = doc.project().environment;
    std::string error;
    ASSERT_TRUE(groupEnvNode(&env, {1}, &error)) << error;  // the shelter alone in a group
    ASSERT_TRUE(moveEnvNodeInto(&env, {0}, {1}, nullptr, &error)) << error;  // the bench joins it: root 0
    ASSERT_TRUE(doc.setEnvironment(env, "Group", &error)) << error;
    ASSERT_EQ(doc.project().environment.roots.size(), 1u);
    // Looking straight down at the street from 10 m, 800 x 800 pixels.
    const glm::mat4 view_proj = glm::perspective(glm::radians(40.0f), 1.0f, 0.1f, 100.0f) *
                                glm::lookAt(glm::vec3(2.0f, 2.0f, 10.0f), glm::vec3(2.0f, 2.0f, 0.0f), glm::vec3(0, 1, 0));
    auto pixelOf = [&](glm::vec3 p) {
        const glm::vec4 c = view_proj * glm::vec4(p, 1.0f);
        return glm::vec2((c.x / c.w * 0.5f + 0.5f) * 800.0f, (0.5f - 0.5f * c.y / c.w) * 800.0f);
    };
    const glm::vec3 bench = envWorldTransform(doc.project().environment, {0, 1}).translation;
    EXPECT_EQ(pickEnvNode(doc, view_proj, 800, 800, pixelOf(bench) + glm::vec2(3, -2), 25.0f, false), EnvPath{0});
    EXPECT_EQ(pickEnvNode(doc, view_proj, 800, 800, pixelOf(bench) + glm::vec2(3, -2), 25.0f, true), (EnvPath{0, 1}));
    EXPECT_TRUE(pickEnvNode(doc, view_proj, 800, 800, pixelOf(bench) + glm::vec2(60, 0), 25.0f, true).empty());
}

}  // namespace
}  // namespace ug::editor
