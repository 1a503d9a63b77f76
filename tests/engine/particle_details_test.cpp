// Strands on the project's detail instances (GeneratorKind::Details, scene/scene_particles.h placeOnDetails):
// the moss of the rock_pile_moss sample seeds on the settled rocks whose origin lies in its box, exactly
// the rocks the whole scene's instantiation puts there, on their upward faces only; the rocks are solids
// its strands never cross, for any thread count; an edit of the rocks' density places the moss again and
// undo puts it back; bad input is named.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "analysis/placed_instances.h"
#include "field/primitive.h"
#include "instancer/instantiator.h"
#include "instancer/settling.h"
#include "particles/particle_json.h"
#include "particles/strand_growth.h"
#include "segment_test_util.h"
#include "scene/document.h"
#include "scene/scene_load.h"
#include "scene/scene_particles.h"

namespace ug {
namespace {

namespace fs = std::filesystem;

const fs::path kMossScene = fs::path(UG_SOURCE_DIR) / "assets/scenes/rock_pile_moss.json";

fs::path tempDir(const char* tag) {
    std::random_device rd;
    return fs::temp_directory_path() / (std::string(tag) + std::to_string(rd()));
}

// An instance's model-space point in the world, written out here rather than through ParticleObstacle.
glm::vec3 worldOf(const PlacedInstance& p, glm::vec3 local) { return p.position + p.rotation * (local * p.scale); }

using Frame = std::tuple<float, float, float, float, float, float, float, float>;
Frame frameOf(glm::vec3 t, glm::quat r, float s) { return {t.x, t.y, t.z, r.w, r.x, r.y, r.z, s}; }

using test::segmentHitsTriangle;

class ParticleDetails : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = new fs::path(tempDir("ug_particle_details_"));
        std::string error;
        project_ = new Project();
        ASSERT_TRUE(loadProject(kMossScene.string(), project_, &error)) << error;
        scene_ = new LoadedScene();
        ASSERT_TRUE(loadScene(*project_, SceneLoadOptions{.cache_dir = (*dir_ / "cache").string(), .threads = 2}, scene_,
                              &error))
            << error;
    }
    static void TearDownTestSuite() {
        delete scene_;
        delete project_;
        std::error_code ec;
        fs::remove_all(*dir_, ec);
        delete dir_;
    }
    static uint32_t rockType() {
        for (uint32_t t = 0; t < scene_->models->size(); ++t)
            if ((*scene_->models)[t].name == "rock") return t;
        ADD_FAILURE() << "no rock type";
        return 0;
    }
    static fs::path* dir_;
    static Project* project_;
    static LoadedScene* scene_;
};
fs::path* ParticleDetails::dir_ = nullptr;
Project* ParticleDetails::project_ = nullptr;
LoadedScene* ParticleDetails::scene_ = nullptr;

