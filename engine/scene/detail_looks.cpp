#include "scene/detail_looks.h"

#include <algorithm>
#include <cassert>

#include "core/parallel.h"
#include "instancer/tile_coord.h"

namespace ug {

uint32_t DetailLooks::lookOf(uint32_t type, glm::vec3 origin) const {
    if (type >= conditions.size() || conditions[type].empty() || !environment) return type;
    const uint32_t k = scatterVariantAt(*environment, conditions[type], origin);
    return k == 0 ? type : variant_first[type] + k - 1;
}

DetailLooks detailLooks(const Project& project, const std::vector<DetailModel>& models,
                        const std::vector<std::vector<DetailModel>>& variant_models,
                        std::shared_ptr<const EnvScene> environment) {
    DetailLooks looks;
    looks.environment = std::move(environment);
    const size_t types = models.size();
    looks.variant_first.assign(types, 0);
    looks.conditions.assign(types, {});
    for (size_t t = 0; t < types; ++t) {
        looks.models.push_back(&models[t]);
        looks.look_type.push_back(uint32_t(t));
    }
    for (size_t t = 0; t < types && t < variant_models.size(); ++t) {
        looks.variant_first[t] = uint32_t(looks.models.size());
        for (size_t k = 0; k < variant_models[t].size(); ++k) {
            looks.models.push_back(&variant_models[t][k]);
            looks.look_type.push_back(uint32_t(t));
            looks.conditions[t].push_back(project.detail_types[t].scatter.variants[k].when);
        }
    }
    assert(!looks.hasVariants() || looks.environment);
    return looks;
}

std::vector<uint32_t> instanceLooks(const DetailLooks& looks, const CandidateSet& candidates, float tile_size_m,
                                    const InstanceStore& store, int threads) {
    if (!looks.hasVariants()) return {};
    const size_t tiles_per_block = 1024;
    const size_t tiles = store.tileCount();
    std::vector<std::vector<uint32_t>> per_block((tiles + tiles_per_block - 1) / tiles_per_block);
    parallelFor(per_block.size(), threads, 1, [&](size_t begin, size_t end, int) {
        std::vector<uint32_t> ids;
        for (size_t b = begin; b < end; ++b)
            for (size_t t = b * tiles_per_block; t < std::min(tiles, (b + 1) * tiles_per_block); ++t) {
                const glm::vec3 origin = tileOrigin(unpackTile(store.tileKey(t)), tile_size_m);
                store.tileIds(t, &ids);
                for (uint32_t j : ids)
                    per_block[b].push_back(looks.lookOf(candidates.type[j], origin + candidates.position[j]));
            }
    });
    std::vector<uint32_t> out;
    out.reserve(store.instanceCount());
    for (const std::vector<uint32_t>& block : per_block) out.insert(out.end(), block.begin(), block.end());
    return out;
}

}  // namespace ug
