// The renderer's GL-free side of static meshes (render_data.h): instance packing (what static_mesh.vert
// reads), the matrix it stands for, the union bounds an entry is culled by, and the frustum test.
#include <gtest/gtest.h>

#include <memory>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "editor/render_data.h"

namespace ug::editor {
namespace {

// A box from lo to hi (two triangles are enough: bounds read the positions only).
std::shared_ptr<const TriangleMesh> boxMesh(glm::vec3 lo, glm::vec3 hi) {
    auto mesh = std::make_shared<TriangleMesh>();
    for (int c = 0; c < 8; ++c)
        mesh->positions.push_back({c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z});
    mesh->indices = {0, 1, 3, 0, 3, 2};
    return mesh;
}

InstanceTransform at(glm::vec3 p, glm::quat q = glm::quat(1, 0, 0, 0), float s = 1.0f) {
    InstanceTransform t;
    t.position = p;
    t.rotation = q;
    t.scale = s;
    return t;
}

void expectNear(glm::vec3 a, glm::vec3 b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

}  // namespace

TEST(StaticMeshData, NoInstancesIsOneCopyAtTheIdentity) {
    MeshInstances entry;
    entry.mesh = boxMesh(glm::vec3(-1), glm::vec3(1));
    const std::vector<GpuStaticInstance> packed = packStaticInstances(entry);
    ASSERT_EQ(packed.size(), 1u);
    EXPECT_EQ(staticInstanceMatrix(packed[0]), glm::mat4(1.0f));
    const Bounds b = staticMeshBounds(entry);
    EXPECT_EQ(b.lo, glm::vec3(-1));
    EXPECT_EQ(b.hi, glm::vec3(1));
}

TEST(StaticMeshData, PackedInstancesMapPointsAsTheTransformSays) {
    MeshInstances entry;
    entry.mesh = boxMesh(glm::vec3(0), glm::vec3(1));
    // 90 degrees about Z, scale 2, at (10, 0, 1); a quaternion 0.1 % too long is renormalized.
    const glm::quat quarter = glm::angleAxis(glm::half_pi<float>(), glm::vec3(0, 0, 1));
    entry.instances = {at({10, 0, 1}, quarter, 2.0f), at({0, 0, 0}, glm::quat(1.001f, 0, 0, 0), 0.5f)};
    const std::vector<GpuStaticInstance> packed = packStaticInstances(entry);
    ASSERT_EQ(packed.size(), 2u);
    EXPECT_EQ(packed[0].position_scale, glm::vec4(10, 0, 1, 2));
    EXPECT_NEAR(glm::length(packed[1].rotation), 1.0f, 1e-7f);
    // By hand: (1, 0, 0) -> rotated to (0, 1, 0), scaled to (0, 2, 0), moved to (10, 2, 1).
    expectNear(glm::vec3(staticInstanceMatrix(packed[0]) * glm::vec4(1, 0, 0, 1)), {10, 2, 1});
    expectNear(glm::vec3(staticInstanceMatrix(packed[0]) * glm::vec4(0, 1, 0, 1)), {8, 0, 1});
    expectNear(glm::vec3(staticInstanceMatrix(packed[1]) * glm::vec4(1, 1, 1, 1)), {0.5f, 0.5f, 0.5f});
}

TEST(StaticMeshData, BoundsAreTheUnionOfTheTurnedBoxes) {
    MeshInstances entry;
    entry.mesh = boxMesh(glm::vec3(0), glm::vec3(2, 1, 1));
    const glm::quat quarter = glm::angleAxis(glm::half_pi<float>(), glm::vec3(0, 0, 1));
    entry.instances = {at({0, 0, 0}), at({10, 0, 0}, quarter, 1.0f), at({0, -5, 3}, glm::quat(1, 0, 0, 0), 0.5f)};
    // Instance 0: [0,2]x[0,1]x[0,1]. Instance 1: x' = -y, y' = x -> [9,10]x[0,2]x[0,1]. Instance 2:
    // [0,1]x[-5,-4.5]x[3,3.5].
    const Bounds b = staticMeshBounds(entry);
    expectNear(b.lo, {0, -5, 0});
    expectNear(b.hi, {10, 2, 3.5f});
    // A 45 degree turn of a unit cube grows its box to sqrt(2) in X and Y (exact for the box, not loose).
    MeshInstances turned;
    turned.mesh = boxMesh(glm::vec3(-0.5f), glm::vec3(0.5f));
    turned.instances = {at({0, 0, 0}, glm::angleAxis(glm::quarter_pi<float>(), glm::vec3(0, 0, 1)))};
    const Bounds t = staticMeshBounds(turned);
    expectNear(t.hi, {std::sqrt(0.5f), std::sqrt(0.5f), 0.5f});
    // The list's union, and nothing for an entry without a mesh.
    MeshInstances empty;
    EXPECT_TRUE(staticMeshBounds(empty).empty());
    const Bounds all = staticMeshesBounds({entry, turned, empty});
    expectNear(all.lo, {-std::sqrt(0.5f), -5, -0.5f});
    expectNear(all.hi, {10, 2, 3.5f});
    EXPECT_TRUE(staticMeshesBounds({}).empty());
}

TEST(StaticMeshData, FrustumTestKeepsWhatTheCameraSees) {
    // From (0, 10, 0) toward the origin (looking down -Y), a 60 degree field, 0.1 - 100 m.
    const glm::mat4 view = glm::lookAt(glm::vec3(0, 10, 0), glm::vec3(0), glm::vec3(0, 0, 1));
    const glm::mat4 view_proj = glm::perspective(glm::radians(60.0f), 1.0f, 0.1f, 100.0f) * view;
    EXPECT_TRUE(boxInFrustum(view_proj, Bounds{glm::vec3(-1), glm::vec3(1)}));
    EXPECT_FALSE(boxInFrustum(view_proj, Bounds{glm::vec3(-1, 20, -1), glm::vec3(1, 22, 1)}));  // behind
    EXPECT_FALSE(boxInFrustum(view_proj, Bounds{glm::vec3(50, -1, -1), glm::vec3(52, 1, 1)}));  // far aside
    EXPECT_FALSE(boxInFrustum(view_proj, Bounds{glm::vec3(-1, -200, -1), glm::vec3(1, -190, 1)}));  // past far
    // A box straddling the view's edge is kept.
    EXPECT_TRUE(boxInFrustum(view_proj, Bounds{glm::vec3(5, -1, -1), glm::vec3(50, 1, 1)}));
    EXPECT_FALSE(boxInFrustum(view_proj, Bounds{}));
}

TEST(StaticMeshData, ChunksPartitionTheInstancesWithTheirOwnBoxes) {
    MeshInstances entry;
    entry.mesh = boxMesh(glm::vec3(-0.5f), glm::vec3(0.5f));
    // Chunks of 8 m: (0, 0) gets instances 0 and 3, (-1, 0) instance 1, (2, -1) instance 2.
    entry.instances = {at({1, 1, 0}), at({-3, 2, 0}), at({17, -0.5f, 5}, glm::quat(1, 0, 0, 0), 2.0f), at({7, 7, 0})};
    const StaticInstanceChunks c = chunkStaticInstances(entry);
    ASSERT_EQ(c.instances.size(), 4u);
    ASSERT_EQ(c.chunks.size(), 3u);
    // Sorted by (ix, iy): (-1, 0), (0, 0), (2, -1); input order within a chunk.
    EXPECT_EQ(c.chunks[0].first, 0u);
    EXPECT_EQ(c.chunks[0].count, 1u);
    EXPECT_EQ(c.chunks[1].first, 1u);
    EXPECT_EQ(c.chunks[1].count, 2u);
    EXPECT_EQ(c.chunks[2].first, 3u);
    EXPECT_EQ(c.chunks[2].count, 1u);
    EXPECT_EQ(c.instances[0].position_scale, glm::vec4(-3, 2, 0, 1));
    EXPECT_EQ(c.instances[1].position_scale, glm::vec4(1, 1, 0, 1));
    EXPECT_EQ(c.instances[2].position_scale, glm::vec4(7, 7, 0, 1));
    EXPECT_EQ(c.instances[3].position_scale, glm::vec4(17, -0.5f, 5, 2));
    expectNear(c.chunks[1].bounds.lo, {0.5f, 0.5f, -0.5f});
    expectNear(c.chunks[1].bounds.hi, {7.5f, 7.5f, 0.5f});
    expectNear(c.chunks[2].bounds.lo, {16, -1.5f, 4});
    expectNear(c.chunks[2].bounds.hi, {18, 0.5f, 6});
    // The whole entry's box is the union, as staticMeshBounds says.
    const Bounds whole = staticMeshBounds(entry);
    EXPECT_EQ(c.bounds.lo, whole.lo);
    EXPECT_EQ(c.bounds.hi, whole.hi);
    expectNear(whole.lo, {-3.5f, -1.5f, -0.5f});
    expectNear(whole.hi, {18, 7.5f, 6});
    // No instances: one chunk holding the copy at the identity; no mesh: nothing.
    entry.instances.clear();
    const StaticInstanceChunks one = chunkStaticInstances(entry);
    ASSERT_EQ(one.chunks.size(), 1u);
    EXPECT_EQ(one.chunks[0].count, 1u);
    EXPECT_TRUE(chunkStaticInstances(MeshInstances{}).chunks.empty());
}

}  // namespace ug::editor
