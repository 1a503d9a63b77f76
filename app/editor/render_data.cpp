#include "editor/render_data.h"

#include "editor/coverage.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include <glm/gtc/quaternion.hpp>

#include <meshoptimizer.h>

#include "instancer/tile_coord.h"

namespace ug::editor {

PackedInstance packInstance(const glm::ivec3& tile, uint32_t candidate, uint32_t drop_code) {
    assert(std::abs(tile.x) <= kPackedTileLimit && std::abs(tile.y) <= kPackedTileLimit &&
           tile.z >= kPackedTileZMin && tile.z <= kPackedTileZMax && candidate < kPackedCandidateLimit &&
           drop_code <= kPackedDropSteps);
    PackedInstance p;
    p.x = (uint32_t(tile.x) & 0xffffu) | ((uint32_t(tile.y) & 0xffffu) << 16);
    p.y = (uint32_t(tile.z) & 0x1ffu) | (candidate << 9) | (drop_code << 25);
    return p;
}

void unpackInstance(PackedInstance p, glm::ivec3* tile, uint32_t* candidate, uint32_t* drop_code) {
    // Sign-extend the fields exactly as the vertex shader does.
    tile->x = int32_t(int16_t(uint16_t(p.x & 0xffffu)));
    tile->y = int32_t(int16_t(uint16_t(p.x >> 16)));
    tile->z = int32_t(p.y << 23) >> 23;
    *candidate = (p.y >> 9) & 0xffffu;
    if (drop_code) *drop_code = p.y >> 25;
}

float packedDropUnit(bool settling, float max_drop_m) {
    return settling && max_drop_m > 0.0f ? max_drop_m / float(kPackedDropSteps) : 0.0f;
}

uint32_t packedDropCode(float drop_m, float drop_unit_m) {
    if (!(drop_unit_m > 0.0f) || !(drop_m > 0.0f)) return 0;
    return std::min(kPackedDropSteps, uint32_t(std::floor(drop_m / drop_unit_m)));
}

DetailLodMesh buildDetailLods(const DetailModel& model, float scale_max) {
    const TriangleMesh& mesh = model.mesh;
    DetailLodMesh out;
    out.name = model.name;
    out.color = mesh.base_color;
    out.positions = mesh.positions;
    out.normals = mesh.normals;
    if (out.normals.size() != out.positions.size()) {
        TriangleMesh copy = mesh;
        computeNormals(&copy);
        out.normals = copy.normals;
    }
    out.scale_max = scale_max;
    const size_t vertex_count = out.positions.size();
    const float* positions = &out.positions[0].x;

    std::vector<uint32_t> lod0(mesh.indices.size());
    meshopt_optimizeVertexCache(lod0.data(), mesh.indices.data(), mesh.indices.size(), vertex_count);

    // Honest levels: a simplification whose silhouette differs from the model's by more than
    // kLodCoverageTolerance at some elevation (a tuft whose blades collapsed, a leaf reduced to a sliver)
    // would thin the field out at the distances it is used. Each level tries coarse to fine and keeps the
    // first faithful result, else the finer level (the grass tuft: its blades are thinner than any error
    // bound that saves triangles, so it keeps its mesh and relies on the impostors).
    const CoverageProfile c0 = measureCoverage(out.positions, lod0.data(), lod0.size());
    auto faithful = [&](const std::vector<uint32_t>& lod) {
        if (lod.size() < 3) return false;
        const CoverageProfile c = measureCoverage(out.positions, lod.data(), lod.size());
        for (int e = 0; e < kCoverageElevations; ++e)
            if (std::abs(c.area_m2[size_t(e)] - c0.area_m2[size_t(e)]) > kLodCoverageTolerance * c0.area_m2[size_t(e)])
                return false;
        return true;
    };

    // LOD 1: topology-preserving simplification to 20-50 % of the triangles, with an error bound
    // (relative to the mesh extent) that stops it before the silhouette changes at 30-90 px on screen.
    std::vector<uint32_t> lod1 = lod0;
    for (const auto& [fraction, error_bound] : {std::pair{0.2f, 0.02f}, std::pair{0.35f, 0.01f}, std::pair{0.5f, 0.005f}}) {
        std::vector<uint32_t> trial(lod0.size());
        const size_t target = std::max<size_t>(3, size_t(float(lod0.size() / 3) * fraction) * 3);
        trial.resize(meshopt_simplify(trial.data(), lod0.data(), lod0.size(), positions, vertex_count, sizeof(glm::vec3),
                                      target, error_bound, 0, nullptr));
        if (!faithful(trial)) continue;
        meshopt_optimizeVertexCache(trial.data(), trial.data(), trial.size(), vertex_count);
        lod1 = std::move(trial);
        break;
    }

    // LOD 2: the sloppy simplifier ignores topology, which thin multi-part models (leaf sheets) need to
    // get down to a few dozen triangles; used at 10-30 px.
    std::vector<uint32_t> lod2 = lod1;
    for (size_t triangles : {24, 48, 96}) {
        if (triangles * 3 >= lod1.size()) break;
        std::vector<uint32_t> trial(lod1.size());
        trial.resize(meshopt_simplifySloppy(trial.data(), lod1.data(), lod1.size(), positions, vertex_count,
                                            sizeof(glm::vec3), triangles * 3, 0.2f, nullptr));
        if (!faithful(trial)) continue;
        lod2 = std::move(trial);
        break;
    }
    out.coverage_m2 = c0.area_m2;
    out.silhouettes = silhouetteMasks(out.positions, lod0.data(), lod0.size());
    // Heavier than kImpostorBudgetTriangles at its coarsest: hand over to the sprite earlier, by the
    // square root of the excess (a sprite's pixels grow with the square of the switch size).
    out.impostor_scale = std::clamp(std::sqrt(float(lod2.size() / 3) / float(kImpostorBudgetTriangles)), 1.0f, 4.0f);

    for (int lod = 0; lod < kMeshLodCount; ++lod) {
        const std::vector<uint32_t>& src = lod == 0 ? lod0 : lod == 1 ? lod1 : lod2;
        out.index_first[size_t(lod)] = uint32_t(out.indices.size());
        out.index_count[size_t(lod)] = uint32_t(src.size());
        out.indices.insert(out.indices.end(), src.begin(), src.end());
    }

    double area = 0.0, up = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::vec3& a = mesh.positions[mesh.indices[t]];
        const glm::vec3 n = glm::cross(mesh.positions[mesh.indices[t + 1]] - a, mesh.positions[mesh.indices[t + 2]] - a);
        area += double(glm::length(n));
        up += double(std::abs(n.z));
    }
    out.upness = area > 0.0 ? float(up / area) : 1.0f;
    Bounds3 b = meshBounds(mesh);
    out.center = 0.5f * (b.min + b.max);
    for (const glm::vec3& p : mesh.positions) out.radius_m = std::max(out.radius_m, glm::length(p));
    return out;
}

