// What the renderer draws, prepared on the CPU and free of GL: detail meshes with their levels of detail;
// the instances resident per tile (each (tile, detail type) owns a slot of the type's instance buffer, so a
// live result re-packs and re-uploads only the tiles it changed); and per view the indirect draw commands
// (frustum culling and LOD choice per tile, one command per visible tile and type, grouped by type and LOD
// for one multi-draw each).
//
// GPU instance format (8 bytes, docs/architecture.md "Rendering"): an instance is (tile t, candidate j, drop
// d), packed as
//   x = uint16(t.x) | uint16(t.y) << 16,   y = uint9(t.z) | j << 9 | c << 25
// so t.x and t.y must lie in [-32768, 32767] (±16 km with 0.5 m tiles), t.z in [-256, 255] (±128 m), a
// Ghost Tile may hold at most 65,536 candidates, and the drop is c in [0, 127] steps of drop_unit_m
// (max_drop / 127: 4 mm for the default 0.5 m; rounded down, so an instance is drawn at most one step
// above where the engine settled it, never inside what it rests on). The vertex shader sign-extends the
// tile coordinates, reads candidate j's frame (position in the tile, rotation, scale) from a buffer
// uploaded once, and rebuilds the world transform
//   world(v) = tileOrigin(t, s) + p_j + R_j (scale_j v) - (0, 0, c drop_unit_m).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "editor/coverage.h"
#include "editor/tile_slots.h"
#include "ghosttile/ghost_tile.h"
#include "instancer/instance_store.h"
#include "io/mesh_instances.h"
#include "instancer/settling.h"
#include "material/material.h"
#include "mesh/detail_model.h"
#include "scene/detail_looks.h"

