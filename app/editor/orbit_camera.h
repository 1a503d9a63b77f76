// The viewport camera: an orbit camera around a target point (Blender-like), Z up, metres. Plain data;
// navigation.h turns mouse and keys into its moves, the renderer only reads its matrices.
#pragma once

#include <functional>

#include <glm/glm.hpp>

#include "field/bounds.h"

namespace ug::editor {

struct OrbitCamera {
    glm::vec3 target{0.0f};
    float distance_m = 10.0f;
    float yaw_rad = -1.5707964f;  // azimuth of the eye around the target (0 = on +X, -pi/2 = on -Y)
    float pitch_rad = 0.6108652f;  // elevation of the eye above the target's horizon (35 degrees)
    float fov_y_rad = 0.7853982f;  // 45 degrees
    float aspect = 16.0f / 9.0f;

    glm::vec3 eye() const;
    glm::mat4 view() const;
    // Near and far planes follow the distance, so a 2 m pile and an 80 m field both keep depth precision.
    float nearPlane() const;
    float farPlane() const;
    glm::mat4 projection() const;
    glm::mat4 viewProjection() const { return projection() * view(); }
};

// Places the camera on the default view of `extent`: looking at its centre from 35 degrees of elevation
// (from the -Y side, a little to the left), at the nearest distance where its eight corners fill 90 % of
// the view.
void frameBounds(const Bounds& extent, OrbitCamera* camera);

// Orbit by screen-space pixel deltas (yaw with dx, pitch with dy; pitch is kept within (-89, 89) degrees).
void orbit(OrbitCamera* camera, float dx_px, float dy_px);
// Moves the target in the view plane so the point under the cursor follows it.
void pan(OrbitCamera* camera, float dx_px, float dy_px, float viewport_height_px);
// Wheel steps: > 0 zooms in (each step 1/1.2 of the distance).
void zoom(OrbitCamera* camera, float steps);

// Wheel steps toward a world point (the ground under the cursor): the eye and the target both scale about
// `pivot` by the zoom factor, so the view direction is kept and `pivot` stays on the same pixel.
void zoomToward(OrbitCamera* camera, float steps, glm::vec3 pivot);

// The height of the ground at a world XY (the terrain, or the ground plane where there is none).
using GroundHeight = std::function<float(glm::vec2 xy_m)>;
constexpr float kEyeGroundMargin_m = 0.05f;  // how far above the ground the eye stays at least
// Keeps the eye at least `margin_m` above the ground under it: first by raising the pitch (the eye swings
// up around the target, the view stays on it), then, if even the steepest pitch is not enough (the target
// itself is under ground), by lifting the target. Returns true when the camera had to move.
bool keepEyeAboveGround(OrbitCamera* camera, const GroundHeight& ground_z, float margin_m = kEyeGroundMargin_m);

enum class ViewPreset { Front, Side, Top };  // Blender's numpad 1 / 3 / 7
void setPreset(OrbitCamera* camera, ViewPreset preset);

}  // namespace ug::editor
