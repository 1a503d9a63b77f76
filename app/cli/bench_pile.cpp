// Rest, packing and tiling rows (issue "piles that rest"): measurements of the sample scenes' results, not
// timings, so one run gives the figure (a "median" of identical values). The definitions are those of
// engine/analysis (rest_metrics.h, tiling_metrics.h), the same as `instantiate --stats` reports.
#include <cstdio>

#include "cli/bench.h"
#include "cli/scene_metrics.h"

namespace ug::cli {

namespace {

bool instantiateScene(const BenchContext& ctx, const std::string& scene, SceneJob* job, InstanceStore* store,
                      std::string* error) {
    if (!loadSceneJob(ctx.assets_dir + "/scenes/" + scene + ".json", ctx.cache_dir, ctx.threads, true, job, error))
        return false;
    Instantiator inst;
    InstanceStats st;
    if (!inst.setInput(instancerInput(*job, job->project.instantiation_seed), error) ||
        !inst.instantiateAll({.threads = ctx.threads}, &st, error))
        return false;
    *store = inst.store();
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
    const Case cases[] = {{"rock_pile", "rock"}, {"stone_hut", "flat_stone"}, {"meadow", nullptr}, {"beaver_dam", nullptr}};
    for (const Case& c : cases) {
        SceneJob job;
        InstanceStore store;
        if (!instantiateScene(ctx, c.scene, &job, &store, error)) return false;
        const SceneMetrics m = measureScene(job, store, ctx.threads);
        const std::string prefix = std::string("pile.") + c.scene;
        addRestRows(prefix, m, rows);
        for (const TypePacking& p : m.packing)
            if (c.pile_type && p.name == c.pile_type)
                rows->push_back({prefix + ".volume_fraction", p.packing.volume_fraction, "", ">= 0.45", std::nullopt,
                                 p.name + ": solid share of the pile's core (mesh volume)"});
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
