// The project's particle systems (Project::particles, format 4): each entry's file read, renamed and
// moved as the entry says, then grown and meshed as `undergrowth grow` does (particles/particle_output.h),
// so that `instantiate`, `run`, `join`, `render` and the editor's view and export all carry the same
// strands. Growth is a pure function of the system: the same meshes for any thread count.
//
// In a region job a system belongs to the one region holding the centre of its strands' bounding box
// (half-open, like instance origins), so that region files side by side hold each system once.
#pragma once

#include <string>
#include <vector>

#include "env/env_scene.h"
#include "field/bounds.h"
#include "instancer/instantiator.h"
#include "instancer/settling.h"
#include "io/mesh_instances.h"
#include "particles/particle_json.h"
#include "scene/project.h"

namespace ug {

// Reads every entry's file (relative to the project's folder). Errors name the project, the entry's JSON
// Pointer and the particle file's own message: "park.json: /particles/1/file: grass.json: /walk/trials:
// 0 is out of range [1, 256]". Two systems with one name are refused (their glTF meshes are named by it).
// `terrain` (may be null) is the ground of the systems' on_terrain generators.
// `environment` (may be null) places the systems among the project's objects (placeAmongObjects).
bool loadSceneParticles(const Project& project, const std::shared_ptr<const HeightField>& terrain,
                        const EnvScene* environment, std::vector<ParticleSystemFile>* out, std::string* error);

// What a system takes from the environmental objects: its "objects" generators' surfaces (every object
// of the type), then, from those within its reach (particleReach), their base geometry as obstacles
// (solids its strands go around) and the surface points of its "objects" attractors, in world
// coordinates, per object in the scene's order. An attractor naming a type the
// project does not have is an error ("attractors[1].object_type: ..."). Surfaces and points equal to the
// ones the scene already holds are kept (same pointer), so a re-placement that changes nothing changes
// nothing.
bool placeAmongObjects(const EnvScene* environment, ParticleScene* scene, std::string* error);

// What a system's "details" generators take from the project's instantiation (GeneratorKind::Details).
struct DetailPlacement {
    const InstancerInput* instancer = nullptr;  // the project's tile, models, compiled types and extent
    const SettleInput* settle = nullptr;        // null or disabled: the candidates' own heights
    std::shared_ptr<const std::vector<DetailModel>> models;  // the Ghost Tile's types' (their meshes)
    int threads = 0;
};

// Whether the system has a "details" generator (placeOnDetails has work to do).
bool growsOnDetails(const ParticleScene& scene);

// Fills every "details" generator's surfaces from the instances of its type whose origin lies in its box,
// instantiated and settled as the whole project would be (instantiateRegion: a pure function, so the box
// alone gives the whole scene's instances there, and the same in a region job), and puts those instances
// as solids into scene->detail_obstacles. A type the project does not have is an error
// ("generators[0].detail_type: the project has no detail type 'moss_rock'"); more than 4,000,000 gathered
// triangles are refused before they are built. Surfaces equal to the ones the scene holds keep their
// pointer, as placeAmongObjects does.
bool placeOnDetails(const DetailPlacement& placement, ParticleScene* scene, std::string* error);

struct SceneStrandStats {
    size_t systems = 0;  // grown and kept (in a region: those it holds)
    uint64_t strands = 0, points = 0, triangles = 0;
    double seconds = 0.0;
};

// Grows and meshes every system (the region's only, when one is given), appending one mesh
// "strands/<name>" each to *meshes. `source` names the project in errors.
bool growSceneParticles(const std::vector<ParticleSystemFile>& systems, const std::string& source, int threads,
                        const Bounds* region, std::vector<MeshInstances>* meshes, SceneStrandStats* stats,
                        std::string* error);

}  // namespace ug
