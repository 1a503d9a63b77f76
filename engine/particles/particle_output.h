// A particle system's strands as the outputs draw them (the glTF export of `undergrowth grow`, the
// renderer of `undergrowth render --particles`, the editor): one static mesh "strands/<name>" — the tubes or
// blades of strand_mesh.h with the system's material — whose extras hold the polylines, so a pipeline can rebuild
// curves, up to kMaxExtrasStrandPoints points (past that, "strands_omitted" says how many there were).
#pragma once

#include <string>
#include <vector>

#include "io/mesh_instances.h"
#include "particles/particle_json.h"
#include "particles/strand_growth.h"

namespace ug {

constexpr size_t kMaxExtrasStrandPoints = 200'000;  // ~6 MB of JSON text

// Grows the strands (a pure function of the system: the same for any thread count) and meshes them.
// Fails with the reason when the growth or the meshing is refused, or when no strand grew.
bool growParticleSystem(const ParticleSystemFile& system, int threads, Strands* strands, MeshInstances* out,
                        std::string* error);
// The meshing half of growParticleSystem, for strands grown otherwise (the editor's StrandRegrower).
bool meshParticleStrands(const ParticleSystemFile& system, const Strands& strands, MeshInstances* out,
                         std::string* error);

// The surfaces the system's mesh generators seed on, placed as they are: one static mesh
// "strands/<name>/surface_<generator>" each (drawn with the model's own colour), so the stone or statue
// the strands grow out of is in the picture and the export; then the models of its mesh attractors, one
// "strands/<name>/attractor_<attractor>" each (the statue the strands reach for).
std::vector<MeshInstances> generatorSurfaces(const ParticleSystemFile& system);

// What every output draws and exports of a system (grow, render --particles, a project's systems):
// growParticleSystem's tubes, then generatorSurfaces, appended to *out.
bool appendParticleSystemMeshes(const ParticleSystemFile& system, int threads, Strands* strands,
                                std::vector<MeshInstances>* out, std::string* error);

}  // namespace ug
