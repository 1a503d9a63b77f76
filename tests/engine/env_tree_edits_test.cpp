// Structural edits of the environmental-object tree (env/env_tree_edits.h): grouping, ungrouping and
// moving a node into a group keep every object where it was in the world (compiled and compared at three
// points of each object's space); the refusals name the node; a group made reusable and instanced again
// adds its objects once more, the first ones unmoved.
#include <gtest/gtest.h>

#include <algorithm>
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

}  // namespace
}  // namespace ug
