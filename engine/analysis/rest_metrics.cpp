#include "analysis/rest_metrics.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>

#include "core/xy_grid.h"
#include "core/parallel.h"
#include "mesh/triangle_bvh.h"

namespace ug {

namespace {

struct WorldSpheres {
    std::vector<glm::vec3> center;
    std::vector<float> radius;
    std::vector<uint32_t> owner;  // instance index
    std::vector<uint32_t> begin;  // per instance: first sphere; instances + 1 entries
    float max_radius = 0.0f;
};

WorldSpheres worldSpheres(std::span<const PlacedInstance> instances, const std::vector<const DetailModel*>& models) {
    WorldSpheres w;
    w.begin.reserve(instances.size() + 1);
    std::vector<Sphere> tmp;
    for (size_t i = 0; i < instances.size(); ++i) {
        w.begin.push_back(uint32_t(w.center.size()));
        placedSpheres(instances[i], *models[instances[i].type], &tmp);
        for (const Sphere& s : tmp) {
            w.center.push_back(s.center);
            w.radius.push_back(s.radius);
            w.owner.push_back(uint32_t(i));
            w.max_radius = std::max(w.max_radius, s.radius);
        }
    }
    w.begin.push_back(uint32_t(w.center.size()));
    return w;
}

XyGrid sphereGrid(const WorldSpheres& w) {
    return XyGrid(std::span<const glm::vec3>(w.center), std::max(2.0f * w.max_radius, 1e-3f));
}

double median(std::vector<float> v) {
    if (v.empty()) return 0.0;
    const size_t m = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + long(m), v.end());
    return double(v[m]);
}

void summarize(RestReport* report, const std::vector<float>& drop, const std::vector<float>& sunk, float threshold_m) {
    for (size_t i = 0; i < drop.size(); ++i) {
        if (drop[i] > threshold_m) ++report->hovering;
        if (drop[i] > 0.05f) ++report->hovering_5cm;
        if (sunk[i] > threshold_m) ++report->sunk;
        report->max_drop_m = std::max(report->max_drop_m, double(drop[i]));
        report->max_sunk_m = std::max(report->max_sunk_m, double(sunk[i]));
    }
    if (drop.empty()) return;
    const double n = double(drop.size());
    report->hovering_fraction = double(report->hovering) / n;
    report->sunk_fraction = double(report->sunk) / n;
    report->median_drop_m = median(drop);
}

}  // namespace

RestReport measureRest(std::span<const PlacedInstance> instances, const std::vector<const DetailModel*>& models,
                       const RestSupport& support, float threshold_m, int threads) {
    RestReport report;
    report.instances = instances.size();
    report.drop_m.assign(instances.size(), 0.0f);
    if (instances.empty()) return report;
    const WorldSpheres w = worldSpheres(instances, models);
    const XyGrid grid = sphereGrid(w);
    std::vector<float>& sunk = report.sunk_m;
    sunk.assign(instances.size(), 0.0f);

    parallelFor(instances.size(), threads, 256, [&](size_t b, size_t e, int) {
        for (size_t i = b; i < e; ++i) {
            float drop = std::numeric_limits<float>::infinity();
            float depth = 0.0f;
            for (uint32_t s = w.begin[i]; s < w.begin[i + 1]; ++s) {
                const glm::vec3 a = w.center[s];
                const float ra = w.radius[s];
                drop = std::min(drop, std::max(0.0f, supportClearance(support, a, ra)));
                depth = std::max(depth, support.heightBelow(a.x, a.y, a.z) - (a.z - ra));
                grid.forEachNear(glm::vec2(a), ra + w.max_radius, [&](uint32_t o) {
                    if (w.owner[o] == i) return;
                    const glm::vec3 bc = w.center[o];
                    if (bc.z > a.z) return;  // a centre above cannot stop a fall
                    const float reach = ra + w.radius[o];
                    const float dx = a.x - bc.x, dy = a.y - bc.y;
                    const float h2 = dx * dx + dy * dy;
                    if (h2 >= reach * reach) return;
                    drop = std::min(drop, std::max(0.0f, a.z - bc.z - std::sqrt(reach * reach - h2)));
                });
            }
            report.drop_m[i] = drop;
            sunk[i] = depth;
        }
    });

    summarize(&report, report.drop_m, sunk, threshold_m);
    return report;
}

std::vector<RestReport> restPerType(const RestReport& all, std::span<const PlacedInstance> instances,
                                    uint32_t type_count, float threshold_m) {
    std::vector<std::vector<float>> drop(type_count), sunk(type_count);
    for (size_t i = 0; i < instances.size() && i < all.drop_m.size(); ++i) {
        if (instances[i].type >= type_count) continue;
        drop[instances[i].type].push_back(all.drop_m[i]);
        sunk[instances[i].type].push_back(all.sunk_m[i]);
    }
    std::vector<RestReport> out(type_count);
    for (uint32_t t = 0; t < type_count; ++t) {
        out[t].instances = drop[t].size();
        summarize(&out[t], drop[t], sunk[t], threshold_m);
    }
    return out;
}

