// Every look a detail instance can take: the detail types' own models (look t is type t), then each
// scattered type's variants (DetailTypeDesc::scatter, §5.3 Fig. 12: wet leaves where η >= 0), in type
// order. Instantiation only ever sees types; the renderer and the exporter draw and write looks, each its
// own instanced mesh and material, and pick an instance's look from the environment at its origin.
//
//   DetailLooks looks = detailLooks(project, *scene.models, *scene.variant_models, scene.environment);
//   uint32_t look = looks.lookOf(type, origin);     // type itself, or one of its variants
#pragma once

#include <memory>
#include <vector>

#include "env/env_scatter.h"
#include "ghosttile/ghost_tile.h"
#include "instancer/instance_store.h"
#include "mesh/detail_model.h"
#include "scene/project.h"

namespace ug {

struct DetailLooks {
    std::vector<const DetailModel*> models;                 // per look; not owned
    std::vector<uint32_t> look_type;                        // per look: the detail type it belongs to
    std::vector<uint32_t> variant_first;                    // per type: its first variant's look
    std::vector<std::vector<ScatterCondition>> conditions;  // per type, one per variant
    std::shared_ptr<const EnvScene> environment;            // where the conditions are evaluated

    size_t size() const { return models.size(); }
    size_t typeCount() const { return variant_first.size(); }
    bool hasVariants() const { return models.size() > variant_first.size(); }
    // The look of an instance of `type` whose origin is at `origin` (world).
    uint32_t lookOf(uint32_t type, glm::vec3 origin) const;
};

// `models`: one per detail type (loadProjectModels); `variant_models`: loadScatterVariantModels' (may be
// empty: no variants); both must outlive the result. `environment` may be null only without variants.
DetailLooks detailLooks(const Project& project, const std::vector<DetailModel>& models,
                        const std::vector<std::vector<DetailModel>>& variant_models,
                        std::shared_ptr<const EnvScene> environment);

// Each instance's look in the store's order (InstanceStore::forEach), blocks of tiles in parallel (the
// result is the same for any thread count): what an export writes and its statistics count, worked out
// once. Empty when no type has variants (every instance is its type's look).
std::vector<uint32_t> instanceLooks(const DetailLooks& looks, const CandidateSet& candidates, float tile_size_m,
                                    const InstanceStore& store, int threads);

}  // namespace ug
