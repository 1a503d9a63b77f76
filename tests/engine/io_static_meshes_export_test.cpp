// Static meshes (io/mesh_instances.h) in the glTF export: read back with tinygltf (an independent reader),
// checked for mesh order, node names, instance transforms back in engine space, plain-node mode, shared
// textures, and the refusals of bad input.
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "io/gltf_scene_export.h"
#include "mesh_test_util.h"

namespace ug {
namespace {

namespace fs = std::filesystem;

// Engine (Z up) -> file (Y up), independently of the exporter: the -90 degree rotation about X.
const glm::quat kToYUp = glm::angleAxis(-glm::half_pi<float>(), glm::vec3(1, 0, 0));

bool load(const std::string& path, tinygltf::Model* model) {
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    const bool ok = fs::path(path).extension() == ".glb" ? loader.LoadBinaryFromFile(model, &err, &warn, path)
                                                         : loader.LoadASCIIFromFile(model, &err, &warn, path);
    EXPECT_TRUE(ok) << path << ": " << err;
    return ok;
}

std::vector<float> floats(const tinygltf::Model& model, int accessor) {
    const tinygltf::Accessor& acc = model.accessors.at(size_t(accessor));
    const tinygltf::BufferView& view = model.bufferViews.at(size_t(acc.bufferView));
    const size_t n = acc.count * size_t(tinygltf::GetNumComponentsInType(uint32_t(acc.type)));
    std::vector<float> out(n);
    std::memcpy(out.data(), model.buffers.at(0).data.data() + view.byteOffset + acc.byteOffset, n * 4);
    return out;
}

glm::vec3 translationOf(const tinygltf::Node& node) {
    return node.translation.size() == 3
               ? glm::vec3(float(node.translation[0]), float(node.translation[1]), float(node.translation[2]))
               : glm::vec3(0.0f);
}

const tinygltf::Node* nodeNamed(const tinygltf::Model& model, const std::string& name) {
    for (const tinygltf::Node& node : model.nodes)
        if (node.name == name) return &node;
    return nullptr;
}

// A world-space instance as the file has it (Y up): where it maps two probe points of the mesh.
struct SeenInstance {
    glm::vec3 origin;  // the image of the mesh's (0, 0, 0)
    glm::vec3 x_tip;   // the image of the mesh's (1, 0, 0), engine axes
};

InstanceTransform at(glm::vec3 p, glm::quat q = glm::quat(1, 0, 0, 0), float s = 1.0f) {
    InstanceTransform t;
    t.position = p;
    t.rotation = q;
    t.scale = s;
    return t;
}

struct Fixture {
    std::shared_ptr<const TriangleMesh> cube = std::make_shared<const TriangleMesh>(test::unitCube());
    TriangleMesh terrain = test::unitCube();
    SceneExport scene;

