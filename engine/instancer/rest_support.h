// What instances rest on besides each other: the terrain where the scene has one, else an optional ground
// plane, and the environment's surfaces above it. Shared by the settling pass (settling.h) and the measurements of engine/analysis, so that
// "rests on the ground" means the same thing to both.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/glm.hpp>

#include "field/height_field.h"

namespace ug {

// Surfaces above the ground that instances rest on too: the environmental objects' base geometry (a seat,
// a roof, a step). EnvScene implements it.
class RestSurfaces {
public:
    virtual ~RestSurfaces() = default;
    // The highest surface at (x, y) at or below z; z itself where (x, y, z) lies inside a solid; -infinity
    // where there is none.
    virtual float surfaceBelow(float x, float y, float z) const = 0;
    // An upper bound of surfaceBelow over the XY rectangle [lo, hi], at any z.
    virtual float surfaceTopIn(glm::vec2 lo, glm::vec2 hi) const = 0;
};

struct RestSupport {
    const HeightField* terrain = nullptr;  // the ground where the scene has a terrain (not owned)
    // Otherwise the plane z = ground_z; -infinity: no plane (instances rest only on each other).
    float ground_z = 0.0f;
    const RestSurfaces* surfaces = nullptr;  // more to rest on, above the ground (not owned); may be null
    float heightAt(float x, float y) const { return terrain ? terrain->sample(x, y) : ground_z; }
    // What a point at (x, y, z) would come to rest on falling straight down: the ground (even above z: a
    // point under the terrain is sunk, not falling) or a surface below it.
    float heightBelow(float x, float y, float z) const {
        const float ground = heightAt(x, y);
        return surfaces ? std::max(ground, surfaces->surfaceBelow(x, y, z)) : ground;
    }
};

// How far the sphere (c, r) can fall straight down before it touches the support (negative: it already
// reaches into it). The underside is sampled at the centre and on two rings, since a sloped terrain is
// touched off-centre; the estimate is never below the true clearance by more than the terrain's
// curvature over the ring spacing (a few tenths of a millimetre on our terrains).
// With surfaces, each sample asks for the surface below the sphere's centre: one between the centre and
// the bottom already holds the sphere (negative clearance).
inline float supportClearance(const RestSupport& support, glm::vec3 c, float r) {
    if (!support.terrain && !support.surfaces) return c.z - r - support.ground_z;
    float clearance = c.z - r - support.heightBelow(c.x, c.y, c.z);
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
            clearance = std::min(clearance, c.z - lift - support.heightBelow(c.x + d * kDir[ring][k][0],
                                                                             c.y + d * kDir[ring][k][1], c.z));
    }
    return clearance;
}

}  // namespace ug