namespace ug::editor {

// LODs 0..2 are meshes (0 = the model, 1 and 2 simplified by meshoptimizer); LOD 3 is the far
// representation: one point sprite per instance (no triangles), as wide as the model's mean projected size.
constexpr int kMeshLodCount = 3;
constexpr int kLodCount = kMeshLodCount + 1;
constexpr int kImpostorLod = kMeshLodCount;
constexpr uint32_t kImpostorTriangles = 0;

constexpr int32_t kPackedTileLimit = 32767;       // |tile.x|, |tile.y| <= this
constexpr int32_t kPackedTileZMin = -256, kPackedTileZMax = 255;
constexpr uint32_t kPackedCandidateLimit = 65536;  // candidate ids < this
constexpr uint32_t kPackedDropSteps = 127;         // drop codes 0..127

struct PackedInstance {
    uint32_t x = 0;  // uint16(tile.x) | uint16(tile.y) << 16
    uint32_t y = 0;  // uint9(tile.z) | candidate << 9 | drop code << 25
};
static_assert(sizeof(PackedInstance) == 8);

// Contract: tile within the limits above, candidate < kPackedCandidateLimit, drop_code <= kPackedDropSteps.
PackedInstance packInstance(const glm::ivec3& tile, uint32_t candidate, uint32_t drop_code = 0);
void unpackInstance(PackedInstance packed, glm::ivec3* tile, uint32_t* candidate, uint32_t* drop_code = nullptr);
// The GPU step for settled drops of up to max_drop_m (0 when nothing settles).
float packedDropUnit(bool settling, float max_drop_m);
// The code of a drop: rounded down to a step, at most kPackedDropSteps.
uint32_t packedDropCode(float drop_m, float drop_unit_m);

// Where LODs switch: by the size an object of the type covers on screen, in pixels (the bounding
// diameter at its largest scale). Below `impostor_px` a type is drawn as impostors, through a band in
// which instances switch one by one (drawnAsMesh) rather than a whole ring of tiles at once.
struct LodSettings {
    float lod1_px = 120.0f;
    float lod2_px = 50.0f;
    float impostor_px = 10.0f;
};

// How the viewport lights the scene (the Render panel's toggles, `edit` and `render` --no-shadows and
// --no-ao). View state, never saved with a scene.
struct ViewportLook {
    bool shadows = true;            // the sun's shadow map
    bool ambient_occlusion = true;  // screen-space, where surfaces meet
    // 4096: at 2048 a close-up's texels (3.3 mm for the meadow seen from 1.5 m) were as wide as a grass
    // blade, whose shadow broke into dotted runs; the still frames took no longer (a still view draws the
    // map once), and neither did an orbit redrawing it.
    int shadow_map_px = 4096;
};

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
    // The model's silhouette area at scale 1 seen from 0, 30, 60 and 90 degrees of elevation (coverage.h):
    // an impostor is a disc of that area, so far details cover the screen as their meshes would.
    std::array<float, 4> coverage_m2{};
    // The area-weighted mean |n.z| of the model's faces: 1 for a flat leaf, about 0.5 for a rock, near 0
    // for a tuft of upright blades. The impostor is lit with a normal tilted that far from the model's up
    // toward the viewer, so a far tuft is as dark as its blades, not lit like a lawn seen from above.
    float upness = 1.0f;
    // The impostor sprite: silhouettes from 0, 30, 60 and 90 degrees (coverage.h, azimuth 0), across a
    // square of side 2 sprite_radius_m around sprite_centre (model space, scale 1).
    SilhouetteMasks silhouettes;
    // Where this type switches to impostors, as a multiple of LodSettings::impostor_px: above 1 for a
    // model whose coarsest faithful mesh is still heavy (a grass tuft keeps ~1,000 triangles, since its
    // blades are thinner than any simplification that saves triangles), so it hands over to its
    // silhouette sprite while the sprite is still large enough to show the blades.
    float impostor_scale = 1.0f;
    float impostorPx(const LodSettings& lod) const { return lod.impostor_px * impostor_scale; }
    // The bounding diameter at the largest scale, in pixels at 1 m: what the LOD choice divides by the
    // distance (buildIndirectDraws on the CPU, u_lod_diameter_px in the shaders).
    float lodDiameterPx(float pixels_per_radian) const { return 2.0f * radius_m * scale_max * pixels_per_radian; }
    float scale_max = 1.0f;                  // the type's largest candidate scale
    // How the type looks (material.h): `color` is its base colour; a texture (final colour, sRGB) is
    // mapped by box projection of the model-space position, as the exporter maps it.
    SurfaceMaterial material;

    uint32_t triangles(int lod) const {
        return lod == kImpostorLod ? kImpostorTriangles : index_count[size_t(lod)] / 3;
    }
};

// Builds LOD 0 (the model, vertex-cache optimised), LOD 1 (meshopt_simplify to ~20 % of the triangles
// with a 2 % error bound) and LOD 2 (meshopt_simplifySloppy to ~24 triangles): simplification never
// fails, a mesh that cannot shrink keeps its previous level, and so does a level whose silhouette area
// (coverage.h) differs from the model's by more than kLodCoverageTolerance at any elevation.
constexpr float kLodCoverageTolerance = 0.2f;
constexpr uint32_t kImpostorBudgetTriangles = 100;
DetailLodMesh buildDetailLods(const DetailModel& model, float scale_max);

// The largest scale among a type's candidates, at least 1 (a type without candidates: 1).
float candidateScaleMax(const CandidateSet& candidates, size_t type);
// Every detail type's LOD meshes (buildDetailLods), in type order, each with its candidates' largest scale
// and, when `looks` is given (Document::materials()), its material (and colour = the material's base).
std::vector<DetailLodMesh> buildTypeMeshes(const std::vector<DetailModel>& models, const CandidateSet& candidates,
                                           const SceneMaterials* looks = nullptr);
// The same for every look (scene/detail_looks.h: the types', then their scatter variants'), a variant with
// its type's largest scale; `materials` holds one per look (Document::materials()).
std::vector<DetailLodMesh> buildLookMeshes(const DetailLooks& looks, const CandidateSet& candidates,
                                           const SceneMaterials* materials);