    Fixture() {
        ExportDetailType type;
        type.name = "cube";
        type.mesh = cube.get();
        type.instances = {at({1, 1, 0}), at({2, 1, 0})};
        scene.types = {type};
        scene.terrain = &terrain;
        MeshInstances bench;
        bench.name = "env/bench";
        bench.mesh = cube;
        bench.extras_json = R"({"kind": "bench", "objects": [3, 4]})";
        MeshInstances icicle;
        icicle.name = "icicles/shape_2";
        icicle.mesh = cube;
        // Chunks of 8 m: the first two share chunk (0, 0), the third is in chunk (-2, 1).
        icicle.instances = {at({1.5f, 2.0f, 3.0f}),
                            at({4.0f, 0.5f, 1.0f}, glm::angleAxis(glm::half_pi<float>(), glm::vec3(0, 0, 1)), 2.0f),
                            at({-10.0f, 12.0f, -0.5f}, glm::quat(1, 0, 0, 0), 0.5f)};
        scene.meshes = {bench, icicle};
    }
};

std::string exportOrFail(const SceneExport& scene, const std::string& name) {
    const std::string path = test::tempPath(name);
    std::string error;
    EXPECT_TRUE(writeSceneGltf(path, scene, &error)) << error;
    return path;
}

std::string refusal(const SceneExport& scene) {
    std::string error;
    EXPECT_FALSE(writeSceneGltf(test::tempPath("refused.glb"), scene, &error));
    return error;
}

}  // namespace

TEST(GltfStaticMeshes, MeshesFollowTypesAndTerrainWithNodesAtIdentityOrChunked) {
    Fixture f;
    for (const char* name : {"static.glb", "static.gltf"}) {
        SCOPED_TRACE(name);
        tinygltf::Model model;
        ASSERT_TRUE(load(exportOrFail(f.scene, name), &model));
        ASSERT_EQ(model.meshes.size(), 4u);
        EXPECT_EQ(model.meshes[0].name, "cube");
        EXPECT_EQ(model.meshes[1].name, "terrain");
        EXPECT_EQ(model.meshes[2].name, "env/bench");
        EXPECT_EQ(model.meshes[3].name, "icicles/shape_2");
        // extras_json, as given; the terrain has none.
        EXPECT_EQ(model.meshes[2].extras.Get("kind").Get<std::string>(), "bench");
        EXPECT_EQ(model.meshes[2].extras.Get("objects").Get(1).GetNumberAsInt(), 4);
        EXPECT_FALSE(model.meshes[1].extras.IsObject());

        // No instances: one root node at the identity named after the entry.
        const tinygltf::Node* bench = nodeNamed(model, "env/bench");
        ASSERT_NE(bench, nullptr);
        EXPECT_EQ(bench->mesh, 2);
        EXPECT_TRUE(bench->translation.empty() && bench->rotation.empty() && bench->scale.empty());
        const tinygltf::Node* terrain = nodeNamed(model, "terrain");
        ASSERT_NE(terrain, nullptr);
        EXPECT_EQ(terrain->mesh, 1);

        // Three instances in two chunks, through the extension, relative to the chunk centres.
        std::vector<std::string> chunk_names;
        std::vector<SeenInstance> seen;
        for (int root : model.scenes[0].nodes) {
            const tinygltf::Node& node = model.nodes[size_t(root)];
            if (node.name.rfind("icicles/shape_2/chunk_", 0) != 0) continue;
            chunk_names.push_back(node.name);
            EXPECT_EQ(node.mesh, 3);
            const tinygltf::Value& attrs = node.extensions.at("EXT_mesh_gpu_instancing").Get("attributes");
            const std::vector<float> t = floats(model, attrs.Get("TRANSLATION").Get<int>());
            const std::vector<float> r = floats(model, attrs.Get("ROTATION").Get<int>());
            const std::vector<float> s = floats(model, attrs.Get("SCALE").Get<int>());
            for (size_t i = 0; i < t.size() / 3; ++i) {
                const glm::vec3 tr = translationOf(node) + glm::vec3(t[3 * i], t[3 * i + 1], t[3 * i + 2]);
                const glm::quat q(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]);
                const glm::vec3 x_file = kToYUp * glm::vec3(1, 0, 0);
                seen.push_back({tr, tr + q * (s[3 * i] * x_file)});
            }
        }
        EXPECT_EQ(chunk_names, (std::vector<std::string>{"icicles/shape_2/chunk_-2_1", "icicles/shape_2/chunk_0_0"}));
        ASSERT_EQ(seen.size(), 3u);
        EXPECT_EQ(std::count(model.extensionsUsed.begin(), model.extensionsUsed.end(), "EXT_mesh_gpu_instancing"), 1);
        // Back in engine space (file (x, y, z) is engine (x, -z, y)); chunk order (-2, 1) then (0, 0).
        const glm::quat to_engine = glm::inverse(kToYUp);
        const glm::vec3 expected_origin[3] = {{-10.0f, 12.0f, -0.5f}, {1.5f, 2.0f, 3.0f}, {4.0f, 0.5f, 1.0f}};
        // The x tips by hand: scale 0.5 no rotation; identity; 90 degrees about Z at scale 2 maps +x to +2y.
        const glm::vec3 expected_tip[3] = {{-9.5f, 12.0f, -0.5f}, {2.5f, 2.0f, 3.0f}, {4.0f, 2.5f, 1.0f}};
        for (int i = 0; i < 3; ++i) {
            const glm::vec3 o = to_engine * seen[size_t(i)].origin, x = to_engine * seen[size_t(i)].x_tip;
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(o[c], expected_origin[i][c], 1e-5f) << i;
                EXPECT_NEAR(x[c], expected_tip[i][c], 1e-5f) << i;
            }
        }
    }
}

