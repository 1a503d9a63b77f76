// Editing the environmental objects through the document (issue 13): a moved bench, a changed global field
// and a footprint trail are undo steps that give back the exact environment, effects and instances; the
// scattered leaves and the settling follow each edit, live, equal to a fresh full run; the edits are saved
// and recovered after a crash; a bad edit is refused and changes nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/hash.h"
#include "env/env_effects.h"
#include "env/env_json.h"
#include "env/env_outputs.h"
#include "instancer/instantiator.h"
#include "instancer/settling.h"
#include "scene/document.h"
#include "scene/env_commands.h"
#include "env_edit_scene.h"
#include "scene_test_util.h"

namespace ug {
namespace {

namespace fs = std::filesystem;

class TempDir : public test::TempDir {
public:
    TempDir() : test::TempDir("ug_document_env_test_") {}
};

std::unique_ptr<Document> openProject(const TempDir& dir, DocumentOptions* options) {
    const fs::path path = dir.path() / "street.json";
    std::ofstream(path) << test::envEditProjectJson();
    *options = DocumentOptions{.cache_dir = (dir.path() / "cache").string(),
                               .config_dir = (dir.path() / "config").string(),
                               .threads = 2,
                               .autosave_interval_s = 10.0};
    std::string error;
    std::unique_ptr<Document> doc = Document::open(path.string(), *options, &error);
    EXPECT_TRUE(doc) << error;
    return doc;
}

void mixBytes(uint64_t* h, const void* data, size_t bytes) {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; i += 8) {
        uint64_t word = 0;
        std::memcpy(&word, p + i, std::min<size_t>(8, bytes - i));
        *h = hashWords(*h, word);
    }
}

// The environment's geometry as the outputs take it (every mesh, vertex and placement, bit for bit),
// computed afresh from the document's compiled environment.
uint64_t effectsDigest(const Document& doc) {
    EnvEffects fx;
    std::string error;
    EXPECT_TRUE(computeEnvEffects(*doc.environment(), {.threads = 2}, &fx, &error)) << error;
    uint64_t h = 1;
    for (const MeshInstances& m : envMeshInstances(*doc.environment(), fx)) {
        mixBytes(&h, m.name.data(), m.name.size());
        mixBytes(&h, m.mesh->positions.data(), m.mesh->positions.size() * sizeof(glm::vec3));
        mixBytes(&h, m.mesh->indices.data(), m.mesh->indices.size() * sizeof(uint32_t));
        for (const InstanceTransform& t : m.instances) mixBytes(&h, &t, sizeof t);
    }
    return h;
}

std::string environmentText(const Document& doc) { return environmentToJson(doc.project().environment).dump(); }

struct Settled {
    InstanceStore store;
    SettledDrops drops;
};

// The live result after the edits, checked against an independent full instantiation and settling of
// what the document holds now.
Settled settledLive(Document& doc) {
    const LiveResult r = doc.waitForResult();
    EXPECT_TRUE(r.ok) << r.error;
    Instantiator inst;
    std::string error;
    EXPECT_TRUE(inst.setInput(doc.instancerInput(), &error)) << error;
    EXPECT_TRUE(inst.instantiateAll({.threads = 2}, nullptr, &error)) << error;
    EXPECT_TRUE(*r.store == inst.store()) << "the live instances differ from a full run";
    SettledDrops full_drops;
    settleAll(doc.settleInputOf(), inst.store(), 2, &full_drops);
    EXPECT_TRUE(r.drops && *r.drops == full_drops) << "the live settling differs from settling everything";
    return Settled{*r.store, r.drops ? *r.drops : SettledDrops()};
}

TEST(DocumentEnvironment, EditsFollowLiveAndUndoGivesBackTheExactEffectsAndInstances) {
    TempDir dir;
    DocumentOptions options;
    auto doc = openProject(dir, &options);
    ASSERT_TRUE(doc);
    std::string error;
    std::vector<std::string> texts{environmentText(*doc)};
    std::vector<uint64_t> effects{effectsDigest(*doc)};
    std::vector<Settled> states{settledLive(*doc)};
    ASSERT_GT(states[0].store.instanceCount(), 20u) << "the leaves scatter";

    // 1. Move the bench 0.8 m along x (a drag: three stamps, one step).
    const uint64_t generation = doc->environmentGeneration();
    doc->beginStroke("Move object");
    for (int k = 1; k <= 3; ++k) {
        EnvironmentDesc env = doc->project().environment;
        envNodeAt(&env, {0})->transform.translation.x = 1.0f + 0.8f * float(k) / 3.0f;
        ASSERT_TRUE(doc->setEnvironment(env, "Move object", &error)) << error;
    }
    doc->endStroke();
    EXPECT_GT(doc->environmentGeneration(), generation);
    texts.push_back(environmentText(*doc));
    effects.push_back(effectsDigest(*doc));
    states.push_back(settledLive(*doc));

    // 2. Warmer and wetter everywhere: the icicles go.
    EnvironmentDesc warm = doc->project().environment;
    warm.global_fields[3].value = 4.0f;
    ASSERT_TRUE(doc->setEnvironment(warm, "Temperature", &error)) << error;
    texts.push_back(environmentText(*doc));
    effects.push_back(effectsDigest(*doc));
    states.push_back(settledLive(*doc));

    // 3. A footprint trail across the open snow and the leaves.
    doc->beginStroke("Footprints");
    for (int k = 0; k < 5; ++k) {
        EnvironmentDesc env = doc->project().environment;
        env.global_fields.push_back(footprintField({0.4f + 0.35f * float(k), 3.2f, 0.0f}));
        ASSERT_TRUE(doc->setEnvironment(env, "Footprints", &error)) << error;
    }
    doc->endStroke();
    texts.push_back(environmentText(*doc));
    effects.push_back(effectsDigest(*doc));
    states.push_back(settledLive(*doc));

    for (size_t k = 1; k < states.size(); ++k)
        EXPECT_NE(effects[k], effects[k - 1]) << "edit " << k << " left the effects as they were";
    // The leaves follow the bench (they rest on its seat) and the footprints (occlusion); not the warmth.
    for (size_t k : {1, 3})
        EXPECT_FALSE(states[k].store == states[k - 1].store && states[k].drops == states[k - 1].drops)
            << "edit " << k << " left the leaves as they were";
    EXPECT_EQ(doc->undoName(), "Footprints");
    for (size_t k = states.size() - 1; k-- > 0;) {
        ASSERT_TRUE(doc->undo());
        EXPECT_EQ(environmentText(*doc), texts[k]) << "undo to state " << k;
        EXPECT_EQ(effectsDigest(*doc), effects[k]) << "undo to state " << k;
        const Settled s = settledLive(*doc);
        EXPECT_TRUE(s.store == states[k].store && s.drops == states[k].drops) << "undo to state " << k;
    }
    EXPECT_FALSE(doc->isDirty());
    for (size_t k = 1; k < states.size(); ++k) {
        ASSERT_TRUE(doc->redo());
        EXPECT_EQ(effectsDigest(*doc), effects[k]) << "redo to state " << k;
    }
    EXPECT_TRUE(settledLive(*doc).store == states.back().store);
}

// A field edit keeps what the instances rest on (so the live instancer settles only the edited region);
// moving an object does not.
TEST(DocumentEnvironment, AFieldEditKeepsTheRestSurfacesAMoveChangesThem) {
    TempDir dir;
    DocumentOptions options;
    auto doc = openProject(dir, &options);
    ASSERT_TRUE(doc);
    std::string error;
    const std::shared_ptr<const EnvScene> start = doc->environment();
    EnvironmentDesc env = doc->project().environment;
    env.global_fields.push_back(footprintField({1.0f, 3.2f, 0.0f}));
    env.global_fields[0].value = 0.3f;
    ASSERT_TRUE(doc->setEnvironment(env, "Footprints", &error)) << error;
    EXPECT_NE(doc->environment(), start);
    EXPECT_TRUE(sameRestSurfaces(*start, *doc->environment()));

    env = doc->project().environment;
    envNodeAt(&env, {0})->transform.translation.y += 0.5f;  // the bench
    ASSERT_TRUE(doc->setEnvironment(env, "Move object", &error)) << error;
    EXPECT_FALSE(sameRestSurfaces(*start, *doc->environment()));
    // Where a slat of the bench's seat was (0.45 m up), the support is now the flat ground.
    EXPECT_NEAR(start->surfaceBelow(1.0f, 1.1f, 2.0f), 0.45f, 0.01f);
    EXPECT_EQ(doc->environment()->surfaceBelow(1.0f, 1.1f, 2.0f), 0.0f);
    settledLive(*doc);
}

// The editor's hidden nodes: the outputs without an object leave out its base mesh, its snow and its
// icicles, and keep every other object's exactly.
TEST(DocumentEnvironment, AHiddenObjectLeavesTheMeshListsWithItsEffects) {
    TempDir dir;
    DocumentOptions options;
    auto doc = openProject(dir, &options);
    ASSERT_TRUE(doc);
    EnvEffects fx;
    std::string error;
    ASSERT_TRUE(computeEnvEffects(*doc->environment(), {.threads = 2}, &fx, &error)) << error;
    const std::vector<MeshInstances> all = envMeshInstances(*doc->environment(), fx);
    const std::vector<uint8_t> hide_bench{1, 0};
    const std::vector<MeshInstances> shown = envMeshInstances(*doc->environment(), fx, &hide_bench);
    size_t bench_meshes = 0, icicles_all = 0, icicles_shown = 0;
    for (const MeshInstances& m : all) {
        if (m.name.rfind("icicles/", 0) == 0) icicles_all += m.instances.size();
        if (m.name.find("bench") != std::string::npos) ++bench_meshes;
    }
    EXPECT_GE(bench_meshes, 2u) << "the bench and its snow";
    // Only the terrain's snow lies on the ground (the editor keeps it out of the sun's shadow map); the
    // bench's snow does not.
    size_t ground_layers = 0;
    for (const MeshInstances& m : all) {
        EXPECT_EQ(m.ground_layer, m.name.rfind("snow/terrain/", 0) == 0) << m.name;
        ground_layers += m.ground_layer;
    }
    EXPECT_GT(ground_layers, 0u);
    for (const MeshInstances& m : shown) {
        EXPECT_EQ(m.name.find("bench"), std::string::npos) << m.name;
        if (m.name.rfind("icicles/", 0) == 0) icicles_shown += m.instances.size();
    }
    EXPECT_GT(icicles_all, 0u);
    EXPECT_LT(icicles_shown, icicles_all) << "the bench's icicles go with it";
    // Everything else unchanged, in order.
    std::vector<const MeshInstances*> others;
    for (const MeshInstances& m : all)
        if (m.name.find("bench") == std::string::npos && m.name.rfind("icicles/", 0) != 0) others.push_back(&m);
    std::vector<const MeshInstances*> kept;
    for (const MeshInstances& m : shown)
        if (m.name.rfind("icicles/", 0) != 0) kept.push_back(&m);
    ASSERT_EQ(others.size(), kept.size());
    for (size_t i = 0; i < kept.size(); ++i) {
        EXPECT_EQ(others[i]->name, kept[i]->name);
        EXPECT_EQ(others[i]->mesh, kept[i]->mesh);
        ASSERT_EQ(others[i]->instances.size(), kept[i]->instances.size());
        for (size_t k = 0; k < kept[i]->instances.size(); ++k)
            EXPECT_EQ(others[i]->instances[k].position, kept[i]->instances[k].position);
    }
}

TEST(DocumentEnvironment, ABadEditIsRefusedWithItsPlaceAndChangesNothing) {
    TempDir dir;
    DocumentOptions options;
    auto doc = openProject(dir, &options);
    ASSERT_TRUE(doc);
    const std::string before = environmentText(*doc);
    const uint64_t generation = doc->environmentGeneration();
    std::string error;
    EnvironmentDesc bad = doc->project().environment;
    bad.roots[1].transform.scale = -1.0f;
    EXPECT_FALSE(doc->setEnvironment(bad, "Scale", &error));
    EXPECT_NE(error.find("scale"), std::string::npos) << error;
    bad = doc->project().environment;
    bad.roots[0].type = 7;  // no such type
    EXPECT_FALSE(doc->setEnvironment(bad, "Type", &error));
    EXPECT_NE(error.find("/environment/tree/0"), std::string::npos) << error;
    bad = doc->project().environment;
    bad.global_fields[0].value = std::nanf("");
    EXPECT_FALSE(doc->setEnvironment(bad, "NaN", &error));
    EXPECT_NE(error.find("/environment/global_fields/0"), std::string::npos) << error;
    bad = doc->project().environment;
    bad.types.pop_back();  // the library is not edited here
    EXPECT_FALSE(doc->setEnvironment(bad, "Types", &error));
    EXPECT_EQ(environmentText(*doc), before);
    EXPECT_EQ(doc->environmentGeneration(), generation);
    EXPECT_FALSE(doc->canUndo());
    EXPECT_FALSE(doc->isDirty());
}

TEST(DocumentEnvironment, EditsAreSavedAndRecoveredAfterACrash) {
    TempDir dir;
    DocumentOptions options;
    std::string error, moved;
    uint64_t moved_effects = 0;
    {
        auto doc = openProject(dir, &options);
        ASSERT_TRUE(doc);
        EnvironmentDesc env = doc->project().environment;
        env.roots[1].transform.yaw_deg = 35.0f;
        env.global_fields.push_back(footprintField({0.5f, 3.0f, 0.0f}));
        ASSERT_TRUE(doc->setEnvironment(env, "Rotate object", &error)) << error;
        moved = environmentText(*doc);
        moved_effects = effectsDigest(*doc);
        ASSERT_TRUE(doc->autosave(&error)) << error;
        doc->waitForResult();
        // The crash: no save, no close.
    }
    const std::string path = (dir.path() / "street.json").string();
    std::unique_ptr<Document> doc = Document::recover(path, options, &error);
    ASSERT_TRUE(doc) << error;
    EXPECT_EQ(environmentText(*doc), moved);
    EXPECT_EQ(effectsDigest(*doc), moved_effects);
    ASSERT_TRUE(doc->save(&error)) << error;
    doc->close();
    doc.reset();
    auto reopened = Document::open(path, options, &error);
    ASSERT_TRUE(reopened) << error;
    EXPECT_EQ(environmentText(*reopened), moved);
    EXPECT_EQ(effectsDigest(*reopened), moved_effects);
}

}  // namespace
}  // namespace ug
