// Collision sphere sets for detail models (Ghost Tile §4.3, Figure 8: "input objects approximated by
// unions of spheres"). The paper cites variational fitting [WSL*06] and medial spheres [SKS12]; we use
// the medial idea in its simplest robust form, a set-cover over surface samples:
//
//  1. Sample the surface densely (area-uniform, stratified along the triangle list).
//  2. At every sample p with outward normal n, the largest ball tangent at p that holds no sample
//     strictly inside ("shrinking ball") has radius
//         r(p) = min over samples q with m.(q - p) > 0 of |q - p|^2 / (2 m.(q - p)),   m = -n,
//     which is the exact solution of |p + r m - q| = r for the binding q; no iteration is needed.
//     Such balls approximate the inner medial axis: they stay inside a closed mesh, so the union is
//     tight. When no sample binds (open or inverted surface) we take r = 0.
//  3. Each candidate is the ball at p + r m with radius max(r, tolerance): thin parts (a leaf blade, a
//     needle, r ~ half the thickness) get balls of about the tolerance, so they need many small
//     spheres, as in the paper's leaves and branches, instead of a few balls bulging off the surface.
//  4. Greedy set cover (lazy, exact greedy): repeatedly take the candidate that covers the most still
//     uncovered samples; a sample is covered when its distance to the ball's surface is within the fit
//     tolerance. If max_spheres is reached first, each uncovered sample grows its nearest sphere just
//     enough, so coverage of the samples always holds (report.radii_grown).
//
// Coverage between samples: the distance to a union of balls is 1-Lipschitz, so a point within h of a
// covered sample is within (fit tolerance + h). We fit to 0.75 of the asked tolerance and then check a
// second, independent sample set, adding any of its points beyond 0.9 of the tolerance to the sample
// set and refitting (at most twice). A third set, again independent, measures what we report.
#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <limits>
#include <queue>

#include "core/hash.h"
#include "core/parallel.h"
#include "mesh/detail_model.h"

