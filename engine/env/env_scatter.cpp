#include "env/env_scatter.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "env/env_effects.h"

namespace ug {

namespace {

float channelValue(const EnvSample& e, EnvChannel c) {
    switch (c) {
        case EnvChannel::Snow: return e.snow;
        case EnvChannel::Icicles: return e.icicles;
        case EnvChannel::Leaves: return e.leaves;
        case EnvChannel::Grass: return e.grass;
        case EnvChannel::Trash: return e.trash;
        case EnvChannel::Occlusion: return e.occlusion;
        case EnvChannel::Humidity: return e.humidity;
        case EnvChannel::Temperature: return e.temperature;
    }
    return 0.0f;
}

// Relative padding of the derived bounds against the few roundings between them and value().
Bounds padded(Bounds b) {
    for (int a = 0; a < 3; ++a) {
        if (std::isfinite(b.lo[a])) b.lo[a] -= std::abs(b.lo[a]) * 1e-5f + 1e-4f;
        if (std::isfinite(b.hi[a])) b.hi[a] += std::abs(b.hi[a]) * 1e-5f + 1e-4f;
    }
    return b;
}

}  // namespace

bool validateScatterSettings(const ScatterSettings& s, const std::string& pointer, std::string* error) {
    if (!(envChannelBit(s.channel) & kScatterChannels)) {
        if (error) *error = pointer + "/channel: expected \"leaves\", \"grass\" or \"trash\"";
        return false;
    }
    if (!std::isfinite(s.thickness_m) || !(s.thickness_m > 0.0f) || s.thickness_m > 100.0f) {
        if (error) *error = pointer + "/thickness_m: must be in (0, 100]";
        return false;
    }
    if (!std::isfinite(s.ramp_m) || !(s.ramp_m > 0.0f) || s.ramp_m > 100.0f) {
        if (error) *error = pointer + "/ramp_m: must be in (0, 100]";
        return false;
    }
    return true;
}

ScatterField::ScatterField(std::shared_ptr<const EnvScene> env, ScatterSettings settings)
    : env_(std::move(env)), settings_(settings), bit_(envChannelBit(settings.channel)) {
    // The support: the channel's fields in XY (c = 0 elsewhere); from the lowest receiving surface to
    // h times the largest c above the highest one in Z.
    Bounds xy;
    float c_max = 0.0f;
    for (const EnvWorldField& f : env_->fields()) {
        if (f.channel != settings_.channel || !(f.value > 0.0f)) continue;
        xy = unite(xy, f.bounds);
        c_max += f.value;
    }
    float z_lo = std::numeric_limits<float>::infinity(), z_hi = -std::numeric_limits<float>::infinity();
    if (env_->terrain() && !env_->terrain()->empty() && (env_->desc().terrain.receives & bit_)) {
        z_lo = env_->terrain()->minHeight();
        z_hi = env_->terrain()->maxHeight();
    }
    for (const EnvObject& o : env_->objects())
        if (env_->types()[o.type].desc.receives & bit_) {
            z_lo = std::min(z_lo, o.bounds.lo.z);
            z_hi = std::max(z_hi, o.bounds.hi.z);
        }
    if (xy.empty() || !(c_max > 0.0f) || !(z_lo <= z_hi)) return;  // 0 everywhere
    bounds_ = padded(Bounds{glm::vec3(xy.lo.x, xy.lo.y, z_lo),
                            glm::vec3(xy.hi.x, xy.hi.y, z_hi + settings_.thickness_m * c_max)});
}

bool ScatterField::receives(int64_t object) const {
    if (object < 0) return (env_->desc().terrain.receives & bit_) != 0;
    return (env_->types()[env_->objects()[size_t(object)].type].desc.receives & bit_) != 0;
}

float ScatterField::value(glm::vec3 p) const {
    if (!contains(bounds_, p)) return 0.0f;
    const EnvScene::Support s = env_->supportBelow(p);
    if (s.inside || !(s.z > -std::numeric_limits<float>::infinity()) || !receives(s.object)) return 0.0f;
    return fromChannels(p, p.z - s.z, env_->channels(p));
}

float ScatterField::fromChannels(glm::vec3 p, float d, const EnvSample& e) const {
    const float c = channelValue(e, settings_.channel);
    // α ≤ 1: where even the open value cannot reach p, the shelter's rays are not cast.
    if (!(e.occlusion * c * settings_.thickness_m - d > 0.0f)) return 0.0f;
    const float alpha = settings_.sheltered ? e.occlusion * env_->shelter(p) : e.occlusion;
    const float v = (alpha * c * settings_.thickness_m - d) / settings_.ramp_m;
    return v > 0.0f ? v : 0.0f;
}

void ScatterField::valueBatch(const glm::vec3* points, size_t n, float* out) const {
    // Supports first (cheap): only the points that rest on a receiving surface within the layer's
    // greatest reach ask for the channels.
    thread_local std::vector<glm::vec3> ask;
    thread_local std::vector<float> ask_d;
    thread_local std::vector<uint32_t> ask_k;
    thread_local std::vector<EnvSample> samples;
    ask.clear();
    ask_d.clear();
    ask_k.clear();
    for (size_t k = 0; k < n; ++k) {
        out[k] = 0.0f;
        const glm::vec3 p = points[k];
        if (!contains(bounds_, p)) continue;
        const EnvScene::Support s = env_->supportBelow(p);
        if (s.inside || !(s.z > -std::numeric_limits<float>::infinity()) || !receives(s.object)) continue;
        ask.push_back(p);
        ask_d.push_back(p.z - s.z);
        ask_k.push_back(uint32_t(k));
    }
    // The channel next, alone: where even α = 1 cannot lift the layer to p (c·h <= d), the occlusion's
    // fields are not summed either. Only c and α are read, each summed in channels()'s order.
    samples.resize(ask.size());
    env_->channelsBatch(ask.data(), ask.size(), samples.data(), bit_);
    size_t kept = 0;
    for (size_t i = 0; i < ask.size(); ++i) {
        const float c = channelValue(samples[i], settings_.channel);
        if (!(c * settings_.thickness_m - ask_d[i] > 0.0f)) continue;
        ask[kept] = ask[i];
        ask_d[kept] = ask_d[i];
        ask_k[kept] = ask_k[i];
        samples[kept] = samples[i];
        ++kept;
    }
    ask.resize(kept);
    thread_local std::vector<EnvSample> occlusion;
    occlusion.resize(kept);
    env_->channelsBatch(ask.data(), kept, occlusion.data(), envChannelBit(EnvChannel::Occlusion));
    for (size_t i = 0; i < kept; ++i) {
        samples[i].occlusion = occlusion[i].occlusion;
        out[ask_k[i]] = fromChannels(ask[i], ask_d[i], samples[i]);
    }
}

Bounds ScatterField::positiveBoundsIn(const Bounds& box) const {
    const Bounds b = intersect(bounds_, box);
    if (b.empty()) return Bounds{};
    const float c_max = env_->channelBound(settings_.channel, b);
    if (!(c_max > 0.0f)) return Bounds{};
    float z_lo = std::numeric_limits<float>::infinity(), z_hi = -std::numeric_limits<float>::infinity();
    if (env_->terrain() && !env_->terrain()->empty() && (env_->desc().terrain.receives & bit_)) {
        const glm::vec2 range = env_->terrain()->heightRange(glm::vec2(b.lo), glm::vec2(b.hi));
        z_lo = range.x;
        z_hi = range.y;
    }
    env_->forObjectsNearXY(b, [&](uint32_t id) {
        const EnvObject& o = env_->objects()[id];
        if (!receives(int64_t(id)) || o.bounds.hi.x < b.lo.x || o.bounds.lo.x > b.hi.x || o.bounds.hi.y < b.lo.y ||
            o.bounds.lo.y > b.hi.y)
            return;
        z_lo = std::min(z_lo, o.bounds.lo.z);
        z_hi = std::max(z_hi, o.bounds.hi.z);
    });
    if (!(z_lo <= z_hi)) return Bounds{};
    const Bounds local = padded(Bounds{glm::vec3(b.lo.x, b.lo.y, z_lo),
                                       glm::vec3(b.hi.x, b.hi.y, z_hi + settings_.thickness_m * c_max)});
    const Bounds out = intersect(b, local);
    return out.empty() ? Bounds{} : out;
}

uint32_t scatterVariantAt(const EnvScene& env, std::span<const ScatterCondition> conditions, glm::vec3 p) {
    if (conditions.empty()) return 0;
    const EnvSample e = env.channels(p);
    for (size_t k = 0; k < conditions.size(); ++k) {
        const float v = channelValue(e, conditions[k].channel);
        if (v >= conditions[k].min && v < conditions[k].max) return uint32_t(k + 1);
    }
    return 0;
}

std::vector<Bounds> scatterDirtyRegion(const EnvScene& before, const EnvScene& after) {
    std::vector<Bounds> boxes = envDirtyRegion(before, after);
    const float drift = std::max(before.shelterDrift(), after.shelterDrift());
    // The lowest point a ray can start from: under the objects, or down in the terrain's lowest valley.
    float bottom = std::min(before.objectBounds().empty() ? 0.0f : before.objectBounds().lo.z,
                            after.objectBounds().empty() ? 0.0f : after.objectBounds().lo.z);
    for (const EnvScene* s : {&before, &after})
        if (s->terrain() && !s->terrain()->empty()) bottom = std::min(bottom, s->terrain()->minHeight());
    for (Bounds& b : boxes) {
        if (b.empty()) continue;
        // Rays reach up from points up to (top - bottom) below the box, drifting that far times the slope.
        const float rise = std::isfinite(b.hi.z) ? std::max(0.0f, b.hi.z - std::min(bottom, b.lo.z)) : 0.0f;
        const float pad = 2.0f * kShelterCellM + drift * rise;
        b.lo = glm::vec3(b.lo.x - pad, b.lo.y - pad, -std::numeric_limits<float>::infinity());
        b.hi = glm::vec3(b.hi.x + pad, b.hi.y + pad, b.hi.z);
    }
    return boxes;
}

}  // namespace ug
