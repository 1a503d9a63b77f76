#include "editor/static_lod.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include <meshoptimizer.h>

#include "core/hash.h"
#include "core/parallel.h"

namespace ug::editor {

namespace {

constexpr uint32_t kNoVertex = std::numeric_limits<uint32_t>::max();
// The relative error bounds tried in turn for the next level: a bound that cannot halve the previous
// level hands over to the next, larger one.
constexpr std::array<float, 4> kLevelErrorBounds = {0.01f, 0.03f, 0.1f, 0.3f};

int64_t cellIndex(float v, float cell_m) {
    return int64_t(std::clamp(std::floor(double(v) / double(cell_m)), -1e15, 1e15));
}

// A piece's triangles with their own compact vertex array: meshoptimizer's cost and memory follow the
// vertex count it is given, and a cell of a 1 M-vertex chunk uses a sixteenth of them.
struct LocalPiece {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;  // empty when the mesh has none (no shading term then)
    std::vector<uint32_t> global;   // local vertex -> mesh vertex
    std::vector<uint32_t> indices;  // local
};

// `local` (mesh vertex -> piece vertex, kNoVertex where unused) is the worker's scratch, sized once and
// reset to kNoVertex where this piece wrote it: a mesh split into thousands of cells must not clear a
// whole vertex-sized array per cell.
LocalPiece gatherPiece(const TriangleMesh& mesh, const std::vector<uint32_t>* triangle_ids,
                       std::vector<uint32_t>* scratch) {
    LocalPiece out;
    std::vector<uint32_t>& local = *scratch;
    if (local.size() < mesh.positions.size()) local.assign(mesh.positions.size(), kNoVertex);
    const size_t triangles = triangle_ids ? triangle_ids->size() : mesh.indices.size() / 3;
    out.indices.reserve(triangles * 3);
    for (size_t t = 0; t < triangles; ++t) {
        const size_t tri = triangle_ids ? (*triangle_ids)[t] : t;
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t v = mesh.indices[tri * 3 + k];
            assert(v < mesh.positions.size());
            if (local[v] == kNoVertex) {
                local[v] = uint32_t(out.positions.size());
                out.positions.push_back(mesh.positions[v]);
                if (mesh.normals.size() == mesh.positions.size()) out.normals.push_back(mesh.normals[v]);
                out.global.push_back(v);
            }
            out.indices.push_back(local[v]);
        }
    }
    for (uint32_t v : out.global) local[v] = kNoVertex;
    return out;
}

// The next level from `previous`, or empty when no bound left halves it. *error_rel: meshoptimizer's
// relative error of the step; *bound: the next bound to try (bounds only grow, so levels coarsen).
std::vector<uint32_t> simplifyStep(const LocalPiece& piece, const std::vector<uint32_t>& previous, size_t* bound,
                                   float* error_rel) {
    const size_t previous_triangles = previous.size() / 3;
    const size_t target = std::max<size_t>(1, previous_triangles / 4) * 3;
    std::vector<uint32_t> out(previous.size());
    for (; *bound < kLevelErrorBounds.size(); ++*bound) {
        float error = 0.0f;
        out.resize(previous.size());
        out.resize(meshopt_simplify(out.data(), previous.data(), previous.size(), &piece.positions[0].x,
                                    piece.positions.size(), sizeof(glm::vec3), target, kLevelErrorBounds[*bound],
                                    meshopt_SimplifyLockBorder, &error));
        if (!out.empty() && double(out.size() / 3) <= double(kStaticLevelShrink) * double(previous_triangles)) {
            *error_rel = error;
            ++*bound;
            return out;
        }
    }
    return {};
}

// How far a level's shading strays, in metres: the level keeps level 0's vertex normals, so a triangle
// that now spans from one rim of a bevelled face to the other spreads the rim's tilted normal over the
// face. Per triangle: its width (smallest altitude) times how much its corner normals differ (largest
// chord between them, ~ the angle); the largest over the level. meshoptimizer 0.18 weighs positions only.
float shadingSpread(const LocalPiece& piece, const std::vector<uint32_t>& indices) {
    if (piece.normals.empty()) return 0.0f;
    float worst = 0.0f;
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
        const glm::vec3 &pa = piece.positions[a], &pb = piece.positions[b], &pc = piece.positions[c];
        const float longest = std::max({glm::length(pb - pa), glm::length(pc - pb), glm::length(pa - pc)});
        if (!(longest > 0.0f)) continue;
        const float width = glm::length(glm::cross(pb - pa, pc - pa)) / longest;
        const glm::vec3 &na = piece.normals[a], &nb = piece.normals[b], &nc = piece.normals[c];
        const float spread = std::max({glm::length(nb - na), glm::length(nc - nb), glm::length(na - nc)});
        worst = std::max(worst, width * spread);
    }
    return worst;
}

}  // namespace