namespace ug {
namespace {

constexpr float kFitToleranceFraction = 0.70f;     // fit below the asked tolerance (see above)
constexpr float kRepairToleranceFraction = 0.80f;  // check-set points beyond this join the fit set
constexpr int kRepairRounds = 6;
constexpr float kBulgeFraction = 0.5f;  // medial balls may stand this much (x tolerance) off the surface
constexpr int kCoarsenAttempts = 4;
constexpr uint64_t kRepairSeedSalt = 0x5e11'0c4e'c4ull;
constexpr uint64_t kReportSeedSalt = 0x0e90'47ull;

bool fail(std::string* error, const std::string& why) {
    if (error) *error = why;
    return false;
}

// Distance along the unit direction d from o to the nearest triangle (Moller-Trumbore), or +inf.
float rayHit(const TriangleMesh& mesh, const glm::vec3& o, const glm::vec3& d) {
    float best = std::numeric_limits<float>::infinity();
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
        const glm::vec3 a = mesh.positions[mesh.indices[t]];
        const glm::vec3 e1 = mesh.positions[mesh.indices[t + 1]] - a, e2 = mesh.positions[mesh.indices[t + 2]] - a;
        const glm::vec3 pv = glm::cross(d, e2);
        const float det = glm::dot(e1, pv);
        if (std::abs(det) < 1e-20f) continue;
        const float inv = 1.0f / det;
        const glm::vec3 tv = o - a;
        const float u = glm::dot(tv, pv) * inv;
        if (u < 0.0f || u > 1.0f) continue;
        const glm::vec3 qv = glm::cross(tv, e1);
        const float v = glm::dot(d, qv) * inv;
        if (v < 0.0f || u + v > 1.0f) continue;
        const float dist = glm::dot(e2, qv) * inv;
        if (dist > 0.0f && dist < best) best = dist;
    }
    return best;
}

// Steps 2-4 above: appends spheres to `spheres` until every point of `points` is within
// `fit_tolerance_m` of the union (growing radii once `max_spheres` is reached). `medial_points` is every
// sample known on the surface; the shrinking balls are bound by them. Returns true if radii were grown.
bool coverPoints(const TriangleMesh& mesh, const std::vector<glm::vec3>& medial_points, const std::vector<glm::vec3>& points,
                 const std::vector<glm::vec3>& normals, const Bounds3& box, float tolerance_m, float fit_tolerance_m,
                 uint32_t max_spheres, float bulge_m, std::vector<Sphere>* spheres) {
    const size_t n = points.size();
    if (n == 0) return false;
    const glm::vec3 extent = box.max - box.min;
    const float max_radius_m = 0.5f * std::max(extent.x, std::max(extent.y, extent.z));
    const glm::vec3 lo = box.min - glm::vec3(tolerance_m), hi = box.max + glm::vec3(tolerance_m);

    // Candidate balls, one per point (a slot per index keeps the result thread-count independent).
    std::vector<Sphere> cand(n);
    parallelFor(n, 0, 64, [&](size_t begin, size_t end, int) {
        for (size_t i = begin; i < end; ++i) {
            const glm::vec3 p = points[i], m = -normals[i];
            float r = std::numeric_limits<float>::max();
            for (const glm::vec3& q : medial_points) {
                const glm::vec3 d = q - p;
                const float along = glm::dot(m, d);
                if (along <= 0.0f) continue;
                r = std::min(r, glm::dot(d, d) / (2.0f * along));
            }
            if (!(r < max_radius_m)) r = 0.0f;  // nothing binds: open or inverted surface here
            // Samples are sparser than a leaf is thick, so a ball bound only by samples can slip through
            // a thin part; the ray along m to the opposite face bounds it by half the local thickness.
            r = std::min(r, 0.5f * rayHit(mesh, p + 1e-6f * max_radius_m * m, m));
            glm::vec3 c = p + r * m;
            // A centre off the model's box means the ball sits in the outside (inverted normals):
            // fall back to a tolerance-sized ball on the sample, which always covers it.
            if (!(glm::all(glm::greaterThanEqual(c, lo)) && glm::all(glm::lessThanEqual(c, hi)))) {
                r = 0.0f;
                c = p;
            }
            cand[i] = Sphere{c, std::max(r + bulge_m, tolerance_m)};
        }
    });

    // Coverage bit sets: bit j of row i = point j within fit tolerance of candidate i's surface.
    const size_t words = (n + 63) / 64;
    std::vector<uint64_t> cover(n * words, 0);
    parallelFor(n, 0, 64, [&](size_t begin, size_t end, int) {
        for (size_t i = begin; i < end; ++i) {
            const float reach = cand[i].radius + fit_tolerance_m;
            const float reach2 = reach * reach;
            uint64_t* row = &cover[i * words];
            for (size_t j = 0; j < n; ++j) {
                const glm::vec3 d = points[j] - cand[i].center;
                if (glm::dot(d, d) <= reach2) row[j / 64] |= uint64_t(1) << (j % 64);
            }
        }
    });

    std::vector<uint64_t> uncovered(words, ~uint64_t(0));
    if (n % 64) uncovered[words - 1] = (uint64_t(1) << (n % 64)) - 1;
    size_t uncovered_count = n;
    auto gainOf = [&](size_t i) {
        size_t g = 0;
        const uint64_t* row = &cover[i * words];
        for (size_t w = 0; w < words; ++w) g += size_t(std::popcount(row[w] & uncovered[w]));
        return g;
    };
    auto take = [&](size_t i, size_t gain) {
        spheres->push_back(cand[i]);
        const uint64_t* row = &cover[i * words];
        for (size_t w = 0; w < words; ++w) uncovered[w] &= ~row[w];
        uncovered_count -= gain;
    };

    // Lazy greedy: gains only shrink, so a popped entry whose fresh gain still beats the next stored
    // (upper-bound) gain is the true maximum. Ties go to the lower index (determinism).
    using Entry = std::pair<size_t, size_t>;  // (gain, n - index): larger is better
    std::priority_queue<Entry> heap;
    for (size_t i = 0; i < n; ++i) heap.push({gainOf(i), n - i});
    while (uncovered_count > 0 && spheres->size() < max_spheres && !heap.empty()) {
        const Entry top = heap.top();
        heap.pop();
        const size_t i = n - top.second;
        const size_t gain = gainOf(i);
        if (gain == 0) continue;
        if (!heap.empty() && Entry{gain, top.second} < heap.top()) {
            heap.push({gain, top.second});
            continue;
        }
        take(i, gain);
    }
    if (uncovered_count == 0) return false;

    // Bound hit: every uncovered point grows its nearest sphere (by gap to the surface) just enough.
    if (spheres->empty()) take(0, gainOf(0));  // max_spheres >= 1 by contract
    bool grown = false;
    for (size_t j = 0; j < n; ++j) {
        if (!(uncovered[j / 64] >> (j % 64) & 1)) continue;
        size_t best = 0;
        float best_gap = std::numeric_limits<float>::max();
        for (size_t s = 0; s < spheres->size(); ++s) {
            const float gap = glm::length(points[j] - (*spheres)[s].center) - (*spheres)[s].radius;
            if (gap < best_gap) {
                best_gap = gap;
                best = s;
            }
        }
        if (best_gap > fit_tolerance_m) {
            Sphere& s = (*spheres)[best];
            // note: growing to half the fit tolerance (not to it) leaves room for the points between
            // samples, which the grown sphere must also reach.
            s.radius = glm::length(points[j] - s.center) - 0.5f * fit_tolerance_m;
            grown = true;
        }
    }
    return grown;
}

float maxDistance(const std::vector<Sphere>& spheres, const std::vector<glm::vec3>& points) {
    float worst = 0.0f;
    for (const glm::vec3& p : points) worst = std::max(worst, distanceToSphereUnion(spheres, p));
    return worst;
}

}  // namespace

