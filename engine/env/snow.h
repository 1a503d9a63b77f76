// The snow cover effect of Grosbellet et al. 2016, §5.1: a mesh laid over an object's up-facing, open
// surfaces, its vertices displaced along the snow direction v by (α·s·g(d) − θ)⁺, where g ramps the
// thickness up from 0 at the patch border over the distance d0 (so the snow meets the object without a
// crack), α is the environment's openness (occlusion × shelter), s the fallen snow and θ the temperature.
//
// Everything but the terrain is computed in ONE OBJECT'S SPACE: objects sharing an environment share one
// mesh (§6.2). The caller's EnvQuery maps object-space points to the world and evaluates the environment
// there; every builder calls it in batches (never once per vertex), and is a pure function of its inputs
// (same inputs, bit-identical mesh; no threads, no unordered iteration).
//
// Three families:
//   - geometry-controlled snow (buildGeometrySnow): extracted from an arbitrary base mesh and refined to a
//     target edge length by uniform subdivision of each face;
//   - procedural snow (buildBoxSnow, buildCylinderSnow, buildSphereSnow): the paper's "black box" effects
//     for shapes common in architecture, generated directly at the target edge length;
//   - terrain snow (buildTerrainSnow): the height field displaced, in world space.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "env/env_sample.h"
#include "field/bounds.h"
#include "field/height_field.h"
#include "mesh/triangle_mesh.h"

