// Structural edits of the environmental-object tree (env/env_tree_edits.h): grouping, ungrouping and
// moving a node into a group keep every object where it was in the world (compiled and compared at three
// points of each object's space); the refusals name the node; a group made reusable and instanced again
// adds its objects once more, the first ones unmoved.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "env/env_scene.h"
#include "env/env_tree_edits.h"

namespace ug {
namespace {

EnvironmentDesc street() {
    const std::string models = (std::filesystem::path(UG_SOURCE_DIR) / "assets" / "env_models").string();
    EnvironmentDesc env;
    EnvTypeDesc bench, shelter;
    bench.name = "bench";
    bench.mesh_path = models + "/bench.glb";
    shelter.name = "bus_shelter";
    shelter.mesh_path = models + "/bus_shelter.glb";
    env.types = {bench, shelter};
    EnvNode a;
    a.type = 0;
    a.transform = {{1.0f, 2.0f, 0.0f}, 30.0f, 1.2f};
    EnvNode b = a, c = a;
    b.transform = {{0.5f, 0.0f, 0.0f}, 10.0f, 1.0f};
    c.type = 1;
    c.transform = {{-1.0f, 0.5f, 0.1f}, -20.0f, 0.9f};
    EnvNode group;
    group.kind = EnvNodeKind::Group;
    group.transform = {{3.0f, 1.0f, 0.0f}, 45.0f, 0.8f};
    group.children = {b, c};
    env.roots = {a, group};
    return env;
}

// Every object's type and where three points of its space land, sorted (an edit may reorder the tree).
std::vector<std::vector<float>> placed(const EnvironmentDesc& desc) {
    EnvScene scene;
    std::string error;
    EXPECT_TRUE(compileEnvScene(desc, "", "test", nullptr, &scene, &error)) << error;
    std::vector<std::vector<float>> out;
    for (const EnvObject& o : scene.objects()) {
        std::vector<float> v{float(o.type)};
        for (glm::vec3 p : {glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 1.0f)}) {
            const glm::vec3 w = o.placement.toWorld(p);
            v.insert(v.end(), {w.x, w.y, w.z});
        }
        out.push_back(v);
    }
    std::sort(out.begin(), out.end());
    return out;
}

::testing::AssertionResult samePlaces(const EnvironmentDesc& a, const EnvironmentDesc& b) {
    const auto pa = placed(a), pb = placed(b);
    if (pa.size() != pb.size()) return ::testing::AssertionFailure() << pa.size() << " vs " << pb.size() << " objects";
    for (size_t i = 0; i < pa.size(); ++i)
        for (size_t k = 0; k < pa[i].size(); ++k)
            if (std::abs(pa[i][k] - pb[i][k]) > 1e-5f)
                return ::testing::AssertionFailure() << "object " << i << " value " << k << ": " << pa[i][k] << " vs " << pb[i][k];
    return ::testing::AssertionSuccess();
}

TEST(EnvTreeEdits, GroupUngroupAndRegroupKeepEveryObjectInPlace) {
    const EnvironmentDesc before = street();
    std::string error;
    EnvironmentDesc grouped = before;
    ASSERT_TRUE(groupEnvNode(&grouped, {0}, &error)) << error;
    EXPECT_EQ(grouped.roots[0].kind, EnvNodeKind::Group);
    EXPECT_EQ(grouped.roots[0].children.size(), 1u);
    EXPECT_TRUE(samePlaces(before, grouped));

    EnvironmentDesc ungrouped = before;
    ASSERT_TRUE(ungroupEnvNode(&ungrouped, {1}, &error)) << error;
    EXPECT_EQ(ungrouped.roots.size(), 3u);
    EXPECT_TRUE(samePlaces(before, ungrouped));

    EnvironmentDesc moved = before;
    EnvPath at;
    ASSERT_TRUE(moveEnvNodeInto(&moved, {0}, {1}, &at, &error)) << error;
    EXPECT_EQ(at, (EnvPath{0, 2})) << "the group moved up to the first root; the node is its third child";
    EXPECT_EQ(moved.roots.size(), 1u);
    EXPECT_TRUE(samePlaces(before, moved));

    // And out again, by ungrouping: still in place.
    ASSERT_TRUE(ungroupEnvNode(&moved, {0}, &error)) << error;
    EXPECT_TRUE(samePlaces(before, moved));
}

TEST(EnvTreeEdits, RefusalsNameTheNodeAndChangeNothing) {
    EnvironmentDesc env = street();
    const EnvironmentDesc before = env;
    std::string error;
    EXPECT_FALSE(ungroupEnvNode(&env, {0}, &error));
    EXPECT_NE(error.find("/tree/0"), std::string::npos) << error;
    EnvironmentDesc nested = env;
    ASSERT_TRUE(groupEnvNode(&nested, {1, 0}, &error)) << error;
    EXPECT_FALSE(moveEnvNodeInto(&nested, {1}, {1, 0}, nullptr, &error));
    EXPECT_NE(error.find("its own subtree"), std::string::npos) << error;
    EXPECT_FALSE(moveEnvNodeInto(&env, {0}, {1, 0}, nullptr, &error)) << "an object is not a group";
    EXPECT_FALSE(groupEnvNode(&env, {7}, &error));
    EXPECT_NE(error.find("/tree/7"), std::string::npos) << error;
    env.roots[1].fields.push_back(EnvFieldDesc{});
    EXPECT_FALSE(ungroupEnvNode(&env, {1}, &error));
    EXPECT_NE(error.find("fields"), std::string::npos) << error;
    env.roots[1].fields.clear();
    EXPECT_TRUE(samePlaces(before, env));
    EXPECT_EQ(env.roots.size(), before.roots.size());
}

TEST(EnvTreeEdits, AReusableGroupInstancedAgainAddsItsObjects) {
    const EnvironmentDesc before = street();
    EnvironmentDesc env = before;
    std::string error;
    ASSERT_TRUE(makeEnvGroupReusable(&env, {1}, "stop", &error)) << error;
    EXPECT_EQ(env.roots[1].kind, EnvNodeKind::Reference);
    EXPECT_TRUE(samePlaces(before, env));
    EXPECT_FALSE(makeEnvGroupReusable(&env, {0}, "stop", &error)) << "not a group";
    ASSERT_TRUE(addEnvReference(&env, "stop", EnvTransform{{8.0f, 8.0f, 0.0f}, 90.0f, 1.0f}, &error)) << error;
    EXPECT_FALSE(addEnvReference(&env, "nowhere", EnvTransform{}, &error));
    EXPECT_EQ(placed(env).size(), placed(before).size() + 2);
}

// The object ranges and the object -> node map agree with the compiler's expansion: each compiled object
// lies in its node's range, and an object's node is placed (world transform) where the compiler put it.
TEST(EnvTreeEdits, ObjectRangesAndPathsFollowTheCompiledTree) {
    EnvironmentDesc env = street();
    std::string error;
    ASSERT_TRUE(makeEnvGroupReusable(&env, {1}, "stop", &error)) << error;
    ASSERT_TRUE(addEnvReference(&env, "stop", EnvTransform{{8.0f, 8.0f, 0.0f}, 90.0f, 1.0f}, &error)) << error;
    ASSERT_TRUE(groupEnvNode(&env, {0}, &error)) << error;  // root 0: a group holding the first bench
    EnvScene scene;
    ASSERT_TRUE(compileEnvScene(env, "", "test", nullptr, &scene, &error)) << error;
    ASSERT_EQ(scene.objects().size(), 5u);
    const std::vector<EnvPath> expected{{0, 0}, {1}, {1}, {2}, {2}};
    for (size_t o = 0; o < scene.objects().size(); ++o) {
        const EnvPath path = envPathOfObject(env, o);
        EXPECT_EQ(path, expected[o]) << "object " << o;
        size_t first = 0, count = 0;
        ASSERT_TRUE(envObjectRange(env, path, &first, &count));
        EXPECT_TRUE(first <= o && o < first + count) << "object " << o << " outside [" << first << ", +" << count << ")";
    }
    size_t first = 0, count = 0;
    ASSERT_TRUE(envObjectRange(env, {2}, &first, &count));
    EXPECT_EQ(first, 3u);
    EXPECT_EQ(count, 2u);
    const glm::vec3 at = envWorldTransform(env, {0, 0}).translation;
    const glm::vec3 compiled = scene.objects()[0].placement.toWorld(glm::vec3(0.0f));
    EXPECT_NEAR(glm::distance(at, compiled), 0.0f, 1e-5f);
    EXPECT_TRUE(envPathOfObject(env, 5).empty());
    EXPECT_EQ(envObjectMask(env, {{2}, {0, 0}, {9}}, 5), (std::vector<uint8_t>{1, 0, 0, 1, 1}));
    EXPECT_TRUE(envObjectMask(env, {{9}}, 5).empty());
    EXPECT_FALSE(envObjectRange(env, {7}, &first, &count));
}

// A nested node given a world transform lands there once compiled (through its parent's turn and scale).
TEST(EnvTreeEdits, AWorldTransformPlacesANestedNode) {
    EnvironmentDesc env = street();
    const EnvTransform want{{4.0f, -2.0f, 0.25f}, 70.0f, 1.5f};
    ASSERT_TRUE(setEnvWorldTransform(&env, {1, 1}, want));  // the shelter inside the turned, scaled group
    EXPECT_FALSE(setEnvWorldTransform(&env, {1, 5}, want));
    EnvScene scene;
    std::string error;
    ASSERT_TRUE(compileEnvScene(env, "", "test", nullptr, &scene, &error)) << error;
    const EnvPlacement& p = scene.objects()[2].placement;
    EXPECT_NEAR(glm::distance(p.toWorld(glm::vec3(0.0f)), want.translation), 0.0f, 1e-5f);
    // One metre along the object's x lands 1.5 m away, turned 70 degrees.
    const glm::vec3 x = p.toWorld(glm::vec3(1.0f, 0.0f, 0.0f)) - want.translation;
    EXPECT_NEAR(glm::length(x), 1.5f, 1e-5f);
    EXPECT_NEAR(std::atan2(x.y, x.x) * 180.0f / 3.14159265f, 70.0f, 1e-3f);
}

// Turned round and round, a node keeps a yaw in [-180, 180] for the same placement.
TEST(EnvTreeEdits, AWorldYawIsWrappedIntoOneTurn) {
    EnvironmentDesc env = street();
    const EnvTransform top = envWorldTransform(env, {0});
    ASSERT_TRUE(setEnvWorldTransform(&env, {0}, EnvTransform{top.translation, 725.0f, top.scale}));
    EXPECT_NEAR(envNodeAt(&env, {0})->transform.yaw_deg, 5.0f, 1e-3f);
    ASSERT_TRUE(setEnvWorldTransform(&env, {0}, EnvTransform{top.translation, -1e5f - 90.0f, top.scale}));
    const float yaw = envNodeAt(&env, {0})->transform.yaw_deg;
    EXPECT_GE(yaw, -180.0f);
    EXPECT_LE(yaw, 180.0f);
    EXPECT_NEAR(std::remainder(yaw - (-1e5f - 90.0f), 360.0f), 0.0f, 0.05f);
}

}  // namespace
}  // namespace ug
