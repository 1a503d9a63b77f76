// Rest, packing and tiling rows (issue "piles that rest"): measurements of the sample scenes' results, not
// timings, so one run gives the figure (a "median" of identical values). The definitions are those of
// engine/analysis (rest_metrics.h, tiling_metrics.h), the same as `instantiate --stats` reports.
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "cli/bench.h"
#include "cli/scene_metrics.h"
#include "scene/sculpt_pile.h"

namespace ug::cli {

namespace {

// The rock pile's rocks in a pile the Sculpt tool builds when held for 40 stamps (brush radius 0.6 m,
// strength 1) on flat ground: one cone at the rocks' angle of repose (scene/sculpt_pile.h, with the tool's
// pile weight 4 and isosurface 0.5), the twigs' density removed.
bool sculptedPile(SceneJob* job, std::string* error) {
    DetailTypeDesc& rock = job->project.detail_types[0];
    const PileCone cone = pileConeForVolume(glm::vec3(0.0f), 40.0f * sculptStampVolume(0.6f, 1.0f, 0.5f),
                                            rock.angle_of_repose_deg);
    rock.density = makeBlendField({pileConePrimitive(cone, 4.0f, 0.5f)});
    subtractSolids(&rock.density, {makeHalfSpace(glm::vec3(0.0f, 0.0f, -0.02f), glm::vec3(0.0f, 0.0f, 1.0f), 0.02f, 10000.0f)});
    for (size_t t = 1; t < job->project.detail_types.size(); ++t) job->project.detail_types[t].density = DensityField{};
    return compileScene(job->project, job->compiled.terrain, &job->compiled, error);
}

bool instantiateScene(const BenchContext& ctx, const std::string& scene, SceneJob* job, InstanceStore* store,
                      SettledDrops* drops, double* settle_seconds, std::string* error) {
    const bool sculpted = scene == "sculpted";
    if (!loadSceneJob(ctx.assets_dir + "/scenes/" + (sculpted ? std::string("rock_pile") : scene) + ".json",
                      ctx.cache_dir, ctx.threads, true, job, error))
        return false;
    if (sculpted && !sculptedPile(job, error)) return false;
    Instantiator inst;
    InstanceStats st;
    if (!inst.setInput(instancerInput(*job, job->project.instantiation_seed), error) ||
        !inst.instantiateAll({.threads = ctx.threads}, &st, error))
        return false;
    *store = inst.store();
    const SettleInput settle = settleInput(job->project, job->compiled.terrain, job->tile, job->models, job->environment.get());
    *settle_seconds = 0.0;
    if (settle.settings.enabled) {
        std::vector<double> seconds;
        for (int r = 0; r < ctx.repetitions(); ++r) {
            const auto t0 = std::chrono::steady_clock::now();
            settleAll(settle, *store, ctx.threads, drops);
            seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        }
        std::sort(seconds.begin(), seconds.end());
        *settle_seconds = seconds[seconds.size() / 2];
    }
    return true;
}

void addRestRows(const std::string& prefix, const SceneMetrics& m, std::vector<BenchRow>* rows) {
    rows->push_back({prefix + ".hovering_fraction", m.rest.hovering_fraction, "", "<= 0.02", std::nullopt,
                     "instances that could drop > 2 cm onto a support"});
    rows->push_back({prefix + ".sunk_fraction", m.rest.sunk_fraction, "", "<= 0", std::nullopt,
                     "instances reaching > 2 cm below the support"});
}

}  // namespace

bool benchPile(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error) {
    struct Case {
        const char* scene;
        const char* pile_type;  // the type whose packing is reported, or null
    };
    const Case cases[] = {{"rock_pile", "rock"},   {"sculpted", "rock"},       {"stone_hut", "flat_stone"},
                          {"meadow", nullptr},     {"beaver_dam", nullptr}};
    for (const Case& c : cases) {
        SceneJob job;
        InstanceStore store;
        SettledDrops drops;
        double settle_seconds = 0.0;
        if (!instantiateScene(ctx, c.scene, &job, &store, &drops, &settle_seconds, error)) return false;
        const bool settled = job.project.settling.settle.enabled;
        const SceneMetrics m = measureScene(job, store, settled ? &drops : nullptr, ctx.threads);
        const std::string prefix = std::string("pile.") + c.scene;
        addRestRows(prefix, m, rows);
        if (settled)
            rows->push_back({std::string("settle.") + c.scene + ".seconds", settle_seconds, "s", "", std::nullopt,
                             "settling pass, median of " + std::to_string(ctx.repetitions()) + ", " +
                                 std::to_string(store.instanceCount()) + " instances"});
        for (const TypePacking& p : m.packing)
            if (c.pile_type && p.name == c.pile_type) {
                rows->push_back({prefix + ".volume_fraction", p.packing.volume_fraction, "", ">= 0.45", std::nullopt,
                                 p.name + ": solid share of the pile's core (mesh volume)"});
                rows->push_back({prefix + ".overlap_fraction", p.packing.overlap_fraction, "", "", std::nullopt,
                                 p.name + ": share of that solid inside two grains at once (interpenetration)"});
            }
        if (std::string(c.scene) == "meadow") {
            rows->push_back({"tiling.meadow.twin_fraction", m.twin_fraction, "", "<= 0.05", std::nullopt,
                             "instances with an exact copy one tile away"});
            const TypeTiling* grass = findTiling(m, "grass_tuft");
            if (grass)
                rows->push_back({"tiling.meadow.spectral_peak", grass->spectrum.ratio, "x", "<= 3", 250.0,
                                 "grass tufts: power at the tile frequency / background"});
        }
        std::fprintf(stderr, "  %s: %llu instances measured\n", c.scene,
                     static_cast<unsigned long long>(m.rest.instances));
    }
    return true;
}

}  // namespace ug::cli
