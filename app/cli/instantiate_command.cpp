// `undergrowth instantiate SCENE.json -o OUT.glb`: the headless batch job. Loads the scene, instantiates
// it (or one region of it, for jobs cut across machines), writes glTF and the statistics.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "cli/env_job.h"
#include "cli/strands_job.h"
#include "cli/instantiation.h"
#include "cli/scene_job.h"
#include "cli/scene_metrics.h"
#include "core/atomic_file.h"
#include "core/hash.h"
#include "core/parallel.h"
#include "io/instance_export.h"
#include "io/instance_list_file.h"

namespace ug::cli {

namespace fs = std::filesystem;

namespace {

int fail(const std::string& message, int code = 1) {
    std::fprintf(stderr, "undergrowth instantiate: %s\n", message.c_str());
    return code;
}

// "xmin,ymin,zmin,xmax,ymax,zmax": six finite numbers with min < max on every axis.
bool parseRegion(const std::string& text, Bounds* out, std::string* error) {
    std::vector<double> v;
    if (!parseNumberList("--region", text, &v, error)) return false;
    if (v.size() != 6) {
        *error = "--region: expected xmin,ymin,zmin,xmax,ymax,zmax (6 numbers), got " + std::to_string(v.size());
        return false;
    }
    for (int a = 0; a < 3; ++a)
        if (!(v[size_t(a)] < v[size_t(a) + 3])) {
            *error = "--region: min must be < max on every axis (" + std::string(1, "xyz"[a]) + ": " +
                     std::to_string(v[size_t(a)]) + " >= " + std::to_string(v[size_t(a) + 3]) + ")";
            return false;
        }
    *out = Bounds{glm::vec3(float(v[0]), float(v[1]), float(v[2])), glm::vec3(float(v[3]), float(v[4]), float(v[5]))};
    return true;
}

}  // namespace

nlohmann::json instanceStatsJson(const SceneJob& job, const InstanceStats& st, uint64_t seed, int threads,
                                 const Bounds* region) {
    nlohmann::json per_type = nlohmann::json::object();
    nlohmann::json types = nlohmann::json::array();
    for (size_t i = 0; i < job.models.size(); ++i) {
        const uint64_t n = i < st.instances_per_type.size() ? st.instances_per_type[i] : 0;
        per_type[job.models[i].name] = n;
        types.push_back({{"name", job.models[i].name},
                         {"instances", n},
                         {"strategy", priorityStrategyName(job.compiled.types[i].strategy)}});
    }
    const Bounds& e = job.compiled.extent;
    nlohmann::json j = {{"scene", job.project.name},
                        {"seed", seed},
                        {"threads", threads},
                        {"instances", st.instances},
                        {"candidates_tested", st.candidates_tested},
                        {"rejected", st.rejected},
                        {"culled", st.culled},
                        {"density_rejected", st.density_rejected},
                        {"constraint_rejected", st.constraint_rejected},
                        {"collision_rejected", st.collision_rejected},
                        {"seconds", st.seconds},
                        {"tiles_touched", st.tiles_touched},
                        {"tiles_with_instances", st.tiles_changed},
                        {"store_bytes", st.store_bytes},
                        {"bytes_per_instance", st.bytes_per_instance},
                        {"instances_per_type", per_type},
                        {"detail_types", types},
                        {"extent", {{"min", {e.lo.x, e.lo.y, e.lo.z}}, {"max", {e.hi.x, e.hi.y, e.hi.z}}}},
                        {"ghost_tile",
                         {{"key", hex64(job.tile.key)},
                          {"candidates", job.tile.stats.candidate_count},
                          {"pairs", job.tile.stats.pair_count},
                          {"tile_size_m", job.tile.settings.tile_size_m},
                          {"delta_m", job.tile.settings.delta_m},
                          {"variants", job.tile.settings.variants}}}};
    if (region)
        j["region"] = {{"min", {region->lo.x, region->lo.y, region->lo.z}},
                       {"max", {region->hi.x, region->hi.y, region->hi.z}}};
    return j;
}

int runInstantiation(const InstantiateRequest& request, const char* command) {
    auto fail = [&](const std::string& message) {
        std::fprintf(stderr, "undergrowth %s: %s\n", command, message.c_str());
        return 1;
    };
    std::string error;
    SceneJob job;
    const std::string& scene = request.scene;
    const int threads = request.threads;
    if (!loadSceneJob(scene, request.cache_dir, threads, false, &job, &error)) return fail(error);
    if (request.expected_tile_key != 0 && job.tile.key != request.expected_tile_key)
        return fail(scene + ": its Ghost Tile is " + hex64(job.tile.key) + ", the plan's " +
                    hex64(request.expected_tile_key) + " (a model or a tile setting changed since); make the plan again");
    const uint64_t seed = request.seed.value_or(job.project.instantiation_seed);
    const Bounds* region = request.region ? &*request.region : nullptr;

    const InstancerInput input = instancerInput(job, seed);
    const SettleInput settle = settleInput(job.project, job.compiled.terrain, job.tile, job.models, job.environment.get());
    if (settle.settings.enabled && !validateSettleInput(settle, &error)) return fail(scene + ": " + error);
    InstanceStats st;
    InstanceStore store;
    int last = -1;
    InstanceOptions options{.threads = threads,
                            .progress =
                                [&](float f) {
                                    const int p = int(f * 100.0f);
                                    if (p / 25 != last / 25) std::fprintf(stderr, "\r  instantiating: %3d%%", p);
                                    last = p;
                                },
                            .max_memory_bytes = request.max_memory_bytes};
    bool ok;
    if (region) {
        if (overlaps(*region, input.extent) == false) return fail(scene + ": --region does not overlap the scene extent");
        // Settled drops depend on the selection a little beyond the region: instantiate that much more,
        // settle, then keep the region's own instances (settling.h, "Locality").
        const float halo = settle.settings.enabled ? settleHaloMetres(settle) : 0.0f;
        const Bounds wide{region->lo - halo, region->hi + halo};
        ok = instantiateRegion(input, wide, options, &store, &st, &error);
    } else {
        Instantiator inst;
        ok = inst.setInput(input, &error) && inst.instantiateAll(options, &st, &error);
        if (ok) store = inst.store();
    }
    if (last >= 0) std::fprintf(stderr, "\n");
    if (!ok) return fail(scene + ": " + error);

    SettledDrops drops;
    double settle_seconds = 0.0;
    if (settle.settings.enabled) {
        const auto t0 = std::chrono::steady_clock::now();
        settleAll(settle, store, threads, &drops);
        if (region) {
            InstanceStore own;
            SettledDrops own_drops;
            cropToRegion(store, drops, job.tile, *region, &own, &own_drops);
            store = std::move(own);
            drops = std::move(own_drops);
            st.instances = store.instanceCount();
            st.instances_per_type.assign(job.models.size(), 0);
            store.forEach([&](uint64_t, uint32_t j) { ++st.instances_per_type[job.tile.candidates.type[j]]; });
        }
        settle_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    nlohmann::json stats = instanceStatsJson(job, st, seed, resolveThreadCount(threads), region);
    if (settle.settings.enabled)
        stats["settling"] = {{"passes", settle.settings.passes},
                             {"max_drop_m", settle.settings.max_drop_m},
                             {"seconds", settle_seconds},
                             {"bytes", drops.byteSize()}};
    // The rest, packing and tiling measurements cost more than the instantiation on big scenes: on request.
    if (request.measure)
        stats["measurements"] =
            sceneMetricsJson(measureScene(job, store, settle.settings.enabled ? &drops : nullptr, threads));
    SceneEnvironmentOutput env;
    if (!computeSceneEnvironment(job, threads, region, false, &env, &error)) return fail(error);
    if (!env.stats.is_null()) stats["environment"] = env.stats;
    nlohmann::json strand_stats;
    if (!computeSceneStrands(job, threads, region, false, &env.meshes, &strand_stats, &error)) return fail(error);
    if (!strand_stats.is_null()) stats["particles"] = strand_stats;
    stats.update(request.stats_extra);
    const SettledDrops* settled = settle.settings.enabled ? &drops : nullptr;
    // A region's file holds the terrain under the region only, so that region files side by side are the
    // world once, not the whole terrain once per region.
    const Bounds terrain_box = region ? intersect(*region, job.compiled.extent) : job.compiled.extent;
    if (!exportJobInstances(job, store, settled, &env.meshes, terrain_box, request.chunk_size_m, request.plain_nodes,
                            threads, &stats, request.out, &error))
        return fail(error);
    if (!request.stats_path.empty() && !writeTextFileAtomically(request.stats_path, stats.dump(2) + "\n", &error))
        return fail(error);
    if (!request.instances_path.empty() &&
        !writeInstanceListFile(request.instances_path, job.tile.key, request.instances_header.dump(), store, settled,
                               &error))
        return fail(error);
    std::printf("%llu instances (%llu candidates tested, %llu rejected) in %.3f s -> %s\n",
                static_cast<unsigned long long>(st.instances), static_cast<unsigned long long>(st.candidates_tested),
                static_cast<unsigned long long>(st.rejected), st.seconds, request.out.c_str());
    return 0;
}

bool exportJobInstances(const SceneJob& job, const InstanceStore& store, const SettledDrops* drops,
                        const std::vector<MeshInstances>* static_meshes, const Bounds& terrain_box, float chunk_size_m,
                        bool plain_nodes, int threads, nlohmann::json* stats, const std::string& out, std::string* error) {
    const SceneLooks looks = sceneLooks(job);
    const std::vector<uint32_t> instance_looks = instanceLooks(job, looks, store, threads);
    (*stats)["instances_per_look"] = lookCountsJson(job, looks, store, instance_looks);
    InstanceExportOptions export_options;
    export_options.static_meshes = static_meshes;
    useLooks(looks, instance_looks, &export_options);
    export_options.chunk_size_m = chunk_size_m > 0.0f ? chunk_size_m : job.project.chunk_size_m;
    export_options.use_instancing_extension = !plain_nodes;
    export_options.drops = drops;
    return exportInstancedScene(out, job.tile, job.models, store, job.compiled.terrain.get(), terrain_box,
                                export_options, stats->dump(), error);
}

int runInstantiateCommand(int argc, char** argv) {
    Args args;
    std::string error;
    const char* usage =
        "usage: undergrowth instantiate SCENE.json -o OUT.glb|OUT.gltf [--stats FILE] [--seed N] [--threads N]\n"
        "       [--region xmin,ymin,zmin,xmax,ymax,zmax] [--cache DIR] [--plain-nodes] [--chunk METRES] [--measure]\n"
        "   or: undergrowth instantiate --plan DIR --task I [--threads N]   (one task of `undergrowth plan`)";
    if (!parseArgs(argc, argv, 2,
                   {"-o", "--out", "--stats", "--seed", "--threads", "--region", "--cache", "--chunk", "--plan", "--task"},
                   {"--plain-nodes", "--measure"}, &args, &error))
        return fail(error + "\n" + usage, 2);
    int threads = 0;
    if (args.has("--threads")) {
        long t;
        if (!parseInt("--threads", args.get("--threads"), 0, 256, &t, &error)) return fail(error, 2);
        threads = int(t);
    }
    if (args.has("--plan") || args.has("--task")) {
        if (!args.has("--plan") || !args.has("--task") || !args.positional.empty())
            return fail(std::string("a plan task takes --plan DIR and --task I and no scene\n") + usage, 2);
        return runPlanTask(args.get("--plan"), args.get("--task"), threads);
    }
    if (args.positional.size() != 1) return fail(usage, 2);
    InstantiateRequest request;
    request.scene = args.positional[0];
    request.threads = threads;
    request.out = args.has("-o") ? args.get("-o") : args.get("--out");
    if (request.out.empty()) return fail(std::string("missing -o OUT.glb\n") + usage, 2);
    const std::string ext = fs::path(request.out).extension().string();
    if (ext != ".glb" && ext != ".gltf") return fail(request.out + ": the output must end in .glb or .gltf", 2);
    if (args.has("--region")) {
        Bounds region;
        if (!parseRegion(args.get("--region"), &region, &error)) return fail(error, 2);
        request.region = region;
    }
    if (args.has("--chunk")) {
        try {
            request.chunk_size_m = std::stof(args.get("--chunk"));
        } catch (...) {
            request.chunk_size_m = -1.0f;
        }
        if (!(request.chunk_size_m > 0.0f) || !std::isfinite(request.chunk_size_m))
            return fail("--chunk: expected a length in metres > 0", 2);
    }
    if (args.has("--seed")) {
        const std::string s = args.get("--seed");
        size_t used = 0;
        uint64_t seed = 0;
        try {
            seed = std::stoull(s, &used);
        } catch (...) {
            used = 0;
        }
        if (used == 0 || used != s.size() || s[0] == '-') return fail("--seed: '" + s + "' is not a whole number >= 0", 2);
        request.seed = seed;
    }
    request.cache_dir = args.get("--cache", (fs::path(request.out).parent_path() / "cache").string());
    request.stats_path = args.get("--stats");
    request.plain_nodes = args.has("--plain-nodes");
    request.measure = args.has("--measure");
    return runInstantiation(request, "instantiate");
}

}  // namespace ug::cli
