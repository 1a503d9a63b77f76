// The glTF export of materials, read back with tinygltf (an independent reader, which decodes the PNGs
// with stb_image): every texture's pixels come back exactly, TEXCOORD_0 follows the box rule of
// material/uv_projection.h on every vertex, cut-outs are MASK, identical images are written once, and
// exports without materials are unchanged.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "io/gltf_scene_export.h"
#include "material/material.h"
#include "material/procedural_texture.h"
#include "material/uv_projection.h"
#include "mesh/procedural_models.h"
#include "mesh/terrain_mesh.h"
#include "scene_test_util.h"

namespace ug {
namespace {

bool load(const std::string& path, tinygltf::Model* model) {
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    const bool ok = std::filesystem::path(path).extension() == ".glb"
                        ? loader.LoadBinaryFromFile(model, &err, &warn, path)
                        : loader.LoadASCIIFromFile(model, &err, &warn, path);
    EXPECT_TRUE(ok) << path << ": " << err;
    return ok;
}

template <typename T>
std::vector<T> elements(const tinygltf::Model& model, int accessor, int components) {
    const tinygltf::Accessor& acc = model.accessors.at(size_t(accessor));
    const tinygltf::BufferView& view = model.bufferViews.at(size_t(acc.bufferView));
    const unsigned char* data = model.buffers.at(size_t(view.buffer)).data.data() + view.byteOffset + acc.byteOffset;
    std::vector<T> out(acc.count * size_t(components));
    std::memcpy(out.data(), data, out.size() * sizeof(T));
    return out;
}

Material make(glm::vec3 color, TextureKind kind, float scale, bool cutout) {
    Material m;
    m.base_color = color;
    m.roughness = 0.7f;
    m.texture = kind;
    m.texture_scale_m = scale;
    m.tint_variation = 0.3f;
    m.alpha_cutout = cutout;
    return m;
}

class MaterialExport : public ::testing::Test {
protected:
    void SetUp() override {
        for (const char* name : {"rock", "leaf_oak", "pebble"}) {
            TriangleMesh mesh;
            ASSERT_TRUE(makeStarterAsset(name, kStarterAssetSeed, &mesh));
            meshes_.push_back(std::move(mesh));
        }
        surfaces_ = {resolveMaterial(make({0.4f, 0.35f, 0.3f}, TextureKind::Rock, 0.1f, false), meshes_[0].base_color),
                     resolveMaterial(make({0.4f, 0.25f, 0.1f}, TextureKind::Leaf, 0.1f, true), meshes_[1].base_color),
                     // the rock's image again (another scale): written once
                     resolveMaterial(make({0.4f, 0.35f, 0.3f}, TextureKind::Rock, 0.04f, false), meshes_[2].base_color)};
        terrain_.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0.2f}, {-1, 1, 0}};
        terrain_.indices = {0, 1, 2, 0, 2, 3};
        // Turned textures: the pebble a quarter turn (exact), the terrain by 30 degrees.
        surfaces_[2].texture_rotation_deg = 90.0f;
        terrain_look_ = resolveMaterial(make({0.3f, 0.25f, 0.2f}, TextureKind::Ground, 0.5f, false), kTerrainColor);
        terrain_look_.texture_rotation_deg = 30.0f;
    }
    SceneExport scene(bool with_materials) const {
        SceneExport s;
        const char* names[] = {"rock", "leaf_oak", "pebble"};
        for (size_t t = 0; t < meshes_.size(); ++t) {
            ExportDetailType type;
            type.name = names[t];
            type.mesh = &meshes_[t];
            type.instances = {InstanceTransform{glm::vec3(float(t), 0.0f, 0.0f)}};
            if (with_materials) type.material = &surfaces_[t];
            s.types.push_back(std::move(type));
        }
        s.terrain = &terrain_;
        if (with_materials) s.terrain_material = &terrain_look_;
        return s;
    }
    std::vector<TriangleMesh> meshes_;
    std::vector<SurfaceMaterial> surfaces_;
    TriangleMesh terrain_;
    SurfaceMaterial terrain_look_;
    test::TempDir dir_{"ug_material_export_"};
};

