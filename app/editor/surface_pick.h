// What a click in the view points at, for putting a new thing there (the Particles window's "click to
// place": issue 14's "place a generator on a surface"), GL-free: the nearest of the ground and the
// environmental objects' base geometry along the ray, with that surface's normal.
#pragma once

#include <cstdint>

#include "editor/tools.h"

namespace ug::editor {

struct ScenePick {
    SurfaceHit hit;        // normal: the face's, turned towards the ray's origin
    int64_t object = -1;   // the environmental object hit; -1: the ground
};

// The ground (pickGround) unless an object's base mesh is nearer along the ray; no hit when neither is met.
ScenePick pickSceneSurface(const Document& doc, const Ray& ray);

}  // namespace ug::editor
