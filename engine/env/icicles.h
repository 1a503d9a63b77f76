// The icicles effect of Grosbellet et al. 2016, §5.2: candidate anchors on an object's drip edges, a
// length h(θ, η) from the environment, and a small library of precomputed icicle shapes (the paper's
// chain of blended spheres, polygonized once) that placed icicles instance.
//
// Everything here is in ONE object's space: the caller evaluates the environment at the anchors
// (env_sample.h) and measures the clearance below each anchor against the whole scene's geometry, so
// objects sharing an environment can share one result (§6.2). Pure functions, no GL, no threads.
//
// Pipeline: findIcicleAnchors(base) -> caller: env + clearance at anchors -> placeIcicles -> instances
// of icicleShapes() (GPU instancing / EXT_mesh_gpu_instancing via icicleTransform), or icicleMesh.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "env/env_sample.h"
#include "mesh/triangle_mesh.h"

namespace ug {

// Refusals made before allocating (absurd spacing over a huge mesh, millions of icicles merged).
constexpr size_t kMaxIcicleAnchors = 2'000'000;
constexpr size_t kMaxIcicleMeshTriangles = 50'000'000;
// Icicles shorter than this are not placed: they would be invisible specks of geometry.
constexpr float kMinIcicleLength_m = 0.005f;
// An icicle is shortened to at most this fraction of the free space below its anchor, so its tip never
// touches the surface underneath (see placeIcicles).
constexpr float kIcicleClearanceUse = 0.95f;

struct IcicleSettings {
    // Object space, unit length: icicles hang along -up, water runs downhill along -up.
    glm::vec3 up{0, 0, 1};
    // Find drip edges on the base mesh (findIcicleAnchors); when false only `anchors` are used.
    bool automatic_anchors = true;
    // Authored anchors (object space), used in addition to the automatic ones, after them, in this order.
    // Their edge_dir is a horizontal unit vector perpendicular to up (arbitrary but fixed).
    std::vector<glm::vec3> anchors;
    // Distance between automatic anchors along a drip edge, metres, >= 1 mm.
    float spacing_m = 0.06f;
    // An edge between two faces is sharp when their normals differ by more than this, degrees in [0, 180).
    float sharp_angle_deg = 40.0f;
    // Cap on the icicle length h, metres, in (0, 10].
    float max_length_m = 0.35f;
    // k_θ: metres of icicle per degree below freezing at neutral humidity (η = 0), >= 0.
    float length_per_degree_m = 0.03f;
    // g_η: how strongly humidity lengthens (η > 0) or shortens (η < 0) icicles, >= 0; 0 ignores η.
    float humidity_gain = 1.0f;
    // Natural unevenness along an eave, in [0, 1): each placed icicle is shortened by a fraction in
    // [0, length_variation) of its length, from a hash of its anchor's position. 0 (the default) keeps
    // every icicle at exactly icicleLength(θ, η); 0.4 looks like a real eave.
    float length_variation = 0.0f;
};

// "" when the settings are usable, else the first problem ("spacing_m must be >= 0.001 m, got 0").
std::string validateIcicleSettings(const IcicleSettings& s);

struct IcicleAnchor {
    glm::vec3 position;  // object space, on the drip edge (the icicle's top)
    glm::vec3 edge_dir;  // unit tangent of the drip edge there (object space)
};

// Drip edges: where water running down the base leaves it. An edge drips when
//  - it is a boundary edge (one face) and a downhill rim of that face: water on the face flows over it
//    (whatever the face's orientation, since single-sided surfaces such as an open roof quad are wound
//    either way); or
//  - it is sharp (the face normals differ by more than sharp_angle_deg), one face is a downhill rim-side
//    face h (water on h flows over the edge) and the other face k is an underside (n_k·up < -0.2, about
//    12° past vertical): water cannot follow the underside and drips (a box's bottom rim, a window sill,
//    a bench seat's front edge, a keel). Concave corners (a ceiling meeting a wall) fail the
//    downhill-rim test, so nothing hangs indoors from them.
// An edge is a downhill rim of face f when f is within 5° of horizontal (water drains off every side),
// or when the edge's outward direction in f's plane is within 60° of f's steepest descent.
// Edges with more than two faces (non-manifold) never drip. Vertices are welded by exact position first,
// so meshes with split (flat-shaded) vertices behave like welded ones; degenerate faces are ignored.
//
// Drip edges are chained into polylines (through vertices joining exactly two drip edges that turn by at
// most 30°), in a canonical order (by welded vertex position), and each chain of length L gets
// n = floor(L / spacing + 0.5) anchors spaced by spacing_m and centred on it (open chains), or n evenly
// spaced ones starting at the chain's first vertex + half a step (closed loops). Authored anchors follow.
// Chains shorter than spacing_m / 2 get none. Deterministic: the same surface gives the same anchors
// whatever its vertex and triangle order, and whether its vertices are split or shared. Empty (with *error set) on invalid settings, indices out of range, non-finite positions, or an
// estimated anchor count above kMaxIcicleAnchors.
std::vector<IcicleAnchor> findIcicleAnchors(const TriangleMesh& base, const IcicleSettings& s,
                                            std::string* error = nullptr);

// The icicle length model:
//   h(θ, η) = min(max_length_m, k_θ · (-θ) · w(η))  for θ < 0,   0 for θ >= 0 (and for NaN),
//   w(η) = 1 + g_η·η for η >= 0 (wet air feeds longer icicles), 1 / (1 - g_η·η) for η < 0 (dry air:
//   shorter, never zero). w is continuous, positive and increasing, so h is non-decreasing as θ falls
//   and as η rises, strictly until the cap. The ice channel i only gates presence (§5.2), it does not
//   scale h. θ is in degrees below (negative) or above freezing.
float icicleLength(float temperature, float humidity, const IcicleSettings& s);

// One precomputed icicle. Local frame: the flat top disc lies in z = 0 (the mesh's max z is exactly 0,
// its top centre the origin), the icicle hangs along -Z and its tip is at z = -length_m exactly.
// Closed, outward wound, with normals, a few hundred triangles.
struct IcicleShape {
    TriangleMesh mesh;
    float length_m;      // the shape's length (top to tip)
    float top_radius_m;  // mean radius of the flat top disc, where the icicle meets the object
    uint32_t seed;       // seed of the horizontal perturbation
};

// The shape library: kIcicleShapeLengths x kIcicleShapeSeeds shapes, length-major (index =
// length_class * kIcicleShapeSeeds + seed), built once on first use (thread-safe function-local static).
// Each is the paper's chain of spheres from the top down, radius and spacing decreasing, each centre
// perturbed horizontally, blended as a Blob-Tree (Wyvill kernel sum) and polygonized by radial root
// finding on horizontal slices (a lathe that follows the blended surface).
constexpr size_t kIcicleShapeLengths = 4;
constexpr size_t kIcicleShapeSeeds = 3;
const std::vector<IcicleShape>& icicleShapes();
// Builds one library shape (length_class < kIcicleShapeLengths, seed < kIcicleShapeSeeds) afresh: what
// icicleShapes() holds at length_class * kIcicleShapeSeeds + seed. About a millisecond.
IcicleShape makeIcicleShape(size_t length_class, uint32_t seed);

// One placed icicle: shape icicleShapes()[shape], its top at `anchor`, turned by yaw_rad about `up`,
// uniformly scaled by `scale` so that its length is length_m (= scale * shape length).
struct IcicleInstance {
    uint32_t shape;
    glm::vec3 anchor;     // object space
    float yaw_rad;        // in [0, 2π)
    float scale;          // > 0
    float length_m;       // the placed length
    glm::vec3 up{0, 0, 1};// the settings' up: the shape's +Z maps onto it
};

// Object-from-shape matrix of an instance: translation to the anchor, local +Z to up, local X to a fixed
// horizontal axis (the projection of object X onto the plane ⟂ up, or of Y when up is nearly X) turned
// by yaw_rad about up, uniform scale.
glm::mat4 icicleTransform(const IcicleInstance& icicle);

// Decides the icicles (§5.2). Anchor j gets one when θ(p_j) < 0 and i(p_j) > 0 (env[j]; NaN never
// passes) and there is room below it. Its natural length is h = icicleLength(θ, η), times
// (1 - length_variation * u), u in [0, 1) hashed from the anchor's position. With free =
// kIcicleClearanceUse * clearance_m[j] (the free distance below the anchor along -up, +inf when open;
// NaN or negative counts as 0): h is kept when free >= h, shortened to free when free >= h / 2 (an
// icicle that grew into a narrow gap), and there is no icicle otherwise; nothing shorter than
// kMinIcicleLength_m is placed. Its shape is the library's length class nearest to h in ratio
// (|log(h / L)|, ties to the shorter class), with the seed within the class and the yaw hashed from the
// anchor's position (so icicles stay put when other anchors are added or removed). Instances follow
// anchor order. Empty with *error set when the three arrays differ in size or the settings are invalid.
std::vector<IcicleInstance> placeIcicles(const std::vector<IcicleAnchor>& anchors, const std::vector<EnvSample>& env,
                                         const std::vector<float>& clearance_m, const IcicleSettings& s,
                                         std::string* error = nullptr);

// The placed icicles merged into one mesh (object space, with normals, icy base_color), for exporters
// without instancing and for tests. Empty with *error set when the result would exceed
// kMaxIcicleMeshTriangles, an instance names a shape outside the library or its scale is not a finite
// positive number.
TriangleMesh icicleMesh(const std::vector<IcicleInstance>& icicles, std::string* error = nullptr);

}  // namespace ug
