// The view a scene opens on, GL-free: the editor's first frame (viewer.cpp) and `undergrowth render`
// without --camera show the same picture.
//
//   const Bounds frame = framingBounds(extent, has_terrain ? &terrain : nullptr, &resident_tiles);
//   OrbitCamera camera = defaultView(frame, float(width) / float(height));
#pragma once

#include "editor/orbit_camera.h"
#include "editor/render_data.h"
#include "field/bounds.h"
#include "mesh/triangle_mesh.h"

namespace ug::editor {

// What "frame all" frames: the cells that hold instances once they are in (a scene's extent is often a
// conservative bound much larger than what fills), else the terrain's surface when there is one (terrain
// non-null and not empty), else the extent. `instances` may be null (not instantiated yet).
Bounds framingBounds(const Bounds& extent, const TriangleMesh* terrain, const ResidentTiles* instances);

// The view a scene opens on: framingBounds, narrowed (in X and Y) to the patch with the most instances, of
// a size at which the type with the most instances fills at least kOpeningDetailFraction of the view's
// height: a 40 m meadow opens on a patch where tufts read as tufts, not on 40 m of speckle, a field of
// haystacks on a haystack; a pile smaller than that opens whole. `meshes` are the types' LOD meshes (their bounding diameters), as the renderer has them.
constexpr float kOpeningDetailFraction = 1.0f / 30.0f;
Bounds openingBounds(const Bounds& extent, const TriangleMesh* terrain, const ResidentTiles* instances,
                     const std::vector<DetailLodMesh>& meshes);

// The default camera on `framing` for a viewport of `aspect` (width / height): frameBounds (orbit_camera.h),
// 35 degrees of elevation from the -Y side, the nearest distance at which all of it fits in 90 % of the view.
OrbitCamera defaultView(const Bounds& framing, float aspect);

}  // namespace ug::editor
