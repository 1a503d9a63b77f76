// Where the sun's shadow map looks (GL-free, so it is unit-tested): one orthographic view along the sun
// direction that covers the part of the scene the camera sees up to the shadow distance, and in depth the
// whole extent, so a caster between the sun and the view (a rock behind the camera, a hill) still throws
// its shadow in. One map rather than cascades: on llvmpipe a second depth pass costs as much as the
// details themselves, and the shadow distance follows the camera, so the texels stay a fixed fraction of
// what is on screen.
#pragma once

#include <glm/glm.hpp>

#include "editor/orbit_camera.h"
#include "field/bounds.h"

namespace ug::editor {

struct ShadowFrame {
    bool valid = false;          // false: the seen part of the frustum misses the extent (nothing to shadow)
    glm::mat4 view_proj{1.0f};   // world -> the shadow map's clip space ([-1, 1]^3)
    glm::mat4 texture{1.0f};     // world -> shadow texture coordinates and depth ([0, 1]^3)
    float texel_m = 0.0f;        // the width of one shadow texel in metres (for the biases)
    float distance_m = 0.0f;     // along the view, how far the shadow map reaches
    glm::vec2 lo{0.0f}, hi{0.0f};  // the rectangle it covers across the sun's rays (light space)
};

// The shadow distance for a camera: a few times its distance to the target, so close-ups get sharp
// shadows and wide views still shadow what fills the screen.
float shadowDistance(const OrbitCamera& camera);

// `camera.aspect` must be the viewport's. `sun_dir` points toward the sun (unit). The light-space box is
// snapped to whole texels of a `map_px` map, so moving the camera slides the map by whole texels (no
// shimmering edges while orbiting slowly).
// `margin` widens the square by that share of its side on every side (texels as much coarser): a frame
// fit with a margin keeps covering the view while the camera orbits or pans a little (shadowFrameHolds).
ShadowFrame fitShadowFrame(const OrbitCamera& camera, const Bounds& extent, const glm::vec3& sun_dir, int map_px,
                           float margin = 0.0f);

// The margin the renderer fits with while the camera moves: a slow orbit drag (a degree or two a frame)
// then redraws the sun's map every few frames instead of every frame, for shadows 1.3 times coarser
// until the camera stops (a still view gets its tight frame back).
constexpr float kMovingShadowMargin = 0.15f;
// Whether `held`, a frame fit for an earlier view of the same extent and sun, still serves a view whose
// own frame is `wanted`: it covers all of it, with texels at most kHeldTexelRatio times as wide (zooming
// in on a held frame would blur the shadows).
constexpr float kHeldTexelRatio = 1.5f;
bool shadowFrameHolds(const ShadowFrame& held, const ShadowFrame& wanted);

}  // namespace ug::editor