float candidateScaleMax(const CandidateSet& candidates, size_t type) {
    float scale = 1.0f;
    if (type < candidates.typeCount())
        for (uint32_t k = candidates.type_begin[type]; k < candidates.type_begin[type + 1]; ++k)
            scale = std::max(scale, candidates.scale[k]);
    return scale;
}

namespace {

// The mesh's material: materials' entry `index` where there is one (its colour the material's base), else
// a plain material of the mesh's own colour.
void useMaterial(DetailLodMesh* mesh, const SceneMaterials* materials, size_t index) {
    if (materials && index < materials->types.size()) {
        mesh->material = materials->types[index];
        mesh->color = materials->types[index].base_color;
    } else {
        mesh->material.base_color = mesh->color;
    }
}

}  // namespace

std::vector<DetailLodMesh> buildTypeMeshes(const std::vector<DetailModel>& models, const CandidateSet& candidates,
                                           const SceneMaterials* looks) {
    std::vector<DetailLodMesh> meshes;
    for (size_t i = 0; i < models.size(); ++i) {
        meshes.push_back(buildDetailLods(models[i], candidateScaleMax(candidates, i)));
        useMaterial(&meshes.back(), looks, i);
    }
    return meshes;
}

std::vector<DetailLodMesh> buildLookMeshes(const DetailLooks& looks, const CandidateSet& candidates,
                                           const SceneMaterials* materials) {
    std::vector<DetailLodMesh> meshes;
    for (size_t l = 0; l < looks.size(); ++l) {
        meshes.push_back(buildDetailLods(*looks.models[l], candidateScaleMax(candidates, looks.look_type[l])));
        useMaterial(&meshes.back(), materials, l);
    }
    return meshes;
}

