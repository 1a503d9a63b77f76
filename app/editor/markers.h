// Overlay geometry, GL-free: user primitives as their skeletons (docs/architecture.md "Rendering": density
// primitives drawn as their skeletons) and the brush outline, as plain line and point lists the renderer
// uploads and draws over the scene.
//   point    a dot at the centre and a circle of radius R in the horizontal plane (the support's outline)
//   segment  the segment, dots at its ends
//   disc     the disc's rim in its own plane and a dot at the centre
//   box      the box's 12 edges
// and around each a translucent hull of its support (addPrimitiveHulls): a sphere of radius R for a point, a
// capsule for a segment, a rounded puck for a disc (the points within R of it), the box for a box.
// The selected primitive is drawn in kSelectedColor; the others in their detail type's colour, lightened.
// Optional overlays near the view target (addTileOverlay, addAnchorOverlay, addSphereOverlay): outlines of
// non-empty tiles, the Ghost Tile candidates' anchor points in them, and the instances' collision spheres;
// each capped so a wide view stays cheap on llvmpipe.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "editor/particle_tools.h"
#include "editor/render_data.h"
#include "scene/document.h"

namespace ug::editor {

struct MarkerVertex {
    glm::vec3 position;
    glm::vec3 color;  // display RGB
};
static_assert(sizeof(MarkerVertex) == 24);

struct MarkerGeometry {
    std::vector<MarkerVertex> hull;   // triangles, drawn translucent (depth-tested, no depth write)
    std::vector<MarkerVertex> lines;  // pairs
    std::vector<MarkerVertex> points;
    std::vector<MarkerVertex> dots;   // small points (anchors)
    void clear() {
        hull.clear();
        lines.clear();
        points.clear();
        dots.clear();
    }
    void append(const MarkerGeometry& other) {
        hull.insert(hull.end(), other.hull.begin(), other.hull.end());
        lines.insert(lines.end(), other.lines.begin(), other.lines.end());
        points.insert(points.end(), other.points.begin(), other.points.end());
        dots.insert(dots.end(), other.dots.begin(), other.dots.end());
    }
};

constexpr glm::vec3 kSelectedColor{1.0f, 0.75f, 0.1f};
constexpr glm::vec3 kBrushColor{0.95f, 0.95f, 0.95f};

// Appends every user primitive's skeleton (terrain kinds have none and are skipped).
void addPrimitiveMarkers(const Document& doc, const std::vector<DetailLodMesh>& meshes, uint64_t selected,
                         MarkerGeometry* out);
// Appends every user primitive's hull (triangles).
void addPrimitiveHulls(const Document& doc, const std::vector<DetailLodMesh>& meshes, uint64_t selected,
                       MarkerGeometry* out);

// A particle system's skeletons (the Particles window's system, while it is open): each attractor a dot
// (a segment's line, a sphere's three great circles) and its reach as three great circles, green when its
// charge at step 0 attracts and red when it repels; generators in
// blue (a rectangle's outline, a sphere's circles, a box's or a mesh's bounding edges around its centre);
// cutters in orange (a plane as a 1 m square around its centre, a sphere's circles, a box's edges); every
// handle's dot (particle_tools.h), the selected one in kSelectedColor.
constexpr glm::vec3 kAttractColor{0.35f, 0.9f, 0.35f};
constexpr glm::vec3 kRepelColor{0.95f, 0.35f, 0.3f};
constexpr glm::vec3 kGeneratorColor{0.4f, 0.65f, 1.0f};
constexpr glm::vec3 kCutterColor{1.0f, 0.6f, 0.2f};
void addParticleMarkers(const ParticleSystemFile& system, ParticleHandle selected, MarkerGeometry* out);

// Overlay caps: beyond them the tiles nearest the target win.
constexpr size_t kOverlayTileCap = 400;         // tile outlines (12 edges each)
constexpr size_t kOverlayAnchorTileCap = 64;    // tiles whose candidates' anchors are drawn
constexpr size_t kOverlaySphereInstanceCap = 300;  // instances whose sphere sets are drawn
constexpr size_t kOverlaySphereCap = 1500;         // spheres (one circle of 32 lines each)

// The resident tiles within `radius_m` of `target` (tile centres), nearest first, at most `cap`.
void nearestTiles(const ResidentTiles& tiles, glm::vec3 target, float radius_m, size_t cap,
                  std::vector<uint32_t>* out);
// Outlines (the cell's 12 edges) of the non-empty tiles near `target`.
void addTileOverlay(const ResidentTiles& tiles, glm::vec3 target, float radius_m, MarkerGeometry* out);
// Every Ghost Tile candidate's anchor (its position in the tile, moved to the tile) of the tiles near the
// target, in its type's colour; the selected instances' anchors brighter than the unselected candidates'.
void addAnchorOverlay(const ResidentTiles& tiles, const CandidateSet& candidates,
                      const std::vector<DetailLodMesh>& meshes, glm::vec3 target, float radius_m, MarkerGeometry* out);
// The collision spheres of the instances near the target, each as its horizontal great circle.
void addSphereOverlay(const ResidentTiles& tiles, const CandidateSet& candidates,
                      const std::vector<DetailModel>& models, glm::vec3 target, float radius_m, MarkerGeometry* out);

// A circle of radius r around `center`, the point the brush works on: draped over the terrain when that
// point is on the ground (`on_ground`), else (a pile's surface, above the ground) flat at its height: a
// ring draped over the ground under a pile's flank lies nearer the camera than the cursor's point and is
// drawn well below the cursor on screen.
void addBrushMarker(const Document& doc, glm::vec3 center, float radius_m, bool on_ground, MarkerGeometry* out);

}  // namespace ug::editor
