// Procedural starter assets: small natural details for the Ghost Tile (rocks, leaves, twigs, grass,
// mushrooms, pine needles), so a fresh install has something to scatter.
//
// Every starter generator is deterministic in its seed (core/hash.h, no generator state), returns a closed,
// outward-wound TriangleMesh (several closed parts may overlap, e.g. a leaf blade and its stem) in
// metres, Z up, centred on its bounding-box centre, with normals and a base_color, and has between 200
// and 3000 triangles. Sizes are the largest bounding-box extent.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mesh/triangle_mesh.h"

namespace ug {

TriangleMesh makeRock(uint64_t seed);          // ~12 cm, noisy displaced icosphere, grey
TriangleMesh makeFlatStone(uint64_t seed);     // ~15 cm, flattened, grey-brown
TriangleMesh makePebble(uint64_t seed);        // ~4 cm, smooth ellipsoid
TriangleMesh makeOakLeaf(uint64_t seed);       // ~11 cm incl. stem, lobed, curled, two-sided, autumn brown
TriangleMesh makeBirchLeaf(uint64_t seed);     // ~9 cm incl. stem, narrow pointed, curled, autumn yellow
TriangleMesh makeTwig(uint64_t seed);          // ~30 cm, tapered, two side branches, brown
TriangleMesh makeGrassTuft(uint64_t seed);     // ~10 cm tall clump of curved tapered blades, green
TriangleMesh makeMushroom(uint64_t seed);      // ~10 cm, stem + domed cap, tan-red
TriangleMesh makePineNeedles(uint64_t seed);   // ~8 cm bundle of thin needles from a sheath, dark green
TriangleMesh makeHayWisp(uint64_t seed);       // ~18 cm, loose straws lying across each other, straw yellow
// Autumn scattered effects. Dry leaves: the same outlines strongly cupped and curled, edges rolled up,
// crinkled, browner and duller. Wet leaves: lying flat (a few mm of relief), darker and more saturated.
TriangleMesh makeOakLeafDry(uint64_t seed);
TriangleMesh makeBirchLeafDry(uint64_t seed);
TriangleMesh makeOakLeafWet(uint64_t seed);
TriangleMesh makeBirchLeafWet(uint64_t seed);
TriangleMesh makePetal(uint64_t seed);         // ~3.5 cm, rounded obovate, slightly cupped, pale pink
TriangleMesh makeTrashCan(uint64_t seed);      // ~12 cm drink can lying on its side, pinched and dented, red
TriangleMesh makeTrashPaper(uint64_t seed);    // ~7 cm crumpled paper ball with sharp creases, off-white
TriangleMesh makeTrashCup(uint64_t seed);      // ~9 cm open paper cup (1 mm wall, rolled lip) on its side, white
TriangleMesh makeTrashBottle(uint64_t seed);   // ~20 cm plastic bottle with neck and cap, lying, green-blue
TriangleMesh makeGrassTuftDried(uint64_t seed);  // ~10 cm, thin drooping blades, some folded over, straw

// A "scanned" boulder for performance work, like what photogrammetry gives artists: about 1 m across,
// a lumpy ellipsoid with mid-scale knobs, fine bumps and per-vertex scan noise, as a uniformly
// subdivided icosahedron (k segments per edge: 20 k^2 triangles, k = round(sqrt(target / 20))), so the
// triangle count is within sqrt(20 target) + 5 of `target_triangles` (clamped to [20, 50'000'000]):
// 1,003,520 for a million. Closed, outward wound, star-shaped about its centre (so never
// self-intersecting), centred, with normals; triangles come face by face and row by row (spatially
// coherent, as scanner output usually is). Deterministic in the seed; about 0.6 s per million
// triangles. Not a starter asset (not in starterAssetNames()).
TriangleMesh makeScannedRock(uint32_t target_triangles, uint64_t seed);

// The starter set, in a fixed order: rock, flat_stone, pebble, leaf_oak, leaf_birch, twig, grass_tuft,
// mushroom, pine_needles, hay_wisp, leaf_oak_dry, leaf_birch_dry, leaf_oak_wet, leaf_birch_wet, petal,
// trash_can, trash_paper, trash_cup, trash_bottle, grass_tuft_dried.
const std::vector<std::string>& starterAssetNames();

// The generator for `name` (one of starterAssetNames()); false for an unknown name.
bool makeStarterAsset(const std::string& name, uint64_t seed, TriangleMesh* out);

// The seed the committed assets in assets/models/ were generated with.
constexpr uint64_t kStarterAssetSeed = 2016;

// Writes <dir>/<name>.glb for every starter asset (seed kStarterAssetSeed), creating `dir` if needed.
// False with "<path>: <reason>" on the first failure.
bool writeStarterAssets(const std::string& dir, std::string* error);

}  // namespace ug