float distanceToSphereUnion(const std::vector<Sphere>& spheres, const glm::vec3& p) {
    float best = std::numeric_limits<float>::infinity();
    for (const Sphere& s : spheres) best = std::min(best, glm::length(p - s.center) - s.radius);
    return std::max(best, 0.0f);
}

void sampleSurface(const TriangleMesh& mesh, uint32_t count, uint64_t seed, std::vector<glm::vec3>* points,
                   std::vector<glm::vec3>* normals) {
    assert(points);
    points->clear();
    if (normals) normals->clear();
    const size_t tri_count = mesh.triangleCount();
    std::vector<double> cumulative(tri_count);
    double total = 0.0;
    for (size_t t = 0; t < tri_count; ++t) {
        const glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                        c = mesh.positions[mesh.indices[3 * t + 2]];
        const double area = 0.5 * double(glm::length(glm::cross(b - a, c - a)));
        total += std::isfinite(area) ? area : 0.0;
        cumulative[t] = total;
    }
    if (!(total > 0.0) || count == 0) return;
    points->reserve(count);
    if (normals) normals->reserve(count);
    for (uint32_t i = 0; i < count; ++i) {
        // Stratified along the cumulative area: sample i falls in the i-th of `count` equal slices, so
        // the set has no large holes along the triangle order (triangles are usually spatially coherent).
        const double u = (double(i) + unitDouble(hashWords(seed, i, 0))) / double(count) * total;
        size_t t = size_t(std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin());
        t = std::min(t, tri_count - 1);
        while (t > 0 && cumulative[t] == cumulative[t - 1]) --t;  // never land on a zero-area triangle
        const glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                        c = mesh.positions[mesh.indices[3 * t + 2]];
        float r1 = std::sqrt(unitFloat(hashWords(seed, i, 1)));
        const float r2 = unitFloat(hashWords(seed, i, 2));
        points->push_back(a * (1.0f - r1) + b * (r1 * (1.0f - r2)) + c * (r1 * r2));
        if (normals) {
            const glm::vec3 n = glm::cross(b - a, c - a);
            const float len = glm::length(n);
            normals->push_back(len > 0.0f ? n / len : glm::vec3(0.0f, 0.0f, 1.0f));
        }
    }
}

