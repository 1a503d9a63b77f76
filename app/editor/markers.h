// Overlay geometry, GL-free: the user primitives drawn as their skeletons (DESIGN.md "Rendering": density
// primitives drawn as their skeletons) and the brush outline, as plain line and point lists the renderer
// uploads and draws over the scene.
//   point    a dot at the centre and a circle of radius R in the horizontal plane (the support's outline)
//   segment  the segment, dots at its ends
//   disc     the disc's rim in its own plane and a dot at the centre
//   box      the box's 12 edges
// The selected primitive is drawn in kSelectedColor; the others in their detail type's colour, lightened.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "editor/render_data.h"
#include "scene/document.h"

namespace ug::editor {

struct MarkerVertex {
    glm::vec3 position;
    glm::vec3 color;  // display RGB
};
static_assert(sizeof(MarkerVertex) == 24);

struct MarkerGeometry {
    std::vector<MarkerVertex> lines;  // pairs
    std::vector<MarkerVertex> points;
    void clear() {
        lines.clear();
        points.clear();
    }
};

constexpr glm::vec3 kSelectedColor{1.0f, 0.75f, 0.1f};
constexpr glm::vec3 kBrushColor{0.95f, 0.95f, 0.95f};

// Appends every user primitive's skeleton (terrain kinds have none and are skipped).
void addPrimitiveMarkers(const Document& doc, const std::vector<DetailLodMesh>& meshes, uint64_t selected,
                         MarkerGeometry* out);
// A circle of radius r on the surface around `center` (draped over the terrain when there is one).
void addBrushMarker(const Document& doc, glm::vec3 center, float radius_m, MarkerGeometry* out);

}  // namespace ug::editor
