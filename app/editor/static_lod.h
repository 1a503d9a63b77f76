// Levels of detail for the renderer's static meshes (io/mesh_instances.h: environmental objects, their snow,
// icicles, terrain snow chunks), GL-free. At upload each entry's mesh gets up to three coarser levels from
// meshoptimizer, each with the error it made (metres, object space); a large entry drawn once (a terrain snow
// chunk: 8 x 8 m, ~1 M triangles) is first split into spatial pieces (splitCellSize cells by triangle
// centroid) simplified one by one with their borders locked, so neighbouring pieces meet at any levels.
// Per frame every visible piece (split entries) or 8 m instance chunk (render_data.h chunkStaticInstances)
// is drawn at the coarsest level whose error projects below kStaticLodErrorPx at the chunk's nearest
// distance to the eye, or not at all when the whole mesh projects below kStaticSkipPx.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "editor/render_data.h"
#include "field/bounds.h"
#include "io/mesh_instances.h"
#include "material/material.h"
#include "mesh/triangle_mesh.h"

namespace ug::editor {

constexpr int kStaticLodLevels = 4;                 // level 0 (the mesh) and up to 3 simplified levels
constexpr float kStaticLodErrorPx = 1.0f;           // a level's error may cover up to this many pixels
constexpr float kStaticSkipPx = 0.5f;               // a chunk whose mesh covers less is not drawn
constexpr float kStaticLevelShrink = 0.5f;          // a level is kept at <= this share of the previous one's triangles
constexpr uint32_t kStaticSplitTriangles = 50'000;  // entries drawn once with more triangles are split
constexpr float kStaticCellM = 2.0f;                // the split's cell side (object-space XY), at least
constexpr uint32_t kStaticCellMinTriangles = 16'384;  // cells grow so that they hold about this many on average
// How much a level's shading error counts against its geometric one (StaticLodPiece::error_m). 1 keeps the
// winter scenes' pictures within 1 % of their pixels of the full meshes'; 0.5 draws montmartre_winter from
// --camera 0,-30,3,16,-60,12 in 0.89 s instead of 1.36 s (llvmpipe, 960 x 540) with 1.1 % instead of
// 0.96 % of its pixels off; 0 (geometry only) spreads flat cobble caps' rim normals over their tops (3 %).
constexpr float kStaticShadingWeight = 1.0f;

// One piece of a static mesh (the whole mesh, or a cell of a split one): its levels' index ranges in
// StaticLodMesh::indices (into the mesh's own vertices, so every level shares level 0's vertex buffer).
struct StaticLodPiece {
    Bounds bounds;  // object space: level 0's vertices
    uint32_t level_count = 1;
    std::array<uint32_t, kStaticLodLevels> first{};
    std::array<uint32_t, kStaticLodLevels> count{};  // indices
    // Object-space metres, the larger of two: the geometric error (meshoptimizer's relative error times the
    // piece's extent, summed over the levels it was simplified through, each from the previous one) and
    // the shading error (the level keeps level 0's normals: its widest triangle's width times the spread
    // of its corner normals, beyond level 0's own). Never below the previous level's. Level 0: 0.
    std::array<float, kStaticLodLevels> error_m{};
    uint32_t triangles(int level) const { return count[size_t(level)] / 3; }
};

struct StaticLodMesh {
    std::vector<uint32_t> indices;  // piece 0's levels 0..n, piece 1's, ...
    std::vector<StaticLodPiece> pieces;
    bool split = false;             // pieces are spatial cells (culled and chosen one by one)
    Bounds bounds;                  // object space: the union of the pieces' boxes
    float diameter() const { return bounds.empty() ? 0.0f : glm::length(bounds.hi - bounds.lo); }
};

// The triangles of `mesh` grouped by the XY cell of their centroid (floor(c / cell_m)), cells sorted by
// (ix, iy), triangle ids ascending within a cell: every triangle in exactly one cell. Empty mesh: none.
std::vector<std::vector<uint32_t>> splitTrianglesIntoCells(const TriangleMesh& mesh, float cell_m);

// The cell side a split of `mesh` uses: kStaticCellM, or larger where the mesh is sparse over its XY box
// (cells of about kStaticCellMinTriangles on average), so a wide mesh does not become thousands of draws.
float splitCellSize(const TriangleMesh& mesh);

// Level 0 is the piece's triangles as given (in their order, so near pictures are unchanged); each further
// level is meshopt_simplify of the previous one toward a quarter of its triangles under a growing error
// bound (relative 1 %, 3 %, 10 %, 30 %), borders locked (meshopt_SimplifyLockBorder: a snow patch keeps its
// rim on the object, a split piece meets its neighbours), kept only at <= kStaticLevelShrink of the previous
// level's triangles. `triangle_ids` (null: all) selects the piece's triangles. `scratch` (optional, reused
// across calls on one thread): a mesh-vertex-sized map, left all unset on return.
StaticLodPiece buildStaticLodPiece(const TriangleMesh& mesh, const std::vector<uint32_t>* triangle_ids,
                                   std::vector<uint32_t>* indices, std::vector<uint32_t>* scratch = nullptr);

// Whether an entry with `instance_count` instances (0: one copy at the identity) and `triangles` triangles
// is split into cells.
inline bool splitsStaticEntry(size_t instance_count, size_t triangles) {
    return instance_count <= 1 && triangles > kStaticSplitTriangles;
}

// Every mesh's levels (split[i]: as cells of splitCellSize), the pieces simplified in parallel on `threads`
// workers (0: all hardware threads); the result does not depend on the thread count.
std::vector<StaticLodMesh> buildStaticLodMeshes(const std::vector<const TriangleMesh*>& meshes,
                                                const std::vector<bool>& split, int threads);

// The levels an entry brings along (MeshInstances::lod_levels: strands through fewer of their points) as
// one piece over the whole mesh: level 0 the mesh, then as many of them as fit, each error at least the
// previous one's. Never split: the levels join every strand end to end, which cells would cut.
StaticLodMesh authoredStaticLod(const TriangleMesh& mesh, const std::vector<MeshLodLevel>& levels);

// The levels kept from one set of static meshes to the next, by mesh object: an environment edit swaps in
// the meshes it reached (a class's new snow) and keeps the others' objects (engine/env: updateEnvEffects
// reuses them), so only the new ones are simplified again. Results equal buildStaticLodMeshes's.
class StaticLodCache {
public:
    // Every mesh's levels; builds those of meshes (object and split flag) not in the previous call, and
    // forgets the meshes this call does not name. *built: how many were built. Shared, not copied: a
    // winter street's terrain snow has millions of indices.
    std::vector<std::shared_ptr<const StaticLodMesh>> levels(const std::vector<std::shared_ptr<const TriangleMesh>>& meshes,
                                                             const std::vector<bool>& split, int threads,
                                                             size_t* built = nullptr);

private:
    struct Kept {
        std::shared_ptr<const TriangleMesh> mesh;  // held, so its address names it while kept
        bool split = false;
        std::shared_ptr<const StaticLodMesh> levels;
    };
    std::vector<Kept> kept_;
};

// Whether a static mesh is drawn into the sun's shadow map. The terrain's snow is not, as the terrain is
// not (renderer.cpp): a layer lying on the ground shadows only itself, at grazing sun, which the sun term
// shades already; and it is the biggest static mesh of a winter scene, redrawn whenever an edit swaps
// meshes (about a third of such a frame on llvmpipe). The objects' snow casts: a snowed roof's shadow is
// the roof's and its snow's.
inline bool castsSunShadow(bool ground_layer) { return !ground_layer; }
inline bool castsSunShadow(const MeshInstances& mesh) { return castsSunShadow(mesh.ground_layer); }

// One static mesh that casts into the sun's map, as far as the map can tell: the mesh and its levels (held,
// so an address names one mesh while it is kept) and a hash of its instances. Two lists of them equal:
// the map drawn for one is the other's (a footprint swaps only the terrain's snow, which casts nothing).
struct SunCaster {
    std::shared_ptr<const TriangleMesh> mesh;
    std::shared_ptr<const std::vector<MeshLodLevel>> lod_levels;
    uint64_t instances_hash = 0;
    bool operator==(const SunCaster&) const = default;
};
// The entries of `meshes` (null: none) that are drawn, in their order: those with triangles.
std::vector<const MeshInstances*> drawnStaticEntries(const std::vector<MeshInstances>* meshes);
// The casters among `meshes`' drawn entries, in their order.
std::vector<SunCaster> sunCasters(const std::vector<MeshInstances>* meshes);

// Everything a static entry's GPU buffers and draw state are made of: the mesh and its authored levels
// (held, so an address names one mesh while kept), its instances (count and hash), its material and
// whether it lies on the ground. Equal keys: the buffers uploaded for one serve the other, so a swap
// uploads only the entries whose key is new (a footprint: the terrain snow chunks it reached).
struct StaticEntryKey {
    std::shared_ptr<const TriangleMesh> mesh;
    std::shared_ptr<const std::vector<MeshLodLevel>> lod_levels;
    size_t instance_count = 0;
    uint64_t instances_hash = 0;
    SurfaceMaterial material;  // the entry's, or the default when it has none
    bool ground_layer = false;
    bool operator==(const StaticEntryKey&) const = default;
};
StaticEntryKey staticEntryKey(const MeshInstances& entry);
// The casters among drawn entries' keys (castsSunShadow: not a ground layer), in their order: what the
// renderer derives from the keys it makes anyway, so a swap hashes each entry's instances once.
std::vector<SunCaster> sunCasters(const std::vector<StaticEntryKey>& keys);

// The level to draw a piece at, -1 for none: with the piece's object-space errors scaled by `scale` (the
// instances' largest), the coarsest level whose error covers less than kStaticLodErrorPx at `distance_m`;
// -1 when `size_m` (the mesh's or piece's bounding diagonal, already scaled) covers less than kStaticSkipPx.
int chooseStaticLevel(const StaticLodPiece& piece, float scale, float size_m, float distance_m,
                      float pixels_per_radian);

// Distance from `eye` to the nearest point of `box` (0 inside).
float distanceToBox(const glm::vec3& eye, const Bounds& box);

// One instanced draw: a level's index range at a run of instances.
struct StaticDrawRange {
    uint32_t first_index = 0, index_count = 0;
    uint32_t first_instance = 0, instance_count = 0;
};

// What the renderer keeps of an entry to choose its draws each frame.
struct StaticEntryLods {
    StaticLodMesh lods;
    std::vector<StaticInstanceChunks::Chunk> chunks;  // the instance buffer's 8 m chunks
    std::vector<Bounds> piece_bounds;  // split entries: each piece's box in engine space (its one instance)
};
// The piece boxes of a split entry in engine space (through its one instance); others: none.
std::vector<Bounds> staticPieceBounds(const StaticLodMesh& lods, const GpuStaticInstance& instance);

// The frame's draws of one entry: per visible piece (split) or chunk, the chosen level made
// `coarser` levels coarser (the renderer passes 0 for both passes), clamped to the piece's coarsest; consecutive chunks at
// the same level merge into one run. Returns the triangles drawn. `out` is cleared first.
uint64_t buildStaticDraws(const StaticEntryLods& entry, const glm::mat4& view_proj, const glm::vec3& eye,
                          float pixels_per_radian, int coarser, std::vector<StaticDrawRange>* out);

}  // namespace ug::editor