TEST_F(ParticleDetails, TheMossSeedsOnTheRocksTheWholeSceneSettlesInItsBoxOnTheirUpwardFaces) {
    ASSERT_EQ(scene_->particles->size(), 1u);
    const ParticleScene& moss = (*scene_->particles)[0].scene;
    ASSERT_EQ(moss.generators.size(), 1u);
    const ParticleGenerator& g = moss.generators[0];
    ASSERT_EQ(g.kind, GeneratorKind::Details);
    ASSERT_EQ(g.detail_type, "rock");
    const Bounds box = Bounds::fromCenterHalf(g.center_m, g.half_extents_m);

    // The reference: the whole scene instantiated and settled at once, its rocks whose (unsettled) origin
    // lies in the box [lo, hi).
    InstancerInput input;
    input.tile = scene_->tile.get();
    for (const DetailModel& m : *scene_->models) input.models.push_back(&m);
    input.types = scene_->compiled.types;
    input.extent = scene_->compiled.extent;
    input.seed = project_->instantiation_seed;
    Instantiator whole;
    std::string error;
    InstanceStats stats;
    ASSERT_TRUE(whole.setInput(input, &error)) << error;
    ASSERT_TRUE(whole.instantiateAll({.threads = 2}, &stats, &error)) << error;
    const SettleInput settle = settleInput(*project_, scene_->terrain, *scene_->tile, *scene_->models);
    ASSERT_TRUE(settle.settings.enabled);
    SettledDrops drops;
    settleAll(settle, whole.store(), 2, &drops);
    const std::vector<PlacedInstance> unsettled = placeInstances(whole.store(), *scene_->tile);
    const std::vector<PlacedInstance> settled = placeInstances(whole.store(), *scene_->tile, &drops);
    const uint32_t rock = rockType();
    std::vector<Frame> want;
    std::vector<PlacedInstance> rocks;
    for (size_t i = 0; i < unsettled.size(); ++i) {
        const glm::vec3 o = unsettled[i].position;
        bool inside = unsettled[i].type == rock;
        for (int a = 0; a < 3; ++a) inside = inside && o[a] >= box.lo[a] && o[a] < box.hi[a];
        if (!inside) continue;
        want.push_back(frameOf(settled[i].position, settled[i].rotation, settled[i].scale));
        rocks.push_back(settled[i]);
    }
    ASSERT_GT(want.size(), 200u);
    // Some were lowered by the settling: the moss sits on the settled rocks, not on the candidates.
    size_t lowered = 0;
    for (size_t i = 0; i < unsettled.size(); ++i) lowered += settled[i].position.z < unsettled[i].position.z;
    EXPECT_GT(lowered, 0u);

    std::vector<Frame> got;
    for (const ParticleObstacle& o : moss.detail_obstacles) {
        EXPECT_EQ(o.mesh.get(), &(*scene_->models)[rock].mesh);
        got.push_back(frameOf(o.translation, o.rotation, o.scale));
    }
    std::sort(want.begin(), want.end());
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, want);

    // The seeding surfaces: the rocks' faces whose world normal has z >= min_normal_z, relative to the box's
    // centre; as many as counted here from the model and the reference frames.
    const TriangleMesh& m = (*scene_->models)[rock].mesh;
    size_t upward = 0;
    for (const PlacedInstance& p : rocks)
        for (size_t t = 0; t < m.triangleCount(); ++t) {
            const glm::vec3 a = worldOf(p, m.positions[m.indices[3 * t]]), b = worldOf(p, m.positions[m.indices[3 * t + 1]]),
                            c = worldOf(p, m.positions[m.indices[3 * t + 2]]);
            const glm::vec3 n = glm::cross(b - a, c - a);
            upward += glm::length(n) > 0.0f && n.z >= g.min_normal_z * glm::length(n);
        }
    ASSERT_TRUE(g.mesh);
    EXPECT_NEAR(double(g.mesh->triangleCount()), double(upward), 0.002 * double(upward));  // rounding at the bound
    EXPECT_LT(upward, rocks.size() * m.triangleCount());
    for (size_t t = 0; t < g.mesh->triangleCount(); ++t) {
        const glm::vec3 a = g.mesh->positions[g.mesh->indices[3 * t]], b = g.mesh->positions[g.mesh->indices[3 * t + 1]],
                        c = g.mesh->positions[g.mesh->indices[3 * t + 2]];
        const glm::vec3 n = glm::cross(b - a, c - a);
        ASSERT_GE(n.z, (g.min_normal_z - 1e-3f) * glm::length(n)) << "triangle " << t;
    }
}

TEST_F(ParticleDetails, MossNeverCrossesARockAndGrowsTheSameForAnyThreadCount) {
    // Fewer strands than the sample's, so that every segment can be checked against every nearby rock.
    ParticleScene moss = (*scene_->particles)[0].scene;
    moss.generators[0].count = 3000;
    moss.walk.steps = 6;
    Strands one, two, eight;
    std::string error;
    ASSERT_TRUE(growStrands(moss, {.threads = 1}, &one, &error)) << error;
    ASSERT_TRUE(growStrands(moss, {.threads = 2}, &two, &error)) << error;
    ASSERT_TRUE(growStrands(moss, {.threads = 8}, &eight, &error)) << error;
    EXPECT_EQ(one.points, two.points);
    EXPECT_EQ(one.points, eight.points);
    EXPECT_EQ(one.offsets, eight.offsets);
    EXPECT_GT(one.stats.solid_hits, 0u);
    // Seeds on a face buried in a neighbouring rock never grow.
    EXPECT_LT(one.offsets.size() - 1, size_t(moss.generators[0].count));
    EXPECT_GT(one.offsets.size() - 1, size_t(moss.generators[0].count) / 2);

    const TriangleMesh& m = (*scene_->models)[rockType()].mesh;
    float model_radius = 0.0f;
    for (const glm::vec3& p : m.positions) model_radius = std::max(model_radius, glm::length(p));
    size_t tested = 0;
    for (size_t s = 0; s + 1 < one.offsets.size(); ++s)
        for (uint32_t i = one.offsets[s]; i + 1 < one.offsets[s + 1]; ++i) {
            const glm::vec3 p = one.points[i], q = one.points[i + 1];
            const bool from_seed = one.parent[s] < 0 && i == one.offsets[s];
            for (const ParticleObstacle& o : moss.detail_obstacles) {
                if (glm::distance(p, o.translation) > model_radius * o.scale + moss.walk.step_length_m) continue;
                const PlacedInstance rock{.position = o.translation, .rotation = o.rotation, .scale = o.scale};
                ++tested;
                for (size_t t = 0; t < m.triangleCount(); ++t)
                    ASSERT_FALSE(segmentHitsTriangle(p, q, worldOf(rock, m.positions[m.indices[3 * t]]),
                                                     worldOf(rock, m.positions[m.indices[3 * t + 1]]),
                                                     worldOf(rock, m.positions[m.indices[3 * t + 2]]), from_seed ? 1e-3 : 0.0))
                        << "strand " << s << " segment " << i << " crosses a rock at (" << o.translation.x << ", "
                        << o.translation.y << ", " << o.translation.z << ")";
            }
        }
    EXPECT_GT(tested, 1000u);
}

