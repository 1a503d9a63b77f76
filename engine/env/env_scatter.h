// Environmental effects that scatter (Grosbellet et al. 2016 §5.3-5.4; docs/architecture.md "Environmental
// objects"): fallen leaves, petals, trash and grass are detail types of the Ghost Tile whose density comes
// from the environment,
//     f(p) = max(0, (α(p)·c(p)·h − d(p)) / s),
// c the effect's channel (leaves, trash or grass), α the occlusion (times the shelter for leaves and
// trash), d the height of p above the surface it would rest on, h the layer's thickness where α·c = 1 and
// s the ramp over which the acceptance grows from 0 at the layer's top to 1 (the paper selects every
// candidate where α·l > d: h = 1 m and a small s). The surface is the highest up-facing one below p:
// the terrain's or an environmental object's, and only when that one receives the channel
// (EnvTypeDesc::receives: a bench seat takes leaves, a tree's crown takes nothing). So leaves lie in a
// layer whose thickness follows α·c (piles where c is large), grass in a thin one thinned where α is low
// (trails); they go through the same instantiator as the rocks and twigs, so they never intersect them
// and update exactly and incrementally.
//
//   auto leaves = std::make_shared<ScatterField>(env, ScatterSettings{.channel = EnvChannel::Leaves});
//   uint32_t e = addExternal(&field, leaves);           // field/density_field.h
//   ... a primitive makeExternal(e) in the type's density ...
//
// Variants (Fig. 12, 14) are chosen per instance from the environment at its origin, after the
// selection, which they never change: scatterVariantAt.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "env/env_scene.h"
#include "field/external_field.h"

namespace ug {

struct ScatterSettings {
    EnvChannel channel = EnvChannel::Leaves;  // Leaves, Grass or Trash
    float thickness_m = 0.05f;                // h, > 0
    float ramp_m = 0.01f;                     // s, > 0
    bool sheltered = true;                    // the shelter multiplies α (leaves and trash; not grass)
};

class ScatterField final : public ExternalField {
public:
    // env must not be null; settings valid (validateScatterSettings).
    ScatterField(std::shared_ptr<const EnvScene> env, ScatterSettings settings);

    float value(glm::vec3 p) const override;
    // The batch's supports one by one, its channels together (EnvScene::channelsBatch): the same bits.
    void valueBatch(const glm::vec3* points, size_t n, float* out) const override;
    Bounds bounds() const override { return bounds_; }
    Bounds positiveBoundsIn(const Bounds& box) const override;

    const ScatterSettings& settings() const { return settings_; }
    const std::shared_ptr<const EnvScene>& environment() const { return env_; }

private:
    bool receives(int64_t object) const;
    // What value() computes once the channels are known: (α·c·h − d)/s, with the shelter's rays cast only
    // where the open value is positive.
    float fromChannels(glm::vec3 p, float d, const EnvSample& e) const;

    std::shared_ptr<const EnvScene> env_;
    ScatterSettings settings_;
    uint32_t bit_ = 0;
    Bounds bounds_;
};

// "<pointer>: <reason>" for a channel that does not scatter or a thickness or ramp that is not in (0, 100].
bool validateScatterSettings(const ScatterSettings& s, const std::string& pointer, std::string* error);

// A variant's condition: the channel's value at the instance's origin in [min, max).
struct ScatterCondition {
    EnvChannel channel = EnvChannel::Humidity;
    float min = -std::numeric_limits<float>::infinity();
    float max = std::numeric_limits<float>::infinity();
};

// 1 + the index of the first condition the environment at p meets, or 0 (the type's own model).
uint32_t scatterVariantAt(const EnvScene& env, std::span<const ScatterCondition> conditions, glm::vec3 p);

// Where an environment edit can change a scattered density: each changed object's or field's box
// (envDirtyRegion) extended down to the bottom of the world (what rests below it, and its shelter) and
// widened by the shelter rays' reach (their 3 x 3 footprint and, with slanting snow, their drift).
std::vector<Bounds> scatterDirtyRegion(const EnvScene& before, const EnvScene& after);

}  // namespace ug
