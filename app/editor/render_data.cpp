#include "editor/render_data.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <meshoptimizer.h>

#include "instancer/tile_coord.h"

namespace ug::editor {

PackedInstance packInstance(const glm::ivec3& tile, uint32_t candidate) {
    assert(std::abs(tile.x) <= kPackedTileLimit && std::abs(tile.y) <= kPackedTileLimit &&
           std::abs(tile.z) <= kPackedTileLimit && candidate < kPackedCandidateLimit);
    PackedInstance p;
    p.x = (uint32_t(tile.x) & 0xffffu) | ((uint32_t(tile.y) & 0xffffu) << 16);
    p.y = (uint32_t(tile.z) & 0xffffu) | (candidate << 16);
    return p;
}

void unpackInstance(PackedInstance p, glm::ivec3* tile, uint32_t* candidate) {
    // Sign-extend the 16-bit fields exactly as the vertex shader does.
    tile->x = int32_t(int16_t(uint16_t(p.x & 0xffffu)));
    tile->y = int32_t(int16_t(uint16_t(p.x >> 16)));
    tile->z = int32_t(int16_t(uint16_t(p.y & 0xffffu)));
    *candidate = p.y >> 16;
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

    // LOD 1: topology-preserving simplification; the error bound (relative to the mesh extent) stops it
    // before the silhouette changes at the distances where LOD 1 is used (about 30-90 px on screen).
    std::vector<uint32_t> lod1(lod0.size());
    const size_t target1 = std::max<size_t>(3, (lod0.size() / 3) / 5 * 3);
    lod1.resize(meshopt_simplify(lod1.data(), lod0.data(), lod0.size(), positions, vertex_count, sizeof(glm::vec3),
                                 target1, 0.02f, 0, nullptr));
    if (lod1.size() < 3) lod1 = lod0;
    meshopt_optimizeVertexCache(lod1.data(), lod1.data(), lod1.size(), vertex_count);

    // LOD 2: the sloppy simplifier ignores topology, which thin multi-part models (grass blades, leaf
    // sheets) need to get down to a couple of dozen triangles; used at 10-30 px.
    std::vector<uint32_t> lod2(lod1.size());
    lod2.resize(meshopt_simplifySloppy(lod2.data(), lod1.data(), lod1.size(), positions, vertex_count,
                                       sizeof(glm::vec3), 24 * 3, 0.2f, nullptr));
    if (lod2.size() < 3) lod2 = lod1;

    for (int lod = 0; lod < kMeshLodCount; ++lod) {
        const std::vector<uint32_t>& src = lod == 0 ? lod0 : lod == 1 ? lod1 : lod2;
        out.index_first[size_t(lod)] = uint32_t(out.indices.size());
        out.index_count[size_t(lod)] = uint32_t(src.size());
        out.indices.insert(out.indices.end(), src.begin(), src.end());
    }

    Bounds3 b = meshBounds(mesh);
    out.center = 0.5f * (b.min + b.max);
    float area = 0.0f;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::vec3& a = mesh.positions[mesh.indices[t]];
        area += 0.5f * glm::length(glm::cross(mesh.positions[mesh.indices[t + 1]] - a, mesh.positions[mesh.indices[t + 2]] - a));
    }
    for (const glm::vec3& p : mesh.positions) out.radius_m = std::max(out.radius_m, glm::length(p));
    // Cauchy: a convex body's mean projected area is a quarter of its surface area; the starter models
    // are closed sheets or near-convex solids, so the square of that area is a fair far-away stand-in.
    out.impostor_half_size_m = 0.5f * std::sqrt(area / 4.0f);
    return out;
}

