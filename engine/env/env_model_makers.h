// The generators behind env/env_models.h, one per model, split by family (env_models_street.cpp,
// env_models_ground.cpp, env_models_buildings.cpp, env_models_tree.cpp). Internal to engine/env.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

#include "env/env_mesh_parts.h"
#include "mesh/triangle_mesh.h"

namespace ug::envmodels {

TriangleMesh makeBench(uint64_t seed);
TriangleMesh makeLamppost(uint64_t seed);
TriangleMesh makeTrashCan(uint64_t seed);
TriangleMesh makeBusShelter(uint64_t seed);
TriangleMesh makeFenceSegment(uint64_t seed);
TriangleMesh makePavementSlab(uint64_t seed);
TriangleMesh makeRoadSegment(uint64_t seed);
TriangleMesh makeTree(uint64_t seed);
TriangleMesh makeFountain(uint64_t seed);
TriangleMesh makeFacade(uint64_t seed);
TriangleMesh makeSteps(uint64_t seed);
TriangleMesh makeFountainWater(uint64_t seed);

// The bench's parts, its footprint centred on `at` (x along the seat, facing +Y); the bus shelter
// reuses it.
void addBench(envparts::MeshBuilder* b, const glm::vec3& at);

}  // namespace ug::envmodels
