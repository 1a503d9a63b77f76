// Closed, flat-shaded parts the environmental starter models (env/env_models.h) are built from: boxes,
// prisms, surfaces of revolution and tapered tubes.
//
// Why flat shading: snow is extracted from up-facing faces and icicles hang from drip edges, and both
// find those by the angle between neighbouring faces. So every face group (a box side, a lathe's profile
// edge, a tube's side) gets vertices of its own: normals never blend across a sharp edge. Inside a
// group (around a cylinder, along a bent tube) vertices are shared so curved sides stay smooth.
//
// Every part is closed and outward wound once its positions are welded: the corners two face groups
// share are computed by the same expression, so they are bit-identical (no T-junctions inside a part).
// Parts may overlap; the model is their union.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "mesh/triangle_mesh.h"

namespace ug::envparts {

// Collects the parts of one model.
class MeshBuilder {
  public:
    // A planar convex polygon (at least 3 corners, in order) as one face group, wound so that its
    // normal points along `outward`.
    void face(const std::vector<glm::vec3>& polygon, const glm::vec3& outward);

    uint32_t vertex(const glm::vec3& p);
    // A triangle wound so that its normal points along `outward`.
    void tri(uint32_t a, uint32_t b, uint32_t c, const glm::vec3& outward);

    // The mesh with area-weighted normals (per face group, as the vertices are) and `color`.
    TriangleMesh finish(const glm::vec3& color);

  private:
    TriangleMesh mesh_;
};

// An oriented box: centre + sum of a_k * axes[k] for a_k in [-half[k], half[k]]; axes orthonormal
// (either handedness: faces are wound by their outward axis). Each face is a grid of cells[k] cells
// along axis k (for snow on large flat tops).
struct Box {
    glm::vec3 centre{0.0f};
    glm::vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    glm::vec3 half{0.5f};
    glm::ivec3 cells{1, 1, 1};
};
void addBox(MeshBuilder* b, const Box& box);
// An axis-aligned box from lo to hi.
void addBox(MeshBuilder* b, const glm::vec3& lo, const glm::vec3& hi, const glm::ivec3& cells = {1, 1, 1});

// A convex polygon (u, v) in the plane origin + u U + v V, extruded by `depth` along W = cross(U, V)
// (U, V orthonormal); the profile may be either winding.
void addPrism(MeshBuilder* b, const std::vector<glm::vec2>& convex_profile, const glm::vec3& origin,
              const glm::vec3& U, const glm::vec3& V, float depth);

// A closed surface of revolution about the vertical axis through `base`: the simple polygon `profile`
// of (r, z) points, counter-clockwise in the (r, z) plane, r >= 0 (edges on the axis, r = 0 at both
// ends, are skipped: the surface closes there). Each profile edge is one face group.
void addLathe(MeshBuilder* b, const glm::vec3& base, const std::vector<glm::vec2>& profile, int segments);

// A closed tube along a polyline (at least 2 points, no zero-length segments) with per-point radii
// (> 0) and flat end caps: smooth sides, hard cap edges.
void addTube(MeshBuilder* b, const std::vector<glm::vec3>& line, const std::vector<float>& radii, int sides);
// A straight cylinder from `from` to `to`.
void addCylinder(MeshBuilder* b, const glm::vec3& from, const glm::vec3& to, float radius, int sides);

}  // namespace ug::envparts
