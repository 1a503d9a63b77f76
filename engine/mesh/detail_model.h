// A detail model: what the Ghost Tile distributes (Ghost Tile §4.1, §4.3).
//   render mesh      - what is drawn and exported;
//   sphere set       - the collision proxy: a union of spheres, transformed exactly by rotation,
//                      translation and uniform scale, so candidate-vs-candidate tests stay cheap;
//   anchor points    - where the density field is sampled to cull and accept a candidate (§5.1).
// All in model space: metres, Z up, origin at the model's pivot (the generated assets put it at the
// centre of the bounding box).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "mesh/triangle_mesh.h"

namespace ug {

struct Sphere {
    glm::vec3 center{0.0f};
    float radius = 0.0f;  // metres, > 0
};

// Limits of the sphere fit, checked before anything is allocated (validateSphereFitSettings). The fit
// costs O(triangles log triangles) for its ray-cast BVH plus about O(surface_samples x log) for the
// medial balls and the set cover, and O(surface_samples) memory: the sample limit keeps one model's fit
// to seconds and a few hundred MB whatever the settings (65,535 samples took 6.6 s on a four-triangle
// model on a loaded 2-core machine, and over the fuzz watchdog's 10 s under ASan; 20,000 take about 1 s;
// the default is 3,000).
constexpr uint32_t kMinSurfaceSamples = 16;
constexpr uint32_t kMaxSurfaceSamples = 20000;
constexpr uint32_t kMaxFitSpheres = 4096;

struct SphereFitSettings {
    uint32_t max_spheres = 96;          // hard upper bound on the fitted set, in [1, kMaxFitSpheres]
    float tolerance_m = 0.0f;           // coverage tolerance; 0 = tolerance_rel * bounding radius
    float tolerance_rel = 0.04f;        // used when tolerance_m == 0
    // Samples the coverage is fitted and checked against, in [kMinSurfaceSamples, kMaxSurfaceSamples].
    // Mesh vertices join them (every k-th, about as many as the samples), and each repair round draws
    // twice as many fresh ones.
    uint32_t surface_samples = 3000;
    uint64_t seed = 1;

    // How to run, not what to compute: the result is bit-identical for any value of these.
    int threads = 0;                            // workers (0 = all hardware threads)
    const std::atomic<bool>* cancel = nullptr;  // set to true to stop early: the fit fails with "cancelled"
    // Called from the calling thread with the fraction done, rising, ending with exactly 1 on success.
    std::function<void(float fraction)> progress;
};

// Fitted sphere set quality. Guarantee: every one of the fit's surface samples lies within
// `tolerance_m` of the union of spheres (distance to the nearest sphere surface, 0 inside).
struct SphereFitReport {
    float tolerance_m = 0.0f;            // the tolerance that was asked for (absolute)
    float max_sample_distance_m = 0.0f;  // worst sample's distance outside the union (<= tolerance_m)
    uint32_t sphere_count = 0;
    bool radii_grown = false;            // the count bound was hit and radii were grown to reach coverage
    // Measured on a second, independent sample set (same count, another seed) after the fit: an honest
    // estimate of the coverage between the fit's samples. The fit aims below tolerance_m (it covers its
    // samples to 0.70 * tolerance_m and repairs check samples beyond 0.80 * tolerance_m), so this is
    // normally <= tolerance_m too, but it is a measurement, not a guarantee.
    float max_check_distance_m = 0.0f;
    uint32_t check_sample_count = 0;
};

enum class AnchorMode : uint8_t {
    Authored,       // DetailModelSource::authored_anchors
    Center,         // one anchor at the model origin
    SphereCenters,  // up to `anchor_count` centres of the collision spheres, spread by farthest-point sampling
    Surface,        // `anchor_count` points sampled on the mesh surface, plus the origin
};

// Where a detail model comes from: a mesh file plus how to derive its collision spheres and anchors.
struct DetailModelSource {
    std::string name;                    // e.g. "rock"
    std::string mesh_path;               // .glb/.gltf (tinygltf) or .obj/.ply/.off/.stl (mesh_readers.h)
    float scale = 1.0f;                  // applied to the file's coordinates to get metres, > 0
    bool y_up = true;                    // glTF files are Y up (spec); set false for Z-up OBJ etc.
    std::vector<Sphere> authored_spheres;  // non-empty: used as-is instead of fitting
    SphereFitSettings fit;
    AnchorMode anchor_mode = AnchorMode::SphereCenters;
    std::vector<glm::vec3> authored_anchors;  // model space, used when anchor_mode == Authored
    uint32_t anchor_count = 8;                // Surface: samples; SphereCenters: at most this many centres
};

struct DetailModel {
    std::string name;
    TriangleMesh mesh;
    std::vector<Sphere> spheres;     // the collision proxy, model space
    std::vector<glm::vec3> anchors;  // model space, at least one
    Sphere bounds;                   // encloses every sphere (not only the mesh)
    SphereFitReport fit_report;      // zeroed for authored sphere sets
};

// Loads the mesh, converts to metres / Z up, fits (or takes) the sphere set and the anchors.
// Errors name the file and the reason: missing file, unreadable or unsupported format, no triangles,
// non-finite coordinates, bad settings (scale <= 0 or NaN, max_spheres out of range, ...).
bool loadDetailModel(const DetailModelSource& source, DetailModel* out, std::string* error);

// Builds a model from an in-memory mesh (no file), with the same fitting and checks. A TriangleMesh is
// already Z up by contract, so `source.y_up` is ignored here; `source.scale` is applied;
// `source.mesh_path` only names the mesh in error messages (with `source.name`).
bool makeDetailModel(const DetailModelSource& source, TriangleMesh mesh, DetailModel* out,
                     std::string* error);

// Checks the fit settings against their ranges and limits, without looking at a mesh. False with a
// message naming the field, e.g. "fit.surface_samples = 1000000 exceeds the limit of 100000".
bool validateSphereFitSettings(const SphereFitSettings& settings, std::string* error);

// Fits a bounded union of spheres that covers the mesh surface within the tolerance (see report).
// The settings are validated first (validateSphereFitSettings), before any work or allocation.
// Deterministic: the same mesh and settings give the same spheres for any thread count.
bool fitSphereSet(const TriangleMesh& mesh, const SphereFitSettings& settings, std::vector<Sphere>* out,
                  SphereFitReport* report, std::string* error);

// Distance from p to the union of spheres: 0 inside, else the gap to the nearest sphere surface.
float distanceToSphereUnion(const std::vector<Sphere>& spheres, const glm::vec3& p);

// Points on the surface, uniformly by area, deterministic in seed; optional per-sample normals.
// O(triangles + count log triangles).
void sampleSurface(const TriangleMesh& mesh, uint32_t count, uint64_t seed, std::vector<glm::vec3>* points,
                   std::vector<glm::vec3>* normals);

}  // namespace ug
