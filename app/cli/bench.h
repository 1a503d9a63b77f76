// `undergrowth bench`: each section appends rows; the command prints the table and writes the JSON.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "io/bench_report.h"

namespace ug::cli {

struct BenchContext {
    bool quick = false;        // fewer repetitions and smaller cases, for CI smoke runs
    int threads = 0;           // 0 = all hardware threads
    std::string assets_dir;
    std::string filter;        // run only sections whose name contains this
    std::string cache_dir = "out/cache";  // Ghost Tile cache for scene-based sections
    int repetitions() const { return quick ? 3 : 7; }
};

// Seconds of wall time since t0 (the sections' timings; medians are taken by the callers).
inline double since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Returns false with an error when a section cannot run at all (e.g. a missing asset).
bool benchGhostTile(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error);
bool benchInstancer(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error);
// Detail model preparation (sphere fit and anchors) on a 1 M-triangle procedural scan.
bool benchModels(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error);
// Rest, packing and tiling of the sample scenes (pile.*, tiling.*): measurements, not timings.
bool benchPile(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error);
// In the editor's window where one opens, else offscreen (EGL); the editor.stamp_* rows need the window.
// Environmental objects: snow and icicles of the winter scenes, a local edit, LOD nodes (env.*).
bool benchEnvironment(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error);
// Scattered effects: leaves and grass of the autumn scenes, LOD nodes on the park, a street edit (env.*).
bool benchScatter(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error);
// Particle sculpting: a fur ball of 100k strands x 64 steps x 8 trials with collisions (particles.*).
bool benchParticles(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error);
// Region jobs: the 1 km^2 world in one process and through a Slurm job array (world.*); skipped without
// a cluster (SLURM_CONF, or root and slurm-wlm for a single-node one) and in --quick.
bool benchWorld(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error);
bool benchRender(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error);

}  // namespace ug::cli
