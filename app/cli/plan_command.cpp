// `undergrowth plan SCENE --out DIR`: cuts a world into region jobs for Slurm (region_plan.h), and
// `undergrowth instantiate --plan DIR --task I`: one of those jobs.
#include <cstdio>
#include <filesystem>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "cli/instantiation.h"
#include "cli/region_plan.h"
#include "cli/scene_job.h"
#include "core/atomic_file.h"
#include "core/hash.h"
#include "io/instance_list_file.h"

namespace ug::cli {

namespace fs = std::filesystem;

namespace {

int failWith(const char* command, const std::string& message, int code = 1) {
    std::fprintf(stderr, "undergrowth %s: %s\n", command, message.c_str());
    return code;
}

bool hashFile(const std::string& path, uint64_t* out, std::string* error) {
    std::vector<unsigned char> bytes;
    if (!readWholeFile(path, &bytes, error, size_t(256) << 20)) return false;
    *out = hashBytes(bytes.data(), bytes.size());
    return true;
}

// A task's outputs are complete for this plan: the instance list (written last) reads back whole and
// names this plan and task, and the glTF and statistics beside it exist.
bool regionDone(const RegionPlan& plan, size_t task) {
    const std::string stem = regionStem(plan, task);
    if (!fs::exists(stem + ".glb") || !fs::exists(stem + ".json")) return false;
    InstanceListFile list;
    std::string error;
    if (!readInstanceListFile(stem + ".ugi", &list, &error)) return false;
    const nlohmann::json header = nlohmann::json::parse(list.header_json, nullptr, false);
    return list.ghost_tile_key == plan.ghost_tile_key && header.is_object() &&
           header.value("plan", std::string()) == hex64(plan.id) &&
           header.value("task", int64_t(-1)) == int64_t(task);
}

}  // namespace

int runPlanCommand(int argc, char** argv) {
    const char* usage =
        "usage: undergrowth plan SCENE.json --out DIR [--memory-per-job BYTES] [--max-jobs N] "
        "[--threads-per-task N]\n"
        "                        [--seed N] [--binary PATH] [--threads N]";
    Args args;
    std::string error;
    if (!parseArgs(argc, argv, 2,
                   {"--out", "-o", "--memory-per-job", "--max-jobs", "--threads-per-task", "--seed",
                    "--binary", "--threads"},
                   {}, &args, &error) ||
        args.positional.size() != 1)
        return failWith("plan", error.empty() ? usage : error + "\n" + usage, 2);
    const std::string dir_arg = args.has("--out") ? args.get("--out") : args.get("-o");
    if (dir_arg.empty()) return failWith("plan", std::string("missing --out DIR\n") + usage, 2);
    uint64_t memory = 4ull << 30;
    long max_jobs = kMaxPlanTasks, task_threads = 1, threads = 0;
    if (args.has("--memory-per-job") && !parseByteSize("--memory-per-job", args.get("--memory-per-job"),
                                                       1ull << 20, 1ull << 44, &memory, &error))
        return failWith("plan", error, 2);
    if ((args.has("--max-jobs") &&
         !parseInt("--max-jobs", args.get("--max-jobs"), 1, kMaxPlanTasks, &max_jobs, &error)) ||
        (args.has("--threads-per-task") &&
         !parseInt("--threads-per-task", args.get("--threads-per-task"), 1, 256, &task_threads, &error)) ||
        (args.has("--threads") && !parseInt("--threads", args.get("--threads"), 0, 256, &threads, &error)))
        return failWith("plan", error, 2);

    RegionPlan plan;
    plan.dir = fs::absolute(dir_arg).lexically_normal().string();
    while (plan.dir.size() > 1 && plan.dir.back() == '/') plan.dir.pop_back();
    plan.scene = fs::absolute(args.positional[0]).lexically_normal().string();
    plan.memory_per_job = memory;
    plan.threads_per_task = int(task_threads);
    plan.binary = args.has("--binary") ? args.get("--binary") : selfExecutablePath();
    std::error_code ec;
    for (const char* sub : {"regions", "logs", "cache"}) fs::create_directories(fs::path(plan.dir) / sub, ec);
    if (ec) return failWith("plan", plan.dir + ": cannot create the plan's folders: " + ec.message());
    if (!hashFile(plan.scene, &plan.scene_hash, &error)) return failWith("plan", error);

    // The Ghost Tile goes into the plan's cache now, so that the tasks only read it (submit.sh adds a
    // cache step that builds it only when the cache has lost it).
    SceneJob job;
    if (!loadSceneJob(plan.scene, (fs::path(plan.dir) / "cache").string(), int(threads), false, &job, &error))
        return failWith("plan", error);
    plan.name = job.project.name;
    plan.ghost_tile_key = job.tile.key;
    plan.seed = job.project.instantiation_seed;
    if (args.has("--seed")) {
        long seed;
        if (!parseInt("--seed", args.get("--seed"), 0, 0x7fffffffffffffffL, &seed, &error))
            return failWith("plan", error, 2);
        plan.seed = uint64_t(seed);
    }
    plan.chunk_size_m = job.project.chunk_size_m;
    plan.extent = job.compiled.extent;
    const InstancerInput input = instancerInput(job, plan.seed);
    const SettleInput settle =
        settleInput(job.project, job.compiled.terrain, job.tile, job.models, job.environment.get());
    const float halo = settle.settings.enabled ? settleHaloMetres(settle) : 0.0f;
    if (!cutIntoRegions(input, halo, int(max_jobs), int(threads), &plan, &error))
        return failWith("plan", plan.scene + ": " + error);
    plan.id = planId(plan);
    if (!writeTextFileAtomically((fs::path(plan.dir) / "plan.json").string(), planJson(plan).dump(2) + "\n",
                                 &error) ||
        !writeSlurmScripts(plan, &error))
        return failWith("plan", error);
    uint64_t largest = 0;
    for (const PlannedRegion& r : plan.regions) largest = std::max(largest, r.footprint_bytes);
    std::printf(
        "plan %s: %zu tasks of %llu MiB (largest instancer footprint %.1f MiB of %llu) -> %s/plan.json\n"
        "submit with: %s/submit.sh [sbatch options]\n",
        hex64(plan.id).c_str(), plan.regions.size(), static_cast<unsigned long long>(memory >> 20),
        double(largest) / double(1 << 20), static_cast<unsigned long long>(plan.instancerBudget() >> 20),
        plan.dir.c_str(), plan.dir.c_str());
    return 0;
}

int runPlanTask(const std::string& plan_dir, const std::string& task_text, int threads) {
    RegionPlan plan;
    std::string error;
    if (!readRegionPlan(plan_dir, &plan, &error)) return failWith("instantiate", error);
    long task;
    if (!parseInt("--task", task_text, 0, long(plan.regions.size()) - 1, &task, &error))
        return failWith("instantiate", error, 2);
    uint64_t scene_hash = 0;
    if (!hashFile(plan.scene, &scene_hash, &error)) return failWith("instantiate", error);
    if (scene_hash != plan.scene_hash)
        return failWith("instantiate", plan.scene + ": changed since plan " + hex64(plan.id) +
                                           " was made; make the plan again (undergrowth plan)");
    const std::string stem = regionStem(plan, size_t(task));
    if (regionDone(plan, size_t(task))) {
        std::printf("task %ld: the outputs of plan %s are already complete (%s.*); skipped\n", task,
                    hex64(plan.id).c_str(), stem.c_str());
        return 0;
    }
    std::printf("task %ld of %zu (plan %s): started\n", task, plan.regions.size(), hex64(plan.id).c_str());
    std::fflush(stdout);
    InstantiateRequest request;
    request.scene = plan.scene;
    request.out = stem + ".glb";
    request.stats_path = stem + ".json";
    request.cache_dir = (fs::path(plan.dir) / "cache").string();
    request.instances_path = stem + ".ugi";
    request.instances_header = {{"plan", hex64(plan.id)}, {"task", task}};
    request.stats_extra = {
        {"plan", {{"id", hex64(plan.id)}, {"task", task}, {"tasks", plan.regions.size()}}}};
    request.threads = threads;
    request.seed = plan.seed;
    request.region = plan.regions[size_t(task)].box;
    request.chunk_size_m = plan.chunk_size_m;
    request.max_memory_bytes = plan.instancerBudget();
    request.expected_tile_key = plan.ghost_tile_key;
    return runInstantiation(request, "instantiate");
}

}  // namespace ug::cli
