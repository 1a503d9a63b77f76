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
};

// The shadow distance for a camera: a few times its distance to the target, so close-ups get sharp
// shadows and wide views still shadow what fills the screen.
float shadowDistance(const OrbitCamera& camera);

// `camera.aspect` must be the viewport's. `sun_dir` points toward the sun (unit). The light-space box is
// snapped to whole texels of a `map_px` map, so moving the camera slides the map by whole texels (no
// shimmering edges while orbiting slowly).
ShadowFrame fitShadowFrame(const OrbitCamera& camera, const Bounds& extent, const glm::vec3& sun_dir, int map_px);

}  // namespace ug::editor
