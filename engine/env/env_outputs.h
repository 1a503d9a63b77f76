// The environment's geometry as the two outputs take it (io/mesh_instances.h: the glTF export and the
// editor's renderer read the same list):
//   "env/<type>"              the type's base mesh at every object of that type (in the region)
//   "snow/<type>/<class>"     one effect class's snow cover (§6.2: computed once) at each of its members
//   "icicles/<shape>"         one icicle shape of the library at every icicle that uses it
//   "snow/terrain/<ix>_<iy>"  one chunk of the terrain's snow (world space, no instances)
// Materials: the types' own (resolved against their mesh colour), snow and ice.
#pragma once

#include <vector>

#include "env/env_effects.h"
#include "io/mesh_instances.h"

namespace ug {

const SurfaceMaterial& snowMaterial();
const SurfaceMaterial& iceMaterial();

std::vector<MeshInstances> envMeshInstances(const EnvScene& scene, const EnvEffects& effects);

}  // namespace ug
