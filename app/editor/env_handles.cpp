#include "editor/env_handles.h"

#include <algorithm>
#include <cmath>

namespace ug::editor {

namespace {

constexpr float kDegPerRad = 57.29577951f;
constexpr float kTurnSnapDeg = 15.0f, kScaleSnap = 0.05f;
constexpr glm::vec3 kHandleColor{0.3f, 0.85f, 1.0f};

glm::vec2 direction(float deg) { return {std::cos(deg / kDegPerRad), std::sin(deg / kDegPerRad)}; }

// Where the ray meets the horizontal plane z = h; false when it runs along the plane or away from it.
bool onPlane(const Ray& ray, float h, glm::vec2* xy) {
    if (std::abs(ray.direction.z) < 1e-6f) return false;
    const float t = (h - ray.origin_m.z) / ray.direction.z;
    if (!(t > 0.0f) || !std::isfinite(t)) return false;
    *xy = glm::vec2(ray.at(t));
    return true;
}

// Degrees in (-180, 180].
float wrapDeg(float deg) {
    deg = std::fmod(deg, 360.0f);
    if (deg <= -180.0f) deg += 360.0f;
    if (deg > 180.0f) deg -= 360.0f;
    return deg;
}

}  // namespace

bool envHandleFrame(const Document& doc, const EnvPath& path, EnvHandleFrame* out) {
    const EnvironmentDesc& env = doc.project().environment;
    size_t first = 0, count = 0;
    if (!envObjectRange(env, path, &first, &count) || count == 0) return false;
    const std::vector<EnvObject>& objects = doc.environment()->objects();
    if (first + count > objects.size()) return false;  // the compiled scene lags the description: no handles
    const EnvTransform world = envWorldTransform(env, path);
    out->origin = world.translation;
    out->yaw_deg = world.yaw_deg;
    // Around every object: the farthest corner of their boxes from the pivot, plus a margin.
    float r2 = 0.0f;
    for (size_t o = first; o < first + count; ++o) {
        const Bounds& b = objects[o].bounds;
        for (float x : {b.lo.x, b.hi.x})
            for (float y : {b.lo.y, b.hi.y}) {
                const glm::vec2 d = glm::vec2(x, y) - glm::vec2(out->origin);
                r2 = std::max(r2, glm::dot(d, d));
            }
    }
    out->radius_m = std::max(0.3f, std::sqrt(r2) + 0.15f);
    // Above the ground (a slope), or at the origin's height (an object standing on a slab or a step).
    out->lift_z = std::max(out->origin.z, groundHeightAt(doc, glm::vec2(out->origin))) + 0.05f;
    return true;
}

glm::vec3 envHandlePoint(const EnvHandleFrame& f, EnvHandle handle) {
    const float deg = handle == EnvHandle::Scale ? f.yaw_deg + 180.0f : f.yaw_deg;
    return glm::vec3(glm::vec2(f.origin) + f.radius_m * direction(deg), f.lift_z);
}

EnvHandle pickEnvHandle(const EnvHandleFrame& f, const glm::mat4& view_proj, float width, float height,
                        glm::vec2 cursor, float max_px) {
    const std::vector<glm::vec3> points{envHandlePoint(f, EnvHandle::Turn), envHandlePoint(f, EnvHandle::Scale)};
    const size_t k = nearestOnScreen(points, view_proj, width, height, cursor, max_px);
    return k == 0 ? EnvHandle::Turn : k == 1 ? EnvHandle::Scale : EnvHandle::None;
}

void addEnvHandleMarkers(const EnvHandleFrame& f, EnvHandle active, MarkerGeometry* out) {
    constexpr int kSegments = 48;
    for (int k = 0; k < kSegments; ++k)
        for (int e = 0; e < 2; ++e) {
            const glm::vec2 p = glm::vec2(f.origin) + f.radius_m * direction(360.0f * float(k + e) / kSegments);
            out->lines.push_back({glm::vec3(p, f.lift_z), kSelectedColor});
        }
    const glm::vec3 pivot(glm::vec2(f.origin), f.lift_z);
    out->points.push_back({pivot, kSelectedColor});
    // Turn: a dot on the ring with a short arc either side (which way it goes). Scale: a square, and a
    // spoke from the pivot (the distance it measures).
    const glm::vec3 turn = envHandlePoint(f, EnvHandle::Turn), scale = envHandlePoint(f, EnvHandle::Scale);
    const glm::vec3 turn_color = active == EnvHandle::Turn ? glm::vec3(1.0f) : kHandleColor;
    const glm::vec3 scale_color = active == EnvHandle::Scale ? glm::vec3(1.0f) : kHandleColor;
    out->points.push_back({turn, turn_color});
    const float arc_deg = std::min(40.0f, 0.35f * kDegPerRad / f.radius_m);
    for (int k = -4; k < 4; ++k)
        for (int e = 0; e < 2; ++e) {
            const float deg = f.yaw_deg + arc_deg * float(k + e) / 4.0f;
            out->lines.push_back({glm::vec3(glm::vec2(f.origin) + (f.radius_m + 0.04f) * direction(deg), f.lift_z),
                                  turn_color});
        }
    const glm::vec2 u = 0.07f * direction(f.yaw_deg), v = 0.07f * direction(f.yaw_deg + 90.0f);
    const glm::vec2 c = glm::vec2(scale);
    const glm::vec2 corners[4] = {c - u - v, c + u - v, c + u + v, c - u + v};
    for (int k = 0; k < 4; ++k) {
        out->lines.push_back({glm::vec3(corners[k], f.lift_z), scale_color});
        out->lines.push_back({glm::vec3(corners[(k + 1) % 4], f.lift_z), scale_color});
    }
    out->lines.push_back({pivot, scale_color * 0.7f});
    out->lines.push_back({scale, scale_color * 0.7f});
}

bool EnvHandleDrag::begin(Document* doc, const EnvPath& path, EnvHandle handle, const Ray& ray) {
    if (active()) end();
    if (handle == EnvHandle::None || !envHandleFrame(*doc, path, &frame_)) return false;
    glm::vec2 at;
    if (!onPlane(ray, frame_.lift_z, &at)) return false;
    grab_ = at - glm::vec2(frame_.origin);
    // Grabbed on the pivot itself there is no angle or distance to follow.
    if (glm::length(grab_) < 1e-3f) return false;
    doc_ = doc;
    path_ = path;
    handle_ = handle;
    start_ = applied_ = envWorldTransform(doc->project().environment, path);
    moves_ = 0;
    doc_->beginStroke(handle == EnvHandle::Turn ? "Turn object" : "Scale object");
    return true;
}

bool EnvHandleDrag::drag(const Ray& ray, bool snap, std::string* error) {
    if (!active()) return true;
    glm::vec2 at;
    if (!onPlane(ray, frame_.lift_z, &at)) return true;
    const glm::vec2 d = at - glm::vec2(frame_.origin);
    if (glm::length(d) < 1e-3f) return true;
    EnvTransform world = start_;
    if (handle_ == EnvHandle::Turn) {
        const float turned = (std::atan2(d.y, d.x) - std::atan2(grab_.y, grab_.x)) * kDegPerRad;
        world.yaw_deg = wrapDeg(start_.yaw_deg + turned);
        if (snap) world.yaw_deg = wrapDeg(kTurnSnapDeg * std::round(world.yaw_deg / kTurnSnapDeg));
        // Below a tenth of a degree the effects would not visibly change.
        if (std::abs(wrapDeg(world.yaw_deg - applied_.yaw_deg)) < 0.1f) return true;
    } else {
        world.scale = start_.scale * glm::length(d) / glm::length(grab_);
        if (snap) world.scale = kScaleSnap * std::round(world.scale / kScaleSnap);
        world.scale = std::clamp(world.scale, kEnvHandleMinScale, kEnvHandleMaxScale);
        if (std::abs(world.scale - applied_.scale) < 1e-3f * applied_.scale) return true;
    }
    EnvironmentDesc env = doc_->project().environment;
    if (!setEnvWorldTransform(&env, path_, world)) return true;  // the tree changed under the drag
    if (!doc_->setEnvironment(env, handle_ == EnvHandle::Turn ? "Turn object" : "Scale object", error)) return false;
    applied_ = world;
    ++moves_;
    return true;
}

void EnvHandleDrag::end() {
    if (!active()) return;
    doc_->endStroke();
    doc_ = nullptr;
    handle_ = EnvHandle::None;
}

}  // namespace ug::editor
