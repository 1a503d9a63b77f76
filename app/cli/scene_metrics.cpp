#include "cli/scene_metrics.h"

#include <cmath>

namespace ug::cli {

SceneMetrics measureScene(const SceneJob& job, const InstanceStore& store, const SettledDrops* drops, int threads) {
    SceneMetrics m;
    for (const DetailModel& d : job.models) m.type_names.push_back(d.name);
    const std::vector<PlacedInstance> all = placeInstances(store, job.tile, drops);
    std::vector<const DetailModel*> models;
    for (const DetailModel& d : job.models) models.push_back(&d);
    // What the scene rests on, as settling sees it (the plane only where the project gives one); a scene
    // without either is measured against z = 0, where the editor draws its ground grid.
    RestSupport support = settleInput(job.project, job.compiled.terrain, job.tile, job.models, job.environment.get()).support;
    if (!support.terrain && !std::isfinite(support.ground_z)) support.ground_z = 0.0f;
    m.rest = measureRest(all, models, support, 0.02f, threads);
    m.rest_per_type = restPerType(m.rest, all, uint32_t(job.models.size()));
    m.rest.drop_m.clear();
    m.rest.sunk_m.clear();
    m.twin_fraction = twinFraction(all, job.tile.settings.tile_size_m);
    for (uint32_t t = 0; t < job.models.size(); ++t) {
        std::vector<PlacedInstance> of_type;
        for (const PlacedInstance& p : all)
            if (p.type == t) of_type.push_back(p);
        if (of_type.empty()) continue;
        TypeTiling tiling{job.models[t].name, of_type.size(), twinFraction(of_type, job.tile.settings.tile_size_m),
                          tilePeriodSpectrum(of_type, job.tile.settings.tile_size_m, {}, threads)};
        m.tiling.push_back(tiling);
        if (job.compiled.types[t].strategy == PriorityStrategy::Elevation)
            m.packing.push_back({job.models[t].name, measurePacking(all, models, support, {t}, 0.02f, threads)});
    }
    return m;
}

namespace {

nlohmann::json restJson(const RestReport& r) {
    return {{"instances", r.instances},
            {"hovering_fraction", r.hovering_fraction},
            {"hovering_5cm", r.hovering_5cm},
            {"sunk_fraction", r.sunk_fraction},
            {"median_drop_m", r.median_drop_m},
            {"max_drop_m", r.max_drop_m},
            {"max_sunk_m", r.max_sunk_m}};
}

}  // namespace

nlohmann::json sceneMetricsJson(const SceneMetrics& m) {
    nlohmann::json rest = restJson(m.rest);
    rest["threshold_m"] = 0.02;
    rest["per_type"] = nlohmann::json::object();
    for (size_t t = 0; t < m.rest_per_type.size() && t < m.type_names.size(); ++t)
        if (m.rest_per_type[t].instances) rest["per_type"][m.type_names[t]] = restJson(m.rest_per_type[t]);
    nlohmann::json tiling = {{"twin_fraction", m.twin_fraction}, {"per_type", nlohmann::json::object()}};
    for (const TypeTiling& t : m.tiling)
        tiling["per_type"][t.name] = {{"instances", t.instances},
                                      {"twin_fraction", t.twin_fraction},
                                      {"spectral_peak", t.spectrum.ratio}};
    nlohmann::json packing = nlohmann::json::object();
    for (const TypePacking& p : m.packing)
        packing[p.name] = {{"volume_fraction", p.packing.volume_fraction},
                           {"overlap_fraction", p.packing.overlap_fraction},
                           {"core_volume_m3", p.packing.core_volume_m3},
                           {"shell_m", p.packing.shell_m}};
    return {{"rest", rest}, {"packing", packing}, {"tiling", tiling}};
}

const TypeTiling* findTiling(const SceneMetrics& m, const std::string& type) {
    for (const TypeTiling& t : m.tiling)
        if (t.name == type) return &t;
    return nullptr;
}

}  // namespace ug::cli
