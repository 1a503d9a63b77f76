// What instances rest on besides each other: the terrain where the scene has one, else an optional ground
// plane. Shared by the settling pass (settling.h) and the measurements of engine/analysis, so that
// "rests on the ground" means the same thing to both.
#pragma once

#include <cmath>
#include <limits>

#include <glm/glm.hpp>

#include "field/height_field.h"

namespace ug {

struct RestSupport {
    const HeightField* terrain = nullptr;  // the ground where the scene has a terrain (not owned)
    // Otherwise the plane z = ground_z; -infinity: no plane (instances rest only on each other).
    float ground_z = 0.0f;
    float heightAt(float x, float y) const { return terrain ? terrain->sample(x, y) : ground_z; }
};

// How far the sphere (c, r) can fall straight down before it touches the support (negative: it already
// reaches into it). The underside is sampled at the centre and on two rings, since a sloped terrain is
// touched off-centre; the estimate is never below the true clearance by more than the terrain's
// curvature over the ring spacing (a few tenths of a millimetre on our terrains).
inline float supportClearance(const RestSupport& support, glm::vec3 c, float r) {
    if (!support.terrain) return c.z - r - support.ground_z;
    float clearance = c.z - r - support.heightAt(c.x, c.y);
    // Two rings of 8 directions, the outer turned by half a step: (cos, sin) of 2 pi k / 8 and of
    // 2 pi (k + 0.5) / 8, at 0.5 r and 0.9 r (lifts sqrt(1 - 0.25) r and sqrt(1 - 0.81) r).
    static constexpr float kDir[2][8][2] = {
        {{1.0f, 0.0f}, {0.70710678f, 0.70710678f}, {0.0f, 1.0f}, {-0.70710678f, 0.70710678f},
         {-1.0f, 0.0f}, {-0.70710678f, -0.70710678f}, {0.0f, -1.0f}, {0.70710678f, -0.70710678f}},
        {{0.92387953f, 0.38268343f}, {0.38268343f, 0.92387953f}, {-0.38268343f, 0.92387953f},
         {-0.92387953f, 0.38268343f}, {-0.92387953f, -0.38268343f}, {-0.38268343f, -0.92387953f},
         {0.38268343f, -0.92387953f}, {0.92387953f, -0.38268343f}}};
    static constexpr float kRel[2] = {0.5f, 0.9f};
    static constexpr float kLift[2] = {0.8660254f, 0.43588989f};
    for (int ring = 0; ring < 2; ++ring) {
        const float d = kRel[ring] * r, lift = kLift[ring] * r;
        for (int k = 0; k < 8; ++k)
            clearance = std::min(clearance, c.z - lift - support.heightAt(c.x + d * kDir[ring][k][0],
                                                                          c.y + d * kDir[ring][k][1]));
    }
    return clearance;
}

}  // namespace ug