TEST_F(ParticleDetails, BadInputIsNamedAndAMossFileGrownAloneIsRefused) {
    std::string error;
    // Grown alone, nothing was placed: the growth says what it needs.
    ParticleSystemFile alone;
    ASSERT_TRUE(loadParticleSystem((fs::path(UG_SOURCE_DIR) / "assets/particles/moss_rock_pile.json").string(), &alone,
                                   &error))
        << error;
    Strands strands;
    EXPECT_FALSE(growStrands(alone.scene, {.threads = 1}, &strands, &error));
    EXPECT_NE(error.find("generators[0].detail_type: no 'rock' instance"), std::string::npos) << error;
    // A type the project does not have.
    ParticleScene wrong = (*scene_->particles)[0].scene;
    wrong.generators[0].detail_type = "boulder";
    InstancerInput input;
    input.tile = scene_->tile.get();
    for (const DetailModel& m : *scene_->models) input.models.push_back(&m);
    input.types = scene_->compiled.types;
    input.extent = scene_->compiled.extent;
    const DetailPlacement placement{.instancer = &input, .models = scene_->models, .threads = 1};
    EXPECT_FALSE(placeOnDetails(placement, &wrong, &error));
    EXPECT_NE(error.find("generators[0].detail_type: the project has no detail type 'boulder'"), std::string::npos)
        << error;
    // A box that holds no rock seeds nothing, and says so when grown.
    ParticleScene empty = (*scene_->particles)[0].scene;
    empty.generators[0].center_m = {40.0f, 40.0f, 0.5f};
    ASSERT_TRUE(placeOnDetails(placement, &empty, &error)) << error;
    EXPECT_FALSE(empty.generators[0].mesh);
    EXPECT_TRUE(empty.detail_obstacles.empty());
    // The file's own fields.
    const auto parse = [&](const std::string& generator) {
        const std::string text = R"({"format": "undergrowth-particles", "format_version": 1, "generators": [)" + generator +
                                 "]}";
        ParticleSystemFile s;
        return parseParticleSystem(nlohmann::json::parse(text), "moss.json", &s, &error);
    };
    EXPECT_FALSE(parse(R"({"kind": "details", "detail_type": "rock", "count": 10, "min_normal_z": 2})"));
    EXPECT_NE(error.find("min_normal_z"), std::string::npos) << error;
    EXPECT_FALSE(parse(R"({"kind": "details", "count": 10})"));
    EXPECT_NE(error.find("detail_type"), std::string::npos) << error;
    EXPECT_FALSE(parse(R"({"kind": "box", "detail_type": "rock", "count": 10})"));
    EXPECT_NE(error.find("/generators/0/detail_type"), std::string::npos) << error;
    EXPECT_TRUE(parse(R"({"kind": "details", "detail_type": "rock", "count": 10, "min_normal_z": 0.5})")) << error;
}

TEST(ParticleDetailsDocument, PaintingTheRocksPlacesTheMossAgainAndUndoPutsItBack) {
    const fs::path dir = tempDir("ug_particle_details_doc_");
    std::string error;
    auto doc = Document::open(kMossScene.string(), DocumentOptions{.cache_dir = (dir / "cache").string(), .threads = 2},
                              &error);
    ASSERT_TRUE(doc) << error;
    const ParticleScene before = (*doc->particles())[0].scene;
    ASSERT_FALSE(before.detail_obstacles.empty());
    const uint64_t generation = doc->particlesGeneration();
    size_t rock = 0;
    while (rock < doc->project().detail_types.size() && doc->project().detail_types[rock].model.name != "rock") ++rock;
    ASSERT_LT(rock, doc->project().detail_types.size());
    // More rocks on the pile's east end.
    ASSERT_NE(doc->addPrimitive(rock, makePoint({1.2f, 0.0f, 0.2f}, 0.6f, 12.0f), &error), 0u) << error;
    const ParticleScene after = (*doc->particles())[0].scene;
    EXPECT_GT(doc->particlesGeneration(), generation);
    EXPECT_NE(after.detail_obstacles, before.detail_obstacles);
    EXPECT_GT(after.detail_obstacles.size(), before.detail_obstacles.size());
    ASSERT_TRUE(doc->undo());
    const ParticleScene undone = (*doc->particles())[0].scene;
    EXPECT_EQ(undone.detail_obstacles, before.detail_obstacles);
    ASSERT_TRUE(undone.generators[0].mesh && before.generators[0].mesh);
    EXPECT_EQ(undone.generators[0].mesh->positions, before.generators[0].mesh->positions);
    doc.reset();
    std::error_code ec;
    fs::remove_all(dir, ec);
}

}  // namespace
}  // namespace ug
