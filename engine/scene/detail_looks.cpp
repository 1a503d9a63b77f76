#include "scene/detail_looks.h"

#include <cassert>

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

}  // namespace ug