namespace {

// Ray parity in model space: a point is inside a closed mesh when a ray from it crosses the surface an odd
// number of times. The direction is skewed off every axis and diagonal so that rays rarely graze an edge.
bool insideMesh(const TriangleBvh& bvh, glm::vec3 q) {
    const glm::vec3 d = glm::normalize(glm::vec3(0.3141f, 0.4719f, 0.8243f));
    int crossings = 0;
    glm::vec3 o = q;
    for (int k = 0; k < 256; ++k) {
        const float t = bvh.rayHit(o, d);
        if (!std::isfinite(t)) break;
        ++crossings;
        o += d * (t + 1e-5f);
    }
    return (crossings & 1) != 0;
}

}  // namespace

PackingReport measurePacking(std::span<const PlacedInstance> all, const std::vector<const DetailModel*>& models,
                             const RestSupport& support, const std::vector<uint32_t>& types, float cell_m,
                             int threads, const Bounds* clip) {
    PackingReport report;
    std::vector<PlacedInstance> pile;
    for (const PlacedInstance& p : all)
        if (types.empty() || std::find(types.begin(), types.end(), p.type) != types.end()) pile.push_back(p);
    if (pile.empty() || !(cell_m > 0.0f)) return report;

    const WorldSpheres w = worldSpheres(pile, models);
    const XyGrid spheres = sphereGrid(w);
    // Instances by their bounding sphere, for the inside test.
    std::vector<glm::vec3> bound_center(pile.size());
    std::vector<float> bound_radius(pile.size());
    float max_bound = 0.0f;
    for (size_t i = 0; i < pile.size(); ++i) {
        const DetailModel& m = *models[pile[i].type];
        bound_center[i] = pile[i].position + pile[i].rotation * (pile[i].scale * m.bounds.center);
        bound_radius[i] = pile[i].scale * m.bounds.radius;
        max_bound = std::max(max_bound, bound_radius[i]);
    }
    const XyGrid bounds_grid(std::span<const glm::vec3>(bound_center), std::max(2.0f * max_bound, 1e-3f));
    report.shell_m = float(median(bound_radius));

    std::vector<std::unique_ptr<TriangleBvh>> bvh(models.size());
    for (const PlacedInstance& p : pile)
        if (!bvh[p.type]) bvh[p.type] = std::make_unique<TriangleBvh>(models[p.type]->mesh, threads);

    glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (size_t i = 0; i < pile.size(); ++i) {
        lo = glm::min(lo, glm::vec2(bound_center[i]) - bound_radius[i]);
        hi = glm::max(hi, glm::vec2(bound_center[i]) + bound_radius[i]);
    }
    float lowest = std::numeric_limits<float>::max();
    for (size_t s = 0; s < w.center.size(); ++s) lowest = std::min(lowest, w.center[s].z - w.radius[s]);
    const int nx = std::max(1, int(std::ceil((hi.x - lo.x) / cell_m)));
    const int ny = std::max(1, int(std::ceil((hi.y - lo.y) / cell_m)));
    std::atomic<uint64_t> core{0}, solid{0}, overlap{0};
    parallelFor(size_t(nx) * size_t(ny), threads, 64, [&](size_t b, size_t e, int) {
        uint64_t my_core = 0, my_solid = 0, my_overlap = 0;
        for (size_t col = b; col < e; ++col) {
            const glm::vec2 xy = lo + cell_m * (glm::vec2(float(col % size_t(nx)), float(col / size_t(nx))) + 0.5f);
            if (clip && !(clip->lo.x <= xy.x && xy.x < clip->hi.x && clip->lo.y <= xy.y && xy.y < clip->hi.y))
                continue;
            const float m = report.shell_m;
            float top = -std::numeric_limits<float>::infinity();
            spheres.forEachNear(xy, w.max_radius + m, [&](uint32_t s) {
                const glm::vec3 c = w.center[s];
                const float r = w.radius[s] + m;
                const float h2 = (xy.x - c.x) * (xy.x - c.x) + (xy.y - c.y) * (xy.y - c.y);
                if (h2 < r * r) top = std::max(top, c.z + std::sqrt(r * r - h2));
            });
            // Without a ground plane the pile stands on its own lowest grains.
            const float ground = support.heightAt(xy.x, xy.y);
            const float bottom = std::isfinite(ground) ? ground : lowest;
            for (float z = bottom + 0.5f * cell_m; z < top - 2.0f * m; z += cell_m) {
                ++my_core;
                const glm::vec3 p(xy, z);
                int inside = 0;  // meshes holding p, counted up to two (solid, and solid twice over)
                bounds_grid.forEachNear(xy, max_bound, [&](uint32_t i) {
                    if (inside >= 2) return;
                    const glm::vec3 d = p - bound_center[i];
                    if (glm::dot(d, d) > bound_radius[i] * bound_radius[i]) return;
                    const glm::vec3 q = glm::conjugate(pile[i].rotation) * (p - pile[i].position) / pile[i].scale;
                    if (insideMesh(*bvh[pile[i].type], q)) ++inside;
                });
                if (inside >= 1) ++my_solid;
                if (inside >= 2) ++my_overlap;
            }
        }
        core += my_core;
        solid += my_solid;
        overlap += my_overlap;
    });
    report.core_samples = core.load();
    report.solid_samples = solid.load();
    report.overlap_samples = overlap.load();
    report.overlap_fraction =
        report.solid_samples ? double(report.overlap_samples) / double(report.solid_samples) : 0.0;
    report.core_volume_m3 = double(report.core_samples) * double(cell_m) * cell_m * cell_m;
    report.volume_fraction =
        report.core_samples ? double(report.solid_samples) / double(report.core_samples) : 0.0;
    return report;
}

}  // namespace ug