// The instances as they live on the GPU: per detail type one instance array (the CPU mirror of the
// type's GPU buffer) in which every resident tile owns a slot (tile_slots.h). A live result rewrites only
// the slots of the tiles it changed and records them as uploads; nothing else moves. Tiles are resident
// when they hold instances; a tile that empties gives its slots back.
struct ResidentTiles {
    struct Type {
        TileSlotAllocator slots;
        std::vector<PackedInstance> mirror;  // allocator.capacity() elements; slot ranges hold instances
    };
    uint32_t type_count = 0;
    float tile_size_m = 0.5f;
    float drop_unit_m = 0.0f;           // packedDropUnit: the shader's step for drop codes
    std::vector<uint64_t> tile_key;     // per resident tile (packed, tile_coord.h)
    std::vector<glm::ivec3> tile_coord;
    std::vector<TileSlot> slot;         // per tile x type (tile * type_count + type)
    std::vector<uint32_t> count;        // per tile x type: instances in the slot
    std::unordered_map<uint64_t, uint32_t> tile_index;  // key -> resident tile
    std::vector<Type> types;
    std::vector<uint64_t> instances_per_type;
    uint64_t instanceCount() const;
    size_t tileCount() const { return tile_key.size(); }
};

// What an update changed, for the renderer to upload: per type the slot ranges written (in instances),
// or the whole mirror when the type's array was reallocated.
struct TileUploads {
    struct Range {
        uint32_t offset = 0, count = 0;
    };
    struct Type {
        bool whole = false;  // upload mirror[0, capacity) (the array grew or was rebuilt)
        std::vector<Range> ranges;
    };
    std::vector<Type> types;
    std::vector<glm::ivec3> tiles;  // the tiles whose slots were written or released
    bool full = false;
    uint64_t tiles_uploaded = 0;    // tiles.size()
    uint64_t bytes_uploaded = 0;    // bytes the renderer will send (whole arrays counted whole)
    void clear();
};

// Fails (with the reason) when a tile or a candidate id does not fit the packed format. Leaves *out as it
// was on failure. Rebuilds everything: tiles in key order, packed tightly (SlotFit::Exact).
// `drops` (optional): the store's settled drops, packed with drop_unit_m (packedDropUnit).
// `looks` (optional, with variants): the arrays are per look instead of per type, each instance in its
// look's (DetailLooks::lookOf at its candidate's origin).
bool rebuildResidentTiles(const InstanceStore& store, const SettledDrops* drops, const CandidateSet& candidates,
                          float tile_size_m, float drop_unit_m, ResidentTiles* out, TileUploads* uploads,
                          std::string* error, const DetailLooks* looks = nullptr);
// Re-packs only the tiles in `changed_keys` (packed tile keys, any order) from `store`: a tile whose
// instances fit its slots is rewritten in place, one that outgrew a slot moves to a new one
// (SlotFit::Rounded), one the store no longer holds is dropped. `out` must have been rebuilt from the
// same candidates. On failure (a tile out of the packed range) *out may be partly updated; rebuild it.
bool updateResidentTiles(const InstanceStore& store, const SettledDrops* drops, const CandidateSet& candidates,
                         const std::vector<uint64_t>& changed_keys, ResidentTiles* out, TileUploads* uploads,
                         std::string* error, const DetailLooks* looks = nullptr);


// The mesh-to-impostor switch, per instance: an instance whose bounding diameter covers `px` pixels is
// drawn as a mesh when px >= impostor_px (1 + kImpostorBand u), u in [0, 1) hashed from the instance
// (instanceHash), so across the band the share of meshes falls smoothly from 1 to 0. The vertex shaders
// (instanced_detail.vert, detail_impostor.vert) evaluate the same rule on the same hash; a tile is drawn
// in both representations when its instances' sizes reach into the band (buildIndirectDraws), and each
// shader then drops the instances that belong to the other.
constexpr float kImpostorBand = 0.6f;
uint32_t instanceHash(PackedInstance packed);
inline float instanceHashUnit(PackedInstance packed) { return float(instanceHash(packed) & 1023u) / 1024.0f; }
inline bool drawnAsMesh(float px, float impostor_px, float u) { return px >= impostor_px * (1.0f + kImpostorBand * u); }

