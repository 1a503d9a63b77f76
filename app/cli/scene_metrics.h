// The measurements of engine/analysis on one instantiated scene, as the CLI reports them: how instances rest
// (hovering and sunk fractions), how piles pack (volume fraction of each type instantiated in elevation
// layers: the pile types) and whether the tile shows (twin fraction, spectral peak per type). Used by
// `instantiate --stats` and the bench's pile.* / tiling.* rows, so both print the same figures.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/rest_metrics.h"
#include "analysis/tiling_metrics.h"
#include "cli/scene_job.h"

namespace ug::cli {

struct TypeTiling {
    std::string name;
    uint64_t instances = 0;
    double twin_fraction = 0.0;
    SpectrumReport spectrum;
};

struct TypePacking {
    std::string name;
    PackingReport packing;
};

struct SceneMetrics {
    std::vector<std::string> type_names;
    RestReport rest;                    // drop_m left empty
    std::vector<RestReport> rest_per_type;
    double twin_fraction = 0.0;         // all instances
    std::vector<TypeTiling> tiling;     // per type with instances
    std::vector<TypePacking> packing;   // per elevation-layered type with instances
};

// `drops`: the store's settled drops, or null (instances where their candidates are).
SceneMetrics measureScene(const SceneJob& job, const InstanceStore& store, const SettledDrops* drops, int threads);
nlohmann::json sceneMetricsJson(const SceneMetrics& m);

// The type's tiling figures, or null when it has no instances.
const TypeTiling* findTiling(const SceneMetrics& m, const std::string& type);

}  // namespace ug::cli
