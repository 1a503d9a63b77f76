// Snow across the seams between objects. Every object's snow is built alone, in its own space, and falls to
// nothing at its border (g(d), snow.h): where two road segments or two paving pieces abut, that drew a
// groove across the road every few metres, as if each piece were a pillow. Here the scene is searched for
// border edges of two objects' up-facing faces that face each other across a joint (snowSidesMeet: within
// kSnowJointGapM, in one plane), both faces open to the sky as the builder tests them; the snow of each
// keeps its depth up to such an edge (SnowSettings::bridged_borders).
//
// Box snow (Montmartre's cobbles) takes part with the four sides of its top, tested for shelter at the top's
// centre (the box's builder drops snow vertex by vertex where shelter is too low).
//
// A pure function of the scene (all of it, also for a region's job: like the effect classes), so the
// joints of an object are part of its effect class's identity (env_effects.cpp): two pieces of pavement
// share one snow mesh only when the same sides of both are bridged, and an update recomputes an object
// whose joints changed because a neighbour moved.
#pragma once

#include <cstdint>
#include <vector>

#include "env/env_scene.h"
#include "env/snow.h"

namespace ug {

// The snow settings an object's geometry snow is built with: the scene's snowfall turned into the object's
// space, its type's angle, d0 and target edge in object units. bridged_borders is left empty.
SnowSettings objectSnowSettings(const EnvScene& scene, const EnvObject& o);

// The box an object type's box snow covers: its mesh's bounding box.
struct SnowBox {
    glm::vec3 center{0.0f}, half_extents{0.0f};
};
SnowBox snowBoxOf(const EnvObjectType& type);

// Per object: its border edges (object space, in the order of snowBorderSides(its type's mesh,
// objectSnowSettings(o)), or of snowBoxSides for box snow) across which another object's snow goes on:
// what its builder takes as SnowSettings::bridged_borders. Empty for objects without geometry or box snow
// (cylinders and spheres have no straight sides to meet).
std::vector<std::vector<SnowSegment>> findSnowJoints(const EnvScene& scene, int threads);

}  // namespace ug
