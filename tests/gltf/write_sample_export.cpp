// Writes sample scene exports for the independent glTF checks (run_gltf_checks.sh):
//
//   write_sample_export DIR
//
// creates DIR if needed, writes the samples, and prints one line per file: "<file name> <instances>
// <types>", where <instances> is every mesh copy the file draws (detail instances, plus one for a
// terrain) as check_gltf.mjs counts them, and <types> the number of detail types.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "core/hash.h"
#include "field/height_field.h"
#include "io/gltf_scene_export.h"
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
};

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

    const std::vector<std::string> names = {"rock", "leaf_oak", "twig"};
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

    const Sample samples[] = {
        {"instanced.glb", true, false, 2000},
        {"instanced.gltf", true, false, 700},
        {"plain_nodes.glb", false, false, 150},
        {"with_terrain.glb", true, true, 500},
    };
    for (const Sample& sample : samples) {
        SceneExport scene;
        scene.delta_m = 0.01f;
        scene.chunk_size_m = 8.0f;
        scene.use_instancing_extension = sample.extension;
        scene.terrain = sample.terrain ? &ground : nullptr;
        scene.scene_extras_json =
            R"({"sample": ")" + sample.file + R"(", "generator": "write_sample_export"})";
        for (size_t t = 0; t < names.size(); ++t) {
            ExportDetailType type;
            type.name = names[t];
            type.mesh = &meshes[t];
            type.collision_spheres = {{glm::vec3(0.0f), 0.05f}};
            type.instances = scatter(sample.per_type, 20.0f, 100 + t);
            scene.types.push_back(std::move(type));
        }
        const std::string path = dir + "/" + sample.file;
        if (!writeSceneGltf(path, scene, &error)) {
            std::fprintf(stderr, "%s\n", error.c_str());
            return 1;
        }
        std::printf("%s %zu %zu\n", sample.file.c_str(),
                    sample.per_type * names.size() + (sample.terrain ? 1 : 0), names.size());
    }
    return 0;
}