uint64_t ResidentTiles::instanceCount() const {
    uint64_t n = 0;
    for (uint64_t c : instances_per_type) n += c;
    return n;
}

void TileUploads::clear() {
    for (Type& t : types) {
        t.whole = false;
        t.ranges.clear();
    }
    tiles.clear();
    full = false;
    tiles_uploaded = bytes_uploaded = 0;
}

namespace {

bool checkTile(const glm::ivec3& coord, std::string* error) {
    if (std::abs(coord.x) <= kPackedTileLimit && std::abs(coord.y) <= kPackedTileLimit && coord.z >= kPackedTileZMin &&
        coord.z <= kPackedTileZMax)
        return true;
    *error = "tile (" + std::to_string(coord.x) + ", " + std::to_string(coord.y) + ", " + std::to_string(coord.z) +
             ") is beyond the renderer's packed range (±" + std::to_string(kPackedTileLimit) + " tiles across, " +
             std::to_string(kPackedTileZMin) + ".." + std::to_string(kPackedTileZMax) +
             " tiles up); the batch commands (instantiate, export) have no such limit";
    return false;
}

// Splits a tile's ascending candidate ids by type: counts[type] (ids of a type are contiguous).
void countByType(const std::vector<uint32_t>& ids, const CandidateSet& c, std::vector<uint32_t>* counts) {
    counts->assign(c.typeCount(), 0);
    size_t k = 0;
    for (uint32_t type = 0; type < c.typeCount(); ++type) {
        const size_t begin = k;
        while (k < ids.size() && ids[k] < c.type_begin[type + 1]) ++k;
        (*counts)[type] = uint32_t(k - begin);
    }
}

// With looks that have variants: regroups a tile's ids (and their drops) by look, ascending within each,
// into *ids / *drops, and counts[look]. Otherwise countByType.
void groupTile(uint64_t key, const CandidateSet& c, float tile_size_m, const DetailLooks* looks,
               std::vector<uint32_t>* ids, std::span<const uint16_t>* drops, std::vector<uint16_t>* drop_scratch,
               std::vector<uint32_t>* counts) {
    if (!looks || !looks->hasVariants()) {
        countByType(*ids, c, counts);
        return;
    }
    const glm::vec3 origin = tileOrigin(unpackTile(key), tile_size_m);
    thread_local std::vector<uint32_t> look_of, sorted;
    look_of.resize(ids->size());
    counts->assign(looks->size(), 0);
    for (size_t k = 0; k < ids->size(); ++k) {
        const uint32_t j = (*ids)[k];
        look_of[k] = looks->lookOf(c.type[j], origin + c.position[j]);
        ++(*counts)[look_of[k]];
    }
    std::vector<uint32_t> start(looks->size() + 1, 0);
    for (size_t l = 0; l < looks->size(); ++l) start[l + 1] = start[l] + (*counts)[l];
    sorted.resize(ids->size());
    drop_scratch->assign(drops->empty() ? 0 : ids->size(), 0);
    for (size_t k = 0; k < ids->size(); ++k) {
        const uint32_t at = start[look_of[k]]++;
        sorted[at] = (*ids)[k];
        if (!drops->empty() && k < drops->size()) (*drop_scratch)[at] = (*drops)[k];
    }
    ids->swap(sorted);
    *drops = std::span<const uint16_t>(*drop_scratch);
}

// Writes tile `t`'s instances of every type into its slots (allocating or moving them as needed) and
// records the uploads.
void writeTile(ResidentTiles* r, uint32_t t, const std::vector<uint32_t>& ids, std::span<const uint16_t> drops,
               const std::vector<uint32_t>& counts, SlotFit fit, TileUploads* uploads) {
    const uint32_t types = r->type_count;
    const glm::ivec3 coord = r->tile_coord[t];
    size_t k = 0;
    for (uint32_t type = 0; type < types; ++type) {
        ResidentTiles::Type& arena = r->types[type];
        TileSlot& slot = r->slot[size_t(t) * types + type];
        uint32_t& count = r->count[size_t(t) * types + type];
        const uint32_t n = counts[type];
        r->instances_per_type[type] -= count;
        r->instances_per_type[type] += n;
        count = n;
        if (n == 0) {
            arena.slots.release(slot);
            slot = TileSlot{};
            continue;  // the tile's type range is gone; nothing to upload (no command points at it)
        }
        if (n > slot.capacity) {
            arena.slots.release(slot);
            slot = arena.slots.allocate(n, fit);
            if (arena.slots.capacity() > arena.mirror.size()) {
                arena.mirror.resize(arena.slots.capacity());
                uploads->types[type].whole = true;
            }
        }
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t code = k + i < drops.size() ? packedDropCode(dropMetres(drops[k + i]), r->drop_unit_m) : 0;
            arena.mirror[slot.offset + i] = packInstance(coord, ids[k + i], code);
        }
        k += n;
        if (!uploads->types[type].whole) uploads->types[type].ranges.push_back({slot.offset, n});
    }
}

