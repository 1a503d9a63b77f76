#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "mesh_test_util.h"
#include "io/gltf_mesh_io.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural_models.h"

namespace ug {
namespace {

std::vector<char> readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void expectContains(const std::string& text, const std::string& part) {
    EXPECT_NE(text.find(part), std::string::npos) << "'" << text << "' lacks '" << part << "'";
}

}  // namespace

TEST(GltfMeshIo, RoundTripGlbAndGltfThroughAnIndependentReader) {
    const TriangleMesh rock = makeRock(1), cube = test::unitCube();
    for (const char* ext : {".glb", ".gltf"}) {
        SCOPED_TRACE(ext);
        const std::string path = test::tempPath(std::string("round_trip") + ext);
        std::string error;
        ASSERT_TRUE(writeGltfMeshes(path, {{"rock", &rock}, {"cube", &cube}}, &error)) << error;
        EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));

        // Independent reader: tinygltf directly, counts and min/max.
        tinygltf::TinyGLTF loader;
        tinygltf::Model model;
        std::string err, warn;
        const bool ok = std::string(ext) == ".glb" ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                                                  : loader.LoadASCIIFromFile(&model, &err, &warn, path);
        ASSERT_TRUE(ok) << err;
        ASSERT_EQ(model.meshes.size(), 2u);
        ASSERT_EQ(model.nodes.size(), 2u);
        const tinygltf::Accessor& pos = model.accessors[size_t(model.meshes[0].primitives[0].attributes.at("POSITION"))];
        EXPECT_EQ(pos.count, rock.positions.size());
        ASSERT_EQ(pos.minValues.size(), 3u);
        ASSERT_EQ(pos.maxValues.size(), 3u);
        const tinygltf::Accessor& idx = model.accessors[size_t(model.meshes[0].primitives[0].indices)];
        EXPECT_EQ(idx.count, rock.indices.size());
        const Bounds3 b = meshBounds(rock);
        EXPECT_NEAR(pos.maxValues[1], b.max.z, 1e-6);   // Y up in the file = engine Z
        EXPECT_NEAR(pos.minValues[2], -b.max.y, 1e-6);  // file Z = -engine Y
        EXPECT_NEAR(model.materials[0].pbrMetallicRoughness.roughnessFactor, 0.9, 1e-9);

        // Our loader, back to Z up: same positions.
        TriangleMesh back;
        ASSERT_TRUE(loadGltfMesh(path, &back, &error)) << error;
        convertYUpToZUp(&back);
        ASSERT_EQ(back.positions.size(), rock.positions.size() + cube.positions.size());
        ASSERT_EQ(back.indices.size(), rock.indices.size() + cube.indices.size());
        for (size_t i = 0; i < rock.positions.size(); ++i)
            ASSERT_LT(glm::length(back.positions[i] - rock.positions[i]), 1e-6f) << i;
        EXPECT_LT(glm::length(back.base_color - rock.base_color), 1e-6f);
    }
}

TEST(GltfMeshIo, StarterAssetsAreWrittenAndReloaded) {
    const std::string dir = test::tempPath("starter");
    std::string error;
    ASSERT_TRUE(writeStarterAssets(dir, &error)) << error;
    for (const std::string& name : starterAssetNames()) {
        TriangleMesh mesh;
        ASSERT_TRUE(loadMeshFile(dir + "/" + name + ".glb", &mesh, &error)) << error;
        EXPECT_GE(mesh.triangleCount(), 200u) << name;
        EXPECT_LE(mesh.triangleCount(), 3000u) << name;
    }
}

TEST(GltfMeshIo, MissingGarbageAndNoTrianglesAreErrorsNamingTheFile) {
    TriangleMesh mesh;
    std::string error;
    const std::string missing = test::tempPath("does_not_exist.glb");
    EXPECT_FALSE(loadMeshFile(missing, &mesh, &error));
    expectContains(error, missing);
    expectContains(error, "no such file");

    const std::string garbage = test::tempPath("garbage.gltf");
    test::writeText(garbage, "{ this is not json");
    EXPECT_FALSE(loadMeshFile(garbage, &mesh, &error));
    expectContains(error, garbage);
    expectContains(error, "parse error");

    const std::string empty = test::tempPath("no_triangles.gltf");
    test::writeText(empty, R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[]}],"scene":0})");
    EXPECT_FALSE(loadMeshFile(empty, &mesh, &error));
    expectContains(error, empty);
    expectContains(error, "no triangles");
}

