// Model rows: preparing a detail model from a scanned-size mesh (issue 16, "real-world models are
// fast"). The mesh is the project's own procedural scan, so no large file is committed.
#include <chrono>
#include <cstdio>

#include "cli/bench.h"
#include "core/parallel.h"
#include "mesh/detail_model.h"
#include "mesh/procedural_models.h"

namespace ug::cli {

bool benchModels(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error) {
    using Clock = std::chrono::steady_clock;
    const TriangleMesh scan = makeScannedRock(1'000'000, 1);
    DetailModelSource source;
    source.name = "scan_1m";
    source.anchor_mode = AnchorMode::Surface;  // anchors from the surface: that pass is O(triangles) too
    source.fit.threads = ctx.threads;
    // Fit and anchors, timed from the in-memory mesh (file reading is another row's business).
    const int rep_count = ctx.quick ? 2 : 5;
    std::vector<double> seconds;
    DetailModel model;
    for (int rep = 0; rep < rep_count; ++rep) {
        TriangleMesh copy = scan;
        const auto t0 = Clock::now();
        if (!makeDetailModel(source, std::move(copy), &model, error)) return false;
        seconds.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    }
    const SphereFitReport& r = model.fit_report;
    const int threads = resolveThreadCount(ctx.threads);
    const std::string reps = "median of " + std::to_string(seconds.size()) + ", " + std::to_string(threads) +
                             (threads == 1 ? " thread" : " threads");
    char tolerance[32];
    std::snprintf(tolerance, sizeof tolerance, "<= %.4g", double(r.tolerance_m));
    rows->push_back({"models.scan_1m.triangles", double(scan.triangleCount()), "triangles", "", std::nullopt,
                     "makeScannedRock(1000000, 1), " + std::to_string(scan.positions.size()) + " vertices"});
    rows->push_back({"models.scan_1m.fit_seconds", median(seconds), "s", "<= 3", std::nullopt,
                     reps + "; sphere fit + surface anchors (all-pairs fit before: 86 s)"});
    rows->push_back(
        {"models.scan_1m.spheres", double(r.sphere_count), "spheres", "", std::nullopt,
         "max_spheres " + std::to_string(source.fit.max_spheres) + (r.radii_grown ? ", coarsened" : "")});
    rows->push_back({"models.scan_1m.coverage_m", double(r.max_check_distance_m), "m", tolerance,
                     std::nullopt,
                     "worst of " + std::to_string(r.check_sample_count) + " independent check samples"});
    std::fprintf(stderr, "  scan_1m %zu triangles: %.3f s, %u spheres, coverage %.4f m (tolerance %.4f m)\n",
                 scan.triangleCount(), median(seconds), r.sphere_count, double(r.max_check_distance_m),
                 double(r.tolerance_m));
    return true;
}

}  // namespace ug::cli