void finishUploads(const ResidentTiles& r, TileUploads* uploads) {
    uploads->tiles_uploaded = uploads->tiles.size();
    uint64_t bytes = 0;
    for (uint32_t type = 0; type < r.type_count; ++type) {
        const TileUploads::Type& u = uploads->types[type];
        if (u.whole) {
            bytes += uint64_t(r.types[type].mirror.size()) * sizeof(PackedInstance);
            continue;
        }
        for (const TileUploads::Range& range : u.ranges) bytes += uint64_t(range.count) * sizeof(PackedInstance);
    }
    uploads->bytes_uploaded = bytes;
}

void removeTile(ResidentTiles* r, uint32_t t) {
    const uint32_t types = r->type_count;
    for (uint32_t type = 0; type < types; ++type) {
        r->types[type].slots.release(r->slot[size_t(t) * types + type]);
        r->instances_per_type[type] -= r->count[size_t(t) * types + type];
    }
    // Swap-and-pop: the last tile takes t's place (its slots do not move, only its index).
    const uint32_t last = uint32_t(r->tile_key.size() - 1);
    r->tile_index.erase(r->tile_key[t]);
    if (t != last) {
        r->tile_key[t] = r->tile_key[last];
        r->tile_coord[t] = r->tile_coord[last];
        std::copy_n(r->slot.begin() + long(size_t(last) * types), types, r->slot.begin() + long(size_t(t) * types));
        std::copy_n(r->count.begin() + long(size_t(last) * types), types, r->count.begin() + long(size_t(t) * types));
        r->tile_index[r->tile_key[t]] = t;
    }
    r->tile_key.pop_back();
    r->tile_coord.pop_back();
    r->slot.resize(r->slot.size() - types);
    r->count.resize(r->count.size() - types);
}

uint32_t addTile(ResidentTiles* r, uint64_t key, const glm::ivec3& coord) {
    const uint32_t t = uint32_t(r->tile_key.size());
    r->tile_key.push_back(key);
    r->tile_coord.push_back(coord);
    r->slot.resize(r->slot.size() + r->type_count);
    r->count.resize(r->count.size() + r->type_count, 0);
    r->tile_index[key] = t;
    return t;
}

void startUploads(uint32_t type_count, TileUploads* uploads) {
    uploads->clear();
    uploads->types.resize(type_count);
}

}  // namespace

bool rebuildResidentTiles(const InstanceStore& store, const SettledDrops* drops, const CandidateSet& candidates,
                          float tile_size_m, float drop_unit_m, ResidentTiles* out, TileUploads* uploads,
                          std::string* error, const DetailLooks* looks) {
    if (candidates.size() > kPackedCandidateLimit) {
        *error = "the Ghost Tile has " + std::to_string(candidates.size()) + " candidates; the renderer packs at most " +
                 std::to_string(kPackedCandidateLimit);
        return false;
    }
    for (size_t t = 0; t < store.tileCount(); ++t)
        if (!checkTile(unpackTile(store.tileKey(t)), error)) return false;
    ResidentTiles r;
    r.type_count = looks && looks->hasVariants() ? uint32_t(looks->size()) : candidates.typeCount();
    r.tile_size_m = tile_size_m;
    r.drop_unit_m = drop_unit_m;
    r.types.resize(r.type_count);
    r.instances_per_type.assign(r.type_count, 0);
    r.tile_key.reserve(store.tileCount());
    r.tile_coord.reserve(store.tileCount());
    r.tile_index.reserve(store.tileCount());
    startUploads(r.type_count, uploads);
    std::vector<uint32_t> ids, counts;
    std::vector<uint16_t> drop_scratch;
    for (size_t i = 0; i < store.tileCount(); ++i) {
        const uint64_t key = store.tileKey(i);
        store.tileIds(i, &ids);
        std::span<const uint16_t> tile_drops = drops ? drops->tile(key) : std::span<const uint16_t>();
        groupTile(key, candidates, tile_size_m, looks, &ids, &tile_drops, &drop_scratch, &counts);
        const uint32_t t = addTile(&r, key, unpackTile(key));
        writeTile(&r, t, ids, tile_drops, counts, SlotFit::Exact, uploads);
        uploads->tiles.push_back(r.tile_coord[t]);
    }
    // Everything is new: each type's array goes up whole.
    for (TileUploads::Type& u : uploads->types) {
        u.whole = true;
        u.ranges.clear();
    }
    uploads->full = true;
    *out = std::move(r);
    finishUploads(*out, uploads);
    return true;
}