TEST(GltfMeshIo, TruncatedGlbNeverCrashesAndAlwaysExplains) {
    const TriangleMesh cube = test::unitCube();
    const std::string full = test::tempPath("full.glb");
    std::string error;
    ASSERT_TRUE(writeGltfMeshes(full, {{"cube", &cube}}, &error)) << error;
    const std::vector<char> bytes = readAll(full);
    const std::string cut = test::tempPath("truncated.glb");
    for (size_t length = 0; length < bytes.size(); length += (length < 64 ? 1 : 7)) {
        std::ofstream(cut, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(length));
        TriangleMesh mesh;
        error.clear();
        EXPECT_FALSE(loadGltfMesh(cut, &mesh, &error)) << length;
        expectContains(error, cut);
    }
}

TEST(GltfMeshIo, NaNPositionsAreRejected) {
    TriangleMesh mesh = test::unitCube();
    mesh.positions[3].x = std::nanf("");
    std::string error;
    const std::string path = test::tempPath("nan.glb");
    EXPECT_FALSE(writeGltfMeshes(path, {{"nan", &mesh}}, &error));
    expectContains(error, path);
    expectContains(error, "non-finite");
}

TEST(MeshLoader, TetrahedronInObjOffStlPly) {
    const std::string obj = test::tempPath("tet.obj"), off = test::tempPath("tet.off"),
                      stl = test::tempPath("tet.stl"), ply = test::tempPath("tet.ply");
    test::writeText(obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n");
    test::writeText(off, "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n");
    test::writeText(ply,
                    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
                    "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n");
    const char* stl_text =
        "solid tet\n"
        "facet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
        "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
        "facet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\n"
        "facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n"
        "endsolid tet\n";
    test::writeText(stl, stl_text);
    for (const std::string& path : {obj, off, stl, ply}) {
        TriangleMesh mesh;
        std::string error;
        ASSERT_TRUE(loadMeshFile(path, &mesh, &error)) << error;
        EXPECT_EQ(mesh.triangleCount(), 4u) << path;
        EXPECT_EQ(mesh.positions.size(), 4u) << path;
        EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
        const Bounds3 b = meshBounds(mesh);
        EXPECT_EQ(b.max, glm::vec3(1.0f)) << path;
    }
}

TEST(MeshLoader, QuadIsTriangulated) {
    const std::string obj = test::tempPath("quad.obj");
    test::writeText(obj, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    TriangleMesh mesh;
    std::string error;
    ASSERT_TRUE(loadMeshFile(obj, &mesh, &error)) << error;
    EXPECT_EQ(mesh.triangleCount(), 2u);
}

TEST(MeshLoader, BadFilesAreErrorsNamingTheFile) {
    TriangleMesh mesh;
    std::string error;
    const std::string garbage = test::tempPath("garbage.off");
    test::writeText(garbage, "\x01\x02 not an off file at all \xff\xfe");
    EXPECT_FALSE(loadMeshFile(garbage, &mesh, &error));
    expectContains(error, garbage);

    const std::string points_only = test::tempPath("points_only.obj");
    test::writeText(points_only, "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    EXPECT_FALSE(loadMeshFile(points_only, &mesh, &error));
    expectContains(error, points_only);

    const std::string nan = test::tempPath("nan.obj");
    test::writeText(nan, "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_FALSE(loadMeshFile(nan, &mesh, &error));
    expectContains(error, nan);

    const std::string unknown = test::tempPath("mesh.xyz");
    test::writeText(unknown, "1 2 3\n");
    EXPECT_FALSE(loadMeshFile(unknown, &mesh, &error));
    expectContains(error, "unsupported");
}

}  // namespace ug