struct ViewParams {
    glm::mat4 view_proj{1.0f};
    glm::vec3 eye{0.0f};
    float pixels_per_radian = 1.0f;  // viewport height / vertical field of view
    // Pixels per metre at unit depth (detail_impostor.vert's u_point_scale): with it, far tiles whose
    // points are all one pixel draw a share of them (pointStride); 0 draws every point.
    float point_scale = 0.0f;
    // Shadow casters (the sun's view): with cull_by_receiver, a cell is kept only when its shadow, the cell
    // swept along shadow_sweep (down the sun's rays, to the bottom of the scene), can reach the camera's
    // view `receiver_view_proj`. The sun's square covers the whole box around what the camera sees; the
    // casters in its corners throw their shadows off screen.
    bool cull_by_receiver = false;
    glm::mat4 receiver_view_proj{1.0f};
    glm::vec3 shadow_sweep{0.0f};
};

// The GL indirect command layouts (GL 4.3 "DrawElementsIndirectCommand", "DrawArraysIndirectCommand").
struct DrawElementsIndirectCommand {
    uint32_t count = 0;           // indices of the LOD
    uint32_t instance_count = 0;  // instances of the tile (or run of tiles) at this LOD
    uint32_t first_index = 0;     // the LOD's first index
    int32_t base_vertex = 0;
    uint32_t base_instance = 0;   // slot offset: where the tile's instances start in the type's buffer
};
struct DrawArraysIndirectCommand {
    uint32_t count = 0;           // impostors: one point per drawn instance
    uint32_t instance_count = 1;
    uint32_t first = 0;           // always 0: gl_VertexID counts the command's points
    uint32_t base_instance = 0;   // the command's PointRun (a per-instance attribute, read once)
};

// Which instances a point command draws: its i-th point is instance offset + i * stride of the type's
// buffer (detail_impostor.vert). A stride above 1 draws one instance in `stride` of a far run, each kept
// with `stride` times the probability of the one-pixel point it stands for, so the expected coverage is
// the same (pointStride) for a fraction of the vertices: llvmpipe shades vertices on one thread.
struct PointRun {
    uint32_t offset = 0;  // the run's first instance (slot offset)
    uint32_t stride = 1;
    uint32_t span = 0;    // instances the run covers (it draws ceil(span / stride) points)
};
constexpr uint32_t kMaxPointStride = 64;
// The largest power of two, at most kMaxPointStride, by which the points of a type seen at most
// `px_per_m` pixels per metre can be thinned: every point there is one pixel (its sprite under 2 px at
// the largest scale) and stride times its largest area, over the elevations, is at most one pixel. 1 when
// some point there may be a sprite.
uint32_t pointStride(const DetailLodMesh& mesh, float px_per_m);
static_assert(sizeof(DrawElementsIndirectCommand) == 20 && sizeof(DrawArraysIndirectCommand) == 16);

