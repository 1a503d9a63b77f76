// What the renderer draws, prepared on the CPU and free of GL: detail meshes with their levels of detail,
// the instances packed for the GPU and grouped by Ghost Tile cell, and per frame the visible instances
// bucketed by detail type and LOD (frustum culling and LOD choice per tile).
//
// GPU instance format (8 bytes, DESIGN.md "Rendering"): an instance is (tile t, candidate j), packed as
//   x = uint16(t.x) | uint16(t.y) << 16,   y = uint16(t.z) | j << 16
// so tile coordinates must lie in [-32768, 32767] (±16 km with 0.5 m tiles) and a Ghost Tile may hold at
// most 65,536 candidates. The vertex shader sign-extends the tile coordinates, reads candidate j's frame
// (position in the tile, rotation, scale) from a buffer uploaded once, and rebuilds the world transform
//   world(v) = tileOrigin(t, s) + p_j + R_j (scale_j v).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "ghosttile/ghost_tile.h"
#include "instancer/instance_store.h"
#include "mesh/detail_model.h"

namespace ug::editor {

// LODs 0..2 are meshes (0 = the model, 1 and 2 simplified by meshoptimizer); LOD 3 is the far
// representation: one point sprite per instance (no triangles), as wide as the model's mean projected size.
constexpr int kMeshLodCount = 3;
constexpr int kLodCount = kMeshLodCount + 1;
constexpr int kImpostorLod = kMeshLodCount;
constexpr uint32_t kImpostorTriangles = 0;

constexpr int32_t kPackedTileLimit = 32767;     // |tile coordinate| <= this
constexpr uint32_t kPackedCandidateLimit = 65536;  // candidate ids < this

struct PackedInstance {
    uint32_t x = 0;  // uint16(tile.x) | uint16(tile.y) << 16
    uint32_t y = 0;  // uint16(tile.z) | candidate << 16
};
static_assert(sizeof(PackedInstance) == 8);

// Contract: |tile| <= kPackedTileLimit on every axis, candidate < kPackedCandidateLimit.
PackedInstance packInstance(const glm::ivec3& tile, uint32_t candidate);
void unpackInstance(PackedInstance packed, glm::ivec3* tile, uint32_t* candidate);

// One detail type's mesh at every mesh LOD: one vertex array, the LODs' index ranges one after the other.
struct DetailLodMesh {
    std::string name;
    glm::vec3 color{0.6f};                   // linear RGB
    std::vector<glm::vec3> positions;        // model space, metres, Z up
    std::vector<glm::vec3> normals;
    std::vector<uint32_t> indices;           // LOD 0, then LOD 1, then LOD 2
    std::array<uint32_t, kMeshLodCount> index_first{};
    std::array<uint32_t, kMeshLodCount> index_count{};
    float radius_m = 0.0f;                   // bounding radius about the model origin
    glm::vec3 center{0.0f};                  // bounding box centre (the impostor's centre)
    float impostor_half_size_m = 0.0f;       // half the side of a square with the mean projected area
    float scale_max = 1.0f;                  // the type's largest candidate scale

    uint32_t triangles(int lod) const {
        return lod == kImpostorLod ? kImpostorTriangles : index_count[size_t(lod)] / 3;
    }
};

// Builds LOD 0 (the model, vertex-cache optimised), LOD 1 (meshopt_simplify to ~20 % of the triangles
// with a 2 % error bound) and LOD 2 (meshopt_simplifySloppy to ~24 triangles): simplification never
// fails, a mesh that cannot shrink keeps its previous level.
DetailLodMesh buildDetailLods(const DetailModel& model, float scale_max);

// The instances grouped by Ghost Tile cell, and inside a cell by detail type (candidate ids of a type are
// contiguous in the Ghost Tile, so the store's ascending ids already are grouped).
struct RenderInstances {
    uint32_t type_count = 0;
    float tile_size_m = 0.5f;
    std::vector<glm::ivec3> tile_coord;           // per cell
    std::vector<uint32_t> tile_type_begin;        // per cell, type_count + 1 offsets into `instances`
    std::vector<PackedInstance> instances;
    std::vector<uint64_t> instances_per_type;
    uint64_t instanceCount() const { return instances.size(); }
};

// Fails (with the reason) when a tile or a candidate id does not fit the packed format.
bool buildRenderInstances(const InstanceStore& store, const CandidateSet& candidates, float tile_size_m,
                          RenderInstances* out, std::string* error);

// Where LODs switch: by the size an object of the type covers on screen, in pixels (the bounding
// diameter at its largest scale). Below `impostor_px` a type is drawn as impostors.
struct LodSettings {
    float lod1_px = 90.0f;
    float lod2_px = 30.0f;
    float impostor_px = 10.0f;
};

struct ViewParams {
    glm::mat4 view_proj{1.0f};
    glm::vec3 eye{0.0f};
    float pixels_per_radian = 1.0f;  // viewport height / vertical field of view
};

// The visible instances of one frame: per type, the instances of LOD 0, 1, 2 and impostors, one after
// the other (`lod_first`, `lod_count` index into `instances`). Vectors keep their capacity across frames.
struct DrawBuckets {
    struct Type {
        std::vector<PackedInstance> instances;
        std::array<uint32_t, kLodCount> lod_first{};
        std::array<uint32_t, kLodCount> lod_count{};
    };
    std::vector<Type> types;
    std::array<std::vector<PackedInstance>, kLodCount> scratch;  // per-LOD staging, reused
    std::vector<float> tile_distance;                            // per cell; < 0: culled
    uint64_t tiles_visible = 0;
    uint64_t tiles_culled = 0;
};

// Frustum culling per tile (the cell grown by the largest object's reach) and one LOD per tile and type
// from the tile's distance to the eye.
void bucketInstances(const RenderInstances& instances, const std::vector<DetailLodMesh>& meshes,
                     const ViewParams& view, const LodSettings& lod, DrawBuckets* out);

}  // namespace ug::editor
