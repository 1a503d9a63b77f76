// Rays against the scene's surfaces, for the editor's brushes (issue 4, "Tools"): the terrain's height
// field and a density field's isosurface. GL-free and camera-free: the caller builds the ray (from the
// mouse through the camera, or straight down from above a world XY in scripted runs).
//
//   Ray ray{.origin_m = eye, .direction = glm::normalize(p - eye)};
//   float t = 0.0f;
//   if (rayHeightField(terrain, ray, 1000.0f, &t)) ground = ray.at(t);
//   if (rayDensityIsosurface(field, ray, 0.5f, 1000.0f, 0.02f, &t)) ...   // the pile's own surface
#pragma once

#include <glm/glm.hpp>

#include "field/bounds.h"
#include "field/density_field.h"
#include "field/height_field.h"

namespace ug {

struct Ray {
    glm::vec3 origin_m{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit length
    glm::vec3 at(float t_m) const { return origin_m + t_m * direction; }
};

// The nearest t in [0, max_t_m] where the ray meets the bilinear surface z = h(x, y) going from above to
// below (the clamped border included: the field extends flat outside its rectangle). The surface is
// found to within 1e-4 of a cell (a march of half-cell steps, then bisection), so ray.at(t).z equals
// h(x, y) to float rounding plus that. False when the ray starts below the surface or never reaches it.
bool rayHeightField(const HeightField& terrain, const Ray& ray, float max_t_m, float* t_m);

// The nearest t in [0, max_t_m] where `field` rises through `iso` along the ray (from f < iso to f >= iso),
// marched in steps of step_m (> 0; a feature thinner than a step can be missed) within the field's
// positive bounds, then bisected to 1e-4 * step_m. False when there is no crossing (a ray that starts
// inside, f >= iso, reports the first crossing after it leaves and re-enters).
bool rayDensityIsosurface(const DensityField& field, const Ray& ray, float iso, float max_t_m, float step_m,
                          float* t_m);

// The part [t0, t1] of the ray inside the box; false when it misses (or the box is empty).
bool clipRayToBounds(const Ray& ray, const Bounds& box, float max_t_m, float* t0, float* t1);

}  // namespace ug
