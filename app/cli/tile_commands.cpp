// `run` (command 1: the editor on a scene when there is a display, else the main job) and `build-tile`:
// load the project, its models and the Ghost Tile (from the verified cache, or built and cached), then
// write what the job produced and say where.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "cli/env_job.h"
#include "cli/strands_job.h"
#include "cli/scene_job.h"
#include "core/parallel.h"
#include "editor/viewer.h"
#include "io/instance_export.h"
#include "core/atomic_file.h"
#include "core/hash.h"
#include "env/env_models.h"
#include "ghosttile/ghost_tile_cache.h"
#include "io/gltf_mesh_io.h"
#include "mesh/procedural_models.h"
#include "scene/document.h"
#include "scene/project.h"

namespace ug::cli {

namespace fs = std::filesystem;

namespace {

nlohmann::json tileStatsJson(const SceneJob& job, const std::string& cache_path) {
    const GhostTileStats& st = job.tile.stats;
    nlohmann::json types = nlohmann::json::array();
    for (size_t t = 0; t < job.models.size(); ++t) {
        const DetailModel& m = job.models[t];
        types.push_back({{"name", m.name},
                         {"candidates", job.project.detail_types[t].ghost.candidate_count},
                         {"spheres", m.spheres.size()},
                         {"anchors", m.anchors.size()},
                         {"triangles", m.mesh.triangleCount()},
                         {"sphere_fit_tolerance_m", m.fit_report.tolerance_m},
                         {"sphere_fit_max_distance_m", m.fit_report.max_sample_distance_m}});
    }
    return {{"scene", job.project.name},
            {"cache", {{"path", cache_path}, {"outcome", cacheOutcomeName(job.outcome)}}},
            {"ghost_tile",
             {{"key", hex64(job.tile.key)},
              {"tile_size_m", job.tile.settings.tile_size_m},
              {"delta_m", job.tile.settings.delta_m},
              {"variants", job.tile.settings.variants},
              {"candidates", st.candidate_count},  // all variants together
              {"pairs", st.pair_count},
              {"rho", st.rho},
              {"build_seconds", st.build_seconds},
              {"graph_bytes", st.graph_bytes},
              {"bytes_per_pair", st.bytes_per_pair}}},
            {"models_seconds", job.models_seconds},
            {"detail_types", types}};
}

// A look at the tile: every candidate's mesh placed at its frame, one merged mesh per detail type,
// capped so the file stays small. Candidates overlap by design (paper Fig. 3).
bool writeTilePreview(const SceneJob& job, const std::string& path, std::string* error) {
    const CandidateSet& c = job.tile.candidates;
    std::vector<TriangleMesh> merged(job.models.size());
    for (uint32_t t = 0; t < c.typeCount(); ++t) {
        const TriangleMesh& src = job.models[t].mesh;
        TriangleMesh& dst = merged[t];
        dst.base_color = src.base_color;
        const uint32_t limit = std::min(c.type_begin[t + 1], c.type_begin[t] + 200u);
        for (uint32_t i = c.type_begin[t]; i < limit; ++i) {
            const uint32_t base = uint32_t(dst.positions.size());
            for (size_t v = 0; v < src.positions.size(); ++v) {
                dst.positions.push_back(c.position[i] + c.rotation[i] * (c.scale[i] * src.positions[v]));
                if (v < src.normals.size()) dst.normals.push_back(c.rotation[i] * src.normals[v]);
            }
            for (uint32_t idx : src.indices) dst.indices.push_back(base + idx);
        }
    }
    std::vector<std::pair<std::string, const TriangleMesh*>> meshes;
    for (size_t t = 0; t < merged.size(); ++t) meshes.push_back({job.models[t].name, &merged[t]});
    return writeGltfMeshes(path, meshes, error);
}

int fail(const char* command, const std::string& message, int code = 1) {
    std::fprintf(stderr, "undergrowth %s: %s\n", command, message.c_str());
    return code;
}

bool parseThreads(const Args& args, int* threads, std::string* error) {
    if (!args.has("--threads")) return true;
    long t;
    if (!parseInt("--threads", args.get("--threads"), 0, 256, &t, error)) return false;
    *threads = int(t);
    return true;
}

// What the editor does, for someone who just ran command 1 (main_menu.cpp, navigation.cpp, tools.h).
constexpr const char* kEditorNextSteps =
    "Opening the editor on %s. What to do next:\n"
    "  look around   middle drag or Alt+left drag orbits, Shift pans, wheel zooms; Home frames the scene,\n"
    "                1 / 3 / 7 front / side / top view\n"
    "  paint         B, then left drag: adds the Tools window's detail types under the brush\n"
    "  sculpt        S, then left drag or hold: pours a pile of the Tools window's pile type, growing as you hold\n"
    "  erase         E, then left drag; select with Q (click, drag to move, X or Delete removes)\n"
    "  undo / redo   Ctrl+Z / Ctrl+Shift+Z; Ctrl+S saves the scene; F12 takes a screenshot\n"
    "  export        the Export window writes glTF (EXT_mesh_gpu_instancing)\n"
    "  without a display: undergrowth run --headless (the batch job), undergrowth render SCENE -o PICTURE.png\n";

bool displayAvailable() {
    for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY"})
        if (const char* v = std::getenv(name); v && *v) return true;
    return false;
}

// The editor on the scene (as `undergrowth edit`). Returns the exit code, or -1 when no window could be
// opened or the editor failed (the caller then runs the headless job, which reports a bad scene itself).
int runEditorOnScene(const std::string& scene, const std::string& cache_dir, int threads, long frames,
                     const std::string& screenshot) {
    std::printf(kEditorNextSteps, scene.c_str());
    std::fflush(stdout);
    editor::ViewerOptions options;
    options.scene_path = scene;
    options.cache_dir = cache_dir;
    options.threads = threads;
    options.config_dir = defaultConfigDir();
    options.frames = int(frames);
    options.finish_each_frame = frames > 0;
    options.screenshot_path = screenshot;
    editor::ViewerResult result;
    std::string error;
    if (editor::runViewer(options, &result, &error) != editor::ViewerStatus::Ok) {
        std::fprintf(stderr, "undergrowth run: note: the editor did not open (%s); running the headless job instead\n",
                     error.c_str());
        return -1;
    }
    if (!result.screenshot.empty()) std::fprintf(stderr, "run: wrote %s\n", result.screenshot.c_str());
    for (const std::string& m : result.messages) std::fprintf(stderr, "run: message: %s\n", m.c_str());
    return 0;
}

int runHeadlessJob(const std::string& scene, const std::string& out_dir, int threads);

}  // namespace

int runMainJob(int argc, char** argv) {
    const char* usage =
        "usage: undergrowth run [SCENE] [--out DIR] [--threads N] [--headless] [--frames N] [--screenshot OUT.png]";
    Args args;
    std::string error;
    if (!parseArgs(argc, argv, 2, {"--out", "--threads", "--frames", "--screenshot"}, {"--headless"}, &args, &error) ||
        args.positional.size() > 1)
        return fail("run", error.empty() ? usage : error + "\n" + usage, 2);
    int threads = 0;
    if (!parseThreads(args, &threads, &error)) return fail("run", error, 2);
    long frames = 0;
    if (args.has("--frames") && !parseInt("--frames", args.get("--frames"), 1, 1000000, &frames, &error))
        return fail("run", error, 2);
    const std::string scene = args.positional.empty() ? assetsDir() + "/scenes/default.json" : args.positional[0];
    const std::string out_dir = args.get("--out", "out");
    const std::string cache_dir = (fs::path(out_dir) / "cache").string();
    if (!args.has("--headless") && displayAvailable()) {
        const int code = runEditorOnScene(scene, cache_dir, threads, frames, args.get("--screenshot"));
        if (code >= 0) return code;
    }
    return runHeadlessJob(scene, out_dir, threads);
}

namespace {

// The main job without a display: the Ghost Tile (statistics, preview, cache) and the scene instantiated,
// settled and exported.
int runHeadlessJob(const std::string& scene, const std::string& out_dir, int threads) {
    std::string error;
    std::error_code ec;
    fs::create_directories(out_dir, ec);
    if (ec) return fail("run", out_dir + ": cannot create the output folder: " + ec.message());

    std::fprintf(stderr, "undergrowth: running %s headless\n", scene.c_str());
    SceneJob job;
    const std::string cache_dir = (fs::path(out_dir) / "cache").string();
    if (!loadSceneJob(scene, cache_dir, threads, false, &job, &error)) return fail("run", error);
    const std::string stem = job.project.name.empty() ? fs::path(scene).stem().string() : job.project.name;
    const std::string stats_path = (fs::path(out_dir) / (stem + ".tile-stats.json")).string();
    const std::string preview_path = (fs::path(out_dir) / (stem + ".tile-preview.glb")).string();
    const std::string cache_path = ghostTileCachePath(cache_dir, job.tile.key);
    if (!writeTextFileAtomically(stats_path, tileStatsJson(job, cache_path).dump(2) + "\n", &error))
        return fail("run", error);
    if (!writeTilePreview(job, preview_path, &error)) return fail("run", error);
    const GhostTileStats& st = job.tile.stats;
    std::printf("Ghost Tile: %u candidates, %llu colliding pairs (rho %.1f), %.3f s, %.2f bytes/pair [%s]\n",
                st.candidate_count, static_cast<unsigned long long>(st.pair_count), st.rho, st.build_seconds,
                st.bytes_per_pair, cacheOutcomeName(job.outcome));

    // The scene itself: instantiate everything and export it.
    const uint64_t seed = job.project.instantiation_seed;
    Instantiator inst;
    InstanceStats ist;
    if (!inst.setInput(instancerInput(job, seed), &error) || !inst.instantiateAll({.threads = threads}, &ist, &error))
        return fail("run", scene + ": " + error);
    const std::string scene_path = (fs::path(out_dir) / (stem + ".glb")).string();
    const std::string scene_stats_path = (fs::path(out_dir) / (stem + ".stats.json")).string();
    nlohmann::json istats = instanceStatsJson(job, ist, seed, resolveThreadCount(threads), nullptr);
    SceneEnvironmentOutput env;
    if (!computeSceneEnvironment(job, threads, nullptr, false, &env, &error)) return fail("run", error);
    if (!env.stats.is_null()) istats["environment"] = env.stats;
    nlohmann::json strand_stats;
    if (!computeSceneStrands(job, threads, nullptr, false, &env.meshes, &strand_stats, &error))
        return fail("run", error);
    if (!strand_stats.is_null()) istats["particles"] = strand_stats;
    const SceneLooks looks = sceneLooks(job);
    const std::vector<uint32_t> instance_looks = instanceLooks(job, looks, inst.store(), threads);
    istats["instances_per_look"] = lookCountsJson(job, looks, inst.store(), instance_looks);
    InstanceExportOptions export_options;
    useLooks(looks, instance_looks, &export_options);
    export_options.static_meshes = &env.meshes;
    export_options.chunk_size_m = job.project.chunk_size_m;
    // Settled like `instantiate` and the editor, so the main job's export rests where they show it.
    const SettleInput settle = settleInput(job.project, job.compiled.terrain, job.tile, job.models, job.environment.get());
    SettledDrops drops;
    if (settle.settings.enabled) {
        if (!validateSettleInput(settle, &error)) return fail("run", scene + ": " + error);
        settleAll(settle, inst.store(), threads, &drops);
        export_options.drops = &drops;
    }
    if (!exportInstancedScene(scene_path, job.tile, job.models, inst.store(), job.compiled.terrain.get(),
                              job.compiled.extent, export_options, istats.dump(), &error) ||
        !writeTextFileAtomically(scene_stats_path, istats.dump(2) + "\n", &error))
        return fail("run", error);
    std::printf("Instances: %llu (%llu candidates tested) in %.3f s\n", static_cast<unsigned long long>(ist.instances),
                static_cast<unsigned long long>(ist.candidates_tested), ist.seconds);
    std::printf("wrote:\n  %s  (the scene, glTF with EXT_mesh_gpu_instancing)\n  %s  (instantiation statistics)\n"
                "  %s  (Ghost Tile statistics)\n  %s  (tile preview, glTF)\n  %s  (cache)\n",
                scene_path.c_str(), scene_stats_path.c_str(), stats_path.c_str(), preview_path.c_str(),
                cache_path.c_str());
    return 0;
}

}  // namespace

int runBuildTileCommand(int argc, char** argv) {
    Args args;
    std::string error;
    if (!parseArgs(argc, argv, 2, {"--cache", "--threads", "--stats"}, {}, &args, &error) || args.positional.size() != 1)
        return fail("build-tile", error.empty() ? "usage: undergrowth build-tile SCENE [--cache DIR] [--stats FILE] [--threads N]"
                                                : error, 2);
    int threads = 0;
    if (!parseThreads(args, &threads, &error)) return fail("build-tile", error, 2);
    const std::string cache_dir = args.get("--cache", "out/cache");
    SceneJob job;
    if (!loadSceneJob(args.positional[0], cache_dir, threads, false, &job, &error)) return fail("build-tile", error);
    const std::string cache_path = ghostTileCachePath(cache_dir, job.tile.key);
    const std::string json = tileStatsJson(job, cache_path).dump(2) + "\n";
    if (args.has("--stats")) {
        if (!writeTextFileAtomically(args.get("--stats"), json, &error)) return fail("build-tile", error);
    } else {
        std::printf("%s", json.c_str());
    }
    return 0;
}

int runMakeAssetsCommand(int argc, char** argv) {
    Args args;
    std::string error;
    if (!parseArgs(argc, argv, 2, {"--out", "--env-out"}, {}, &args, &error) || !args.positional.empty())
        return fail("make-assets",
                    error.empty() ? "usage: undergrowth make-assets [--out DIR] [--env-out DIR]" : error, 2);
    const std::string dir = args.get("--out", assetsDir() + "/models");
    // The environmental objects go next to the detail models (assets/env_models by default).
    fs::path models_dir(dir);
    if (!models_dir.has_filename()) models_dir = models_dir.parent_path();  // "out/models/"
    const std::string env_dir = args.get("--env-out", (models_dir.parent_path() / "env_models").string());
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (!writeStarterAssets(dir, &error)) return fail("make-assets", error);
    std::printf("wrote the starter models to %s\n", dir.c_str());
    if (!writeEnvStarterModels(env_dir, &error)) return fail("make-assets", error);
    std::printf("wrote the environmental starter models to %s\n", env_dir.c_str());
    return 0;
}

}  // namespace ug::cli
