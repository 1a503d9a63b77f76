// The environment's geometry as the two outputs take it (io/mesh_instances.h: the glTF export and the
// editor's renderer read the same list):
//   "env/<type>"              the type's base mesh at every object of that type (in the region)
//   "snow/<type>/<class>"     one effect class's snow cover (§6.2: computed once) at each of its members
//   "icicles/<shape>"         one icicle shape of the library at every icicle that uses it
//   "snow/terrain/<ix>_<iy>"  one chunk of the terrain's snow (world space, no instances)
// Materials: the types' own (resolved against their mesh colour), snow and ice.
#pragma once

#include <cstdint>
#include <vector>

#include "env/env_effects.h"
#include "io/mesh_instances.h"

namespace ug {

const SurfaceMaterial& snowMaterial();
const SurfaceMaterial& iceMaterial();

// `hidden` (optional, one entry per object): objects whose entry is non-zero are left out with their snow
// and icicles (the editor's hidden nodes); a mesh left with no instance is left out.
std::vector<MeshInstances> envMeshInstances(const EnvScene& scene, const EnvEffects& effects,
                                            const std::vector<uint8_t>* hidden = nullptr);

}  // namespace ug
