// Writes sample scene exports for the independent glTF checks (run_gltf_checks.sh):
//
//   write_sample_export DIR
//
// creates DIR if needed, writes the samples, and prints one line per file: "<file name> <instances>
// <types>", where <instances> is every mesh copy the file draws (detail instances, plus one for a
// terrain and for each static mesh copy) as check_gltf.mjs counts them, and <types> the number of detail
// types; the samples with materials or static meshes add "<images> <textured materials>": the distinct
// texture images the file must hold and the materials with a baseColorTexture. The static-mesh samples
// (io/mesh_instances.h) add a mesh at the identity with extras and an instanced, textured one.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "core/hash.h"
#include "field/height_field.h"
#include "io/gltf_scene_export.h"
#include "material/material.h"
#include "mesh/procedural_models.h"
#include "mesh/terrain_mesh.h"

namespace {

using namespace ug;

// Deterministic values in [0, 1) without a generator state: the same samples on every machine.
float unit(uint64_t seed, uint64_t i, uint64_t k) {
    return unitFloat(hashWords(seed, i, k));
}

std::vector<InstanceTransform> scatter(size_t count, float half_extent_m, uint64_t seed) {
    std::vector<InstanceTransform> out(count);
    for (size_t i = 0; i < count; ++i) {
        InstanceTransform& inst = out[i];
        inst.position = glm::vec3((unit(seed, i, 0) * 2.0f - 1.0f) * half_extent_m,
                                  (unit(seed, i, 1) * 2.0f - 1.0f) * half_extent_m, unit(seed, i, 2) * 0.5f);
        const glm::vec3 axis =
            glm::normalize(glm::vec3(unit(seed, i, 3) - 0.5f, unit(seed, i, 4) - 0.5f, 1.0f));
        inst.rotation = glm::angleAxis(unit(seed, i, 5) * 6.2831853f, axis);
        inst.scale = 0.7f + 0.6f * unit(seed, i, 6);
    }
    return out;
}

struct Sample {
    std::string file;
    bool extension = true;
    bool terrain = false;
    size_t per_type = 0;
    bool materials = false;
    bool statics = false;  // two static meshes (SceneExport::meshes)
};

Material makeMaterial(glm::vec3 color, TextureKind texture, float scale_m, float tint, bool cutout) {
    Material m;
    m.base_color = color;
    m.roughness = 0.8f;
    m.texture = texture;
    m.texture_scale_m = scale_m;
    m.tint_variation = tint;
    m.alpha_cutout = cutout;
    return m;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: write_sample_export DIR\n");
        return 2;
    }
    const std::string dir = argv[1];
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) {
        std::fprintf(stderr, "%s: cannot create the folder: %s\n", dir.c_str(), ec.message().c_str());
        return 1;
    }

    // The material samples add a pebble with the rock's material (the same image, written once) and put a
    // cut-out leaf, bark and a ground texture on the terrain: 4 distinct images, 5 textured materials.
    const std::vector<std::string> names = {"rock", "leaf_oak", "twig", "pebble"};
    const size_t plain_types = 3;  // the samples without materials keep their first three types
    const glm::vec3 stone(0.36f, 0.33f, 0.29f);
    const std::vector<Material> looks = {
        makeMaterial(stone, TextureKind::Rock, 0.12f, 0.35f, false),
        makeMaterial({0.42f, 0.24f, 0.08f}, TextureKind::Leaf, 0.103f, 0.4f, true),
        makeMaterial({0.25f, 0.17f, 0.10f}, TextureKind::Bark, 0.08f, 0.25f, false),
        makeMaterial(stone, TextureKind::Rock, 0.05f, 0.4f, false),
    };
    std::vector<TriangleMesh> meshes(names.size());
    for (size_t t = 0; t < names.size(); ++t) {
        if (!makeStarterAsset(names[t], kStarterAssetSeed, &meshes[t])) {
            std::fprintf(stderr, "unknown starter asset %s\n", names[t].c_str());
            return 1;
        }
    }

    ProceduralTerrainDesc desc;
    desc.origin_m = glm::vec2(-20.0f);
    desc.cell_size_m = 0.5f;
    desc.width = desc.height = 81;
    HeightField hf;
    TriangleMesh ground;
    std::string error;
    if (!makeProceduralHeightField(desc, &hf, &error) ||
        !heightFieldMesh(hf, Bounds::everything(), 64, &ground, &error)) {
        std::fprintf(stderr, "terrain: %s\n", error.c_str());
        return 1;
    }

    std::vector<SurfaceMaterial> surfaces;
    for (size_t t = 0; t < names.size(); ++t) surfaces.push_back(resolveMaterial(looks[t], meshes[t].base_color));
    const SurfaceMaterial ground_look =
        resolveMaterial(makeMaterial(kTerrainColor, TextureKind::Ground, 0.5f, 0.0f, false), kTerrainColor);
    const size_t images = 4, textured_materials = 5;

    const Sample samples[] = {
        {"instanced.glb", true, false, 2000},
        {"instanced.gltf", true, false, 700},
        {"plain_nodes.glb", false, false, 150},
        {"with_terrain.glb", true, true, 500},
        {"materials.glb", true, true, 400, true},
        {"materials.gltf", true, true, 120, true},
        {"materials_plain_nodes.glb", false, true, 60, true},
        {"static_meshes.glb", true, true, 100, false, true},
        {"static_meshes_plain_nodes.gltf", false, true, 40, false, true},
    };
    // The static meshes: a "bench" (the rock mesh, one copy at the identity, with extras) and 300 textured
    // "icicles" (the twig mesh with the rock's material: one image, one textured material).
    const auto bench_mesh = std::make_shared<const TriangleMesh>(meshes[0]);
    const auto icicle_mesh = std::make_shared<const TriangleMesh>(meshes[2]);
    const auto icicle_look = std::make_shared<const SurfaceMaterial>(surfaces[0]);
    const size_t icicle_count = 300;
    for (const Sample& sample : samples) {
        SceneExport scene;
        scene.delta_m = 0.01f;
        scene.chunk_size_m = 8.0f;
        scene.use_instancing_extension = sample.extension;
        scene.terrain = sample.terrain ? &ground : nullptr;
        if (sample.materials) scene.terrain_material = &ground_look;
        const size_t type_count = sample.materials ? names.size() : plain_types;
        scene.scene_extras_json =
            R"({"sample": ")" + sample.file + R"(", "generator": "write_sample_export"})";
        for (size_t t = 0; t < type_count; ++t) {
            ExportDetailType type;
            type.name = names[t];
            type.mesh = &meshes[t];
            type.collision_spheres = {{glm::vec3(0.0f), 0.05f}};
            type.instances = scatter(sample.per_type, 20.0f, 100 + t);
            if (sample.materials) type.material = &surfaces[t];
            scene.types.push_back(std::move(type));
        }
        if (sample.statics) {
            MeshInstances bench;
            bench.name = "env/bench";
            bench.mesh = bench_mesh;
            bench.extras_json = R"({"kind": "bench"})";
            MeshInstances icicles;
            icicles.name = "icicles/shape_0";
            icicles.mesh = icicle_mesh;
            icicles.material = icicle_look;
            icicles.instances = scatter(icicle_count, 20.0f, 900);
            scene.meshes = {bench, icicles};
        }
        const std::string path = dir + "/" + sample.file;
        if (!writeSceneGltf(path, scene, &error)) {
            std::fprintf(stderr, "%s\n", error.c_str());
            return 1;
        }
        const size_t static_copies = sample.statics ? 1 + icicle_count : 0;
        std::printf("%s %zu %zu", sample.file.c_str(),
                    sample.per_type * type_count + (sample.terrain ? 1 : 0) + static_copies, type_count);
        if (sample.materials) std::printf(" %zu %zu", images, textured_materials);
        else if (sample.statics) std::printf(" 1 1");
        std::printf("\n");
    }
    return 0;
}
