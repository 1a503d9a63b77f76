// `undergrowth join DIR [-o WORLD.glb]`: after a plan's tasks (region_plan.h), checks that every region is
// there and from this plan, writes DIR/manifest.json (regions, bounds, counts, hashes) and, when the world
// fits, one glTF of the whole world, exported from the regions' ids exactly as a single process would.
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "cli/env_job.h"
#include "cli/strands_job.h"
#include "cli/instantiation.h"
#include "cli/region_plan.h"
#include "cli/scene_job.h"
#include "core/atomic_file.h"
#include "core/hash.h"
#include "io/instance_list_file.h"

namespace ug::cli {

namespace fs = std::filesystem;

namespace {

int fail(const std::string& message, int code = 1) {
    std::fprintf(stderr, "undergrowth join: %s\n", message.c_str());
    return code;
}

// Instances exported per byte budget: a TRS per instance (40 bytes) plus the index and node overhead.
constexpr uint64_t kJoinedBytesPerInstance = 48;

struct RegionResult {
    uint64_t instances = 0;
    bool has_drops = false;
    uint64_t glb_bytes = 0;
    uint64_t glb_hash = 0;
    InstanceListFile list;  // empty unless the world is joined
};

std::string taskList(const std::vector<size_t>& tasks) {
    std::string s;
    for (size_t i = 0; i < tasks.size(); ++i) s += (i ? "," : "") + std::to_string(tasks[i]);
    return s;
}

// Every region's instance list, checked against the plan, one at a time. The lists are kept for joining
// while the world's instances stay within `keep_instances` (0: none kept); past that every list is let
// go, so a world too big to join never has to fit in memory. Errors name the region's file.
bool readRegions(const RegionPlan& plan, uint64_t keep_instances, std::vector<RegionResult>* out,
                 std::string* error) {
    std::vector<size_t> missing;
    for (size_t i = 0; i < plan.regions.size(); ++i) {
        const std::string stem = regionStem(plan, i);
        if (!fs::exists(stem + ".ugi") || !fs::exists(stem + ".glb") || !fs::exists(stem + ".json"))
            missing.push_back(i);
    }
    if (!missing.empty()) {
        *error = std::to_string(missing.size()) + " of " + std::to_string(plan.regions.size()) +
                 " regions are missing (tasks " + taskList(missing) +
                 "); run them again: sbatch --array=" + taskList(missing) + " " + plan.dir + "/job.sbatch";
        return false;
    }
    out->resize(plan.regions.size());
    uint64_t total = 0;
    for (size_t i = 0; i < plan.regions.size(); ++i) {
        const std::string stem = regionStem(plan, i);
        RegionResult& r = (*out)[i];
        if (!readInstanceListFile(stem + ".ugi", &r.list, error)) return false;
        r.instances = r.list.store.instanceCount();
        r.has_drops = r.list.has_drops;
        total += r.instances;
        const nlohmann::json header = nlohmann::json::parse(r.list.header_json, nullptr, false);
        const std::string from = header.is_object() ? header.value("plan", std::string("?")) : "?";
        if (from != hex64(plan.id) || r.list.ghost_tile_key != plan.ghost_tile_key)
            return (*error = stem + ".ugi: region " + std::to_string(i) + " is from plan " + from +
                             ", not from plan " + hex64(plan.id) +
                             " (a stale output of an earlier plan?); run task " + std::to_string(i) +
                             " again",
                    false);
        if (header.value("task", int64_t(-1)) != int64_t(i))
            return (*error = stem + ".ugi: holds task " + std::to_string(header.value("task", int64_t(-1))) +
                             ", not task " + std::to_string(i),
                    false);
        if (r.has_drops != (*out)[0].has_drops)
            return (*error = stem + ".ugi: settled drops in some regions and not in others", false);
        if (total > keep_instances)
            for (size_t k = 0; k <= i; ++k) (*out)[k].list = InstanceListFile{};
        std::vector<unsigned char> glb;
        if (!readWholeFile(stem + ".glb", &glb, error)) return false;
        r.glb_bytes = glb.size();
        r.glb_hash = hashBytes(glb.data(), glb.size());
    }
    return true;
}

// The union of the regions, tile by tile in key order; an instance in two regions means the regions
// overlap, which a plan never does: refused.
bool mergeRegions(const std::vector<RegionResult>& regions, InstanceStore* store, SettledDrops* drops,
                  std::string* error) {
    struct Entry {
        uint64_t key;
        uint32_t id;
        uint16_t drop;
        uint32_t region;
    };
    std::vector<Entry> all;
    uint64_t total = 0;
    for (const RegionResult& r : regions) total += r.instances;
    all.reserve(total);
    std::vector<uint32_t> ids;
    for (uint32_t ri = 0; ri < regions.size(); ++ri) {
        const InstanceListFile& l = regions[ri].list;
        for (size_t t = 0; t < l.store.tileCount(); ++t) {
            const uint64_t key = l.store.tileKey(t);
            l.store.tileIds(t, &ids);
            const std::span<const uint16_t> d = l.has_drops ? l.drops.tile(key) : std::span<const uint16_t>{};
            for (size_t k = 0; k < ids.size(); ++k)
                all.push_back({key, ids[k], l.has_drops ? d[k] : uint16_t(0), ri});
        }
    }
    std::sort(all.begin(), all.end(),
              [](const Entry& a, const Entry& b) { return a.key != b.key ? a.key < b.key : a.id < b.id; });
    const bool has_drops = !regions.empty() && regions[0].has_drops;
    std::vector<uint16_t> tile_drops;
    for (size_t i = 0; i < all.size();) {
        size_t j = i;
        ids.clear();
        tile_drops.clear();
        for (; j < all.size() && all[j].key == all[i].key; ++j) {
            if (j > i && all[j].id == all[j - 1].id) {
                *error = "regions " + std::to_string(all[j - 1].region) + " and " +
                         std::to_string(all[j].region) + " both hold candidate " + std::to_string(all[j].id) +
                         " of tile " + hex64(all[j].key) + ": the regions overlap";
                return false;
            }
            ids.push_back(all[j].id);
            tile_drops.push_back(all[j].drop);
        }
        store->appendTile(all[i].key, ids);
        if (has_drops) drops->append(all[i].key, tile_drops);
        i = j;
    }
    return true;
}

nlohmann::json manifestJson(const RegionPlan& plan, const std::vector<RegionResult>& regions, uint64_t total) {
    nlohmann::json manifest_regions = nlohmann::json::array();
    for (size_t i = 0; i < regions.size(); ++i) {
        const std::string stem = fs::path(regionStem(plan, i)).lexically_relative(plan.dir).string();
        const Bounds& b = plan.regions[i].box;
        manifest_regions.push_back({{"task", i},
                                    {"min", {b.lo.x, b.lo.y, b.lo.z}},
                                    {"max", {b.hi.x, b.hi.y, b.hi.z}},
                                    {"instances", regions[i].instances},
                                    {"glb", stem + ".glb"},
                                    {"glb_bytes", regions[i].glb_bytes},
                                    {"glb_hash", hex64(regions[i].glb_hash)}});
    }
    return {{"format", "undergrowth-world-manifest"},
            {"format_version", 1},
            {"plan", hex64(plan.id)},
            {"scene", plan.scene},
            {"scene_hash", hex64(plan.scene_hash)},
            {"instances", total},
            {"regions", manifest_regions},
            {"joined", nullptr}};
}

// The regions' ids merged and exported as one process exports the scene (same glTF, instance for
// instance); the environment's effects are computed once for the whole world, not stitched together.
bool exportJoinedWorld(const RegionPlan& plan, const std::vector<RegionResult>& regions, int threads,
                       const std::string& out, std::string* error) {
    InstanceStore store;
    SettledDrops drops;
    if (!mergeRegions(regions, &store, &drops, error)) return (*error = plan.dir + ": " + *error, false);
    SceneJob job;
    if (!loadSceneJob(plan.scene, (fs::path(plan.dir) / "cache").string(), threads, true, &job, error))
        return false;
    if (job.tile.key != plan.ghost_tile_key)
        return (*error = plan.scene + ": its Ghost Tile changed since plan " + hex64(plan.id) +
                         "; make the plan again",
                false);
    // The lists' checksums catch damage, not a list written by something else: every id must name a
    // candidate of this tile before the export looks it up.
    uint64_t bad_id = 0;
    std::vector<uint64_t> per_type(job.models.size(), 0);
    store.forEach([&](uint64_t, uint32_t j) {
        if (j >= job.tile.candidates.size())
            bad_id = uint64_t(j) + 1;
        else
            ++per_type[job.tile.candidates.type[j]];
    });
    if (bad_id != 0)
        return (*error = plan.dir + ": a region holds candidate " + std::to_string(bad_id - 1) +
                         ", but the Ghost Tile has " + std::to_string(job.tile.candidates.size()) +
                         "; run the plan's tasks again",
                false);
    SceneEnvironmentOutput env;
    if (!computeSceneEnvironment(job, threads, nullptr, true, &env, error)) return false;
    nlohmann::json strand_stats;
    if (!computeSceneStrands(job, threads, nullptr, true, &env.meshes, &strand_stats, error)) return false;
    nlohmann::json per_type_json = nlohmann::json::object();
    for (size_t i = 0; i < job.models.size(); ++i) per_type_json[job.models[i].name] = per_type[i];
    nlohmann::json stats = {{"scene", job.project.name},
                            {"seed", plan.seed},
                            {"plan", hex64(plan.id)},
                            {"regions", regions.size()},
                            {"instances", store.instanceCount()},
                            {"instances_per_type", per_type_json}};
    if (!env.stats.is_null()) stats["environment"] = env.stats;
    if (!strand_stats.is_null()) stats["particles"] = strand_stats;
    return exportJobInstances(job, store, regions[0].has_drops ? &drops : nullptr, &env.meshes,
                              job.compiled.extent, plan.chunk_size_m, false, threads, &stats, out, error);
}

}  // namespace

int runJoinCommand(int argc, char** argv) {
    const char* usage =
        "usage: undergrowth join DIR [-o WORLD.glb|WORLD.gltf] [--max-bytes BYTES] [--threads N]";
    Args args;
    std::string error;
    if (!parseArgs(argc, argv, 2, {"-o", "--out", "--max-bytes", "--threads"}, {}, &args, &error) ||
        args.positional.size() != 1)
        return fail(error.empty() ? usage : error + "\n" + usage, 2);
    const std::string out = args.has("-o") ? args.get("-o") : args.get("--out");
    if (!out.empty()) {
        const std::string ext = fs::path(out).extension().string();
        if (ext != ".glb" && ext != ".gltf") return fail(out + ": the output must end in .glb or .gltf", 2);
    }
    // A GLB's length is a 32-bit field: 4 GiB at most, whatever the budget.
    uint64_t max_bytes = 2ull << 30;
    long threads = 0;
    if (args.has("--max-bytes") &&
        !parseByteSize("--max-bytes", args.get("--max-bytes"), 1, (4ull << 30) - 1, &max_bytes, &error))
        return fail(error, 2);
    if (args.has("--threads") && !parseInt("--threads", args.get("--threads"), 0, 256, &threads, &error))
        return fail(error, 2);

    RegionPlan plan;
    if (!readRegionPlan(args.positional[0], &plan, &error)) return fail(error);
    std::vector<RegionResult> regions;
    const uint64_t joinable = out.empty() ? 0 : max_bytes / kJoinedBytesPerInstance;
    if (!readRegions(plan, joinable, &regions, &error)) return fail(error);
    uint64_t total = 0;
    for (const RegionResult& r : regions) total += r.instances;
    nlohmann::json manifest = manifestJson(plan, regions, total);
    const uint64_t estimate = total * kJoinedBytesPerInstance;
    if (!out.empty() && total > joinable) {
        manifest["joined_refused"] = "about " + std::to_string(estimate >> 20) + " MiB, more than --max-bytes";
        std::printf("the world (%llu instances, about %llu MiB) is bigger than --max-bytes (%llu MiB): it stays "
                    "as %zu region files plus the manifest\n",
                    static_cast<unsigned long long>(total), static_cast<unsigned long long>(estimate >> 20),
                    static_cast<unsigned long long>(max_bytes >> 20), regions.size());
    } else if (!out.empty()) {
        if (!exportJoinedWorld(plan, regions, int(threads), out, &error)) return fail(error);
        manifest["joined"] = fs::absolute(out).lexically_normal().string();
    }
    const std::string manifest_path = (fs::path(plan.dir) / "manifest.json").string();
    if (!writeTextFileAtomically(manifest_path, manifest.dump(2) + "\n", &error)) return fail(error);
    std::printf("%zu regions of plan %s, %llu instances -> %s%s%s\n", regions.size(), hex64(plan.id).c_str(),
                static_cast<unsigned long long>(total), manifest_path.c_str(),
                manifest["joined"].is_null() ? "" : ", ", manifest["joined"].is_null() ? "" : out.c_str());
    return 0;
}

}  // namespace ug::cli