std::vector<std::vector<uint32_t>> splitTrianglesIntoCells(const TriangleMesh& mesh, float cell_m) {
    std::map<std::pair<int64_t, int64_t>, std::vector<uint32_t>> cells;
    const size_t triangles = mesh.indices.size() / 3;
    for (size_t t = 0; t < triangles; ++t) {
        const glm::vec3 c = (mesh.positions[mesh.indices[t * 3]] + mesh.positions[mesh.indices[t * 3 + 1]] +
                             mesh.positions[mesh.indices[t * 3 + 2]]) /
                            3.0f;
        cells[{cellIndex(c.x, cell_m), cellIndex(c.y, cell_m)}].push_back(uint32_t(t));
    }
    std::vector<std::vector<uint32_t>> out;
    out.reserve(cells.size());
    for (auto& [key, ids] : cells) out.push_back(std::move(ids));
    return out;
}

float splitCellSize(const TriangleMesh& mesh) {
    const size_t triangles = mesh.indices.size() / 3;
    if (triangles == 0) return kStaticCellM;
    Bounds box;
    for (uint32_t v : mesh.indices) box = unite(box, Bounds{mesh.positions[v], mesh.positions[v]});
    const double area = double(box.hi.x - box.lo.x) * double(box.hi.y - box.lo.y);
    const double cell = std::sqrt(area * double(kStaticCellMinTriangles) / double(triangles));
    if (!(cell > double(kStaticCellM))) return kStaticCellM;  // dense, flat in XY (a wall), or not finite
    return float(std::min(cell, 1e6));
}

StaticLodPiece buildStaticLodPiece(const TriangleMesh& mesh, const std::vector<uint32_t>* triangle_ids,
                                   std::vector<uint32_t>* indices, std::vector<uint32_t>* scratch) {
    StaticLodPiece piece;
    std::vector<uint32_t> own;
    const LocalPiece local = gatherPiece(mesh, triangle_ids, scratch ? scratch : &own);
    for (const glm::vec3& p : local.positions) piece.bounds = unite(piece.bounds, Bounds{p, p});
    auto append = [&](const std::vector<uint32_t>& level, int k) {
        piece.first[size_t(k)] = uint32_t(indices->size());
        piece.count[size_t(k)] = uint32_t(level.size());
        for (uint32_t v : level) indices->push_back(local.global[v]);
    };
    append(local.indices, 0);
    piece.level_count = 1;
    if (local.indices.empty()) return piece;
    const float scale = meshopt_simplifyScale(&local.positions[0].x, local.positions.size(), sizeof(glm::vec3));
    std::vector<uint32_t> previous = local.indices;
    const float shading0 = shadingSpread(local, local.indices);
    float geometric = 0.0f;
    size_t bound = 0;
    while (piece.level_count < uint32_t(kStaticLodLevels)) {
        float error_rel = 0.0f;
        std::vector<uint32_t> level = simplifyStep(local, previous, &bound, &error_rel);
        if (level.empty()) break;
        const int k = int(piece.level_count);
        geometric += error_rel * scale;
        const float shading = kStaticShadingWeight * std::max(0.0f, shadingSpread(local, level) - shading0);
        piece.error_m[size_t(k)] = std::max({piece.error_m[size_t(k - 1)], geometric, shading});
        append(level, k);
        ++piece.level_count;
        previous = std::move(level);
    }
    return piece;
}