TEST_F(MaterialExport, TexturesUvsAndCutoutsReadBackExactly) {
    for (const char* file : {"m.glb", "m.gltf"}) {
        const std::string path = (dir_.path() / file).string();
        std::string error;
        ASSERT_TRUE(writeSceneGltf(path, scene(true), &error)) << error;
        tinygltf::Model model;
        ASSERT_TRUE(load(path, &model));
        // rock + pebble share one image; leaf and ground have their own.
        ASSERT_EQ(model.images.size(), 3u) << file;
        ASSERT_EQ(model.textures.size(), 3u);
        ASSERT_EQ(model.samplers.size(), 1u);
        EXPECT_EQ(model.samplers[0].wrapS, TINYGLTF_TEXTURE_WRAP_REPEAT);
        EXPECT_EQ(model.samplers[0].wrapT, TINYGLTF_TEXTURE_WRAP_REPEAT);
        ASSERT_EQ(model.materials.size(), 4u);
        const std::vector<const TextureImage*> expected = {surfaces_[0].texture.get(), surfaces_[1].texture.get(),
                                                           surfaces_[2].texture.get(), terrain_look_.texture.get()};
        for (size_t m = 0; m < model.materials.size(); ++m) {
            const tinygltf::Material& mat = model.materials[m];
            const int tex = mat.pbrMetallicRoughness.baseColorTexture.index;
            ASSERT_GE(tex, 0) << m;
            const tinygltf::Image& image = model.images.at(size_t(model.textures.at(size_t(tex)).source));
            EXPECT_EQ(image.mimeType, "image/png");
            EXPECT_GE(image.bufferView, 0);  // embedded in the buffer, not a URI
            ASSERT_EQ(image.width, kTextureSize);
            ASSERT_EQ(image.height, kTextureSize);
            ASSERT_EQ(image.component, 4);
            // PNG is lossless: the decoded pixels are the texture's bytes.
            EXPECT_EQ(image.image, expected[m]->rgba) << "material " << m;
            EXPECT_EQ(mat.pbrMetallicRoughness.baseColorFactor, std::vector<double>({1, 1, 1, 1}));
            EXPECT_FLOAT_EQ(float(mat.pbrMetallicRoughness.roughnessFactor), 0.7f);
            EXPECT_EQ(mat.pbrMetallicRoughness.metallicFactor, 0.0);
            EXPECT_EQ(mat.alphaMode, m == 1 ? "MASK" : "OPAQUE");
            if (m == 1) {
                EXPECT_EQ(mat.alphaCutoff, 0.5);
            }
            EXPECT_EQ(mat.doubleSided, m == 1);
            // The turn is in the extras only where there is one (pebble 90, terrain 30).
            const float turn = m == 2 ? 90.0f : m == 3 ? 30.0f : 0.0f;
            EXPECT_EQ(mat.extras.Has("texture_rotation_deg"), turn != 0.0f) << m;
            if (turn != 0.0f) {
                EXPECT_EQ(mat.extras.Get("texture_rotation_deg").GetNumberAsDouble(), double(turn));
            }
        }
        EXPECT_EQ(model.materials[0].pbrMetallicRoughness.baseColorTexture.index,
                  model.materials[2].pbrMetallicRoughness.baseColorTexture.index);

        // Every vertex's uv is the box rule on its triangles' common axis (detail types, positions back
        // in engine Z up: (x, y, z) file -> (x, -z, y)), or world XY for the terrain, then turned: the
        // pebble's quarter turn is (u, v) -> (-v, u) exactly; the terrain's 30 degrees within rounding.
        for (size_t k = 0; k < model.meshes.size(); ++k) {
            const tinygltf::Primitive& prim = model.meshes[k].primitives.at(0);
            ASSERT_TRUE(prim.attributes.count("TEXCOORD_0")) << model.meshes[k].name;
            const int pos_acc = prim.attributes.at("POSITION"), uv_acc = prim.attributes.at("TEXCOORD_0");
            ASSERT_EQ(model.accessors[size_t(uv_acc)].count, model.accessors[size_t(pos_acc)].count);
            const std::vector<float> p = elements<float>(model, pos_acc, 3), uv = elements<float>(model, uv_acc, 2);
            const bool terrain = model.meshes[k].name == "terrain";
            const float scale = terrain ? 0.5f : surfaces_[k].texture_scale_m;
            const tinygltf::Accessor& idx = model.accessors[size_t(prim.indices)];
            ASSERT_EQ(idx.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
            const std::vector<uint16_t> indices = elements<uint16_t>(model, prim.indices, 1);
            auto engine = [&](size_t v) { return glm::vec3(p[v * 3], -p[v * 3 + 2], p[v * 3 + 1]); };
            for (size_t t = 0; t + 2 < indices.size(); t += 3) {
                const glm::vec3 a = engine(indices[t]), b = engine(indices[t + 1]), c = engine(indices[t + 2]);
                const glm::vec3 n = glm::cross(b - a, c - a);
                for (int j = 0; j < 3; ++j) {
                    const size_t v = indices[t + size_t(j)];
                    const glm::vec2 flat = terrain ? planarXyUv(engine(v), scale) : boxProjectUv(engine(v), n, scale);
                    const glm::vec2 got(uv[v * 2], uv[v * 2 + 1]);
                    if (terrain) {
                        const double cos30 = std::sqrt(3.0) / 2.0, sin30 = 0.5;
                        EXPECT_NEAR(got.x, cos30 * flat.x - sin30 * flat.y, 1e-5) << "terrain vertex " << v;
                        EXPECT_NEAR(got.y, sin30 * flat.x + cos30 * flat.y, 1e-5) << "terrain vertex " << v;
                        continue;
                    }
                    const glm::vec2 want = k == 2 ? glm::vec2(-flat.y, flat.x) : flat;
                    // The Y-up conversion only permutes and negates components: positions, and with them
                    // each triangle's axis, come back exactly, so the uvs must match exactly.
                    EXPECT_EQ(got, want) << model.meshes[k].name << " vertex " << v;
                }
            }
        }
    }
}

TEST_F(MaterialExport, WithoutMaterialsNothingChanges) {
    const std::string path = (dir_.path() / "plain.glb").string();
    std::string error;
    ASSERT_TRUE(writeSceneGltf(path, scene(false), &error)) << error;
    tinygltf::Model model;
    ASSERT_TRUE(load(path, &model));
    EXPECT_TRUE(model.images.empty());
    EXPECT_TRUE(model.textures.empty());
    EXPECT_TRUE(model.samplers.empty());
    for (const tinygltf::Mesh& mesh : model.meshes) EXPECT_FALSE(mesh.primitives[0].attributes.count("TEXCOORD_0"));
    const std::vector<double> rock(model.materials[0].pbrMetallicRoughness.baseColorFactor);
    EXPECT_FLOAT_EQ(float(rock[0]), meshes_[0].base_color.x);
    EXPECT_DOUBLE_EQ(model.materials[0].pbrMetallicRoughness.roughnessFactor, 0.9);
    // An untextured material: its colour and roughness, no TEXCOORD_0.
    SurfaceMaterial flat = resolveMaterial(make({0.2f, 0.4f, 0.6f}, TextureKind::None, 0.1f, false), glm::vec3(1.0f));
    SceneExport s = scene(false);
    s.types[0].material = &flat;
    ASSERT_TRUE(writeSceneGltf(path, s, &error)) << error;
    model = tinygltf::Model();
    ASSERT_TRUE(load(path, &model));
    EXPECT_TRUE(model.images.empty());
    EXPECT_FALSE(model.meshes[0].primitives[0].attributes.count("TEXCOORD_0"));
    EXPECT_FLOAT_EQ(float(model.materials[0].pbrMetallicRoughness.baseColorFactor[2]), 0.6f);
    EXPECT_EQ(model.materials[0].alphaMode, "OPAQUE");
}

TEST_F(MaterialExport, BadMaterialsAreRefusedNamingTheType) {
    const std::string path = (dir_.path() / "bad.glb").string();
    std::string error;
    SurfaceMaterial bad = surfaces_[0];
    bad.roughness = 1.5f;
    SceneExport s = scene(false);
    s.types[1].material = &bad;
    EXPECT_FALSE(writeSceneGltf(path, s, &error));
    EXPECT_NE(error.find("detail type 1 'leaf_oak': material: roughness must be in [0, 1] (got 1.5)"), std::string::npos)
        << error;
    auto broken = std::make_shared<TextureImage>(*surfaces_[0].texture);
    broken->rgba.resize(10);
    bad = surfaces_[0];
    bad.texture = broken;
    s.types[1].material = &bad;
    EXPECT_FALSE(writeSceneGltf(path, s, &error));
    EXPECT_NE(error.find("material: texture is 256 x 256 with 10 bytes"), std::string::npos) << error;
    bad = surfaces_[0];
    bad.texture_rotation_deg = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(writeSceneGltf(path, s, &error));
    EXPECT_NE(error.find("material: texture_rotation_deg must be in [-360, 360] (got nan)"), std::string::npos) << error;
    bad = surfaces_[0];
    bad.texture_scale_m = 0.0f;
    s.types[1].material = nullptr;
    s.terrain_material = &bad;
    EXPECT_FALSE(writeSceneGltf(path, s, &error));
    EXPECT_NE(error.find("terrain material: texture_scale_m must be finite and > 0 (got 0)"), std::string::npos) << error;
    EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace ug