bool updateResidentTiles(const InstanceStore& store, const SettledDrops* drops, const CandidateSet& candidates,
                         const std::vector<uint64_t>& changed_keys, ResidentTiles* r, TileUploads* uploads,
                         std::string* error, const DetailLooks* looks) {
    assert(r->type_count == (looks && looks->hasVariants() ? uint32_t(looks->size()) : candidates.typeCount()));
    startUploads(r->type_count, uploads);
    std::vector<uint32_t> ids, counts;
    std::vector<uint16_t> drop_scratch;
    for (const uint64_t key : changed_keys) {
        const glm::ivec3 coord = unpackTile(key);
        const int64_t in_store = store.findTile(key);
        const auto it = r->tile_index.find(key);
        if (in_store < 0) {
            if (it == r->tile_index.end()) continue;  // appeared and vanished again between two polls
            removeTile(r, it->second);
            uploads->tiles.push_back(coord);
            continue;
        }
        if (!checkTile(coord, error)) return false;
        store.tileIds(size_t(in_store), &ids);
        std::span<const uint16_t> tile_drops = drops ? drops->tile(key) : std::span<const uint16_t>();
        groupTile(key, candidates, r->tile_size_m, looks, &ids, &tile_drops, &drop_scratch, &counts);
        const uint32_t t = it != r->tile_index.end() ? it->second : addTile(r, key, coord);
        writeTile(r, t, ids, tile_drops, counts, SlotFit::Rounded, uploads);
        uploads->tiles.push_back(coord);
    }
    for (TileUploads::Type& u : uploads->types)
        if (u.whole) u.ranges.clear();
    finishUploads(*r, uploads);
    return true;
}

namespace {

// Gribb & Hartmann: the six clip planes of a view-projection matrix, as (n, d) with n.p + d >= 0 inside.
std::array<glm::vec4, 6> frustumPlanes(const glm::mat4& m) {
    const glm::vec4 r0(m[0][0], m[1][0], m[2][0], m[3][0]);
    const glm::vec4 r1(m[0][1], m[1][1], m[2][1], m[3][1]);
    const glm::vec4 r2(m[0][2], m[1][2], m[2][2], m[3][2]);
    const glm::vec4 r3(m[0][3], m[1][3], m[2][3], m[3][3]);
    return {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r3 + r2, r3 - r2};
}

bool boxOutside(const std::array<glm::vec4, 6>& planes, const glm::vec3& lo, const glm::vec3& hi) {
    for (const glm::vec4& p : planes) {
        // The box corner farthest along the plane normal: if even it is outside, the whole box is.
        const glm::vec3 c(p.x >= 0.0f ? hi.x : lo.x, p.y >= 0.0f ? hi.y : lo.y, p.z >= 0.0f ? hi.z : lo.z);
        if (p.x * c.x + p.y * c.y + p.z * c.z + p.w < 0.0f) return true;
    }
    return false;
}

// The box swept along `sweep` (every p + t sweep, t in [0, 1]) is outside when even its farthest point
// along a plane's normal is: the farthest corner, moved along the sweep if that goes further.
bool sweptBoxOutside(const std::array<glm::vec4, 6>& planes, const glm::vec3& lo, const glm::vec3& hi,
                     const glm::vec3& sweep) {
    for (const glm::vec4& p : planes) {
        const glm::vec3 c(p.x >= 0.0f ? hi.x : lo.x, p.y >= 0.0f ? hi.y : lo.y, p.z >= 0.0f ? hi.z : lo.z);
        const float along = p.x * sweep.x + p.y * sweep.y + p.z * sweep.z;
        if (p.x * c.x + p.y * c.y + p.z * c.z + p.w + std::max(along, 0.0f) < 0.0f) return true;
    }
    return false;
}

}  // namespace