TEST(GltfStaticMeshes, PlainNodeModeRealizesOneNodePerInstance) {
    Fixture f;
    f.scene.use_instancing_extension = false;
    tinygltf::Model model;
    ASSERT_TRUE(load(exportOrFail(f.scene, "static_plain.glb"), &model));
    EXPECT_TRUE(model.extensionsUsed.empty());
    std::map<int, int> nodes_per_mesh;
    for (const tinygltf::Node& node : model.nodes) {
        EXPECT_TRUE(node.extensions.empty()) << node.name;
        if (node.mesh >= 0) ++nodes_per_mesh[node.mesh];
    }
    EXPECT_EQ(nodes_per_mesh, (std::map<int, int>{{0, 2}, {1, 1}, {2, 1}, {3, 3}}));
    // Instance 1 (chunk (0, 0), centre (4, 4)): translation (0, -3.5, 1) from its chunk, in Y up (0, 1, 3.5).
    const tinygltf::Node* one = nodeNamed(model, "icicles/shape_2/1");
    const tinygltf::Node* chunk = nodeNamed(model, "icicles/shape_2/chunk_0_0");
    ASSERT_TRUE(one && chunk);
    EXPECT_EQ(translationOf(*chunk), glm::vec3(4.0f, 0.0f, -4.0f));
    EXPECT_EQ(translationOf(*one), glm::vec3(0.0f, 1.0f, 3.5f));
    EXPECT_EQ(one->scale, (std::vector<double>{2.0, 2.0, 2.0}));
    EXPECT_NE(nodeNamed(model, "icicles/shape_2/0"), nullptr);
    EXPECT_NE(nodeNamed(model, "icicles/shape_2/2"), nullptr);
}

TEST(GltfStaticMeshes, SharedTextureImagesAreWrittenOnce) {
    Fixture f;
    auto image = std::make_shared<TextureImage>();
    image->width = image->height = 2;
    image->rgba.assign(16, 200);
    auto material = std::make_shared<SurfaceMaterial>();
    material->texture_kind = TextureKind::Bark;
    material->texture = image;
    auto same_pixels = std::make_shared<SurfaceMaterial>(*material);
    same_pixels->texture = std::make_shared<TextureImage>(*image);  // another object, identical bytes
    f.scene.meshes[0].material = material;
    f.scene.meshes[1].material = same_pixels;
    tinygltf::Model model;
    ASSERT_TRUE(load(exportOrFail(f.scene, "static_textured.glb"), &model));
    EXPECT_EQ(model.images.size(), 1u);
    for (int m : {2, 3}) {
        const tinygltf::Primitive& prim = model.meshes[size_t(m)].primitives[0];
        EXPECT_EQ(prim.attributes.count("TEXCOORD_0"), 1u);
        EXPECT_EQ(model.materials[size_t(prim.material)].pbrMetallicRoughness.baseColorTexture.index, 0);
    }
}

TEST(GltfStaticMeshes, BadEntriesAreRefusedWithTheReason) {
    auto refused = [](auto edit) {
        Fixture f;
        edit(&f.scene);
        return refusal(f.scene);
    };
    EXPECT_NE(refused([](SceneExport* s) { s->meshes[1].name = "cube"; }).find("static mesh 1 'cube': duplicate name"),
              std::string::npos);
    EXPECT_NE(refused([](SceneExport* s) { s->meshes[0].name = "terrain"; }).find("'terrain': duplicate name"),
              std::string::npos);
    EXPECT_NE(refused([](SceneExport* s) { s->meshes[1].name = "env/bench"; }).find("duplicate name"),
              std::string::npos);
    EXPECT_NE(refused([](SceneExport* s) { s->types[0].name = "terrain"; }).find("taken by a detail type"),
              std::string::npos);
    EXPECT_NE(refused([](SceneExport* s) { s->meshes[0].name.clear(); }).find("static mesh 0 has an empty name"),
              std::string::npos);
    EXPECT_NE(refused([](SceneExport* s) { s->meshes[0].mesh = nullptr; }).find("'env/bench': mesh is null"),
              std::string::npos);
    EXPECT_NE(refused([](SceneExport* s) { s->meshes[1].instances[2].scale = 0.0f; })
                  .find("static mesh 1 'icicles/shape_2' instance 2: scale must be > 0"),
              std::string::npos);
    EXPECT_NE(refused([](SceneExport* s) { s->meshes[1].instances[0].rotation = glm::quat(2, 0, 0, 0); })
                  .find("instance 0: rotation is not a unit quaternion"),
              std::string::npos);
    EXPECT_NE(refused([](SceneExport* s) { s->meshes[1].instances[1].position.x = NAN; })
                  .find("instance 1: non-finite"),
              std::string::npos);
    EXPECT_NE(refused([](SceneExport* s) { s->meshes[0].extras_json = "[1, 2]"; })
                  .find("extras_json must be empty or a JSON object"),
              std::string::npos);
    // The plain-node cap counts the static meshes' instances too.
    const std::string cap = refused([](SceneExport* s) {
        s->use_instancing_extension = false;
        s->meshes[1].instances.resize(kMaxPlainNodeInstances - 1);  // + the type's 2
    });
    EXPECT_NE(cap.find("too many for one plain node each"), std::string::npos) << cap;
}

}  // namespace ug