bool fitSphereSet(const TriangleMesh& mesh, const SphereFitSettings& settings, std::vector<Sphere>* out,
                  SphereFitReport* report, std::string* error) {
    assert(out);
    if (settings.max_spheres < 1 || settings.max_spheres > 4096)
        return fail(error, "fit.max_spheres = " + std::to_string(settings.max_spheres) + " is outside [1, 4096]");
    if (!std::isfinite(settings.tolerance_m) || settings.tolerance_m < 0.0f)
        return fail(error, "fit.tolerance_m = " + std::to_string(settings.tolerance_m) + " must be finite and >= 0");
    if (settings.tolerance_m == 0.0f && !(std::isfinite(settings.tolerance_rel) && settings.tolerance_rel > 0.0f))
        return fail(error, "fit.tolerance_rel = " + std::to_string(settings.tolerance_rel) +
                               " must be finite and > 0 when fit.tolerance_m is 0");
    if (settings.surface_samples < 16 || settings.surface_samples > 1000000)
        return fail(error, "fit.surface_samples = " + std::to_string(settings.surface_samples) +
                               " is outside [16, 1000000]");
    std::string why;
    if (!validateMesh(mesh, &why)) return fail(error, "mesh: " + why);

    const Bounds3 box = meshBounds(mesh);
    const glm::vec3 centre = 0.5f * (box.min + box.max);
    float bounding_radius_m = 0.0f;
    for (const glm::vec3& p : mesh.positions) bounding_radius_m = std::max(bounding_radius_m, glm::length(p - centre));
    const float tolerance_m = settings.tolerance_m > 0.0f ? settings.tolerance_m : settings.tolerance_rel * bounding_radius_m;
    if (!(tolerance_m > 0.0f) || !std::isfinite(tolerance_m))
        return fail(error, "mesh: degenerate (zero size), cannot derive a tolerance");

    std::vector<glm::vec3> points, normals;
    sampleSurface(mesh, settings.surface_samples, settings.seed, &points, &normals);
    if (points.empty()) return fail(error, "mesh: zero surface area");

    const float fit_tolerance_m = kFitToleranceFraction * tolerance_m;
    // Balls may stand kBulgeFraction * tolerance off the surface: each then covers much more of a smooth
    // surface, and stays within the tolerance band. If the count bound is still hit, coarser balls
    // (doubling the allowance) are tried before radii are grown point by point.
    std::vector<Sphere> spheres;
    bool grown = false;
    // Vertices join the samples: tips and corners (a grass blade's point) have too little area to be
    // sampled reliably but are where coverage fails first. A stride keeps big meshes cheap.
    {
        TriangleMesh with_normals;
        const std::vector<glm::vec3>* vertex_normals = &mesh.normals;
        if (mesh.normals.size() != mesh.positions.size()) {
            with_normals.positions = mesh.positions;
            with_normals.indices = mesh.indices;
            computeNormals(&with_normals);
            vertex_normals = &with_normals.normals;
        }
        const size_t stride = std::max<size_t>(1, mesh.positions.size() / settings.surface_samples);
        for (size_t v = 0; v < mesh.positions.size(); v += stride) {
            points.push_back(mesh.positions[v]);
            normals.push_back((*vertex_normals)[v]);
        }
    }
    const std::vector<glm::vec3> base_points = points, base_normals = normals;
    for (int attempt = 0; attempt < kCoarsenAttempts; ++attempt) {
        const float bulge_m = kBulgeFraction * float(1 << attempt) * tolerance_m;
        points = base_points;
        normals = base_normals;
        spheres.clear();
        grown = coverPoints(mesh, points, points, normals, box, tolerance_m, fit_tolerance_m, settings.max_spheres, bulge_m, &spheres);
        // Repair rounds: fresh independent samples that fall too far out are covered incrementally (the
        // spheres found so far stay), then join the sample set.
        for (int round = 0; round < kRepairRounds; ++round) {
            std::vector<glm::vec3> fresh, fresh_normals, bad, bad_normals;
            sampleSurface(mesh, 2 * settings.surface_samples, hashWords(settings.seed, kRepairSeedSalt, uint64_t(round)), &fresh,
                          &fresh_normals);
            for (size_t j = 0; j < fresh.size(); ++j)
                if (distanceToSphereUnion(spheres, fresh[j]) > kRepairToleranceFraction * tolerance_m) {
                    bad.push_back(fresh[j]);
                    bad_normals.push_back(fresh_normals[j]);
                }
            if (bad.empty()) break;
            points.insert(points.end(), bad.begin(), bad.end());
            normals.insert(normals.end(), bad_normals.begin(), bad_normals.end());
            grown |= coverPoints(mesh, points, bad, bad_normals, box, tolerance_m, fit_tolerance_m, settings.max_spheres, bulge_m, &spheres);
        }

        if (!grown) {
            grown = attempt > 0;  // a coarser pass than the first is a radius increase too
            break;
        }
    }
    std::vector<glm::vec3> check_points;
    sampleSurface(mesh, settings.surface_samples, hashWords(settings.seed, kReportSeedSalt), &check_points, nullptr);
    *out = std::move(spheres);
    if (report) {
        *report = SphereFitReport{};
        report->tolerance_m = tolerance_m;
        report->max_sample_distance_m = maxDistance(*out, points);
        report->sphere_count = uint32_t(out->size());
        report->radii_grown = grown;
        report->max_check_distance_m = maxDistance(*out, check_points);
        report->check_sample_count = uint32_t(check_points.size());
    }
    return true;
}

}  // namespace ug