std::vector<StaticLodMesh> buildStaticLodMeshes(const std::vector<const TriangleMesh*>& meshes,
                                                const std::vector<bool>& split, int threads) {
    assert(split.size() == meshes.size());
    // One job per piece over all meshes, so that a single huge split entry still spreads over the workers.
    struct Job {
        size_t mesh = 0;
        std::vector<uint32_t> triangle_ids;
        bool whole = true;
        StaticLodPiece piece;
        std::vector<uint32_t> indices;
    };
    std::vector<Job> jobs;
    std::vector<StaticLodMesh> out(meshes.size());
    for (size_t m = 0; m < meshes.size(); ++m) {
        if (!meshes[m] || meshes[m]->indices.empty()) continue;
        out[m].split = split[m];
        if (!split[m]) {
            jobs.push_back(Job{m, {}, true, {}, {}});
            continue;
        }
        for (std::vector<uint32_t>& ids : splitTrianglesIntoCells(*meshes[m], splitCellSize(*meshes[m])))
            jobs.push_back(Job{m, std::move(ids), false, {}, {}});
    }
    const int workers = resolveThreadCount(threads);
    std::vector<std::vector<uint32_t>> scratch(static_cast<size_t>(workers));
    parallelFor(jobs.size(), workers, 1, [&](size_t begin, size_t end, int worker) {
        for (size_t j = begin; j < end; ++j) {
            Job& job = jobs[j];
            job.piece = buildStaticLodPiece(*meshes[job.mesh], job.whole ? nullptr : &job.triangle_ids, &job.indices,
                                            &scratch[size_t(worker)]);
            job.triangle_ids = {};
        }
    });
    // Merged in job order: the same bytes for any thread count.
    for (Job& job : jobs) {
        StaticLodMesh& mesh = out[job.mesh];
        const uint32_t offset = uint32_t(mesh.indices.size());
        for (uint32_t k = 0; k < job.piece.level_count; ++k) job.piece.first[k] += offset;
        mesh.indices.insert(mesh.indices.end(), job.indices.begin(), job.indices.end());
        mesh.bounds = unite(mesh.bounds, job.piece.bounds);
        mesh.pieces.push_back(job.piece);
    }
    return out;
}

float distanceToBox(const glm::vec3& eye, const Bounds& box) {
    const glm::vec3 d = glm::max(glm::max(box.lo - eye, eye - box.hi), glm::vec3(0.0f));
    return glm::length(d);
}

int chooseStaticLevel(const StaticLodPiece& piece, float scale, float size_m, float distance_m,
                      float pixels_per_radian) {
    if (!(distance_m > 0.0f)) return 0;  // the eye inside the chunk: full detail
    const float px_per_m = pixels_per_radian / distance_m;
    if (size_m * px_per_m < kStaticSkipPx) return -1;
    int level = 0;
    for (uint32_t k = 1; k < piece.level_count; ++k)
        if (piece.error_m[k] * scale * px_per_m < kStaticLodErrorPx) level = int(k);
    return level;
}

std::vector<Bounds> staticPieceBounds(const StaticLodMesh& lods, const GpuStaticInstance& instance) {
    std::vector<Bounds> out;
    if (!lods.split) return out;
    out.reserve(lods.pieces.size());
    for (const StaticLodPiece& piece : lods.pieces) out.push_back(staticInstanceBox(instance, piece.bounds));
    return out;
}

uint64_t buildStaticDraws(const StaticEntryLods& entry, const glm::mat4& view_proj, const glm::vec3& eye,
                          float pixels_per_radian, int coarser, std::vector<StaticDrawRange>* out) {
    out->clear();
    uint64_t triangles = 0;
    const StaticLodMesh& lods = entry.lods;
    if (lods.pieces.empty() || entry.chunks.empty()) return 0;
    auto emit = [&](const StaticLodPiece& piece, int level, uint32_t first_instance, uint32_t instances,
                    bool may_merge) {
        level = std::min(level + coarser, int(piece.level_count) - 1);
        const uint32_t first = piece.first[size_t(level)], count = piece.count[size_t(level)];
        triangles += uint64_t(count / 3) * instances;
        if (may_merge && !out->empty()) {
            StaticDrawRange& last = out->back();
            if (last.first_index == first && last.index_count == count &&
                last.first_instance + last.instance_count == first_instance) {
                last.instance_count += instances;
                return;
            }
        }
        out->push_back({first, count, first_instance, instances});
    };
    if (lods.split) {
        // One instance (chunk 0); each piece culled and chosen on its own.
        const StaticInstanceChunks::Chunk& chunk = entry.chunks.front();
        for (size_t p = 0; p < lods.pieces.size() && p < entry.piece_bounds.size(); ++p) {
            const Bounds& box = entry.piece_bounds[p];
            if (!boxInFrustum(view_proj, box)) continue;
            const int level = chooseStaticLevel(lods.pieces[p], chunk.scale_max, glm::length(box.hi - box.lo),
                                                distanceToBox(eye, box), pixels_per_radian);
            if (level >= 0) emit(lods.pieces[p], level, chunk.first, chunk.count, false);
        }
        return triangles;
    }
    const StaticLodPiece& piece = lods.pieces.front();
    // Chunks lie one after the other in the instance buffer: a run merges while they stay contiguous (no
    // chunk between them culled or skipped) and at one level.
    for (const StaticInstanceChunks::Chunk& chunk : entry.chunks) {
        if (!boxInFrustum(view_proj, chunk.bounds)) continue;
        const int level = chooseStaticLevel(piece, chunk.scale_max, lods.diameter() * chunk.scale_max,
                                            distanceToBox(eye, chunk.bounds), pixels_per_radian);
        if (level >= 0) emit(piece, level, chunk.first, chunk.count, true);
    }
    return triangles;
}

