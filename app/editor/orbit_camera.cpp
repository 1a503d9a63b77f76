#include "editor/orbit_camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace ug::editor {

namespace {
constexpr float kPitchLimitRad = 1.5533431f;  // 89 degrees: the view matrix degenerates at the pole
constexpr float kOrbitRadPerPx = 0.005f;
}  // namespace

glm::vec3 OrbitCamera::eye() const {
    const float c = std::cos(pitch_rad);
    return target + distance_m * glm::vec3(c * std::cos(yaw_rad), c * std::sin(yaw_rad), std::sin(pitch_rad));
}

glm::mat4 OrbitCamera::view() const { return glm::lookAt(eye(), target, glm::vec3(0.0f, 0.0f, 1.0f)); }

float OrbitCamera::nearPlane() const { return std::max(distance_m * 0.01f, 0.005f); }
float OrbitCamera::farPlane() const { return distance_m * 100.0f + 100.0f; }

glm::mat4 OrbitCamera::projection() const { return glm::perspective(fov_y_rad, aspect, nearPlane(), farPlane()); }

void frameBounds(const Bounds& extent, OrbitCamera* camera) {
    const glm::vec3 lo = extent.lo, hi = extent.hi;
    camera->target = 0.5f * (lo + hi);
    camera->pitch_rad = glm::radians(35.0f);
    camera->yaw_rad = glm::radians(-105.0f);
    // The nearest distance at which the extent's eight corners all project inside 90 % of the view
    // (bisection: "fits" is monotonic in the distance for a box around the target). A bounding sphere
    // would leave a flat terrain at half the width of the screen.
    const float radius = std::max(0.5f * glm::length(hi - lo), 0.05f);
    auto fits = [&](float distance) {
        OrbitCamera c = *camera;
        c.distance_m = distance;
        const glm::mat4 m = c.viewProjection();
        for (int k = 0; k < 8; ++k) {
            const glm::vec3 p((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
            const glm::vec4 q = m * glm::vec4(p, 1.0f);
            if (q.w <= 0.0f || std::abs(q.x / q.w) > 0.9f || std::abs(q.y / q.w) > 0.9f) return false;
        }
        return true;
    };
    float near_d = 0.05f * radius, far_d = 20.0f * radius;
    for (int i = 0; i < 40; ++i) {
        const float mid = 0.5f * (near_d + far_d);
        (fits(mid) ? far_d : near_d) = mid;
    }
    camera->distance_m = far_d;
}

void orbit(OrbitCamera* camera, float dx_px, float dy_px) {
    camera->yaw_rad -= dx_px * kOrbitRadPerPx;
    camera->pitch_rad = std::clamp(camera->pitch_rad + dy_px * kOrbitRadPerPx, -kPitchLimitRad, kPitchLimitRad);
}

void pan(OrbitCamera* camera, float dx_px, float dy_px, float viewport_height_px) {
    // Metres per pixel at the target's depth.
    const float m_per_px = 2.0f * camera->distance_m * std::tan(0.5f * camera->fov_y_rad) / std::max(viewport_height_px, 1.0f);
    const glm::mat4 v = camera->view();
    const glm::vec3 right(v[0][0], v[1][0], v[2][0]);
    const glm::vec3 up(v[0][1], v[1][1], v[2][1]);
    camera->target += (-dx_px * right + dy_px * up) * m_per_px;
}

void zoom(OrbitCamera* camera, float steps) {
    camera->distance_m = std::clamp(camera->distance_m * std::pow(1.2f, -steps), 0.02f, 1.0e5f);
}

void zoomToward(OrbitCamera* camera, float steps, glm::vec3 pivot) {
    const float before = camera->distance_m;
    zoom(camera, steps);
    const float k = camera->distance_m / before;  // 1 when the zoom is at its limit
    camera->target = pivot + (camera->target - pivot) * k;
}

bool keepEyeAboveGround(OrbitCamera* camera, const GroundHeight& ground_z, float margin_m) {
    bool moved = false;
    // Raising the pitch moves the eye's XY, hence the ground under it: a few rounds settle it (terrains
    // are smooth at the scale of a camera step); whatever is left is taken up by the target below.
    for (int round = 0; round < 8; ++round) {
        const glm::vec3 eye = camera->eye();
        const float floor_z = ground_z(glm::vec2(eye)) + margin_m;
        if (!(eye.z < floor_z)) return moved;
        moved = true;
        const float s = (floor_z - camera->target.z) / std::max(camera->distance_m, 1e-6f);
        if (s >= std::sin(kPitchLimitRad)) break;
        // Slightly above the exact pitch, so rounding leaves the eye above the floor, not on it.
        camera->pitch_rad = std::min(kPitchLimitRad, std::asin(std::max(s, -1.0f)) + 1e-4f);
    }
    const glm::vec3 eye = camera->eye();
    const float floor_z = ground_z(glm::vec2(eye)) + margin_m;
    if (eye.z < floor_z) {
        camera->target.z += floor_z - eye.z + 1e-4f;
        moved = true;
    }
    return moved;
}

void setPreset(OrbitCamera* camera, ViewPreset preset) {
    switch (preset) {
        case ViewPreset::Front: camera->yaw_rad = glm::radians(-90.0f); camera->pitch_rad = 0.0f; break;
        case ViewPreset::Side: camera->yaw_rad = 0.0f; camera->pitch_rad = 0.0f; break;
        case ViewPreset::Top: camera->yaw_rad = glm::radians(-90.0f); camera->pitch_rad = kPitchLimitRad; break;
    }
}

}  // namespace ug::editor
