// Scene export to glTF: every file is read back with tinygltf directly (not our loader), and checked
// for instance counts, chunk partition, unit rotations, extras, and the Z-up -> Y-up conversion of whole
// instance transforms.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <random>
#include <set>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "field/height_field.h"
#include "io/gltf_scene_export.h"
#include "mesh/procedural_models.h"
#include "mesh/terrain_mesh.h"
#include "mesh_test_util.h"

namespace ug {
namespace {

namespace fs = std::filesystem;

constexpr const char* kExt = "EXT_mesh_gpu_instancing";

// Engine (Z up) -> file (Y up), written independently of the exporter: the -90 degree rotation about X.
glm::vec3 zUpToYUp(glm::vec3 v) {
    return glm::angleAxis(-glm::half_pi<float>(), glm::vec3(1, 0, 0)) * v;
}

glm::quat randomRotation(std::mt19937& rng) {
    std::normal_distribution<float> n(0.0f, 1.0f);
    return glm::normalize(glm::quat(n(rng), n(rng), n(rng), n(rng)));
}

std::vector<InstanceTransform> randomInstances(size_t count, float extent_m, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> xy(-extent_m, extent_m), z(-1.0f, 2.0f), s(0.5f, 2.0f);
    std::vector<InstanceTransform> out(count);
    for (InstanceTransform& inst : out) {
        inst.position = glm::vec3(xy(rng), xy(rng), z(rng));
        inst.rotation = randomRotation(rng);
        inst.scale = s(rng);
    }
    return out;
}

bool load(const std::string& path, tinygltf::Model* model) {
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    const bool ok = fs::path(path).extension() == ".glb" ? loader.LoadBinaryFromFile(model, &err, &warn, path)
                                                         : loader.LoadASCIIFromFile(model, &err, &warn, path);
    EXPECT_TRUE(ok) << path << ": " << err;
    return ok;
}

// The accessor's elements as floats (tightly packed float accessors, which is all the exporter writes).
std::vector<float> floats(const tinygltf::Model& model, int accessor) {
    const tinygltf::Accessor& acc = model.accessors.at(size_t(accessor));
    EXPECT_EQ(acc.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
    const tinygltf::BufferView& view = model.bufferViews.at(size_t(acc.bufferView));
    EXPECT_EQ(view.byteStride, 0u);
    const size_t n = acc.count * size_t(tinygltf::GetNumComponentsInType(uint32_t(acc.type)));
    const std::vector<unsigned char>& data = model.buffers.at(size_t(view.buffer)).data;
    const size_t start = view.byteOffset + acc.byteOffset;
    EXPECT_LE(start + n * 4, view.byteOffset + view.byteLength);
    EXPECT_LE(view.byteOffset + view.byteLength, data.size());
    std::vector<float> out(n);
    std::memcpy(out.data(), data.data() + start, n * 4);
    return out;
}

glm::vec3 vec3At(const std::vector<float>& v, size_t i) {
    return {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
}
glm::quat quatAt(const std::vector<float>& v, size_t i) {  // file order x, y, z, w
    return glm::quat(v[4 * i + 3], v[4 * i], v[4 * i + 1], v[4 * i + 2]);
}

glm::vec3 nodeTranslation(const tinygltf::Node& node) {
    return node.translation.size() == 3
               ? glm::vec3(float(node.translation[0]), float(node.translation[1]), float(node.translation[2]))
               : glm::vec3(0.0f);
}

// One instance as the file describes it: the world transform of the node that holds it (only
// translations above it, which the test asserts), then the instance's T, R, S.
struct FileInstance {
    std::string type;
    std::string chunk_node;  // "<type>/chunk_<ix>_<iy>"
    glm::vec3 node_translation{0.0f};
    glm::vec3 t{0.0f};
    glm::quat r{1, 0, 0, 0};
    glm::vec3 s{1.0f};
    glm::vec3 world(glm::vec3 v) const { return node_translation + t + r * (s * v); }
};

// Every instance in the file, whether through the extension or plain nodes. Checks the structure along
// the way: each scene root is a chunk node; instancing accessors agree in count.
std::vector<FileInstance> fileInstances(const tinygltf::Model& model) {
    std::vector<FileInstance> out;
    for (int root : model.scenes.at(0).nodes) {
        const tinygltf::Node& node = model.nodes.at(size_t(root));
        if (node.name == "terrain") continue;
        EXPECT_TRUE(node.rotation.empty() && node.scale.empty() && node.matrix.empty()) << node.name;
        const std::string type = node.name.substr(0, node.name.find("/chunk_"));
        auto ext = node.extensions.find(kExt);
        if (ext != node.extensions.end()) {
            EXPECT_GE(node.mesh, 0);
            const tinygltf::Value& attrs = ext->second.Get("attributes");
            const std::vector<float> t = floats(model, attrs.Get("TRANSLATION").Get<int>());
            const std::vector<float> r = floats(model, attrs.Get("ROTATION").Get<int>());
            const std::vector<float> s = floats(model, attrs.Get("SCALE").Get<int>());
            EXPECT_EQ(t.size() / 3, r.size() / 4);
            EXPECT_EQ(t.size() / 3, s.size() / 3);
            for (size_t i = 0; i < t.size() / 3; ++i)
                out.push_back(
                    {type, node.name, nodeTranslation(node), vec3At(t, i), quatAt(r, i), vec3At(s, i)});
        } else {
            EXPECT_LT(node.mesh, 0) << node.name << ": a plain chunk node holds its instances as children";
            for (int c : node.children) {
                const tinygltf::Node& child = model.nodes.at(size_t(c));
                EXPECT_GE(child.mesh, 0);
                EXPECT_EQ(child.rotation.size(), 4u);
                EXPECT_EQ(child.scale.size(), 3u);
                const std::vector<double>& q = child.rotation;
                out.push_back(
                    {type, node.name, nodeTranslation(node), nodeTranslation(child),
                     glm::quat(float(q[3]), float(q[0]), float(q[1]), float(q[2])),
                     glm::vec3(float(child.scale[0]), float(child.scale[1]), float(child.scale[2]))});
            }
        }
    }
    return out;
}

// The JSON part of a .gltf or .glb, parsed independently of tinygltf (for exact extras comparisons).
nlohmann::json rawJson(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.rfind("glTF", 0) == 0) {
        uint32_t json_length = 0;
        std::memcpy(&json_length, bytes.data() + 12, 4);
        return nlohmann::json::parse(bytes.substr(20, json_length));
    }
    return nlohmann::json::parse(bytes);
}

struct Fixture {
    TriangleMesh cube = test::unitCube();
    TriangleMesh rock = makeRock(3);
    SceneExport scene;

    Fixture(size_t cubes, size_t rocks) {
        ExportDetailType a;
        a.name = "cube";
        a.mesh = &cube;
        a.collision_spheres = {{glm::vec3(0.1f, 0.2f, 0.3f), 0.5f}, {glm::vec3(-0.1f, 0.0f, 0.25f), 0.25f}};
        a.instances = randomInstances(cubes, 30.0f, 1);
        ExportDetailType b;
        b.name = "rock";
        b.mesh = &rock;
        b.collision_spheres = {{glm::vec3(0.0f), 0.06f}};
        b.instances = randomInstances(rocks, 12.0f, 2);
        scene.types = {a, b};
        scene.delta_m = 0.02f;
        scene.chunk_size_m = 8.0f;
        scene.scene_extras_json = R"({"instances": 5, "tiles": [1, 2], "nested": {"ok": true}})";
    }
};

std::string exportOrFail(const SceneExport& scene, const std::string& name) {
    const std::string path = test::tempPath(name);
    std::string error;
    EXPECT_TRUE(writeSceneGltf(path, scene, &error)) << error;
    return path;
}

std::vector<std::string> leftovers(const std::string& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
    return names;
}

}  // namespace

TEST(GltfSceneExport, InstancesArePartitionedIntoChunksWithUnitRotations) {
    Fixture f(700, 300);
    for (const char* name : {"chunks.glb", "chunks.gltf"}) {
        SCOPED_TRACE(name);
        const std::string path = exportOrFail(f.scene, name);
        tinygltf::Model model;
        ASSERT_TRUE(load(path, &model));
        EXPECT_EQ(model.extensionsUsed, std::vector<std::string>{kExt});
        EXPECT_TRUE(model.extensionsRequired.empty());
        ASSERT_EQ(model.meshes.size(), 2u);
        EXPECT_EQ(model.meshes[0].name, "cube");
        EXPECT_EQ(model.meshes[1].name, "rock");

        const std::vector<FileInstance> found = fileInstances(model);
        std::map<std::string, size_t> per_type;
        std::set<std::string> chunk_names;
        std::map<std::string, std::vector<glm::vec3>> positions;  // engine space, recovered from the file
        for (const FileInstance& inst : found) {
            ++per_type[inst.type];
            chunk_names.insert(inst.chunk_node);
            ASSERT_NEAR(glm::length(inst.r), 1.0f, 1e-6f);
            ASSERT_TRUE(std::isfinite(inst.t.x) && std::isfinite(inst.t.y) && std::isfinite(inst.t.z));
            ASSERT_TRUE(inst.s.x > 0 && inst.s.x == inst.s.y && inst.s.y == inst.s.z);
            // Y up -> Z up: (x, y, z) -> (x, -z, y).
            const glm::vec3 w = inst.world(glm::vec3(0.0f));
            const glm::vec3 p(w.x, -w.z, w.y);
            // Partition: the instance lies in the chunk its node is named after.
            int ix = 0, iy = 0;
            const std::string suffix = inst.chunk_node.substr(inst.chunk_node.find("/chunk_") + 7);
            ASSERT_EQ(std::sscanf(suffix.c_str(), "%d_%d", &ix, &iy), 2) << inst.chunk_node;
            EXPECT_EQ(int(std::floor(p.x / 8.0f)), ix) << p.x;
            EXPECT_EQ(int(std::floor(p.y / 8.0f)), iy) << p.y;
            positions[inst.type].push_back(p);
        }
        EXPECT_EQ(per_type["cube"], 700u);
        EXPECT_EQ(per_type["rock"], 300u);
        // Chunk nodes are unique, and 60 m of cubes in 8 m chunks means many of them.
        size_t chunk_nodes = 0;
        for (int root : model.scenes[0].nodes)
            chunk_nodes += model.nodes[size_t(root)].name.find("/chunk_") != std::string::npos;
        EXPECT_EQ(chunk_names.size(), chunk_nodes);
        EXPECT_GT(chunk_nodes, 50u);

        // Every input position comes back once (match after sorting; tolerance for float round trips).
        for (const ExportDetailType& type : f.scene.types) {
            std::vector<glm::vec3> want;
            for (const InstanceTransform& inst : type.instances) want.push_back(inst.position);
            std::vector<glm::vec3>& got = positions[type.name];
            auto less = [](glm::vec3 a, glm::vec3 b) { return a.x < b.x; };
            std::sort(want.begin(), want.end(), less);
            std::sort(got.begin(), got.end(), less);
            ASSERT_EQ(want.size(), got.size());
            for (size_t i = 0; i < want.size(); ++i)
                ASSERT_LT(glm::length(want[i] - got[i]), 1e-4f) << type.name;
        }
    }
}

// The conversion test: for a vertex v and an instance (p, q, s), the engine places v at p + q (s v); the
// file must place the file's vertex v' at C(p + q (s v)), with C the Z-up -> Y-up rotation, computed here
// with glm::angleAxis rather than the exporter's swizzles.
TEST(GltfSceneExport, WholeInstanceTransformsConvertFromZUpToYUp) {
    TriangleMesh mesh = test::unitCube();
    for (glm::vec3& p : mesh.positions)
        p = p * glm::vec3(1.0f, 2.0f, 3.0f) + glm::vec3(0.3f, -0.2f, 0.5f);  // asymmetric
    ExportDetailType type;
    type.name = "box";
    type.mesh = &mesh;
    std::mt19937 rng(5);
    for (int i = 0; i < 40; ++i) {
        InstanceTransform inst;
        inst.position =
            glm::vec3(float(i) * 3.7f - 60.0f, float(i % 7) * -5.3f + 1000.0f, float(i % 3) - 1.0f);
        inst.rotation = randomRotation(rng);
        inst.scale = 0.5f + 0.1f * float(i);
        type.instances.push_back(inst);
    }
    SceneExport scene;
    scene.types = {type};
    scene.chunk_size_m = 10.0f;
    for (bool extension : {true, false}) {
        SCOPED_TRACE(extension ? "extension" : "plain nodes");
        scene.use_instancing_extension = extension;
        const std::string path = exportOrFail(scene, extension ? "convert_ext.glb" : "convert_plain.glb");
        tinygltf::Model model;
        ASSERT_TRUE(load(path, &model));
        const tinygltf::Primitive& prim = model.meshes.at(0).primitives.at(0);
        const std::vector<float> file_vertices = floats(model, prim.attributes.at("POSITION"));
        ASSERT_EQ(file_vertices.size(), mesh.positions.size() * 3);

        const std::vector<FileInstance> found = fileInstances(model);
        ASSERT_EQ(found.size(), type.instances.size());
        // Match file instances to input ones by position (order in the file is by chunk).
        size_t checked = 0;
        for (const InstanceTransform& inst : type.instances) {
            const glm::vec3 want_origin = zUpToYUp(inst.position);
            const FileInstance* match = nullptr;
            for (const FileInstance& fi : found)
                if (glm::length(fi.world(glm::vec3(0.0f)) - want_origin) < 1e-3f) match = &fi;
            ASSERT_NE(match, nullptr);
            for (size_t k = 0; k < mesh.positions.size(); ++k) {
                const glm::vec3 engine_world =
                    inst.position + inst.rotation * (inst.scale * mesh.positions[k]);
                const glm::vec3 file_world = match->world(vec3At(file_vertices, k));
                ASSERT_LT(glm::length(file_world - zUpToYUp(engine_world)), 2e-4f)
                    << "vertex " << k << " of the instance at " << inst.position.x << ", " << inst.position.y;
                ++checked;
            }
        }
        EXPECT_EQ(checked, type.instances.size() * mesh.positions.size());
    }
}

TEST(GltfSceneExport, MeshesCarryConvertedCollisionSpheresDeltaAndTheSceneExtras) {
    Fixture f(10, 5);
    for (const char* name : {"extras.glb", "extras.gltf"}) {
        SCOPED_TRACE(name);
        const std::string path = exportOrFail(f.scene, name);
        tinygltf::Model model;
        ASSERT_TRUE(load(path, &model));
        // tinygltf's view of the extras.
        const tinygltf::Value& cube_extras = model.meshes.at(0).extras;
        ASSERT_TRUE(cube_extras.IsObject());
        EXPECT_NEAR(cube_extras.Get("delta").GetNumberAsDouble(), 0.02, 1e-7);
        ASSERT_EQ(cube_extras.Get("collision_spheres").ArrayLen(), 2u);
        // An independent JSON parse for exact values: sphere (0.1, 0.2, 0.3) r 0.5 -> (0.1, 0.3, -0.2).
        const nlohmann::json json = rawJson(path);
        const nlohmann::json& spheres = json["meshes"][0]["extras"]["collision_spheres"];
        ASSERT_EQ(spheres.size(), 2u);
        EXPECT_FLOAT_EQ(spheres[0][0].get<float>(), 0.1f);
        EXPECT_FLOAT_EQ(spheres[0][1].get<float>(), 0.3f);
        EXPECT_FLOAT_EQ(spheres[0][2].get<float>(), -0.2f);
        EXPECT_FLOAT_EQ(spheres[0][3].get<float>(), 0.5f);
        EXPECT_FLOAT_EQ(spheres[1][1].get<float>(), 0.25f);
        EXPECT_FLOAT_EQ(spheres[1][2].get<float>(), -0.0f);
        EXPECT_EQ(json["meshes"][1]["extras"]["collision_spheres"].size(), 1u);
        EXPECT_FLOAT_EQ(json["meshes"][1]["extras"]["delta"].get<float>(), 0.02f);
        EXPECT_EQ(json["scenes"][json["scene"].get<int>()]["extras"],
                  nlohmann::json::parse(f.scene.scene_extras_json));
        // Materials: one per type from base_color, metallic 0, rough, single-sided.
        ASSERT_EQ(model.materials.size(), 2u);
        const tinygltf::Material& rock = model.materials[size_t(model.meshes[1].primitives[0].material)];
        EXPECT_NEAR(rock.pbrMetallicRoughness.baseColorFactor[0], f.rock.base_color.x, 1e-6);
        EXPECT_EQ(rock.pbrMetallicRoughness.metallicFactor, 0.0);
        EXPECT_NEAR(rock.pbrMetallicRoughness.roughnessFactor, 0.9, 1e-9);
        EXPECT_FALSE(rock.doubleSided);
        // POSITION has min/max, uint16 indices for these small meshes.
        const tinygltf::Accessor& pos =
            model.accessors[size_t(model.meshes[1].primitives[0].attributes.at("POSITION"))];
        EXPECT_EQ(pos.minValues.size(), 3u);
        EXPECT_EQ(pos.maxValues.size(), 3u);
        EXPECT_EQ(model.accessors[size_t(model.meshes[1].primitives[0].indices)].componentType,
                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
        if (std::string(name).ends_with(".gltf")) {
            EXPECT_EQ(json["buffers"][0]["uri"].get<std::string>().rfind(
                          "data:application/octet-stream;base64,", 0),
                      0u);
        }
    }
}

TEST(GltfSceneExport, PlainNodeModeWritesOneNodePerInstanceWithoutTheExtension) {
    Fixture f(120, 80);
    f.scene.use_instancing_extension = false;
    for (const char* name : {"plain.glb", "plain.gltf"}) {
        SCOPED_TRACE(name);
        const std::string path = exportOrFail(f.scene, name);
        tinygltf::Model model;
        ASSERT_TRUE(load(path, &model));
        EXPECT_TRUE(model.extensionsUsed.empty());
        size_t with_mesh = 0;
        for (const tinygltf::Node& node : model.nodes) {
            EXPECT_TRUE(node.extensions.empty());
            with_mesh += node.mesh >= 0;
        }
        EXPECT_EQ(with_mesh, 200u);
        std::map<std::string, size_t> per_type;
        for (const FileInstance& inst : fileInstances(model)) {
            ++per_type[inst.type];
            EXPECT_NEAR(glm::length(inst.r), 1.0f, 1e-6f);
        }
        EXPECT_EQ(per_type["cube"], 120u);
        EXPECT_EQ(per_type["rock"], 80u);
    }
}

TEST(GltfSceneExport, TerrainBigMeshesAndEmptyTypes) {
    ProceduralTerrainDesc desc;
    desc.width = desc.height = 300;  // 90,000 vertices: needs uint32 indices
    desc.origin_m = glm::vec2(-150.0f);
    HeightField hf;
    std::string error;
    ASSERT_TRUE(makeProceduralHeightField(desc, &hf, &error)) << error;
    TriangleMesh terrain;
    ASSERT_TRUE(heightFieldMesh(hf, Bounds::everything(), 1000, &terrain, &error)) << error;
    Fixture f(3, 0);  // rocks: a type without instances still gets its mesh, but no node
    f.scene.terrain = &terrain;
    const std::string path = exportOrFail(f.scene, "terrain.glb");
    tinygltf::Model model;
    ASSERT_TRUE(load(path, &model));
    ASSERT_EQ(model.meshes.size(), 3u);
    EXPECT_EQ(model.meshes[1].name, "rock");
    const tinygltf::Mesh& mesh = model.meshes[2];
    EXPECT_EQ(mesh.name, "terrain");
    EXPECT_EQ(model.accessors[size_t(mesh.primitives[0].indices)].componentType,
              TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
    EXPECT_EQ(model.accessors[size_t(mesh.primitives[0].attributes.at("POSITION"))].count, 90000u);
    const tinygltf::Material& material = model.materials[size_t(mesh.primitives[0].material)];
    EXPECT_NEAR(material.pbrMetallicRoughness.baseColorFactor[0], kTerrainColor.x, 1e-6);
    size_t terrain_nodes = 0, rock_nodes = 0;
    for (const tinygltf::Node& node : model.nodes) {
        terrain_nodes += node.name == "terrain" && node.mesh == 2;
        rock_nodes += node.mesh == 1;
    }
    EXPECT_EQ(terrain_nodes, 1u);
    EXPECT_EQ(rock_nodes, 0u);
    // A terrain vertex: engine (x, y, z) is file (x, z, -y).
    const std::vector<float> v = floats(model, mesh.primitives[0].attributes.at("POSITION"));
    EXPECT_EQ(v[0], terrain.positions[0].x);
    EXPECT_EQ(v[1], terrain.positions[0].z);
    EXPECT_EQ(v[2], -terrain.positions[0].y);

    // A scene with nothing in it is still a valid, loadable file (no empty arrays, no buffer).
    SceneExport empty;
    const std::string empty_path = exportOrFail(empty, "empty.gltf");
    tinygltf::Model empty_model;
    ASSERT_TRUE(load(empty_path, &empty_model));
    EXPECT_TRUE(empty_model.buffers.empty());
    EXPECT_EQ(rawJson(empty_path).count("meshes"), 0u);
}

TEST(GltfSceneExport, FarFromTheOriginChunkCentresKeepPrecision) {
    TriangleMesh cube = test::unitCube();
    ExportDetailType type;
    type.name = "cube";
    type.mesh = &cube;
    InstanceTransform inst;
    inst.position = glm::vec3(12345.678f, -54321.25f, 3.5f);
    type.instances = {inst};
    SceneExport scene;
    scene.types = {type};
    const std::string path = exportOrFail(scene, "far.glb");
    tinygltf::Model model;
    ASSERT_TRUE(load(path, &model));
    const std::vector<FileInstance> found = fileInstances(model);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].chunk_node, "cube/chunk_1543_-6791");
    // The node carries the chunk centre exactly; the instance offset is small.
    const tinygltf::Node& node = model.nodes[size_t(model.scenes[0].nodes[0])];
    EXPECT_DOUBLE_EQ(node.translation[0], 1543.5 * 8.0);
    EXPECT_DOUBLE_EQ(node.translation[2], 6790.5 * 8.0);
    EXPECT_LT(glm::length(found[0].t), 8.0f);
    const double x = node.translation[0] + found[0].t.x, z = node.translation[2] + found[0].t.z;
    EXPECT_NEAR(x, 12345.678, 2e-3);
    EXPECT_NEAR(-z, -54321.25, 2e-3);
}

TEST(GltfSceneExport, SlightlyOffRotationsAreNormalized) {
    Fixture f(1, 0);
    f.scene.types[0].instances[0].rotation = glm::quat(1.0005f, 0.0f, 0.0f, 0.0f);
    const std::string path = exportOrFail(f.scene, "renormalized.glb");
    tinygltf::Model model;
    ASSERT_TRUE(load(path, &model));
    const std::vector<FileInstance> found = fileInstances(model);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_NEAR(glm::length(found[0].r), 1.0f, 1e-7f);
}

TEST(GltfSceneExport, InvalidUtf8InNamesIsReplacedNotThrown) {
    Fixture f(4, 2);
    f.scene.types[0].name = "cube\xff";
    const std::string path = exportOrFail(f.scene, "utf8.gltf");
    tinygltf::Model model;
    ASSERT_TRUE(load(path, &model));
    EXPECT_EQ(model.meshes.at(0).name, "cube\xef\xbf\xbd");  // U+FFFD
}

TEST(GltfSceneExport, RejectsBadInputNamingTheTypeAndInstance) {
    TriangleMesh empty_mesh;
    struct Case {
        const char* what;
        void (*edit)(SceneExport*, TriangleMesh*);
        const char* reason;
    };
    const Case cases[] = {
        {"null mesh", [](SceneExport* s, TriangleMesh*) { s->types[1].mesh = nullptr; },
         "detail type 1 'rock': mesh is null"},
        {"empty mesh", [](SceneExport* s, TriangleMesh* e) { s->types[0].mesh = e; },
         "detail type 0 'cube': mesh: no triangles"},
        {"NaN position",
         [](SceneExport* s, TriangleMesh*) {
             s->types[1].instances[3].position.y = std::numeric_limits<float>::quiet_NaN();
         },
         "'rock' instance 3: non-finite"},
        {"infinite scale",
         [](SceneExport* s, TriangleMesh*) {
             s->types[0].instances[7].scale = std::numeric_limits<float>::infinity();
         },
         "'cube' instance 7: non-finite"},
        {"NaN rotation",
         [](SceneExport* s, TriangleMesh*) {
             s->types[0].instances[0].rotation.x = std::numeric_limits<float>::quiet_NaN();
         },
         "'cube' instance 0: non-finite"},
        {"non-unit rotation",
         [](SceneExport* s, TriangleMesh*) { s->types[0].instances[2].rotation = glm::quat(1.01f, 0, 0, 0); },
         "'cube' instance 2: rotation is not a unit quaternion"},
        {"zero scale", [](SceneExport* s, TriangleMesh*) { s->types[1].instances[0].scale = 0.0f; },
         "'rock' instance 0: scale must be > 0"},
        {"zero chunk", [](SceneExport* s, TriangleMesh*) { s->chunk_size_m = 0.0f; }, "chunk_size_m"},
        {"negative chunk", [](SceneExport* s, TriangleMesh*) { s->chunk_size_m = -8.0f; }, "chunk_size_m"},
        {"NaN chunk",
         [](SceneExport* s, TriangleMesh*) { s->chunk_size_m = std::numeric_limits<float>::quiet_NaN(); },
         "chunk_size_m"},
        {"tiny chunk", [](SceneExport* s, TriangleMesh*) { s->chunk_size_m = 1e-30f; },
         "too far from the origin"},
        {"NaN delta",
         [](SceneExport* s, TriangleMesh*) { s->delta_m = std::numeric_limits<float>::quiet_NaN(); },
         "delta_m"},
        {"duplicate names", [](SceneExport* s, TriangleMesh*) { s->types[1].name = "cube"; },
         "detail type 1 'cube': duplicate type name"},
        {"empty name", [](SceneExport* s, TriangleMesh*) { s->types[0].name.clear(); },
         "detail type 0 has an empty name"},
        {"bad sphere", [](SceneExport* s, TriangleMesh*) { s->types[0].collision_spheres[1].radius = -1.0f; },
         "'cube': collision sphere 1"},
        {"invalid extras", [](SceneExport* s, TriangleMesh*) { s->scene_extras_json = "{\"a\": }"; },
         "scene_extras_json is not valid JSON"},
        {"extras not an object", [](SceneExport* s, TriangleMesh*) { s->scene_extras_json = "[1, 2]"; },
         "must be a JSON object"},
        {"invalid terrain", [](SceneExport* s, TriangleMesh* e) { s->terrain = e; },
         "terrain mesh: no triangles"},
    };
    const std::string dir = test::tempPath("export_errors");
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string path = dir + "/scene.glb";
    // A good file first: a failed export must leave it as it was, and leave nothing else behind.
    Fixture good(20, 10);
    std::string error;
    ASSERT_TRUE(writeSceneGltf(path, good.scene, &error)) << error;
    const uintmax_t good_size = fs::file_size(path);
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        Fixture f(20, 10);
        c.edit(&f.scene, &empty_mesh);
        error.clear();
        EXPECT_FALSE(writeSceneGltf(path, f.scene, &error));
        EXPECT_EQ(error.rfind(path + ": ", 0), 0u) << error;
        EXPECT_NE(error.find(c.reason), std::string::npos) << error;
        EXPECT_EQ(fs::file_size(path), good_size);
        EXPECT_EQ(leftovers(dir), std::vector<std::string>{"scene.glb"});
    }

    // Plain nodes refuse huge scenes and point to the extension.
    Fixture big(0, 0);
    big.scene.types[0].instances.assign(kMaxPlainNodeInstances + 1, InstanceTransform{});
    big.scene.use_instancing_extension = false;
    EXPECT_FALSE(writeSceneGltf(path, big.scene, &error));
    EXPECT_NE(error.find("EXT_mesh_gpu_instancing"), std::string::npos) << error;

    // Paths: an unknown extension, a folder that does not exist (nothing created there).
    EXPECT_FALSE(writeSceneGltf(dir + "/scene.obj", good.scene, &error));
    EXPECT_NE(error.find(".glb or .gltf"), std::string::npos) << error;
    const std::string missing = dir + "/no/such/folder/scene.gltf";
    EXPECT_FALSE(writeSceneGltf(missing, good.scene, &error));
    EXPECT_EQ(error.rfind(missing + ": ", 0), 0u) << error;
    EXPECT_FALSE(fs::exists(dir + "/no"));
    EXPECT_EQ(leftovers(dir), std::vector<std::string>{"scene.glb"});
}

}  // namespace ug
