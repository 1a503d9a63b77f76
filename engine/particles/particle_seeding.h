// Seeding particles on a generator's surface by jittering a stratified area parameterisation (Beneš &
// Espinosa 2000 §3): the surface is cut into `count` strata of equal area, one particle per stratum at a
// hashed place inside it, so particles cover the whole surface without clumps or a regular grid.
//
// Strata: the surface's area-preserving parameterisation (s, t) in [0, 1]² (the sphere's is Archimedes'
// cylinder, z = 1 − 2t) is cut into rows; row r gets n_r cells with n_r as even as an integer split allows,
// and its height is n_r / count, so every cell has area 1 / count of the surface. A box splits count
// over its faces in proportion to their areas (floors of the running sum), then each face as a rectangle:
// equal area per face, equal within 1 / count of the box's otherwise.
//
// The jitter keeps 1/1024 of a cell's width from its borders, so a point mapped back through the inverse
// parameterisation in floating point always lands in its own stratum (locateStratum); the density is
// uniform over the rest of the cell.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "particles/particle_scene.h"

namespace ug {

// One particle's start: where, the surface normal there, and its frame (the heading is q · +z).
struct ParticleSeeds {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::quat> frames;
};

// Appends generator `generator_index`'s particles (gen.count of them, in stratum order) to *out; random
// numbers are hashed from (seed, generator index, stratum), so a generator's seeds do not depend on the
// others. gen must be valid (validateParticleScene); `terrain` is needed (non-null) by an on_terrain one.
void seedGenerator(const ParticleGenerator& gen, uint32_t generator_index, uint64_t seed, ParticleSeeds* out,
                   const HeightField* terrain = nullptr);

// The stratum (in [0, gen.count)) the surface point p lies in, found from p through the inverse
// parameterisation alone; used by the tests to check that seeding puts one particle in each.
uint32_t locateStratum(const ParticleGenerator& gen, glm::vec3 p);

// The frame whose +z is the unit direction d with the least rotation from `from`'s +z (no twist about
// the heading, so a strand's frame is transported along it).
glm::quat turnFrameTo(const glm::quat& from, glm::vec3 d);

// A unit direction uniformly distributed over the cap of half-angle cone_rad around +z, from two
// uniform numbers in [0, 1).
glm::vec3 coneDirection(float cone_rad, float u, float v);
// The same from the cone's cosine (the walk's inner loop computes it once).
glm::vec3 coneDirectionCos(float cos_cone, float u, float v);

// cos(2πt) and sin(2πt) for t in [0, 1), within 2 units in the last place of float: the angle is
// reduced to an eighth of a turn around the nearest quarter and the Taylor series taken to the 10th
// (cosine) and 9th (sine) power, below float's rounding there. No library call, so loops of it vectorise,
// and the same bits wherever no multiply-add is fused (strand_growth.cpp is built with -ffp-contract=off).
inline void cosSinOfTurns(float t, float* c, float* s) {
    const int quarter = int(4.0f * t + 0.5f);  // 0..4, t >= 0
    const float x = (t - 0.25f * float(quarter)) * 6.28318530717958648f;  // in [-π/4, π/4]
    const float x2 = x * x;
    const float sx = x * (1.0f + x2 * (-1.0f / 6.0f + x2 * (1.0f / 120.0f + x2 * (-1.0f / 5040.0f + x2 * (1.0f / 362880.0f)))));
    const float cx = 1.0f + x2 * (-0.5f + x2 * (1.0f / 24.0f + x2 * (-1.0f / 720.0f + x2 * (1.0f / 40320.0f + x2 * (-1.0f / 3628800.0f)))));
    // A quarter turn maps (cos, sin) to (-sin, cos).
    const int q = quarter & 3;
    *c = q == 0 ? cx : q == 1 ? -sx : q == 2 ? -cx : sx;
    *s = q == 0 ? sx : q == 1 ? cx : q == 2 ? -sx : -cx;
}

// coneDirectionCos for n pairs (u[i], v[i]) at once, into x, y, z: the random walk's trials. The turn
// about the axis takes its cosine and sine from cosSinOfTurns, not the C library's, so the loop runs
// several trials at a time (with -fno-math-errno, the square root is an instruction); the directions
// differ from coneDirectionCos's in the last bit or two.
inline void coneDirectionsCos(float cos_cone, size_t n, const float* u, const float* v, float* x, float* y, float* z) {
    for (size_t i = 0; i < n; ++i) {
        const float cos_t = 1.0f - u[i] * (1.0f - cos_cone);
        const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
        float c, s;
        cosSinOfTurns(v[i], &c, &s);
        x[i] = sin_t * c;
        y[i] = sin_t * s;
        z[i] = cos_t;
    }
}

}  // namespace ug