bool buildRenderInstances(const InstanceStore& store, const CandidateSet& candidates, float tile_size_m,
                          RenderInstances* out, std::string* error) {
    RenderInstances r;
    r.type_count = candidates.typeCount();
    r.tile_size_m = tile_size_m;
    r.instances_per_type.assign(r.type_count, 0);
    if (candidates.size() > kPackedCandidateLimit) {
        *error = "the Ghost Tile has " + std::to_string(candidates.size()) + " candidates; the renderer packs at most " +
                 std::to_string(kPackedCandidateLimit);
        return false;
    }
    r.instances.reserve(store.instanceCount());
    r.tile_coord.reserve(store.tileCount());
    r.tile_type_begin.reserve(store.tileCount() * (r.type_count + 1));
    std::vector<uint32_t> ids;
    for (size_t t = 0; t < store.tileCount(); ++t) {
        const glm::ivec3 coord = unpackTile(store.tileKey(t));
        if (std::abs(coord.x) > kPackedTileLimit || std::abs(coord.y) > kPackedTileLimit ||
            std::abs(coord.z) > kPackedTileLimit) {
            *error = "tile (" + std::to_string(coord.x) + ", " + std::to_string(coord.y) + ", " + std::to_string(coord.z) +
                     ") is beyond the renderer's packed range of ±" + std::to_string(kPackedTileLimit) + " tiles";
            return false;
        }
        store.tileIds(t, &ids);
        r.tile_coord.push_back(coord);
        size_t k = 0;
        for (uint32_t type = 0; type < r.type_count; ++type) {
            r.tile_type_begin.push_back(uint32_t(r.instances.size()));
            const uint32_t end = candidates.type_begin[type + 1];
            for (; k < ids.size() && ids[k] < end; ++k) {
                r.instances.push_back(packInstance(coord, ids[k]));
                ++r.instances_per_type[type];
            }
        }
        r.tile_type_begin.push_back(uint32_t(r.instances.size()));
    }
    *out = std::move(r);
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

}  // namespace

void bucketInstances(const RenderInstances& in, const std::vector<DetailLodMesh>& meshes, const ViewParams& view,
                     const LodSettings& lod, DrawBuckets* out) {
    const uint32_t types = in.type_count;
    assert(meshes.size() == types);
    out->types.resize(types);
    out->tiles_visible = 0;
    out->tiles_culled = 0;
    const auto planes = frustumPlanes(view.view_proj);
    float reach = 0.0f;  // how far an object can stick out of the cell that holds its origin
    std::vector<float> diameter_px_at_1m(types);
    for (uint32_t i = 0; i < types; ++i) {
        reach = std::max(reach, meshes[i].radius_m * meshes[i].scale_max);
        diameter_px_at_1m[i] = 2.0f * meshes[i].radius_m * meshes[i].scale_max * view.pixels_per_radian;
    }
    const float s = in.tile_size_m;
    const float half_diagonal = 0.5f * std::sqrt(3.0f) * s;
    // Pass 1: cull each cell once and keep its distance (negative: culled).
    out->tile_distance.resize(in.tile_coord.size());
    for (size_t t = 0; t < in.tile_coord.size(); ++t) {
        const glm::vec3 lo = tileOrigin(in.tile_coord[t], s);
        if (boxOutside(planes, lo - reach, lo + s + reach)) {
            out->tile_distance[t] = -1.0f;
            ++out->tiles_culled;
            continue;
        }
        ++out->tiles_visible;
        out->tile_distance[t] = std::max(glm::length(lo + 0.5f * s - view.eye) - half_diagonal, 1e-3f);
    }
    // Pass 2, per type: one LOD per visible cell, its instances appended to that LOD's list.
    for (uint32_t i = 0; i < types; ++i) {
        for (auto& v : out->scratch) v.clear();
        for (size_t t = 0; t < in.tile_coord.size(); ++t) {
            const float distance = out->tile_distance[t];
            if (distance < 0.0f) continue;
            const uint32_t b = in.tile_type_begin[t * (types + 1) + i];
            const uint32_t e = in.tile_type_begin[t * (types + 1) + i + 1];
            if (b == e) continue;
            const float px = diameter_px_at_1m[i] / distance;
            const int level = px >= lod.lod1_px ? 0 : px >= lod.lod2_px ? 1 : px >= lod.impostor_px ? 2 : kImpostorLod;
            auto& dst = out->scratch[size_t(level)];
            dst.insert(dst.end(), in.instances.begin() + b, in.instances.begin() + e);
        }
        DrawBuckets::Type& type = out->types[i];
        type.instances.clear();
        for (int level = 0; level < kLodCount; ++level) {
            type.lod_first[size_t(level)] = uint32_t(type.instances.size());
            type.lod_count[size_t(level)] = uint32_t(out->scratch[size_t(level)].size());
            type.instances.insert(type.instances.end(), out->scratch[size_t(level)].begin(), out->scratch[size_t(level)].end());
        }
    }
}

}  // namespace ug::editor
