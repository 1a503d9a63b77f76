// The environmental objects' geometric effects, snow cover and icicles (Grosbellet et al. 2016 §5.1-§5.2,
// §6.2; docs/architecture.md "Environmental objects"), computed for a compiled EnvScene as a pure function
// of it: the same for any thread count and any split into regions, and the same after an incremental
// update as after a full one.
//
//   EnvEffects fx;
//   computeEnvEffects(env, EnvEffectsOptions{.threads = 0}, &fx, &error);
//   // after an edit (env2 compiled from the edited project):
//   EnvEffects fx2;
//   updateEnvEffects(env2, fx, envDirtyRegion(env, env2), {}, &fx2, &error);   // == computeEnvEffects(env2)
//
// Effect instancing (§6.2): every object's environment is sampled at fixed points of its type's bounds
// (kSignaturePoints); objects of one type with the same effect settings and scale whose samples are within
// `sharing_threshold` (mean squared difference) of a class's first object join that class when their snow
// is bridged across the same borders to neighbouring objects (findSnowJoints), in tree order; a class's effects are computed once, from its first object, in object space, and placed at every
// member. The classes are always formed over the whole scene, so a region's job computes the same classes
// (those with a member in the region) as the whole scene's, and the union of the regions is the whole.
//
// Incremental: a class's result is reused when its first object is the same (type, placement, settings),
// its snow is bridged across the same borders (a neighbour that moved away changes them), and the vertical
// column over its bounds meets no dirty box (shelter and icicle clearance look up and down the column,
// fields are queried inside the bounds); a terrain chunk's when its column meets none.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "env/env_scene.h"
#include "env/icicles.h"
#include "env/snow.h"
#include "field/bounds.h"
#include "mesh/triangle_mesh.h"

namespace ug {

constexpr int kSignaturePoints = 18;        // 3 x 3 x 2 points inside the type's bounds
constexpr float kTerrainSnowChunkM = 4.0f;  // terrain snow is made and updated in squares of this size

struct EnvEffectsOptions {
    int threads = 0;                // 0 = all hardware threads
    const Bounds* region = nullptr; // only objects whose origin lies in it, and terrain chunks whose lower
                                    // corner does (null: everything)
};

struct EffectClass {
    uint32_t type = 0;
    uint32_t first = 0;                 // the object it is computed from
    EnvObject source;                   // a copy of that object (what a later update compares against)
    std::vector<SnowSegment> snow_joints;  // its borders another object's snow continues beyond (snow_joints.h):
                                           // every member has the same
    std::vector<uint32_t> members;      // objects placed with it, ascending (in the region when there is one)
    std::shared_ptr<const TriangleMesh> snow;   // object space; null or empty: no snow
    std::vector<IcicleInstance> icicles;        // object space
    bool computed = false;              // false: no member in the region (nothing made)
    bool reused = false;                // true: taken from the previous result (updateEnvEffects)
};

struct TerrainSnowChunk {
    int ix = 0, iy = 0;                         // the chunk's square: [ix, ix + 1) * kTerrainSnowChunkM ...
    std::shared_ptr<const TriangleMesh> mesh;   // world space
    bool reused = false;
};

struct EnvEffectsStats {
    size_t objects = 0;              // in the region (all without one)
    size_t effect_computations = 0;  // classes computed (or reused) for them
    size_t classes_reused = 0;
    size_t terrain_chunks = 0, terrain_chunks_reused = 0;
    uint64_t snow_triangles = 0;        // as placed: every member counts its class's mesh, plus the terrain
    uint64_t snow_triangles_unique = 0; // as computed (and stored once)
    uint64_t icicles = 0;               // as placed
};

struct EnvEffects {
    std::vector<EffectClass> classes;
    std::vector<uint32_t> class_of;      // per object: its class
    std::vector<TerrainSnowChunk> terrain_snow;
    EnvEffectsStats stats;
};

bool computeEnvEffects(const EnvScene& scene, const EnvEffectsOptions& options, EnvEffects* out, std::string* error);

// As computeEnvEffects(scene, options), reusing `previous` (computed with the same options on the scene
// before the edit) wherever the edit's dirty boxes cannot have changed the result.
bool updateEnvEffects(const EnvScene& scene, const EnvEffects& previous, const std::vector<Bounds>& dirty,
                      const EnvEffectsOptions& options, EnvEffects* out, std::string* error);

// Where an edit can change effects: the bounds of every object and field found in only one of the two
// scenes (matched by content: type, placement and settings; channel, value, shape and owner); everything
// when the snowfall (direction or spread) differs.
std::vector<Bounds> envDirtyRegion(const EnvScene& before, const EnvScene& after);

}  // namespace ug
