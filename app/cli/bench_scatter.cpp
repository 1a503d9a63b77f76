// Scattered environmental effects (issue 12): fallen leaves and grass of the three autumn scenes after the
// environmental-objects paper's Table 1 (Grosbellet et al. 2016, a 2016 Core i7: the `paper` column), what
// LOD nodes save on the park, and one local edit of the street until the instance set is final.
//
// Each effect is timed alone, as the paper reports it: the other detail types keep their candidates in
// the Ghost Tile but lose their density, so the instantiator skips them without testing one.
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "cli/bench.h"
#include "cli/scene_job.h"
#include "env/env_scatter.h"
#include "instancer/settling.h"
#include "instancer/tile_coord.h"

namespace ug::cli {

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

bool loadAutumn(const BenchContext& ctx, const std::string& scene, SceneJob* job, std::string* error) {
    return loadSceneJob(ctx.assets_dir + "/scenes/" + scene + ".json", ctx.cache_dir, ctx.threads, true, job, error);
}

// The job's input with only the types scattering `channel` keeping their density; false when it has none.
bool onlyChannel(const SceneJob& job, EnvChannel channel, InstancerInput* input) {
    bool any = false;
    for (size_t t = 0; t < job.project.detail_types.size(); ++t) {
        const ScatterDesc& s = job.project.detail_types[t].scatter;
        if (s.enabled && s.settings.channel == channel) any = true;
        else input->types[t].field = nullptr;
    }
    return any;
}

struct Timed {
    double seconds = 0.0;  // median
    InstanceStats stats;   // of the last run
};

bool timeInstantiation(const BenchContext& ctx, const InstancerInput& input, int reps, Timed* out, std::string* error) {
    Instantiator inst;
    if (!inst.setInput(input, error)) return false;
    std::vector<double> seconds;
    for (int r = 0; r < reps; ++r) {
        if (!inst.instantiateAll({.threads = ctx.threads}, &out->stats, error)) return false;
        seconds.push_back(out->stats.seconds);
    }
    out->seconds = median(seconds);
    return true;
}

struct EffectRow {
    const char* scene;   // assets/scenes/<scene>_autumn.json
    const char* prefix;  // env.<prefix>.<effect>_*
    EnvChannel channel;
    const char* effect;  // "leaves", "grass"
    double paper_seconds, paper_instances;  // Table 1
    const char* seconds_target;
    const char* instances_target;
};

const EffectRow kEffectRows[] = {
    {"road_autumn", "road", EnvChannel::Leaves, "leaves", 6.73, 1461e3, "<= 0.7", ">= 1400000"},
    {"road_autumn", "road", EnvChannel::Grass, "grass", 4.76, 3020e3, "<= 0.5", ">= 3000000"},
    {"park_autumn", "park", EnvChannel::Leaves, "leaves", 4.53, 839e3, "<= 0.45", ""},
    {"park_autumn", "park", EnvChannel::Grass, "grass", 1.86, 1050e3, "<= 0.2", ""},
    {"street_autumn", "street", EnvChannel::Leaves, "leaves", 0.12, 36e3, "", ""},
};

bool effectRow(const BenchContext& ctx, const SceneJob& job, const EffectRow& e, std::vector<BenchRow>* rows,
               std::string* error) {
    InstancerInput input = instancerInput(job, job.project.instantiation_seed);
    if (!onlyChannel(job, e.channel, &input)) return (*error = std::string(e.scene) + ": no " + e.effect + " type"), false;
    const int reps = ctx.repetitions();
    Timed t;
    if (!timeInstantiation(ctx, input, reps, &t, error)) return false;
    const std::string p = std::string("env.") + e.prefix + "." + e.effect;
    rows->push_back({p + "_seconds", t.seconds, "s", e.seconds_target, e.paper_seconds,
                     "median of " + std::to_string(reps) + ", " + std::to_string(t.stats.candidates_tested) +
                         " candidates tested"});
    rows->push_back({p + "_instances", double(t.stats.instances), "instances", e.instances_target, e.paper_instances,
                     std::to_string(t.stats.tiles_touched) + " tiles touched"});
    std::fprintf(stderr, "  %-14s %-6s %9llu instances from %11llu candidates (%llu alive, %llu culled)  %.3f s\n",
                 e.scene, e.effect, static_cast<unsigned long long>(t.stats.instances),
                 static_cast<unsigned long long>(t.stats.candidates_tested),
                 static_cast<unsigned long long>(t.stats.alive), static_cast<unsigned long long>(t.stats.culled),
                 t.seconds);
    return true;
}

// The park's leaves and grass with its trees' LOD nodes acting as plain groups (every tree's own fields
// queried), then with the LOD nodes' fields in their place (§6.1). The environment's effects are instanced
// per class either way.
bool parkLodRow(const BenchContext& ctx, SceneJob& job, std::vector<BenchRow>* rows, std::string* error) {
    double seconds[2] = {0.0, 0.0};
    uint64_t instances[2] = {0, 0};
    size_t fields[2] = {0, 0};
    for (int lod = 0; lod < 2; ++lod) {
        Project project = job.project;
        project.environment.use_lod_nodes = lod == 1;
        auto env = std::make_shared<EnvScene>();
        if (!compileEnvScene(project.environment, project.base_dir, job.path, job.compiled.terrain, env.get(), error,
                             job.environment.get()))
            return false;
        fields[lod] = env->fields().size();
        InstancerInput input = instancerInput(job, project.instantiation_seed);
        for (size_t t = 0; t < project.detail_types.size(); ++t)
            if (project.detail_types[t].scatter.enabled &&
                !compileDetailType(project, t, job.compiled.terrain, &input.types[t], error, env))
                return false;
        Timed t;
        if (!timeInstantiation(ctx, input, ctx.quick ? 1 : 3, &t, error)) return false;
        seconds[lod] = t.seconds;
        instances[lod] = t.stats.instances;
    }
    rows->push_back({"env.park.lod_speedup", seconds[0] / std::max(seconds[1], 1e-9), "x", ">= 1", 24.0 / 4.5,
                     std::to_string(fields[0]) + " fields as groups (" + std::to_string(instances[0]) +
                         " instances), " + std::to_string(fields[1]) + " with LOD nodes (" +
                         std::to_string(instances[1]) + "); paper 24.0 s -> 4.5 s with effect instancing too"});
    return true;
}

// Every tile of the extent meeting one of the boxes: where an edit of the environment changed the support.
std::vector<uint64_t> tilesMeeting(std::span<const Bounds> boxes, const Bounds& extent, float tile_size_m) {
    std::vector<uint64_t> out;
    for (const Bounds& b : boxes) {
        const Bounds c = intersect(b, extent);
        if (c.empty()) continue;
        const glm::ivec3 lo = tileOf(c.lo, tile_size_m), hi = tileOf(c.hi, tile_size_m);
        for (int x = lo.x; x <= hi.x; ++x)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int z = lo.z; z <= hi.z; ++z) out.push_back(packTile(glm::ivec3(x, y, z)));
    }
    return out;
}