uint32_t instanceHash(PackedInstance packed) {
    // The shaders' hash (instanced_detail.vert, detail_impostor.vert), bit for bit; the drop code is left
    // out so settling never changes an instance's colour or LOD.
    uint32_t h = (packed.x * 2654435761u) ^ ((packed.y & 0x1ffffffu) * 2246822519u);
    h ^= h >> 15;
    h *= 2246822519u;
    h ^= h >> 13;
    return h >> 10;
}

uint32_t pointStride(const DetailLodMesh& m, float px_per_m) {
    const float scale = m.scale_max;
    const float sprite_px = 2.0f * m.silhouettes.radius * m.silhouettes.extent * scale * px_per_m;
    if (!(sprite_px < 2.0f)) return 1;  // a sprite shows its silhouette: every one is drawn (and a NaN)
    const float most_m2 = *std::max_element(m.coverage_m2.begin(), m.coverage_m2.end());
    const float area_px = most_m2 * scale * scale * px_per_m * px_per_m;
    uint32_t stride = 1;
    while (stride < kMaxPointStride && 2.0f * float(stride) * area_px <= 1.0f) stride *= 2;
    return stride;
}

namespace {

// The most pixels per metre a point in the box can be drawn at: the shader's u_point_scale / clip w, and w
// (linear in the position) is least at a corner. 0 when the box reaches the eye's plane (no bound).
float mostPixelsPerMetre(const glm::mat4& view_proj, float point_scale, glm::vec3 lo, glm::vec3 hi) {
    float w_min = std::numeric_limits<float>::max();
    for (int c = 0; c < 8; ++c) {
        const glm::vec4 p((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z, 1.0f);
        w_min = std::min(w_min, (view_proj * p).w);
    }
    return w_min > 1e-3f ? point_scale / w_min : 0.0f;
}

}  // namespace

void buildIndirectDraws(const ResidentTiles& in, const std::vector<DetailLodMesh>& meshes, const ViewParams& view,
                        const LodSettings& lod, IndirectDraws* out) {
    const uint32_t types = in.type_count;
    assert(meshes.size() == types);
    out->elements.clear();
    out->points.clear();
    out->point_runs.clear();
    out->groups.assign(types, {});
    out->tiles_visible = 0;
    out->tiles_culled = 0;
    const auto planes = frustumPlanes(view.view_proj);
    const auto receiver = frustumPlanes(view.receiver_view_proj);
    float reach = 0.0f;  // how far an object can stick out of the cell that holds its origin
    std::vector<float> diameter_px_at_1m(types);
    for (uint32_t i = 0; i < types; ++i) {
        reach = std::max(reach, meshes[i].radius_m * meshes[i].scale_max);
        diameter_px_at_1m[i] = meshes[i].lodDiameterPx(view.pixels_per_radian);
    }
    const float s = in.tile_size_m;
    const float half_diagonal = 0.5f * std::sqrt(3.0f) * s;
    const size_t tile_count = in.tileCount();
    // Pass 1: cull each cell once and keep its distance (negative: culled) and, for thinning far points,
    // the most pixels per metre its points can have (the cell grown by the reach, and by the deepest
    // settled drop below; 0: not thinned).
    const glm::vec3 drop_max(0.0f, 0.0f, in.drop_unit_m * float(kPackedDropSteps));
    out->tile_distance.resize(tile_count);
    out->tile_point_px.resize(tile_count);
    for (size_t t = 0; t < tile_count; ++t) {
        const glm::vec3 lo = tileOrigin(in.tile_coord[t], s);
        // A caster's shadow starts where the caster is, settled drop included (the cell's instances may sit
        // up to drop_max below it).
        if (boxOutside(planes, lo - reach, lo + s + reach) ||
            (view.cull_by_receiver &&
             sweptBoxOutside(receiver, lo - reach - drop_max, lo + s + reach, view.shadow_sweep))) {
            out->tile_distance[t] = -1.0f;
            ++out->tiles_culled;
            continue;
        }
        ++out->tiles_visible;
        out->tile_distance[t] = std::max(glm::length(lo + 0.5f * s - view.eye) - half_diagonal, 1e-3f);
        out->tile_point_px[t] =
            view.point_scale > 0.0f ? mostPixelsPerMetre(view.view_proj, view.point_scale, lo - reach - drop_max, lo + s + reach)
                                    : 0.0f;
    }
    // Pass 2, per type: one LOD per visible cell, a command for the cell's slot in that LOD's group. A
    // command that starts where the group's previous one ends extends it instead (adjacent slots).
    for (uint32_t i = 0; i < types; ++i) {
        for (auto& v : out->scratch) v.clear();
        const size_t points_first = out->points.size();
        for (size_t t = 0; t < tile_count; ++t) {
            const float distance = out->tile_distance[t];
            if (distance < 0.0f) continue;
            const uint32_t n = in.count[t * types + i];
            if (n == 0) continue;
            const uint32_t offset = in.slot[t * types + i].offset;
            // The instances' origins lie in the cell, so their sizes on screen lie between these two.
            const float px_near = diameter_px_at_1m[i] / distance;
            const float px_far = diameter_px_at_1m[i] / (distance + 2.0f * half_diagonal);
            const float impostor_px = meshes[i].impostorPx(lod);
            if (px_far < impostor_px * (1.0f + kImpostorBand)) {  // some may be impostors (drawnAsMesh)
                const float px_per_m = out->tile_point_px[t];
                const uint32_t stride = px_per_m > 0.0f ? pointStride(meshes[i], px_per_m) : 1;
                // A run of the same stride that ends where this tile's slot begins takes it in.
                PointRun* run = out->points.size() > points_first ? &out->point_runs.back() : nullptr;
                if (run && run->stride == stride && run->offset + run->span == offset) {
                    run->span += n;
                } else {
                    out->point_runs.push_back({offset, stride, n});
                    out->points.push_back({0, 1, 0, uint32_t(out->points.size())});
                    run = &out->point_runs.back();
                }
                const uint32_t drawn_before = out->points.back().count;
                out->points.back().count = (run->span + stride - 1) / stride;
                out->groups[i][kImpostorLod].instances += out->points.back().count - drawn_before;
            }
            if (px_near < impostor_px) continue;  // none is a mesh
            const int level = px_near >= lod.lod1_px ? 0 : px_near >= lod.lod2_px ? 1 : 2;
            out->groups[i][size_t(level)].instances += n;
            auto& dst = out->scratch[size_t(level)];
            if (!dst.empty() && dst.back().base_instance + dst.back().instance_count == offset) {
                dst.back().instance_count += n;
                continue;
            }
            const DetailLodMesh& m = meshes[i];
            dst.push_back({m.index_count[size_t(level)], n, m.index_first[size_t(level)], 0, offset});
        }
        for (int level = 0; level < kMeshLodCount; ++level) {
            IndirectDraws::Group& g = out->groups[i][size_t(level)];
            g.first = uint32_t(out->elements.size());
            g.count = uint32_t(out->scratch[size_t(level)].size());
            out->elements.insert(out->elements.end(), out->scratch[size_t(level)].begin(), out->scratch[size_t(level)].end());
        }
        IndirectDraws::Group& g = out->groups[i][kImpostorLod];
        g.first = uint32_t(points_first);
        g.count = uint32_t(out->points.size() - points_first);
    }
}

std::vector<GpuStaticInstance> packStaticInstances(const MeshInstances& entry) {
    if (entry.instances.empty()) return {GpuStaticInstance{}};
    std::vector<GpuStaticInstance> out(entry.instances.size());
    for (size_t i = 0; i < out.size(); ++i) {
        const InstanceTransform& t = entry.instances[i];
        const float norm = glm::length(t.rotation);
        const glm::quat q = norm > 0.0f ? t.rotation / norm : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
        out[i].position_scale = glm::vec4(t.position, t.scale);
        out[i].rotation = glm::vec4(q.x, q.y, q.z, q.w);
    }
    return out;
}

glm::mat4 staticInstanceMatrix(const GpuStaticInstance& g) {
    const glm::quat q(g.rotation.w, g.rotation.x, g.rotation.y, g.rotation.z);
    const glm::mat3 rs = glm::mat3_cast(q) * g.position_scale.w;
    glm::mat4 m(rs);
    m[3] = glm::vec4(glm::vec3(g.position_scale), 1.0f);
    return m;
}

namespace {

// The mesh's object-space box as centre and half extents; false without vertices.
bool localBox(const MeshInstances& entry, glm::vec3* centre, glm::vec3* half) {
    if (!entry.mesh || entry.mesh->positions.empty()) return false;
    Bounds local;
    for (const glm::vec3& p : entry.mesh->positions) local = unite(local, Bounds{p, p});
    *centre = 0.5f * (local.lo + local.hi);
    *half = 0.5f * (local.hi - local.lo);
    return true;
}

// The engine-space box of that box turned by one instance: exact for the box (centre moved, half extents
// through |R| s).
Bounds instanceBox(const GpuStaticInstance& g, glm::vec3 centre, glm::vec3 half) {
    const glm::mat4 m = staticInstanceMatrix(g);
    const glm::mat3 abs_rs(glm::abs(glm::vec3(m[0])), glm::abs(glm::vec3(m[1])), glm::abs(glm::vec3(m[2])));
    const glm::vec3 c = glm::vec3(m * glm::vec4(centre, 1.0f)), h = abs_rs * half;
    return Bounds{c - h, c + h};
}

// A chunk index, clamped so that absurd positions still sort (they only lose culling precision).
int64_t chunkIndex(float v, float chunk_m) {
    return int64_t(std::clamp(std::floor(double(v) / double(chunk_m)), -1e15, 1e15));
}

}  // namespace

Bounds staticInstanceBox(const GpuStaticInstance& instance, const Bounds& local) {
    if (local.empty()) return local;
    return instanceBox(instance, 0.5f * (local.lo + local.hi), 0.5f * (local.hi - local.lo));
}

Bounds staticMeshBounds(const MeshInstances& entry) {
    Bounds out;
    glm::vec3 centre, half;
    if (!localBox(entry, &centre, &half)) return out;
    for (const GpuStaticInstance& g : packStaticInstances(entry)) out = unite(out, instanceBox(g, centre, half));
    return out;
}

StaticInstanceChunks chunkStaticInstances(const MeshInstances& entry, float chunk_m) {
    StaticInstanceChunks out;
    glm::vec3 centre, half;
    if (!localBox(entry, &centre, &half)) return out;
    const std::vector<GpuStaticInstance> packed = packStaticInstances(entry);
    struct Key {
        int64_t ix, iy;
        uint32_t index;
    };
    std::vector<Key> keys(packed.size());
    for (size_t i = 0; i < packed.size(); ++i)
        keys[i] = {chunkIndex(packed[i].position_scale.x, chunk_m), chunkIndex(packed[i].position_scale.y, chunk_m),
                   uint32_t(i)};
    std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
        if (a.ix != b.ix) return a.ix < b.ix;
        if (a.iy != b.iy) return a.iy < b.iy;
        return a.index < b.index;
    });
    out.instances.reserve(packed.size());
    for (size_t k = 0; k < keys.size(); ++k) {
        const GpuStaticInstance& g = packed[keys[k].index];
        const Bounds box = instanceBox(g, centre, half);
        if (k == 0 || keys[k].ix != keys[k - 1].ix || keys[k].iy != keys[k - 1].iy)
            out.chunks.push_back({uint32_t(k), 0, Bounds{}});
        StaticInstanceChunks::Chunk& chunk = out.chunks.back();
        ++chunk.count;
        chunk.scale_max = std::max(chunk.scale_max, g.position_scale.w);
        chunk.bounds = unite(chunk.bounds, box);
        out.bounds = unite(out.bounds, box);
        out.instances.push_back(g);
    }
    return out;
}

Bounds staticMeshesBounds(const std::vector<MeshInstances>& meshes) {
    Bounds out;
    for (const MeshInstances& entry : meshes) out = unite(out, staticMeshBounds(entry));
    return out;
}

bool boxInFrustum(const glm::mat4& view_proj, const Bounds& box) {
    return !box.empty() && !boxOutside(frustumPlanes(view_proj), box.lo, box.hi);
}

}  // namespace ug::editor
