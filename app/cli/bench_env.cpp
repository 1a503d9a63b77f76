// Environmental-object rows (issue 11): snow cover and icicles of the three winter scenes, after the
// paper's Table 1 (Grosbellet et al. 2016, a 2016 Core i7: the `paper` column), a local edit until the
// effects are final, and what LOD nodes save on field queries (§6.1).
#include <algorithm>
#include <chrono>
#include <random>

#include "cli/bench.h"
#include "env/env_effects.h"
#include "scene/project.h"
#include "scene/scene_compile.h"

namespace ug::cli {

namespace {

struct EnvJob {
    Project project;
    std::shared_ptr<const HeightField> terrain;
    EnvScene env;
};

bool loadEnvJob(const BenchContext& ctx, const std::string& scene, EnvJob* job, std::string* error) {
    const std::string path = ctx.assets_dir + "/scenes/" + scene + ".json";
    return loadProject(path, &job->project, error) && loadTerrain(job->project, &job->terrain, error) &&
           compileEnvScene(job->project.environment, job->project.base_dir, path, job->terrain, &job->env, error);
}

// The full computation's median time and its result.
bool timeEffects(const BenchContext& ctx, const EnvScene& env, int reps, EnvEffects* fx, double* seconds,
                 std::string* error) {
    std::vector<double> t;
    for (int r = 0; r < reps; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        if (!computeEnvEffects(env, {.threads = ctx.threads}, fx, error)) return false;
        t.push_back(since(t0));
    }
    *seconds = median(t);
    return true;
}

struct SceneRow {
    const char* scene;
    const char* prefix;
    double paper_seconds, paper_triangles;  // Table 1
    const char* target;
};

bool sceneRows(const BenchContext& ctx, const SceneRow& s, std::vector<BenchRow>* rows, std::string* error) {
    EnvJob job;
    if (!loadEnvJob(ctx, s.scene, &job, error)) return false;
    EnvEffects fx;
    double seconds = 0.0;
    if (!timeEffects(ctx, job.env, ctx.quick ? 1 : 5, &fx, &seconds, error)) return false;
    const std::string p = std::string("env.") + s.prefix;
    const std::string reps = ctx.quick ? "one run" : "median of 5";
    rows->push_back({p + ".snow_seconds", seconds, "s", s.target, s.paper_seconds,
                     reps + ": snow and icicles of " + std::to_string(job.env.objects().size()) + " objects"});
    rows->push_back({p + ".snow_triangles", double(fx.stats.snow_triangles), "triangles", "", s.paper_triangles,
                     "as placed; " + std::to_string(fx.stats.snow_triangles_unique) + " computed"});
    rows->push_back({p + ".effect_computations", double(fx.stats.effect_computations), "classes", "", std::nullopt,
                     "for " + std::to_string(fx.stats.objects) + " objects (effect instancing)"});
    rows->push_back({p + ".icicles", double(fx.stats.icicles), "icicles", "", std::nullopt, "as placed"});
    return true;
}

// One local edit of the street until snow and icicles are final: a footprint added, then the bench moved,
// alternately; each edit recompiles the tree (meshes reused) and updates the effects incrementally.
bool streetUpdateRow(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error) {
    EnvJob job;
    if (!loadEnvJob(ctx, "street_winter", &job, error)) return false;
    EnvEffects fx;
    if (!computeEnvEffects(job.env, {.threads = ctx.threads}, &fx, error)) return false;
    EnvironmentDesc desc = job.project.environment;
    size_t bench = 0;
    while (bench < desc.roots.size() && !(desc.roots[bench].kind == EnvNodeKind::Object &&
                                          desc.types[desc.roots[bench].type].name == "bench"))
        ++bench;
    if (bench == desc.roots.size()) return (*error = "street_winter: no bench to move"), false;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.5f, 9.5f);
    std::vector<double> ms;
    EnvScene before = std::move(job.env);
    const int edits = ctx.quick ? 6 : 40;
    for (int e = 0; e < edits; ++e) {
        const auto t0 = std::chrono::steady_clock::now();
        if (e % 2 == 0) {
            EnvFieldDesc step;
            step.channel = EnvChannel::Occlusion;
            step.value = 0.85f;
            step.shape = makePoint(glm::vec3(u(rng), u(rng), 0.0f), 0.13f, 0.85f);
            desc.global_fields.push_back(step);
        } else {
            desc.roots[bench].transform.translation.x = u(rng);
        }
        EnvScene after;
        EnvEffects next;
        if (!compileEnvScene(desc, job.project.base_dir, "street_winter", job.terrain, &after, error, &before) ||
            !updateEnvEffects(after, fx, envDirtyRegion(before, after), {.threads = ctx.threads}, &next, error))
            return false;
        ms.push_back(since(t0) * 1000.0);
        before = std::move(after);
        fx = std::move(next);
    }
    std::sort(ms.begin(), ms.end());
    const double p95 = ms[std::min(ms.size() - 1, size_t(double(ms.size()) * 0.95))];
    rows->push_back({"env.street.update_p95_ms", p95, "ms", "<= 30", 100.0,
                     std::to_string(edits) + " edits (footprints, a moved bench): recompile + incremental update; "
                                             "paper: \"< 0.1 s\""});
    return true;
}

// §6.1: the road's tree groups as LOD nodes. Each of a group's objects sheds leaves (a point field of its
// own); the LOD node replaces them by one field over the group. Queries over the scene, with and without.
bool lodRow(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error) {
    EnvJob job;
    if (!loadEnvJob(ctx, "road_winter", &job, error)) return false;
    EnvironmentDesc desc = job.project.environment;
    for (NamedEnvGroup& g : desc.groups) {
        g.group.kind = EnvNodeKind::Lod;
        EnvFieldDesc whole;
        whole.channel = EnvChannel::Leaves;
        whole.value = 0.3f;
        whole.shape = makePoint(glm::vec3(0.0f), 4.5f, 0.3f);
        g.group.fields.push_back(whole);
        for (EnvNode& c : g.group.children) {
            EnvFieldDesc own;
            own.channel = EnvChannel::Leaves;
            own.value = 0.05f;
            own.shape = makePoint(glm::vec3(0.0f, 0.0f, 0.0f), 1.2f, 0.05f);
            c.fields.push_back(own);
        }
    }
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-35.0f, 35.0f);
    std::vector<glm::vec3> pts(ctx.quick ? 20000 : 200000);
    for (glm::vec3& p : pts) p = glm::vec3(u(rng), u(rng) * 0.25f, 0.05f);  // the band the trees stand in
    double t[2] = {0, 0};
    size_t fields[2] = {0, 0};
    for (int lod = 0; lod < 2; ++lod) {
        desc.use_lod_nodes = lod == 1;
        EnvScene env;
        if (!compileEnvScene(desc, job.project.base_dir, "road_winter", job.terrain, &env, error, &job.env)) return false;
        fields[lod] = env.fields().size();
        std::vector<double> runs;
        for (int r = 0; r < (ctx.quick ? 1 : 5); ++r) {
            const auto t0 = std::chrono::steady_clock::now();
            float sum = 0.0f;
            for (const glm::vec3& p : pts) sum += env.channels(p).leaves;
            runs.push_back(since(t0));
            if (!(sum >= 0.0f)) return (*error = "road_winter: leaves field is NaN"), false;
        }
        t[lod] = median(runs);
    }
    rows->push_back({"env.road.lod_query_speedup", t[0] / std::max(t[1], 1e-9), "x", ">= 1", 3.0,
                     std::to_string(pts.size()) + " queries: " + std::to_string(fields[0]) + " fields as groups, " +
                         std::to_string(fields[1]) + " with LOD nodes (paper Fig. 16: 3x)"});
    return true;
}

}  // namespace

bool benchEnvironment(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error) {
    const SceneRow scenes[] = {{"street_winter", "street", 0.13, 0.5e6, "<= 0.03"},
                               {"road_winter", "road", 4.01, 20.2e6, "<= 1"},
                               {"montmartre_winter", "montmartre", 2.09, 78.8e6, "<= 0.5"}};
    for (const SceneRow& s : scenes)
        if (!sceneRows(ctx, s, rows, error)) return false;
    return streetUpdateRow(ctx, rows, error) && lodRow(ctx, rows, error);
}

}  // namespace ug::cli
