// What a click in the view points at, for putting a new thing there (the Particles window's "click to
// place": issue 14's "place a generator on a surface"), GL-free: the nearest of the ground, the
// environmental objects' base geometry and the detail instances' models along the ray, with that
// surface's normal.
#pragma once

#include <cstdint>
#include <span>

#include "analysis/placed_instances.h"

#include "editor/tools.h"

namespace ug::editor {

struct ScenePick {
    SurfaceHit hit;            // normal: the face's, turned towards the ray's origin
    int64_t object = -1;       // the environmental object hit; -1: none
    int64_t instance = -1;     // the detail instance hit (its index in `instances`); -1: none
    uint32_t detail_type = 0;  // the hit instance's type
};

// The ground (pickGround) unless an object's base mesh or a detail instance's model (`instances`, placed as
// the view shows them: placeInstances with the settled drops; their types index doc.models()) is nearer
// along the ray; no hit when none is met.
ScenePick pickSceneSurface(const Document& doc, const Ray& ray, std::span<const PlacedInstance> instances = {});

}  // namespace ug::editor
