// Region jobs on Slurm (issue 15, docs/worlds.md): world_250m run in one process and as a plan's job array
// on a Slurm cluster, and the scheduler's overhead between the two; then the 1 km^2 world, which does not
// fit one process, through Slurm alone. Runs the undergrowth binary
// itself, as a studio would: `instantiate` for the single process, `plan`, the plan's submit.sh (Ghost
// Tile step, job array, join) for Slurm. The cluster is the one SLURM_CONF names, else a single-node one
// started for the section by scripts/slurm-local.sh (root only); without either the section says so and
// adds no rows. Not in --quick: a cluster's start and a world's run are minutes, not a smoke test.
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "cli/bench.h"
#include "cli/cli_args.h"

namespace ug::cli {

namespace {

namespace fs = std::filesystem;

// Runs a shell command; its standard output in *out (stderr goes to the bench's stderr). The exit code,
// or -1 when it could not run or was killed.
int shell(const std::string& command, std::string* out = nullptr) {
    FILE* p = popen(command.c_str(), "r");
    if (!p) return -1;
    std::string text;
    char buffer[4096];
    size_t n;
    while ((n = fread(buffer, 1, sizeof buffer, p)) > 0) text.append(buffer, n);
    const int status = pclose(p);
    if (out) *out = text;
    return status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The cluster the section submits to: an existing one (SLURM_CONF) or one it starts and stops.
class BenchCluster {
  public:
    ~BenchCluster() {
        if (!local_dir_.empty())
            shell("bash " + shellQuote(script_) + " stop " + shellQuote(local_dir_) + " >/dev/null 2>&1");
    }
    // False with the reason when no cluster can be had (the section is skipped, not failed).
    bool open(const std::string& scratch, std::string* why) {
        if (const char* conf = std::getenv("SLURM_CONF"); conf && *conf) return true;
        if (shell("command -v sbatch >/dev/null && command -v slurmctld >/dev/null && command -v munged "
                  ">/dev/null") != 0)
            return (*why = "no Slurm here (sbatch, slurmctld, munged: apt-get install slurm-wlm munge)",
                    false);
        if (geteuid() != 0)
            return (*why = "a single-node cluster needs root; or set SLURM_CONF to a cluster", false);
        script_ = std::string(UG_SOURCE_DIR) + "/scripts/slurm-local.sh";
        const std::string dir = scratch + "/slurm";
        std::string out;
        if (shell("bash " + shellQuote(script_) + " start " + shellQuote(dir) + " 2>&1", &out) != 0)
            return (*why = "the single-node cluster did not start: " + out, false);
        local_dir_ = dir;
        setenv("SLURM_CONF", (dir + "/slurm.conf").c_str(), 1);
        return true;
    }

  private:
    std::string script_, local_dir_;
};

// Waits until none of the jobs is pending or running; false after `limit_s`.
bool waitForJobs(const std::string& ids, double limit_s) {
    const auto t0 = std::chrono::steady_clock::now();
    while (since(t0) < limit_s) {
        std::string out;
        if (shell("squeue -h -j " + ids + " -t PD,R,CG,CF,RQ,S 2>/dev/null", &out) == 0 && out.empty())
            return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return false;
}

bool readJson(const std::string& path, nlohmann::json* out, std::string* error) {
    std::ifstream in(path);
    *out = nlohmann::json::parse(in, nullptr, false);
    if (out->is_discarded()) return (*error = path + ": not readable JSON", false);
    return true;
}

struct SingleRun {
    double seconds = 0;
    uint64_t instances = 0;
};

bool runSingle(const std::string& bin, const std::string& scene, const std::string& dir, int threads,
               SingleRun* out, std::string* error) {
    const std::string stats = dir + "/single.stats.json";
    const auto t0 = std::chrono::steady_clock::now();
    const std::string command = shellQuote(bin) + " instantiate " + shellQuote(scene) + " -o " +
                                shellQuote(dir + "/single.glb") + " --cache " + shellQuote(dir + "/cache") +
                                " --stats " + shellQuote(stats) + " --threads " + std::to_string(threads) +
                                " >/dev/null";
    if (shell(command) != 0) return (*error = "single-process run failed: " + command, false);
    out->seconds = since(t0);
    nlohmann::json j;
    if (!readJson(stats, &j, error)) return false;
    out->instances = j.value("instances", uint64_t(0));
    return true;
}

struct SlurmRun {
    double seconds = 0;
    uint64_t instances = 0;
    size_t tasks = 0;
};

// The plan's submit.sh (Ghost Tile step -> array -> join), timed from submission until the join ends.
bool runThroughSlurm(const std::string& plan, SlurmRun* out, std::string* error) {
    for (const char* sub : {"regions", "logs"}) {
        std::error_code ec;
        fs::remove_all(fs::path(plan) / sub, ec);
        fs::create_directories(fs::path(plan) / sub, ec);
    }
    std::string ids;
    const auto t0 = std::chrono::steady_clock::now();
    if (shell("bash " + shellQuote(plan + "/submit.sh") + " 2>&1", &ids) != 0)
        return (*error = "submit.sh failed: " + ids, false);
    // "cache A|- array B join C"
    char cache[32] = {}, array[32] = {}, join[32] = {};
    if (std::sscanf(ids.c_str(), "cache %31s array %31s join %31s", cache, array, join) != 3)
        return (*error = "submit.sh printed '" + ids + "'", false);
    const std::string jobs = std::string(cache) == "-" ? std::string(array) + "," + join
                                                       : std::string(cache) + "," + array + "," + join;
    if (!waitForJobs(jobs, 6 * 3600.0)) return (*error = "the plan's jobs did not end within 6 hours", false);
    out->seconds = since(t0);
    nlohmann::json manifest;
    if (!readJson(plan + "/manifest.json", &manifest, error))
        return (*error += " (the join did not finish: see " + plan + "/logs)", false);
    out->instances = manifest.value("instances", uint64_t(0));
    out->tasks = manifest.contains("regions") ? manifest["regions"].size() : 0;
    return true;
}

bool makePlan(const std::string& bin, const std::string& scene, const std::string& plan, size_t* tasks,
              std::string* error) {
    std::string out;
    const std::string command = shellQuote(bin) + " plan " + shellQuote(scene) + " --out " +
                                shellQuote(plan) + " --threads-per-task 1 2>&1";
    if (shell(command, &out) != 0) return (*error = "plan failed: " + out, false);
    nlohmann::json j;
    if (!readJson(plan + "/plan.json", &j, error)) return false;
    *tasks = j["regions"].size();
    return true;
}

}  // namespace

bool benchWorld(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error) {
    if (ctx.quick) {
        std::fprintf(stderr,
                     "bench: world skipped in --quick (minutes on a Slurm cluster; "
                     "tests/cli/run_world_tests.sh checks the jobs)\n");
        return true;
    }
    const std::string scratch =
        (fs::temp_directory_path() / ("ug-bench-world-" + std::to_string(getpid()))).string();
    std::error_code ec;
    fs::create_directories(scratch, ec);
    struct Cleanup {
        std::string dir;
        ~Cleanup() {
            std::error_code e;
            fs::remove_all(dir, e);
        }
    } cleanup{scratch};
    BenchCluster cluster;
    std::string why;
    if (!cluster.open(scratch, &why)) {
        std::fprintf(stderr, "bench: world skipped: %s\n", why.c_str());
        return true;
    }
    const std::string bin = selfExecutablePath();

    // The scheduler's overhead on a world that still fits one process: one process with every thread
    // against the plan's job array (1 thread a task), alternately, on a warm cache; the plan's default
    // memory per job.
    const std::string small = ctx.assets_dir + "/scenes/world_250m.json";
    const std::string small_plan = scratch + "/plan_250m";
    size_t small_tasks = 0;
    if (!makePlan(bin, small, small_plan, &small_tasks, error)) return false;
    if (shell(shellQuote(bin) + " build-tile " + shellQuote(small) + " --cache " +
              shellQuote(scratch + "/cache") + " >/dev/null") != 0)
        return (*error = small + ": build-tile failed", false);
    const int threads = ctx.threads > 0 ? ctx.threads : int(std::thread::hardware_concurrency());
    std::vector<double> single_s, slurm_s;
    SingleRun single;
    SlurmRun slurm;
    for (int r = 0; r < 3; ++r) {
        if (!runSingle(bin, small, scratch, threads, &single, error) ||
            !runThroughSlurm(small_plan, &slurm, error))
            return false;
        if (slurm.instances != single.instances)
            return (*error = "the joined world holds " + std::to_string(slurm.instances) +
                             " instances, the single process " + std::to_string(single.instances),
                    false);
        single_s.push_back(single.seconds);
        slurm_s.push_back(slurm.seconds);
        std::fprintf(stderr, "bench: world_250m run %d: one process %.1f s, Slurm %.1f s\n", r + 1,
                     single.seconds, slurm.seconds);
    }
    const double one = median(single_s), many = median(slurm_s);
    const std::string note = "world_250m, " + std::to_string(single.instances) + " instances, median of 3";
    rows->push_back({"world.single.seconds", one, "s", "", std::nullopt,
                     note + ": instantiate with " + std::to_string(threads) + " threads, glTF written"});
    rows->push_back({"world.slurm.seconds", many, "s", "", std::nullopt,
                     note + ": submit.sh until the join ends, " + std::to_string(small_tasks) +
                         " tasks of 1 thread, regions and joined glTF written"});
    rows->push_back({"world.slurm.overhead_percent", 100.0 * (many - one) / one, "%", "<= 15", std::nullopt,
                     "(Slurm - one process) / one process, same world, same machine"});

    // The 1 km^2 world, which no single process here may hold (the instancer's 8 GiB check refuses it).
    const std::string world = ctx.assets_dir + "/scenes/world_1km.json";
    const std::string world_plan = scratch + "/plan_1km";
    size_t tasks = 0;
    if (!makePlan(bin, world, world_plan, &tasks, error)) return false;
    rows->push_back({"world.plan_tasks", double(tasks), "tasks", ">= 16", std::nullopt,
                     "world_1km (1 km^2) at the default --memory-per-job (4 GiB)"});
    if (!runThroughSlurm(world_plan, &slurm, error)) return false;
    rows->push_back({"world.1km.slurm_seconds", slurm.seconds, "s", "", std::nullopt,
                     "one run: submit.sh until the join ends, " + std::to_string(tasks) +
                         " tasks of 1 thread on this machine"});
    rows->push_back({"world.1km.instances", double(slurm.instances), "instances", "", std::nullopt,
                     "the joined world's count (the manifest)"});
    return true;
}

}  // namespace ug::cli