namespace ug {

// Any builder refuses, before allocating, an output it estimates larger than this many triangles
// (about 1.8 GiB of mesh and per-vertex data).
constexpr size_t kMaxSnowTriangles = 50'000'000;

struct SnowSegment {
    glm::vec3 a{0.0f}, b{0.0f};
    float gap_m = 0.0f;  // the width of the joint beyond it (object space): the snow reaches half way across
    bool operator==(const SnowSegment&) const = default;
};

struct SnowSettings {
    glm::vec3 up{0, 0, 1};          // object space: the displacement direction v (minus the snowfall
                                    // direction); unit length (within 1e-3; used normalised)
    float max_face_angle_deg = 60;  // faces whose normal is within this angle of `up` take snow; in [0, 90]
    float d0_m = 0.05f;             // g(d)'s border slope distance, > 0
    float target_edge_m = 0.05f;    // refinement target: snow edges no longer than this, > 0 (see
                                    // buildGeometrySnow for the one exception)
    float min_open = 0.5f;          // snow only where shelter >= this, in [0, 1]: a base face is tested at
                                    // its centroid (geometry snow), a vertex of procedural or terrain snow
                                    // at itself (a vertex below it gets no snow)
    // Geometry and box snow: border edges of the base (object space, endpoints exactly as in the mesh or
    // snowBoxSides, either order) across which another object's snow goes on (findSnowJoints, env/snow_joints.h): like a joint
    // within the mesh they are no border for g(d), so snow keeps its depth over the seam between two road
    // segments or paving pieces, and its points on them move half way across the joint. An entry that is
    // no border edge of the extracted faces is ignored.
    std::vector<SnowSegment> bridged_borders;
};

// Checks every field of `s` (finite, in range, `up` unit). Returns false with a reason otherwise.
bool validateSnowSettings(const SnowSettings& s, std::string* error);

// g(d) = (1 − (1 − d/d0)²)⁴ for d < d0, 1 otherwise (d >= 0; d0 > 0). g(0) = 0, g(d0) = 1.
float snowEdgeProfile(float d_m, float d0_m);

// Metres of snow one degree above freezing melts (θ is in degrees: the same channel decides where icicles
// freeze, θ < 0, and where snow melts).
constexpr float kSnowMeltPerDegreeM = 0.02f;

// The paper's displacement (α·s·g(d) − θ)⁺ with θ as melt: (α·s·g(d) − kSnowMeltPerDegreeM·max(θ, 0))⁺,
// α being e.openness() (occlusion × shelter); frost adds no snow. Metres along `up`. A NaN input gives
// NaN (the builders report it instead of hiding it in the clamp). The builders pin border vertices
// (d = 0) to 0, so the snow never lifts off its base; geometry snow bridges a narrow joint between two
// patches of one mesh (snow_geometry.cpp markJoints), which is no border.
float snowDisplacement(const EnvSample& e, float d_m, float d0_m);

struct SnowCover {
    TriangleMesh mesh;           // object space (world space for terrain snow), normals recomputed after
                                 // displacement, base_color snow white (0.9, 0.92, 0.95); empty when no
                                 // snow lies anywhere
    size_t base_faces_used = 0;  // faces of the base that took snow (geometry snow; 1 for the procedural
                                 // shapes and the terrain when any snow lies there, else 0)
    size_t patch_count = 0;      // connected snow patches extracted (geometry snow), else 1 or 0
    // Per vertex of `mesh` (same order and size as mesh.positions):
    std::vector<glm::vec3> surface_positions;  // the point on the base surface before displacement (half
                                               // way across a joint for the points on its edges)
    std::vector<float> displacement_m;         // metres moved along `up` (0 on the border)
    std::vector<float> border_distance_m;      // d(p) used by g: 0 on the border; +inf where the point is
                                               // farther than d0 from any border (or has none: terrain)
    size_t triangles_before_drop = 0;  // refined triangles, before dropping the bare ones (statistics)
};

// Geometry-controlled snow. Extracts the faces of `base` whose normal (from the winding) is within
// max_face_angle of `up` and whose centroid has shelter >= min_open, groups them into patches (connected
// through shared edges, after welding exactly coincident base vertices), and refines each face by uniform
// subdivision: a face wants n0 = ceil(longest edge / target) segments per side, an edge is split into
// the larger n0 of the faces sharing it (identically for both, so their vertices coincide and are welded
// by construction), and a face into n² sub-triangles, n the largest count of its edges; where one of its
// edges has fewer segments, the grid nodes on that edge snap to the nearest of the edge's points (the
// degenerate triangles are dropped). Where neighbouring faces want the same n0 (regular meshes: quads
// split in two, uniform grids) every snow edge is <= target; in the transition strips between faces
// that want different counts the bound is 1.5 × target. The total is at most 4 Σ n0².
// The patch border is made of base vertices and points on base edges, with d = 0, so displaced by 0
// (g(0) = 0): no crack with the base. d(p) is the Euclidean distance from a vertex to the nearest border
// edge of its own patch (computed exactly below d0; beyond, only "at least d0" matters). Each vertex
// moves by snowDisplacement(...) along `up`; triangles whose three vertices have zero displacement are
// dropped (bare). The environment is queried twice: once at the candidate faces' centroids, once at
// every snow vertex.
// Returns false with a reason for: an invalid base mesh, invalid settings, an output estimated over
// kMaxSnowTriangles (both the area estimate area / (target² · √3/4) · 2 and the exact subdivision count
// are checked before allocating), or a non-finite displacement from the environment. *out is untouched
// on failure.
bool buildGeometrySnow(const TriangleMesh& base, const SnowSettings& s, const EnvQuery& env, SnowCover* out,
                       std::string* error);

// Joints. Snow bridges a gap of at most kSnowJointGapM between two border edges at one height (within
// kSnowJointHeightM vertically, whatever the wind) that face each other: a paving slab's 8 mm joints within
// a model, the seam between two road segments. Placed objects may also overlap by up to kSnowJointOverlapM
// (positions rounded in a scene file).
constexpr float kSnowJointGapM = 0.02f;
constexpr float kSnowJointHeightM = 0.005f;
constexpr float kSnowJointOverlapM = 0.002f;

// A border edge of a base mesh's up-facing faces: its ends, the unit direction across it toward its face
// (square to `up`) and that face's centroid (where the builder tests shelter).
struct SnowBorderSide {
    glm::vec3 a{0.0f}, b{0.0f}, inward{0.0f}, face_centroid{0.0f};
};

// The border edges of the faces buildGeometrySnow extracts from `base` with `s`, before shelter (the
// extraction's geometric part: faces within max_face_angle of up, vertices welded), in edge order, leaving
// out those whose ends differ in height (Z) by more than 2 kSnowJointHeightM (they never meet another). Empty
// for an invalid mesh or settings.
std::vector<SnowBorderSide> snowBorderSides(const TriangleMesh& base, const SnowSettings& s);

// The width of the joint from p to q: how far q's ends lie beyond p's edge, on average (0 where they
// overlap). Snow on both sides reaches half way across it, so the two covers meet over the joint.
float snowJointGap(const SnowBorderSide& p, const SnowBorderSide& q);

// Whether p and q face each other across a joint: parallel (within 5 degrees), inward directions opposed,
// q's ends beyond p's edge line by -overlap_m to kSnowJointGapM and within kSnowJointHeightM of its height
// (Z), alongside each other over at least half the shorter edge; and the same from q's side.
bool snowSidesMeet(const SnowBorderSide& p, const SnowBorderSide& q, float overlap_m);

// Procedural snow (§5.1 "black box" effects), generated directly at the target edge length. The shapes are
// given in object space with their top towards +Z; the snow lies on the top when `up` is within
// max_face_angle of +Z (otherwise the cover is empty and the call succeeds) and is displaced along `up`.
// The border is the shape's rim (d = 0 there, so displaced by 0); d is the exact distance to the rim.
//   box:      the top face z = center.z + half_extents.z of the axis-aligned box, a grid of right
//             triangles (cell diagonals <= target); d = distance to the rectangle's sides.
//   cylinder: the top disc of the upright cylinder (base disc centred at base_center, axis +Z), a disc of
//             concentric rings (ring k has 6k vertices); d = radius − distance to the axis.
//   sphere:   the cap of the sphere whose normals are within max_face_angle of `up` (a sphere has no
//             preferred top, so the cap follows `up`), rings of constant polar angle; d = the geodesic
//             distance to the cap's rim. max_face_angle 0 gives an empty cover.
// Returns false with a reason for non-finite or non-positive sizes, invalid settings, or an output over
// kMaxSnowTriangles (counted before allocating).
bool buildBoxSnow(glm::vec3 center, glm::vec3 half_extents, const SnowSettings& s, const EnvQuery& env,
                  SnowCover* out, std::string* error);
// The box top's four sides (-y, +x, +y, -x; face_centroid the top's centre) for the joint search; a side
// of them in s.bridged_borders is no rim for buildBoxSnow (d ignores it, the grid reaches half way across
// its joint). Empty when the top takes no snow or the input is invalid.
std::vector<SnowBorderSide> snowBoxSides(glm::vec3 center, glm::vec3 half_extents, const SnowSettings& s);
bool buildCylinderSnow(glm::vec3 base_center, float radius, float height, const SnowSettings& s,
                       const EnvQuery& env, SnowCover* out, std::string* error);
bool buildSphereSnow(glm::vec3 center, float radius, const SnowSettings& s, const EnvQuery& env,
                     SnowCover* out, std::string* error);

// The terrain's snow: the height field over the XY rectangle of `region` (clipped to the field's
// rectangle), sampled on a regular grid of spacing <= cell_m (the rectangle's sides land exactly on grid
// lines), each sample (x, y, h(x, y)) displaced along s.up by snowDisplacement with d = +inf (g = 1: the
// terrain has no border inside the region), in WORLD space (the caller's EnvQuery is the identity map
// there). max_face_angle and target_edge_m are not used (the grid is the refinement; validated all the
// same). Bare triangles are dropped as for geometry snow. Returns false with a reason for an empty height
// field, a non-finite or empty region, a region that does not overlap the field, cell_m not finite and
// > 0, or more than kMaxSnowTriangles (estimated before allocating).
bool buildTerrainSnow(const HeightField& hf, const Bounds& region, float cell_m, const SnowSettings& s,
                      const EnvQuery& env, SnowCover* out, std::string* error);

}  // namespace ug