// One local edit of the street until the instance set and its settling are final: a leaf pile stamped,
// then the bench moved, alternately. Each edit recompiles the environment (meshes reused) and the
// scattered types' densities, updates the instances over scatterDirtyRegion, and settles again the tiles
// that changed and those the edit's boxes meet (their support moved). Checked at the end against
// instantiating and settling the edited street from scratch.
bool streetEditRow(const BenchContext& ctx, SceneJob& job, std::vector<BenchRow>* rows, std::string* error) {
    Instantiator inst;
    InstanceStats st;
    if (!inst.setInput(instancerInput(job, job.project.instantiation_seed), error) ||
        !inst.instantiateAll({.threads = ctx.threads}, &st, error))
        return false;
    Project project = job.project;
    EnvironmentDesc& desc = project.environment;
    size_t bench = 0;
    while (bench < desc.roots.size() && !(desc.roots[bench].kind == EnvNodeKind::Object &&
                                          desc.types[desc.roots[bench].type].name == "bench"))
        ++bench;
    if (bench == desc.roots.size()) return (*error = job.path + ": no bench to move"), false;
    std::shared_ptr<const EnvScene> before = job.environment;
    const bool settles = project.settling.settle.enabled;
    SettledDrops drops;
    SettleHistory history;  // as the live instancer keeps it
    if (settles)
        settleAll(settleInput(project, job.compiled.terrain, job.tile, job.models, before.get()), inst.store(),
                  ctx.threads, &drops, &history);
    const glm::vec3 seat = desc.roots[bench].transform.translation;
    const int edits = ctx.quick ? 6 : 40;
    std::vector<double> ms, settled_ms;  // until the instance set is final; and its settling too
    std::vector<uint64_t> changed;
    for (int e = 0; e < edits; ++e) {
        const float a = float(e) * 2.39996f;  // golden-angle spiral: every edit somewhere new
        const auto t0 = Clock::now();
        if (e % 2 == 0) {
            EnvFieldDesc pile;
            pile.channel = EnvChannel::Leaves;
            pile.value = 2.0f;
            pile.shape = makePoint(glm::vec3(5.0f + 3.5f * std::cos(a), 5.0f + 3.5f * std::sin(a), 0.0f), 0.5f, 2.0f);
            desc.global_fields.push_back(pile);
        } else {
            desc.roots[bench].transform.translation = seat + glm::vec3(0.6f * std::cos(a), 0.3f * std::sin(a), 0.0f);
        }
        auto after = std::make_shared<EnvScene>();
        if (!compileEnvScene(desc, project.base_dir, job.path, job.compiled.terrain, after.get(), error, before.get()))
            return false;
        std::vector<InstanceTypeSettings> types = inst.input().types;
        for (size_t t = 0; t < project.detail_types.size(); ++t)
            if (project.detail_types[t].scatter.enabled &&
                !compileDetailType(project, t, job.compiled.terrain, &types[t], error, after))
                return false;
        const std::vector<Bounds> dirty = scatterDirtyRegion(*before, *after);
        if (!inst.update(std::move(types), dirty, {.threads = ctx.threads}, &st, &changed, error)) return false;
        ms.push_back(msSince(t0));
        if (settles) {
            std::vector<uint64_t> resettle = tilesMeeting(dirty, job.compiled.extent, job.tile.settings.tile_size_m);
            resettle.insert(resettle.end(), changed.begin(), changed.end());
            std::sort(resettle.begin(), resettle.end());
            resettle.erase(std::unique(resettle.begin(), resettle.end()), resettle.end());
            settleUpdate(settleInput(project, job.compiled.terrain, job.tile, job.models, after.get()), inst.store(),
                         resettle, ctx.threads, &drops, nullptr, &history);
            settled_ms.push_back(msSince(t0));
        }
        before = after;
    }
    // The same street edited in one go, instantiated and settled from scratch.
    InstancerInput fresh_input = inst.input();
    Instantiator fresh;
    if (!fresh.setInput(fresh_input, error) || !fresh.instantiateAll({.threads = ctx.threads}, &st, error)) return false;
    if (!(fresh.store() == inst.store()))
        return (*error = job.path + ": the street's incremental instances differ from a full run after its edits"), false;
    if (settles) {
        SettledDrops full;
        SettleHistory full_history;
        settleAll(settleInput(project, job.compiled.terrain, job.tile, job.models, before.get()), fresh.store(),
                  ctx.threads, &full, &full_history);
        if (!(full == drops) || full_history.after_pass != history.after_pass)
            return (*error = job.path + ": the street's incremental settling differs from settling it in full"), false;
    }
    auto p95 = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v[std::min(v.size() - 1, size_t(double(v.size()) * 0.95))];
    };
    rows->push_back({"env.street.leaf_edit_p95_ms", p95(ms), "ms", "<= 16", std::nullopt,
                     std::to_string(edits) + " edits (leaf piles, a moved bench): environment, densities, "
                                             "incremental update; " +
                         std::to_string(inst.store().instanceCount()) + " instances after, equal to a full run"});
    if (settles)
        rows->push_back({"env.street.leaf_edit_settled_p95_ms", p95(settled_ms), "ms", "", std::nullopt,
                         "the same edits and settling again where they reach (settleUpdate), equal to settling "
                         "in full"});
    return true;
}

}  // namespace

bool benchScatter(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error) {
    std::string loaded;
    SceneJob job;
    for (const EffectRow& e : kEffectRows) {
        if (loaded != e.scene) {
            job = SceneJob{};
            if (!loadAutumn(ctx, e.scene, &job, error)) return false;
            loaded = e.scene;
            if (loaded == "street_autumn" && !streetEditRow(ctx, job, rows, error)) return false;
        }
        if (!effectRow(ctx, job, e, rows, error)) return false;
        if (loaded == "park_autumn" && e.channel == EnvChannel::Grass && !parkLodRow(ctx, job, rows, error))
            return false;
    }
    return true;
}

}  // namespace ug::cli
