// The editor's live strands (app/editor/live_strands.h): the worker's meshes are the ones every output
// makes of the same systems, bit for bit; submissions that come while it grows are coalesced into the
// newest; an attractor's move is re-grown incrementally; a cancelled growth shows nothing new.
#include <gtest/gtest.h>

#include <memory>

#include "editor/live_strands.h"
#include "editor_test_util.h"
#include "particles/particle_output.h"

namespace ug::editor {
namespace {

ParticleSystemFile grassSystem(const std::string& name, float x) {
    ParticleSystemFile s;
    s.name = name;
    ParticleGenerator g;
    g.center_m = {x, 0.0f, 0.0f};
    g.axis_u_m = {0.3f, 0.0f, 0.0f};
    g.axis_v_m = {0.0f, 0.3f, 0.0f};
    g.count = 400;
    g.heading_cone_deg = 10.0f;
    s.scene.generators.push_back(g);
    Attractor up;
    up.a_m = {x, 0.0f, 5.0f};
    Attractor wind;
    wind.a_m = {x + 0.2f, 0.0f, 0.15f};
    wind.influence_m = 0.15f;
    wind.charge = {ChargeKey{0, 2.0f}};
    s.scene.attractors = {up, wind};
    s.scene.walk.steps = 16;
    s.scene.walk.step_length_m = 0.01f;
    s.scene.walk.strand_radius_m = 0.002f;
    s.mesh.shape = StrandShape::Blade;
    return s;
}

// What `instantiate` and `render` make of the systems.
std::vector<MeshInstances> outputsOf(const std::vector<ParticleSystemFile>& systems) {
    std::vector<MeshInstances> out;
    for (const ParticleSystemFile& s : systems) {
        Strands strands;
        std::string error;
        EXPECT_TRUE(appendParticleSystemMeshes(s, 1, &strands, &out, &error)) << error;
    }
    return out;
}

using test::expectSameMeshes;

TEST(LiveStrands, GrowsWhatTheOutputsGrowAndCoalescesSubmissions) {
    auto systems = std::make_shared<std::vector<ParticleSystemFile>>(
        std::vector<ParticleSystemFile>{grassSystem("a", 0.0f), grassSystem("b", 1.0f)});
    LiveStrands live(2);
    live.submit(systems, 1);
    live.waitIdle();
    LiveStrandsResult r;
    ASSERT_TRUE(live.poll(&r));
    EXPECT_FALSE(live.poll(&r));  // handed over once
    EXPECT_EQ(r.generation, 1u);
    EXPECT_TRUE(r.error.empty()) << r.error;
    expectSameMeshes(r.meshes, outputsOf(*systems));

    // Three edits in a row: only the newest need be shown, and it is the newest's strands.
    std::vector<ParticleSystemFile> edited = *systems;
    for (uint64_t g = 2; g <= 4; ++g) {
        edited[0].scene.attractors[1].a_m.x += 0.02f;
        live.submit(std::make_shared<std::vector<ParticleSystemFile>>(edited), g);
    }
    live.waitIdle();
    ASSERT_TRUE(live.poll(&r));
    EXPECT_EQ(r.generation, 4u);
    expectSameMeshes(r.meshes, outputsOf(edited));
    // The moved attractor reaches part of one system: the rest was taken from the record.
    EXPECT_TRUE(r.report.incremental);
    EXPECT_GT(r.report.reused, r.report.recomputed);
}

TEST(LiveStrands, ACancelledGrowthShowsNothingAndTheEditUndoneReusesEveryMove) {
    std::vector<ParticleSystemFile> before{grassSystem("a", 0.0f), grassSystem("b", 1.0f)};
    LiveStrands live(2);
    live.submit(std::make_shared<std::vector<ParticleSystemFile>>(before), 1);
    live.waitIdle();
    LiveStrandsResult r;
    ASSERT_TRUE(live.poll(&r));
    EXPECT_FALSE(r.cancelled);
    EXPECT_EQ(live.progress(), 0.0f);  // idle
    // An edit cancelled before its growth could start (the editor's Cancel comes while it grows; a
    // cancel for it before it starts still counts): cancelled, no meshes.
    std::vector<ParticleSystemFile> edited = before;
    edited[0].scene.walk.steps = 40;
    live.cancel(2);
    live.submit(std::make_shared<std::vector<ParticleSystemFile>>(edited), 2);
    live.waitIdle();
    ASSERT_TRUE(live.poll(&r));
    EXPECT_EQ(r.generation, 2u);
    EXPECT_TRUE(r.cancelled);
    EXPECT_TRUE(r.meshes.empty());
    // The edit undone (a newer generation, not cancelled): every move from the records kept.
    live.submit(std::make_shared<std::vector<ParticleSystemFile>>(before), 3);
    live.waitIdle();
    ASSERT_TRUE(live.poll(&r));
    EXPECT_FALSE(r.cancelled);
    EXPECT_EQ(r.generation, 3u);
    EXPECT_TRUE(r.report.incremental);
    EXPECT_EQ(r.report.recomputed, 0u);
    expectSameMeshes(r.meshes, outputsOf(before));
}

TEST(LiveStrands, ASystemThatCannotGrowIsNamedAndTheOthersAreShown) {
    std::vector<ParticleSystemFile> systems{grassSystem("fine", 0.0f), grassSystem("huge", 1.0f)};
    systems[1].mesh.max_triangles = 10;
    LiveStrands live(1);
    live.submit(std::make_shared<std::vector<ParticleSystemFile>>(systems), 7);
    live.waitIdle();
    LiveStrandsResult r;
    ASSERT_TRUE(live.poll(&r));
    EXPECT_NE(r.error.find("particle system 'huge': mesh.max_triangles"), std::string::npos) << r.error;
    ASSERT_EQ(r.meshes.size(), 1u);
    EXPECT_EQ(r.meshes[0].name, "strands/fine");
}

}  // namespace
}  // namespace ug::editor
