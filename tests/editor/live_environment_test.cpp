// The editor's environment tools and live effects (app/editor/env_tools.h, live_environment.h) on a real
// document: a drag of an object over the ground is one undo step that keeps its height above the ground;
// the footprint brush leaves one footprint a stride, left and right of the walked line, as one step; the
// worker's meshes after a burst of coalesced edits are those a full computation makes of the document's
// environment, bit for bit, and an undo gives back the first ones.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>

#include "editor/channel_map.h"
#include "editor/env_tools.h"
#include "editor/live_environment.h"
#include "env/env_outputs.h"
#include "editor_test_util.h"
#include "scene/document.h"

namespace ug::editor {
namespace {

using test::expectSameMeshes;
using OpenDocument = test::OpenEnvDocument;

std::vector<MeshInstances> fullMeshes(const Document& doc) {
    EnvEffects fx;
    std::string error;
    EXPECT_TRUE(computeEnvEffects(*doc.environment(), {.threads = 1}, &fx, &error)) << error;
    return envMeshInstances(*doc.environment(), fx);
}

TEST(EnvTools, DraggingAnObjectKeepsItsHeightAboveTheGroundAndIsOneUndoStep) {
    OpenDocument o;
    ASSERT_TRUE(o.doc);
    Document& doc = *o.doc;
    const glm::vec3 start = doc.project().environment.roots[0].transform.translation;
    EnvObjectDrag drag;
    ASSERT_TRUE(drag.begin(&doc, {0}, rayDownOnto(doc, glm::vec2(start))));
    std::string error;
    for (int k = 1; k <= 5; ++k)
        ASSERT_TRUE(drag.drag(rayDownOnto(doc, glm::vec2(start) + glm::vec2(0.2f * float(k), 0.1f * float(k))), &error))
            << error;
    drag.end();
    EXPECT_EQ(drag.moves(), 5);
    const glm::vec3 moved = doc.project().environment.roots[0].transform.translation;
    EXPECT_NEAR(moved.x, start.x + 1.0f, 1e-4f);
    EXPECT_NEAR(moved.y, start.y + 0.5f, 1e-4f);
    EXPECT_NEAR(moved.z - groundHeightAt(doc, glm::vec2(moved)), start.z - groundHeightAt(doc, glm::vec2(start)), 1e-5f);
    EXPECT_EQ(doc.undoName(), "Move object");
    ASSERT_TRUE(doc.undo());
    EXPECT_EQ(doc.project().environment.roots[0].transform.translation, start);
    EXPECT_FALSE(doc.canUndo()) << "the whole drag was one step";
}

TEST(EnvTools, TheFootprintBrushLeavesOneFootprintAStrideLeftAndRight) {
    OpenDocument o;
    ASSERT_TRUE(o.doc);
    Document& doc = *o.doc;
    const size_t fields = doc.project().environment.global_fields.size();
    WeatherStroke walk;
    std::string error;
    ASSERT_TRUE(walk.begin(&doc, WeatherSettings{}, {0.5f, 3.2f, 0.0f}, &error)) << error;
    // One big jump of the mouse: every footprint in between is left.
    ASSERT_TRUE(walk.drag({0.5f + 6.5f * kFootprintStrideM, 3.2f, 0.0f}, &error)) << error;
    walk.end();
    EXPECT_EQ(walk.stamps(), 7);
    const std::vector<EnvFieldDesc>& f = doc.project().environment.global_fields;
    ASSERT_EQ(f.size(), fields + 7);
    for (size_t k = 0; k < 7; ++k) {
        const EnvFieldDesc& print = f[fields + k];
        EXPECT_EQ(print.channel, EnvChannel::Occlusion);
        EXPECT_FALSE(print.everywhere);
        EXPECT_NEAR(print.shape.center_m.x, 0.5f + float(k) * kFootprintStrideM, 1e-4f);
        EXPECT_NEAR(print.shape.center_m.y, 3.2f + (k % 2 == 0 ? kFootprintHalfGaitM : -kFootprintHalfGaitM), 1e-5f);
    }
    EXPECT_EQ(doc.undoName(), "Footprints");
    ASSERT_TRUE(doc.undo());
    EXPECT_EQ(doc.project().environment.global_fields.size(), fields) << "the walk was one step";
}

// The temperature a point field adds at `p` (env/env_scene.h sums a channel's fields).
float temperatureAt(const Document& doc, glm::vec3 p) { return doc.environment()->sample(p).temperature; }

TEST(EnvTools, AWarmStrokeMeltsTheSnowUnderItAndEraseTakesItBack) {
    OpenDocument o;
    ASSERT_TRUE(o.doc);
    Document& doc = *o.doc;
    const glm::vec3 under(1.0f, 3.0f, 0.0f), beside(3.5f, 0.5f, 0.0f);
    const float cold = temperatureAt(doc, under);
    ASSERT_LT(cold, 0.0f);
    const size_t fields = doc.project().environment.global_fields.size();
    WeatherStroke warm;
    std::string error;
    ASSERT_TRUE(warm.begin(&doc, WeatherSettings{WeatherBrush::Warm, 0.6f, 1.0f}, {0.5f, 3.0f, 0.0f}, &error)) << error;
    ASSERT_TRUE(warm.drag({1.5f, 3.0f, 0.0f}, &error)) << error;
    warm.end();
    EXPECT_EQ(warm.stamps(), 1 + 3) << "one stamp every radius / 2";
    EXPECT_GT(temperatureAt(doc, under), 0.0f) << "above freezing under the stroke";
    EXPECT_EQ(temperatureAt(doc, beside), cold) << "nothing changes away from it";
    EXPECT_EQ(doc.undoName(), "Warm brush");

    // Erase over half the stroke removes the stamps whose centre it covers, and nothing else.
    WeatherStroke erase;
    ASSERT_TRUE(erase.begin(&doc, WeatherSettings{WeatherBrush::Erase, 0.35f, 1.0f}, {0.5f, 3.0f, 0.0f}, &error)) << error;
    erase.end();
    EXPECT_EQ(erase.erased(), 2);
    EXPECT_EQ(doc.project().environment.global_fields.size(), fields + 2);
    ASSERT_TRUE(doc.undo());
    ASSERT_TRUE(doc.undo());
    EXPECT_EQ(temperatureAt(doc, under), cold);
    // A trail (a segment field) is erased from anywhere along it, not only at its first end.
    EnvironmentDesc env = doc.project().environment;
    EnvFieldDesc trail;
    trail.channel = EnvChannel::Occlusion;
    trail.value = 0.8f;
    trail.shape = makeSegment({0.5f, 0.5f, 0.0f}, {3.5f, 0.5f, 0.0f}, 0.2f, trail.value);
    env.global_fields.push_back(trail);
    ASSERT_TRUE(doc.setEnvironment(env, "Trail", &error)) << error;
    WeatherStroke erase_trail;
    ASSERT_TRUE(erase_trail.begin(&doc, WeatherSettings{WeatherBrush::Erase, 0.3f, 1.0f}, {2.5f, 0.7f, 0.0f}, &error))
        << error;
    erase_trail.end();
    EXPECT_EQ(erase_trail.erased(), 1);
    EXPECT_EQ(doc.project().environment.global_fields.size(), fields);
    // Bad settings are refused before anything changes.
    WeatherStroke bad;
    EXPECT_FALSE(bad.begin(&doc, WeatherSettings{WeatherBrush::Wet, std::nanf(""), 1.0f}, under, &error));
    EXPECT_NE(error.find("wet brush"), std::string::npos) << error;
    EXPECT_FALSE(bad.active());
    EXPECT_EQ(doc.project().environment.global_fields.size(), fields);
}

TEST(ChannelMap, TheShelterMapIsLowUnderTheShelterOpenElsewhereAndColouredByItsLegend) {
    OpenDocument o;
    ASSERT_TRUE(o.doc);
    const Document& doc = *o.doc;
    ChannelMapSettings view;
    view.on = true;
    view.channel = kChannelMapChannels - 1;  // the shelter
    view.height_m = 0.3f;
    ASSERT_STREQ(channelMapName(view.channel), "shelter");
    const ChannelMap map = buildChannelMap(doc, view, 0.1f);
    ASSERT_EQ(map.columns, 40);  // the 4 m extent
    ASSERT_EQ(map.rows, 40);
    ASSERT_EQ(map.values.size(), 1600u);
    EXPECT_EQ(map.geometry.hull.size(), 1600u * 6u + 3u * map.surface_triangles);
    const auto value = [&](glm::vec2 xy) {
        return map.values[size_t(std::floor(xy.y / 0.1f)) * 40u + size_t(std::floor(xy.x / 0.1f))];
    };
    const glm::vec3 shelter = doc.project().environment.roots[1].transform.translation;
    EXPECT_LT(value(glm::vec2(shelter) + glm::vec2(0.05f)), 0.5f) << "under the shelter's roof";
    EXPECT_EQ(value({0.25f, 3.75f}), 1.0f) << "in the open";
    EXPECT_EQ(map.lo, 0.0f);
    EXPECT_EQ(map.hi, 1.0f);
    // Each cell's colour is its value's place on the ramp between the legend's ends.
    for (size_t k = 0; k < map.values.size(); k += 97)
        EXPECT_EQ(map.geometry.hull[k * 6].color, channelMapColor((map.values[k] - map.lo) / (map.hi - map.lo)));
    // The slice follows the ground: every corner 0.3 m above it (the cells come first, then the surfaces).
    for (size_t k = 0; k < 1600u * 6u; k += 331) {
        const glm::vec3 p = map.geometry.hull[k].position;
        EXPECT_NEAR(p.z, groundHeightAt(doc, glm::vec2(p)) + 0.3f, 1e-5f);
    }
    int c = -1;
    EXPECT_TRUE(channelMapFromName("temperature", &c));
    EXPECT_EQ(c, int(EnvChannel::Temperature));
    EXPECT_FALSE(channelMapFromName("rain", &c));
}

// On the objects' surfaces: every triangle of their base meshes, each vertex coloured by the channel just
// outside it; the shelter's roof is open on top, the seat of its own bench under it is sheltered.
TEST(ChannelMap, OnTheSurfacesTheRoofIsOpenAndTheSeatUnderItSheltered) {
    OpenDocument o;
    ASSERT_TRUE(o.doc);
    const Document& doc = *o.doc;
    ChannelMapSettings view;
    view.on = true;
    view.channel = kChannelMapChannels - 1;  // the shelter
    const ChannelMap map = buildChannelMap(doc, view, 0.1f);
    const EnvScene& env = *doc.environment();
    ASSERT_EQ(env.objects().size(), 2u);
    const TriangleMesh& bench = *env.types()[env.objects()[0].type].mesh;
    const TriangleMesh& shelter = *env.types()[env.objects()[1].type].mesh;
    EXPECT_EQ(map.surface_triangles, (bench.indices.size() + shelter.indices.size()) / 3);
    ASSERT_EQ(map.surface_values.size(), bench.positions.size() + shelter.positions.size());
    EXPECT_EQ(map.geometry.hull.size(), size_t(map.columns * map.rows) * 6u + 3u * map.surface_triangles);
    // The shelter's up-facing vertices: open at the roof's top, sheltered low down (its bench's seat).
    float top_z = -1e9f;
    for (const glm::vec3& p : shelter.positions) top_z = std::max(top_z, p.z);
    float roof = 1.0f, seat = 1.0f;
    for (size_t v = 0; v < shelter.positions.size(); ++v) {
        if (shelter.normals[v].z < 0.9f) continue;
        const float value = map.surface_values[bench.positions.size() + v];
        if (shelter.positions[v].z > top_z - 0.01f) roof = std::min(roof, value);
        if (shelter.positions[v].z < 1.0f) seat = std::min(seat, value);
    }
    EXPECT_EQ(roof, 1.0f) << "the roof's top is open";
    EXPECT_LT(seat, 0.5f) << "the seat under the roof is sheltered";
    // Each drawn vertex carries its value's colour: the first triangle of the shelter's mesh.
    const size_t first = size_t(map.columns * map.rows) * 6u + bench.indices.size();
    for (size_t k = 0; k < 3; ++k)
        EXPECT_EQ(map.geometry.hull[first + k].color,
                  channelMapColor((map.surface_values[bench.positions.size() + shelter.indices[k]] - map.lo) /
                                  (map.hi - map.lo)));
    view.surfaces = false;
    EXPECT_EQ(buildChannelMap(doc, view, 0.1f).surface_triangles, 0u);
}

TEST(LiveEnvironment, CoalescedEditsEndEqualToAFullComputationAndUndoGivesBackTheFirst) {
    OpenDocument o;
    ASSERT_TRUE(o.doc);
    Document& doc = *o.doc;
    const std::vector<MeshInstances> first = fullMeshes(doc);
    EnvEffects loaded;
    std::string error;
    ASSERT_TRUE(computeEnvEffects(*doc.environment(), {.threads = 2}, &loaded, &error)) << error;
    LiveEnvironment live(2, doc.environment(), std::make_shared<const EnvEffects>(std::move(loaded)));
    // A drag of the shelter and a walk, submitted as fast as the UI would, without waiting.
    EnvObjectDrag drag;
    const glm::vec3 start = doc.project().environment.roots[1].transform.translation;
    ASSERT_TRUE(drag.begin(&doc, {1}, rayDownOnto(doc, glm::vec2(start))));
    for (int k = 1; k <= 6; ++k) {
        ASSERT_TRUE(drag.drag(rayDownOnto(doc, glm::vec2(start) - glm::vec2(0.15f * float(k), 0.0f)), &error)) << error;
        live.submit(doc.environment(), doc.environmentGeneration());
    }
    drag.end();
    WeatherStroke walk;
    ASSERT_TRUE(walk.begin(&doc, WeatherSettings{}, {0.4f, 0.6f, 0.0f}, &error)) << error;
    ASSERT_TRUE(walk.drag({2.4f, 1.2f, 0.0f}, &error)) << error;
    walk.end();
    live.submit(doc.environment(), doc.environmentGeneration());
    live.waitIdle();
    LiveEnvironmentResult r;
    ASSERT_TRUE(live.poll(&r));
    EXPECT_TRUE(r.error.empty()) << r.error;
    EXPECT_EQ(r.generation, doc.environmentGeneration()) << "the newest submission is the one shown";
    EXPECT_GT(r.dirty_boxes, 0u);
    expectSameMeshes(r.meshes, fullMeshes(doc));

    ASSERT_TRUE(doc.undo());
    ASSERT_TRUE(doc.undo());
    live.submit(doc.environment(), doc.environmentGeneration());
    live.waitIdle();
    ASSERT_TRUE(live.poll(&r));
    expectSameMeshes(r.meshes, first);
}

}  // namespace
}  // namespace ug::editor
