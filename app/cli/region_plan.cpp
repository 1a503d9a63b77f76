#include "cli/region_plan.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "cli/cli_args.h"
#include "core/atomic_file.h"
#include "core/hash.h"
#include "ghosttile/ghost_tile_cache.h"

namespace ug::cli {

namespace fs = std::filesystem;

namespace {

nlohmann::json vec3Json(const glm::vec3& v) { return {v.x, v.y, v.z}; }

nlohmann::json boundsJson(const Bounds& b) { return {{"min", vec3Json(b.lo)}, {"max", vec3Json(b.hi)}}; }

// Regions ix in [0, nx) of `count` chunks starting at chunk `first`: whole chunks, the outer edges pushed a
// chunk past the extent so that nothing on its boundary falls between regions.
void regionSpan(int64_t first, int64_t count, int n, int i, float chunk, float lo, float hi, float* out_lo,
                float* out_hi) {
    const int64_t a = first + count * i / n, b = first + count * (i + 1) / n;
    *out_lo = i == 0 ? lo - chunk : float(double(a) * chunk);
    *out_hi = i == n - 1 ? hi + chunk : float(double(b) * chunk);
}

std::string metres(float v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", double(v));
    return text;
}

std::string mib(uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", double(bytes) / double(1 << 20));
    return text;
}

// The deciding fields, in a fixed order: the id is their hash.
nlohmann::json decidingJson(const RegionPlan& plan) {
    nlohmann::json regions = nlohmann::json::array();
    for (const PlannedRegion& r : plan.regions) regions.push_back(boundsJson(r.box));
    return {{"scene_hash", hex64(plan.scene_hash)}, {"ghost_tile_key", hex64(plan.ghost_tile_key)},
            {"seed", plan.seed},                    {"chunk_size_m", plan.chunk_size_m},
            {"regions", regions}};
}

// Reading the plan back: a missing or mistyped key throws with its JSON Pointer.
struct PlanReader {
    const nlohmann::json& j;
    const nlohmann::json& at(const nlohmann::json& o, const std::string& key, const std::string& where) const {
        if (!o.is_object() || !o.contains(key)) throw std::runtime_error(where + "/" + key + ": missing");
        return o.at(key);
    }
    std::string text(const nlohmann::json& o, const std::string& key, const std::string& where = "") const {
        const nlohmann::json& v = at(o, key, where);
        if (!v.is_string()) throw std::runtime_error(where + "/" + key + ": expected a string");
        return v.get<std::string>();
    }
    uint64_t hex(const nlohmann::json& o, const std::string& key, const std::string& where = "") const {
        const std::string s = text(o, key, where);
        size_t used = 0;
        uint64_t v = 0;
        try {
            v = std::stoull(s, &used, 16);
        } catch (...) {
            used = 0;
        }
        if (used == 0 || used != s.size()) throw std::runtime_error(where + "/" + key + ": '" + s + "' is not a hex hash");
        return v;
    }
    uint64_t whole(const nlohmann::json& o, const std::string& key, const std::string& where = "") const {
        const nlohmann::json& v = at(o, key, where);
        if (!v.is_number_unsigned()) throw std::runtime_error(where + "/" + key + ": expected a whole number >= 0");
        return v.get<uint64_t>();
    }
    float number(const nlohmann::json& o, const std::string& key, const std::string& where = "") const {
        const nlohmann::json& v = at(o, key, where);
        if (!v.is_number() || !std::isfinite(v.get<double>()))
            throw std::runtime_error(where + "/" + key + ": expected a finite number");
        return v.get<float>();
    }
    glm::vec3 point(const nlohmann::json& o, const std::string& key, const std::string& where) const {
        const nlohmann::json& v = at(o, key, where);
        if (!v.is_array() || v.size() != 3) throw std::runtime_error(where + "/" + key + ": expected [x, y, z]");
        glm::vec3 p;
        for (int a = 0; a < 3; ++a) {
            if (!v[size_t(a)].is_number() || !std::isfinite(v[size_t(a)].get<double>()))
                throw std::runtime_error(where + "/" + key + "/" + std::to_string(a) + ": expected a finite number");
            p[a] = v[size_t(a)].get<float>();
        }
        return p;
    }
    Bounds box(const nlohmann::json& o, const std::string& where) const {
        const Bounds b{point(o, "min", where), point(o, "max", where)};
        for (int a = 0; a < 3; ++a)
            if (!(b.lo[a] < b.hi[a])) throw std::runtime_error(where + ": min must be < max on every axis");
        return b;
    }
};

}  // namespace

uint64_t planId(const RegionPlan& plan) {
    const std::string text = decidingJson(plan).dump();
    return hashBytes(text.data(), text.size());
}

bool cutIntoRegions(const InstancerInput& input, float halo_m, int max_jobs, int threads, RegionPlan* plan,
                    std::string* error) {
    const float c = plan->chunk_size_m;
    const Bounds& e = input.extent;
    const int64_t cx0 = int64_t(std::floor(e.lo.x / c)), cy0 = int64_t(std::floor(e.lo.y / c));
    const int64_t chunks_x = std::max<int64_t>(1, int64_t(std::ceil(e.hi.x / c)) - cx0);
    const int64_t chunks_y = std::max<int64_t>(1, int64_t(std::ceil(e.hi.y / c)) - cy0);
    const uint64_t budget = plan->instancerBudget();
    // The footprint of a box, counted without a limit (the instancer's check is the same count against
    // the budget); UINT64_MAX when the instancer refuses the box for another reason (`why` says which).
    const InstanceOptions unbounded{.threads = threads, .max_memory_bytes = UINT64_MAX};
    auto footprint = [&](const Bounds& box, std::string* why) {
        RegionFootprint f;
        return measureRegionFootprint(input, box, unbounded, &f, why) ? f.bytes() : UINT64_MAX;
    };
    // A grid of at least k regions shaped like the extent in chunks (so regions stay about square).
    auto gridFor = [&](double k, int* gx, int* gy) {
        *gx = int(std::clamp<double>(std::ceil(std::sqrt(k * double(chunks_x) / double(chunks_y))), 1.0,
                                     double(chunks_x)));
        *gy = int(std::clamp<double>(std::ceil(k / *gx), 1.0, double(chunks_y)));
    };
    // Footprints shrink about in proportion to a region's area: start from the whole world's over the
    // budget, then scale the grid by the largest region's excess until every region fits (a couple of
    // rounds), rather than one cut at a time (quadratic in the tasks).
    int nx = 1, ny = 1;
    std::string why;
    const uint64_t whole = footprint({e.lo - halo_m, e.hi + halo_m}, &why);
    if (whole != UINT64_MAX && whole > budget) gridFor(std::ceil(double(whole) / double(budget)), &nx, &ny);
    for (;;) {
        if (int64_t(nx) * ny > max_jobs) {
            *error = "the world needs more than --max-jobs " + std::to_string(max_jobs) + " regions of at most " +
                     mib(budget) + " MiB of instancer state each; raise --memory-per-job or --max-jobs";
            return false;
        }
        plan->regions.clear();
        std::string worst_reason;
        uint64_t worst = 0;
        for (int iy = 0; iy < ny; ++iy)
            for (int ix = 0; ix < nx; ++ix) {
                PlannedRegion r;
                regionSpan(cx0, chunks_x, nx, ix, c, e.lo.x, e.hi.x, &r.box.lo.x, &r.box.hi.x);
                regionSpan(cy0, chunks_y, ny, iy, c, e.lo.y, e.hi.y, &r.box.lo.y, &r.box.hi.y);
                r.box.lo.z = e.lo.z - c;
                r.box.hi.z = e.hi.z + c;
                r.footprint_bytes = footprint({r.box.lo - halo_m, r.box.hi + halo_m}, &why);
                if (r.footprint_bytes > worst) {
                    worst = r.footprint_bytes;
                    worst_reason = r.footprint_bytes == UINT64_MAX ? why : "";
                }
                plan->regions.push_back(r);
            }
        if (worst <= budget) return true;
        if (nx >= chunks_x && ny >= chunks_y) {
            *error = "a single chunk of " + metres(c) + " m needs more than the instancer's " + mib(budget) +
                     " MiB (half of --memory-per-job)" + (worst_reason.empty() ? "" : ": " + worst_reason) +
                     "; raise --memory-per-job or lower instantiation.chunk_size_m";
            return false;
        }
        int gx = nx, gy = ny;
        if (worst != UINT64_MAX)
            gridFor(std::ceil(double(nx) * double(ny) * double(worst) / double(budget)), &gx, &gy);
        if (int64_t(gx) * gy <= int64_t(nx) * ny) {
            // No progress from the estimate: cut the side with more chunks per region once more.
            gx = nx;
            gy = ny;
            if ((double(chunks_x) / nx >= double(chunks_y) / ny && nx < chunks_x) || ny >= chunks_y)
                ++gx;
            else
                ++gy;
        }
        nx = gx;
        ny = gy;
    }
}

nlohmann::json planJson(const RegionPlan& plan) {
    nlohmann::json regions = nlohmann::json::array();
    for (size_t i = 0; i < plan.regions.size(); ++i) {
        const std::string stem = fs::path(regionStem(plan, i)).lexically_relative(plan.dir).string();
        nlohmann::json r = boundsJson(plan.regions[i].box);
        r["task"] = i;
        r["footprint_bytes"] = plan.regions[i].footprint_bytes;
        r["outputs"] = {{"glb", stem + ".glb"}, {"stats", stem + ".json"}, {"instances", stem + ".ugi"}};
        regions.push_back(r);
    }
    return {{"format", "undergrowth-plan"},
            {"format_version", 1},
            {"id", hex64(plan.id)},
            {"name", plan.name},
            {"scene", plan.scene},
            {"scene_hash", hex64(plan.scene_hash)},
            {"ghost_tile_key", hex64(plan.ghost_tile_key)},
            {"seed", plan.seed},
            {"chunk_size_m", plan.chunk_size_m},
            {"extent", boundsJson(plan.extent)},
            {"memory_per_job", plan.memory_per_job},
            {"threads_per_task", plan.threads_per_task},
            {"binary", plan.binary},
            {"cache", "cache"},
            {"regions", regions}};
}

bool readRegionPlan(const std::string& dir, RegionPlan* plan, std::string* error) {
    const std::string path = (fs::path(dir) / "plan.json").string();
    std::string text;
    if (!readTextFile(path, &text, error, size_t(64) << 20)) return false;
    try {
        const nlohmann::json j = nlohmann::json::parse(text);
        const PlanReader r{j};
        if (r.text(j, "format") != "undergrowth-plan") throw std::runtime_error("/format: not an undergrowth plan");
        if (r.whole(j, "format_version") != 1) throw std::runtime_error("/format_version: this build reads version 1");
        RegionPlan p;
        p.dir = fs::absolute(dir).lexically_normal().string();
        while (p.dir.size() > 1 && p.dir.back() == '/') p.dir.pop_back();
        p.name = r.text(j, "name");
        p.scene = r.text(j, "scene");
        p.scene_hash = r.hex(j, "scene_hash");
        p.ghost_tile_key = r.hex(j, "ghost_tile_key");
        p.seed = r.whole(j, "seed");
        p.chunk_size_m = r.number(j, "chunk_size_m");
        if (!(p.chunk_size_m > 0.0f)) throw std::runtime_error("/chunk_size_m: must be > 0");
        p.extent = r.box(r.at(j, "extent", ""), "/extent");
        p.memory_per_job = r.whole(j, "memory_per_job");
        p.threads_per_task = int(std::min<uint64_t>(r.whole(j, "threads_per_task"), 256));
        p.binary = r.text(j, "binary");
        const nlohmann::json& regions = r.at(j, "regions", "");
        if (!regions.is_array() || regions.empty() || regions.size() > size_t(kMaxPlanTasks))
            throw std::runtime_error("/regions: expected 1 to " + std::to_string(kMaxPlanTasks) + " regions");
        for (size_t i = 0; i < regions.size(); ++i) {
            const std::string where = "/regions/" + std::to_string(i);
            PlannedRegion region;
            region.box = r.box(regions[i], where);
            region.footprint_bytes = r.whole(regions[i], "footprint_bytes", where);
            p.regions.push_back(region);
        }
        p.id = planId(p);
        if (r.hex(j, "id") != p.id)
            throw std::runtime_error("/id: does not match the plan's fields (edited by hand?); make the plan again");
        *plan = std::move(p);
        return true;
    } catch (const std::exception& e) {
        *error = path + ": " + e.what();
        return false;
    }
}

std::string regionStem(const RegionPlan& plan, size_t task) {
    char name[32];
    std::snprintf(name, sizeof name, "region_%04zu", task);
    return (fs::path(plan.dir) / "regions" / name).string();
}

bool writeSlurmScripts(const RegionPlan& plan, std::string* error) {
    for (const std::string* p : {&plan.dir, &plan.binary, &plan.scene})
        if (p->find_first_of(" \t\n%'\"\\") != std::string::npos) {
            *error = *p + ": Slurm's #SBATCH lines cannot hold this path (whitespace, quotes or '%'); use another";
            return false;
        }
    const std::string bin = shellQuote(plan.binary), dir = shellQuote(plan.dir);
    const uint64_t mem_mib = std::max<uint64_t>(1, (plan.memory_per_job + (1u << 20) - 1) >> 20);
    const std::string common = "#SBATCH --cpus-per-task=" + std::to_string(plan.threads_per_task) +
                               "\n#SBATCH --mem=" + std::to_string(mem_mib) + "M\n#SBATCH --open-mode=append\n";
    const std::string head = "#!/bin/bash\n# Undergrowth plan " + hex64(plan.id) + " for " + plan.scene +
                             " (written by undergrowth plan; see docs/worlds.md).\n";
    struct Script {
        const char* name;
        std::string text;
    };
    const std::vector<Script> scripts = {
        {"cache.sbatch",
         head + "# Step 1: the Ghost Tile, built once (or verified) into the cache the tasks read.\n" +
             "#SBATCH --job-name=ug-cache\n" + common + "#SBATCH --output=" + plan.dir + "/logs/cache.log\n" +
             "exec " + bin + " build-tile " + shellQuote(plan.scene) + " --cache " + dir +
             "/cache --threads \"${SLURM_CPUS_PER_TASK:-1}\"\n"},
        {"job.sbatch",
         head + "# Step 2: task i instantiates region i; a requeued task overwrites nothing half-written, and a\n" +
             "# task whose outputs are complete for this plan is skipped.\n" + "#SBATCH --job-name=ug-regions\n" +
             "#SBATCH --array=0-" + std::to_string(plan.regions.size() - 1) + "\n#SBATCH --requeue\n" + common +
             "#SBATCH --output=" + plan.dir + "/logs/task_%a.log\n" + "exec " + bin + " instantiate --plan " + dir +
             " --task \"$SLURM_ARRAY_TASK_ID\" --threads \"${SLURM_CPUS_PER_TASK:-1}\"\n"},
        {"join.sbatch",
         head + "# Step 3: check every region and put the world together (DIR/manifest.json, DIR/world.glb).\n" +
             "#SBATCH --job-name=ug-join\n" + common + "#SBATCH --output=" + plan.dir + "/logs/join.log\n" + "exec " +
             bin + " join " + dir + " -o " + dir + "/world.glb\n"},
        {"submit.sh",
         "#!/bin/bash\n# Submits plan " + hex64(plan.id) +
             ": the cache step (only when the plan's Ghost Tile is not in the cache yet:\n"
             "# `plan` leaves it there, and every task verifies what it loads), the region array after it, the\n"
             "# join after the array. Prints \"cache ID|- array ID join ID\".\n"
             "# Arguments go to every sbatch (e.g. --partition=batch --account=world).\n"
             "set -euo pipefail\n"
             "dir=" + dir + "\n"
             "cache=-\n"
             "after=()\n"
             "if [ ! -s " + shellQuote(ghostTileCachePath(plan.dir + "/cache", plan.ghost_tile_key)) + " ]; then\n"
             "  cache=$(sbatch --parsable \"$@\" \"$dir/cache.sbatch\")\n"
             "  cache=${cache%%;*}\n"
             "  after=(--dependency=afterok:$cache)\n"
             "fi\n"
             "array=$(sbatch --parsable \"$@\" \"${after[@]}\" \"$dir/job.sbatch\")\n"
             "join=$(sbatch --parsable \"$@\" --dependency=afterok:${array%%;*} \"$dir/join.sbatch\")\n"
             "echo \"cache $cache array ${array%%;*} join ${join%%;*}\"\n"},
    };
    for (const Script& s : scripts) {
        const std::string path = (fs::path(plan.dir) / s.name).string();
        if (!writeTextFileAtomically(path, s.text, error)) return false;
        std::error_code ec;
        fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                        fs::perm_options::add, ec);
    }
    return true;
}

}  // namespace ug::cli