StaticLodMesh authoredStaticLod(const TriangleMesh& mesh, const std::vector<MeshLodLevel>& levels) {
    StaticLodMesh out;
    StaticLodPiece piece;
    for (const glm::vec3& p : mesh.positions) piece.bounds = unite(piece.bounds, Bounds{p, p});
    out.indices = mesh.indices;
    piece.first[0] = 0;
    piece.count[0] = uint32_t(mesh.indices.size());
    for (size_t k = 0; k < levels.size() && k + 1 < size_t(kStaticLodLevels); ++k) {
        const uint32_t level = piece.level_count++;
        piece.first[level] = uint32_t(out.indices.size());
        piece.count[level] = uint32_t(levels[k].indices.size());
        piece.error_m[level] = std::max(levels[k].error_m, piece.error_m[level - 1]);
        out.indices.insert(out.indices.end(), levels[k].indices.begin(), levels[k].indices.end());
    }
    out.bounds = piece.bounds;
    out.pieces.push_back(piece);
    return out;
}

std::vector<const MeshInstances*> drawnStaticEntries(const std::vector<MeshInstances>* meshes) {
    std::vector<const MeshInstances*> out;
    if (meshes)
        for (const MeshInstances& entry : *meshes)
            if (entry.mesh && !entry.mesh->indices.empty()) out.push_back(&entry);
    return out;
}

std::vector<SunCaster> sunCasters(const std::vector<MeshInstances>* meshes) {
    std::vector<StaticEntryKey> keys;
    for (const MeshInstances* entry : drawnStaticEntries(meshes)) keys.push_back(staticEntryKey(*entry));
    return sunCasters(keys);
}

std::vector<SunCaster> sunCasters(const std::vector<StaticEntryKey>& keys) {
    std::vector<SunCaster> out;
    for (const StaticEntryKey& key : keys)
        if (castsSunShadow(key.ground_layer)) out.push_back({key.mesh, key.lod_levels, key.instances_hash});
    return out;
}

StaticEntryKey staticEntryKey(const MeshInstances& entry) {
    static_assert(sizeof(InstanceTransform) == 8 * sizeof(float), "instances are hashed as bytes: no padding");
    return {entry.mesh, entry.lod_levels, entry.instances.size(),
            hashBytes(entry.instances.data(), entry.instances.size() * sizeof(InstanceTransform)),
            entry.material ? *entry.material : SurfaceMaterial{}, entry.ground_layer};
}

std::vector<std::shared_ptr<const StaticLodMesh>> StaticLodCache::levels(
    const std::vector<std::shared_ptr<const TriangleMesh>>& meshes, const std::vector<bool>& split, int threads,
    size_t* built) {
    assert(split.size() == meshes.size());
    std::map<std::pair<const TriangleMesh*, bool>, size_t> known;
    for (size_t k = 0; k < kept_.size(); ++k) known[{kept_[k].mesh.get(), kept_[k].split}] = k;
    std::vector<const TriangleMesh*> missing;
    std::vector<bool> missing_split;
    std::vector<size_t> missing_at;
    std::vector<std::shared_ptr<const StaticLodMesh>> out(meshes.size());
    for (size_t i = 0; i < meshes.size(); ++i) {
        const auto it = known.find({meshes[i].get(), split[i]});
        if (it != known.end()) {
            out[i] = kept_[it->second].levels;
        } else {
            missing.push_back(meshes[i].get());
            missing_split.push_back(split[i]);
            missing_at.push_back(i);
        }
    }
    std::vector<StaticLodMesh> fresh = buildStaticLodMeshes(missing, missing_split, threads);
    for (size_t k = 0; k < fresh.size(); ++k) out[missing_at[k]] = std::make_shared<const StaticLodMesh>(std::move(fresh[k]));
    std::vector<Kept> next;
    next.reserve(meshes.size());
    for (size_t i = 0; i < meshes.size(); ++i) next.push_back(Kept{meshes[i], split[i], out[i]});
    kept_ = std::move(next);
    if (built) *built = missing.size();
    return out;
}

}  // namespace ug::editor
