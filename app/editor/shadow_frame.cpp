#include "editor/shadow_frame.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace ug::editor {

float shadowDistance(const OrbitCamera& camera) { return std::max(3.0f * camera.distance_m, 1.0f); }

ShadowFrame fitShadowFrame(const OrbitCamera& camera, const Bounds& extent, const glm::vec3& sun_dir, int map_px,
                           float margin) {
    ShadowFrame out;
    if (map_px <= 0 || !(extent.hi.x >= extent.lo.x && extent.hi.y >= extent.lo.y && extent.hi.z >= extent.lo.z))
        return out;
    const glm::vec3 centre = 0.5f * (extent.lo + extent.hi);
    const glm::vec3 up = std::abs(sun_dir.z) > 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(0.0f, 0.0f, 1.0f);
    // Light space: x, y across the sun's rays, -z along them (glm::lookAt's convention).
    const glm::mat4 light_view = glm::lookAt(centre + sun_dir, centre, up);

    // The seen frustum, from the near plane to the shadow distance.
    const glm::mat4 v = camera.view();
    const glm::vec3 right(v[0][0], v[1][0], v[2][0]), cam_up(v[0][1], v[1][1], v[2][1]);
    const glm::vec3 forward(-v[0][2], -v[1][2], -v[2][2]);
    const glm::vec3 eye = camera.eye();
    const float tan_y = std::tan(0.5f * camera.fov_y_rad), tan_x = tan_y * camera.aspect;
    const float near_m = camera.nearPlane();
    out.distance_m = shadowDistance(camera);
    glm::vec3 f_lo(1e30f), f_hi(-1e30f);
    for (float d : {near_m, out.distance_m})
        for (int k = 0; k < 4; ++k) {
            const float sx = (k & 1) ? 1.0f : -1.0f, sy = (k & 2) ? 1.0f : -1.0f;
            const glm::vec3 p = eye + d * (forward + sx * tan_x * right + sy * tan_y * cam_up);
            const glm::vec3 q = glm::vec3(light_view * glm::vec4(p, 1.0f));
            f_lo = glm::min(f_lo, q);
            f_hi = glm::max(f_hi, q);
        }
    glm::vec3 e_lo(1e30f), e_hi(-1e30f);
    for (int k = 0; k < 8; ++k) {
        const glm::vec3 p((k & 1) ? extent.hi.x : extent.lo.x, (k & 2) ? extent.hi.y : extent.lo.y,
                          (k & 4) ? extent.hi.z : extent.lo.z);
        const glm::vec3 q = glm::vec3(light_view * glm::vec4(p, 1.0f));
        e_lo = glm::min(e_lo, q);
        e_hi = glm::max(e_hi, q);
    }
    // Across the rays: what is seen, and only where the scene is. Along them: the whole extent.
    glm::vec2 lo = glm::max(glm::vec2(f_lo), glm::vec2(e_lo)), hi = glm::min(glm::vec2(f_hi), glm::vec2(e_hi));
    if (!(hi.x > lo.x && hi.y > lo.y)) return out;
    // A square map: the larger side sets the texel; snapping both corners to it keeps texels fixed in
    // the world while the box slides.
    const float side = std::max(hi.x - lo.x, hi.y - lo.y) * 1.02f * (1.0f + 2.0f * std::max(margin, 0.0f));
    out.texel_m = side / float(map_px);
    const glm::vec2 mid = 0.5f * (lo + hi);
    lo = glm::floor((mid - 0.5f * side) / out.texel_m) * out.texel_m;
    hi = lo + glm::vec2(side + out.texel_m);
    const float depth_margin = 0.01f * (e_hi.z - e_lo.z) + 0.01f;
    // lookAt looks down -z: the near plane is at -e_hi.z, the far at -e_lo.z.
    const glm::mat4 proj = glm::ortho(lo.x, hi.x, lo.y, hi.y, -e_hi.z - depth_margin, -e_lo.z + depth_margin);
    out.view_proj = proj * light_view;
    const glm::mat4 to_unit = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
    out.texture = to_unit * out.view_proj;
    out.lo = lo;
    out.hi = hi;
    out.valid = true;
    return out;
}

bool shadowFrameHolds(const ShadowFrame& held, const ShadowFrame& wanted) {
    if (!held.valid || !wanted.valid) return false;
    return held.lo.x <= wanted.lo.x && held.lo.y <= wanted.lo.y && held.hi.x >= wanted.hi.x &&
           held.hi.y >= wanted.hi.y && held.texel_m <= kHeldTexelRatio * wanted.texel_m;
}

}  // namespace ug::editor
