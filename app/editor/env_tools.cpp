#include "editor/env_tools.h"

#include <cctype>
#include <algorithm>
#include <cmath>
#include <limits>

namespace ug::editor {

EnvPath pickEnvNode(const Document& doc, const glm::mat4& view_proj, float width, float height, glm::vec2 cursor,
                    float max_px, bool nested) {
    std::vector<glm::vec3> origins;
    for (const EnvObject& o : doc.environment()->objects()) origins.push_back(o.placement.t);
    const size_t object = nearestOnScreen(origins, view_proj, width, height, cursor, max_px);
    if (object == SIZE_MAX) return {};
    EnvPath path = envPathOfObject(doc.project().environment, object);
    if (!nested && path.size() > 1) path.erase(path.begin() + 1, path.end());
    return path;
}

bool placementPoint(const Document& doc, const Ray& ray, glm::vec3* out) {
    const SurfaceHit ground = pickGround(doc, ray);
    if (!ground.hit) return false;
    *out = ground.point_m;
    const EnvScene& env = *doc.environment();
    if (env.objects().empty()) return true;
    constexpr float kStepM = 0.02f;
    constexpr int kMaxSteps = 20000;
    const float reach = glm::distance(ray.origin_m, ground.point_m);
    const float step = std::max(kStepM, reach / float(kMaxSteps));
    for (float t = 0.0f; t < reach; t += step) {
        const glm::vec3 q = ray.at(t);
        const EnvScene::Support s = env.supportBelow(q);
        if (s.inside || !(s.z > -std::numeric_limits<float>::infinity())) continue;  // in a wall, or over nothing
        if (q.z - s.z <= step) {
            *out = glm::vec3(q.x, q.y, s.z);
            return true;
        }
    }
    return true;
}

EnvironmentDesc withNodeMovedTo(const Document& doc, const EnvPath& path, glm::vec2 xy) {
    EnvironmentDesc env = doc.project().environment;
    if (!envNodeAt(env, path)) return env;
    EnvTransform world = envWorldTransform(env, path);
    const float above = world.translation.z - groundHeightAt(doc, glm::vec2(world.translation));
    world.translation = glm::vec3(xy, groundHeightAt(doc, xy) + above);
    setEnvWorldTransform(&env, path, world);
    return env;
}

bool EnvObjectDrag::begin(Document* doc, const EnvPath& path, const Ray& ray) {
    if (active()) end();
    if (!envNodeAt(doc->project().environment, path)) return false;
    doc_ = doc;
    path_ = path;
    start_m_ = envWorldTransform(doc->project().environment, path).translation;
    grab_m_ = dragGrab(ray, start_m_);
    applied_offset_m_ = glm::vec3(0.0f);
    moves_ = 0;
    doc_->beginStroke("Move object");
    return true;
}

bool EnvObjectDrag::drag(const Ray& ray, std::string* error) {
    if (!active()) return true;
    glm::vec3 offset;
    if (!dragOffset(ray, grab_m_, applied_offset_m_, false, &offset)) return true;
    // Below a centimetre the snow would not visibly change: a still mouse does not recompute it.
    if (glm::length(offset - applied_offset_m_) < 0.01f) return true;
    if (!envNodeAt(doc_->project().environment, path_)) return true;  // the tree changed under the drag
    if (!doc_->setEnvironment(withNodeMovedTo(*doc_, path_, glm::vec2(start_m_ + offset)), "Move object", error))
        return false;
    applied_offset_m_ = offset;
    ++moves_;
    return true;
}

void EnvObjectDrag::end() {
    if (!active()) return;
    doc_->endStroke();
    doc_ = nullptr;
}

namespace {

const char* const kWeatherBrushNames[kWeatherBrushCount] = {"footprints", "warm", "cold", "wet",
                                                            "leaves", "trash", "grass", "erase"};

}  // namespace

const char* weatherBrushName(WeatherBrush brush) { return kWeatherBrushNames[int(brush)]; }

bool weatherBrushFromName(const std::string& name, WeatherBrush* out) {
    for (int k = 0; k < kWeatherBrushCount; ++k)
        if (name == kWeatherBrushNames[k]) {
            *out = WeatherBrush(k);
            return true;
        }
    return false;
}

EnvFieldDesc weatherField(const WeatherSettings& s, glm::vec3 at) {
    // A few degrees melt the paper's street snow (snow.h kSnowMeltPerDegreeM) or bring its icicles.
    constexpr float kWarmthDeg = 8.0f, kWetness = 0.5f, kPile = 1.0f;
    EnvFieldDesc f;
    switch (s.brush) {
        case WeatherBrush::Warm: f.channel = EnvChannel::Temperature, f.value = kWarmthDeg; break;
        case WeatherBrush::Cold: f.channel = EnvChannel::Temperature, f.value = -kWarmthDeg; break;
        case WeatherBrush::Wet: f.channel = EnvChannel::Humidity, f.value = kWetness; break;
        case WeatherBrush::Leaves: f.channel = EnvChannel::Leaves, f.value = kPile; break;
        case WeatherBrush::Trash: f.channel = EnvChannel::Trash, f.value = kPile; break;
        case WeatherBrush::Grass: f.channel = EnvChannel::Grass, f.value = kPile; break;
        case WeatherBrush::Footprints:
        case WeatherBrush::Erase: return footprintField(at);  // not used: they have their own stamps
    }
    f.value *= s.strength;
    f.shape = makePoint(at, s.radius_m, f.value);
    return f;
}

float WeatherStroke::spacing() const {
    return settings_.brush == WeatherBrush::Footprints ? kFootprintStrideM : 0.5f * settings_.radius_m;
}

bool WeatherStroke::begin(Document* doc, const WeatherSettings& settings, glm::vec3 ground, std::string* error) {
    if (active()) end();
    if (!(settings.radius_m > 0.0f) || !(settings.strength > 0.0f) || !std::isfinite(settings.radius_m) ||
        !std::isfinite(settings.strength)) {
        *error = std::string(weatherBrushName(settings.brush)) + " brush: radius and strength must be finite and > 0";
        return false;
    }
    doc_ = doc;
    settings_ = settings;
    stamps_ = erased_ = 0;
    last_m_ = ground;
    std::string name = weatherBrushName(settings.brush);
    name[0] = char(std::toupper(name[0]));
    doc_->beginStroke(settings.brush == WeatherBrush::Footprints ? name : name + " brush");
    return stamp(ground, glm::vec2(1.0f, 0.0f), error);
}

bool WeatherStroke::drag(glm::vec3 ground, std::string* error) {
    if (!active()) return true;
    // Stamps along the straight line from the last one: a fast mouse leaves every stamp in between.
    for (;;) {
        const glm::vec2 d = glm::vec2(ground) - glm::vec2(last_m_);
        const float len = glm::length(d);
        if (len < spacing()) return true;
        const glm::vec2 heading = d / len;
        const glm::vec2 xy = glm::vec2(last_m_) + heading * spacing();
        const glm::vec3 at(xy, groundHeightAt(*doc_, xy));
        if (!stamp(at, heading, error)) return false;
        last_m_ = at;
    }
}

namespace {

// How far (x, y) is from a local field's skeleton seen from above: its segment (a trail) or its centre.
float skeletonDistanceXY(const Primitive& shape, glm::vec2 xy) {
    const glm::vec2 a(shape.center_m);
    if (shape.kind != PrimitiveKind::Segment) return glm::length(xy - a);
    const glm::vec2 ab = glm::vec2(shape.end_m) - a;
    const float len2 = glm::dot(ab, ab);
    const float t = len2 > 0.0f ? std::clamp(glm::dot(xy - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
    return glm::length(xy - (a + t * ab));
}

}  // namespace

bool WeatherStroke::stamp(glm::vec3 at, glm::vec2 heading, std::string* error) {
    EnvironmentDesc env = doc_->project().environment;
    if (settings_.brush == WeatherBrush::Erase) {
        const size_t before = env.global_fields.size();
        std::erase_if(env.global_fields, [&](const EnvFieldDesc& f) {
            return !f.everywhere && skeletonDistanceXY(f.shape, glm::vec2(at)) <= settings_.radius_m;
        });
        ++stamps_;
        if (env.global_fields.size() == before) return true;  // nothing there: no empty step
        erased_ += int(before - env.global_fields.size());
    } else if (settings_.brush == WeatherBrush::Footprints) {
        // Left foot, right foot: half a gait to either side of the walked line.
        const float side = stamps_ % 2 == 0 ? kFootprintHalfGaitM : -kFootprintHalfGaitM;
        const glm::vec2 xy = glm::vec2(at) + glm::vec2(-heading.y, heading.x) * side;
        env.global_fields.push_back(footprintField(glm::vec3(xy, groundHeightAt(*doc_, xy))));
        ++stamps_;
    } else {
        env.global_fields.push_back(weatherField(settings_, at));
        ++stamps_;
    }
    return doc_->setEnvironment(env, "Weather brush", error);  // the stroke names the step
}

void WeatherStroke::end() {
    if (!active()) return;
    doc_->endStroke();
    doc_ = nullptr;
}

}  // namespace ug::editor