// One frame's indirect draws: a command per visible (tile, type) at the tile's LOD, grouped by (type, LOD)
// so each group is one multi-draw. Commands of tiles whose slots are adjacent in the buffer merge into one
// (a tight rebuild lays neighbouring tiles out in key order). Vectors keep their capacity across frames.
struct IndirectDraws {
    struct Group {
        uint32_t first = 0;      // into `elements` (mesh LODs) or `points` (kImpostorLod)
        uint32_t count = 0;      // commands
        uint64_t instances = 0;  // instances the commands draw
    };
    std::vector<DrawElementsIndirectCommand> elements;  // type 0 LOD 0..2, type 1 LOD 0..2, ...
    std::vector<DrawArraysIndirectCommand> points;      // type 0, type 1, ...
    std::vector<PointRun> point_runs;                   // beside `points`: command k reads run k
    std::vector<std::array<Group, kLodCount>> groups;   // per type
    std::array<std::vector<DrawElementsIndirectCommand>, kMeshLodCount> scratch;  // per LOD, reused
    std::vector<float> tile_distance;                   // per resident tile; < 0: culled
    std::vector<float> tile_point_px;                   // per visible tile: most pixels per metre (0: no bound)
    uint64_t tiles_visible = 0;
    uint64_t tiles_culled = 0;
    uint64_t commandCount() const { return elements.size() + points.size(); }
};

// Frustum culling per tile (the cell grown by the largest object's reach) and one LOD per tile and type
// from the tile's distance to the eye; then the commands.
void buildIndirectDraws(const ResidentTiles& tiles, const std::vector<DetailLodMesh>& meshes,
                        const ViewParams& view, const LodSettings& lod, IndirectDraws* out);

// ---- Static meshes (io/mesh_instances.h: the terrain-like geometry of environmental objects, snow,
// icicles): one mesh drawn at its instances by glDrawElementsInstanced, culled per entry. ----

// One instance as static_mesh.vert reads it (two vec4 per-instance attributes): world =
// position + rotate(rotation, scale * v); the normal is rotate(rotation, n) (uniform scale).
struct GpuStaticInstance {
    glm::vec4 position_scale{0.0f, 0.0f, 0.0f, 1.0f};  // xyz: engine-space position, w: uniform scale
    glm::vec4 rotation{0.0f, 0.0f, 0.0f, 1.0f};        // unit quaternion (x, y, z, w), renormalized
};
static_assert(sizeof(GpuStaticInstance) == 32);

// The entry's instances packed for the GPU; no instances: one at the identity (MeshInstances' rule).
std::vector<GpuStaticInstance> packStaticInstances(const MeshInstances& entry);
// The model matrix an instance stands for (what the shader computes, for tests and CPU-side checks).
glm::mat4 staticInstanceMatrix(const GpuStaticInstance& instance);

// Engine-space box of the whole entry: the union over its instances of the mesh's object-space box turned
// by each instance (exact for the box: centre moved, half extents through |R| s). Empty without a mesh
// or vertices.
Bounds staticMeshBounds(const MeshInstances& entry);
// The engine-space box of an object-space box turned by one instance (exact for the box: centre moved,
// half extents through |R| s). Empty in, empty out.
Bounds staticInstanceBox(const GpuStaticInstance& instance, const Bounds& local);
// The union over a list (empty list: the empty box).
Bounds staticMeshesBounds(const std::vector<MeshInstances>& meshes);

// An entry's instances grouped into square XY chunks (chunk (floor(x / chunk_m), floor(y / chunk_m)) of the
// instance's position; sorted by (ix, iy), input order within a chunk), each with the box of its instances:
// the renderer culls the entry by `bounds`, then each chunk, and draws the runs of visible chunks (so
// thousands of icicles spread over a scene cost what the view holds). No mesh: nothing.
constexpr float kStaticChunkM = 8.0f;
struct StaticInstanceChunks {
    struct Chunk {
        uint32_t first = 0, count = 0;  // into `instances`
        Bounds bounds;
        float scale_max = 0.0f;  // the largest instance scale (what the LOD choice scales errors by)
    };
    std::vector<GpuStaticInstance> instances;
    std::vector<Chunk> chunks;
    Bounds bounds;  // staticMeshBounds
};
StaticInstanceChunks chunkStaticInstances(const MeshInstances& entry, float chunk_m = kStaticChunkM);
// False when `box` is wholly outside the view-projection's frustum (the tiles' test); the empty box is
// never visible.
bool boxInFrustum(const glm::mat4& view_proj, const Bounds& box);

}  // namespace ug::editor
