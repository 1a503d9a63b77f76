// Procedural starter environmental objects: architecture-scale base meshes (street furniture, ground
// pieces, a bare tree, a fountain and its water, a facade) for the environmental-objects effects (snow cover from
// up-facing faces, icicles from drip edges; Grosbellet et al. 2016), so a fresh install has something to
// cover. The detail starter set is mesh/procedural_models.h; these follow its conventions.
//
// Every model is deterministic in its seed (core/hash.h, no generator state; only the tree's branching
// uses it, the other designs are fixed), in metres, Z up, with normals and a base_color. Its origin is
// the footprint centre at ground level: z = 0 is the ground it stands on and nothing is below it; a
// model with a front faces +Y. Models are unions of closed, outward-wound parts (boxes, prisms,
// cylinders with 24 to 48 sides, surfaces of revolution, tapered tubes) that may overlap, and are
// flat-shaded: each face group has vertices of its own, so sharp edges stay sharp for snow extraction
// and drip-edge detection (smooth only around a cylinder's or tube's side). No degenerate triangles;
// between 100 and 30,000 triangles each.
//
// The set (bounding boxes are x × y × z, metres):
//   bench          1.6 × 0.61 × 0.89; four seat slats with their top at z = 0.45, three backrest slats on
//                  tilted back legs, two leg frames at x = ±0.62.
//   lamppost       pole of radius 0.06 m to z = 4 on a turned base, an arm along +Y to y = 0.72 and a
//                  lamp head hanging from it: glass housing under a low conical roof with a rim (drip
//                  edge at z = 3.74); 0.56 × 1.18 × 4.05.
//   trash_can      standing cylinder of radius 0.3 m, 0.9 m tall, with a lid rim of radius 0.33 m from
//                  z = 0.83 (its underside is a drip edge) and a domed lid.
//   bus_shelter    3.2 × 1.6 roof slab 0.1 m thick from z = 2.4 to 2.5, two posts and a thin glass back
//                  wall at y = -0.55, and the bench under the roof (seat front at y = 0.17).
//   fence_segment  2 m along x: two posts (1.18 m with caps), two rails, 14 pickets with pointed tops
//                  (1.08 m) in front of the rails.
//   pavement_slab  2 × 2: 4 × 4 paving slabs 0.12 m thick with 8 mm joints, and a kerb 0.15 m wide and
//                  0.15 m high along the +Y edge.
//   road_segment   4 × 4 asphalt slab 0.1 m thick (top at z = 0.1), top face a 32 × 32 grid.
//   tree           bare deciduous tree, scaled to exactly 5 m tall: a root flare, a tapered trunk (radius
//                  about 0.25 m at the base) to about 3 m, and three further levels of tapered branches
//                  (a leader and 2 to 3 side branches each); the crown about 2.8 × 2.3 m.
//   fountain       round basin of 2 m diameter (ring wall 0.5 m high, a rim of radius 1.05 m with drip
//                  edges inside and out, floor at z = 0.15), a central column with a bowl and a spout.
//   facade         4 m wide × 6 m tall wall, 0.4 m deep (y from -0.2 to 0.2, front at +Y): 2 × 2 window
//                  openings 0.9 × 1.4 m recessed 0.2 m (centred at x = ±1; bottoms at z = 1.0 and 3.9),
//                  each with a frame (mullion at its centre, transom), open shutters beside it and a sill
//                  protruding 0.07 m from the wall face (z from bottom - 0.06 to the bottom); a cornice,
//                  and a balcony on the upper floor (slab 3.4 × 0.7 m, top at z = 3.0,
//                  railing to z = 3.95).
//   steps          four steps 1.5 m wide, 0.3 m treads and 0.16 m risers, climbing towards -Y (the
//                  lowest step at the front).
//   fountain_water the fountain's water: a disc of radius 0.86 m from the ground to z = 0.38 (4 cm under
//                  the basin wall's lip), placed at the fountain's origin.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mesh/triangle_mesh.h"

namespace ug {

// The set, in a fixed order: bench, lamppost, trash_can, bus_shelter, fence_segment, pavement_slab,
// road_segment, tree, fountain, facade, steps, fountain_water.
const std::vector<std::string>& envStarterNames();

// The generator for `name` (one of envStarterNames()); false (out untouched) for an unknown name.
bool makeEnvStarterModel(const std::string& name, uint64_t seed, TriangleMesh* out);

// The seed the committed models in assets/env_models/ were generated with.
constexpr uint64_t kEnvStarterSeed = 2016;

// Writes <dir>/<name>.glb for every env starter model (seed kEnvStarterSeed), creating `dir` if needed;
// glTF as writeStarterAssets writes it (io/gltf_mesh_io.h: Y up, one mesh and node each). False with
// "<path>: <reason>" on the first failure.
bool writeEnvStarterModels(const std::string& dir, std::string* error);

}  // namespace ug
