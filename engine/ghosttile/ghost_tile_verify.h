// The Ghost Tile cache is a trust boundary: a studio shares one cache folder across a farm, so a file
// that passed its checksum may still have been written by a buggy or hostile writer (a payload rewritten
// and re-checksummed). Before a loaded tile is used, it is checked against the scene's own inputs.
#pragma once

#include <string>

#include "ghosttile/ghost_tile.h"

namespace ug {

// How many collision-graph rows and single edges are re-derived from the sphere sets (chosen by a hash
// of the tile's key, so a check is repeatable). Full rows catch missing edges, single edges catch
// invented ones; together they cost a few milliseconds on the largest sample tiles.
constexpr uint32_t kVerifiedRows = 24;
constexpr uint32_t kVerifiedEdges = 2048;

// Checks, in this order, and stops at the first disagreement (the message says which value differs):
//  - the settings (tile size, δ, seed, variants) equal the input's, bit for bit;
//  - the candidate frames equal a fresh generateCandidates(input), bit for bit: type ranges and counts,
//    finite positions in the tile, unit quaternions and scales in range all follow from that;
//  - the collision graph has one row per candidate and is symmetric (every edge (i, j, v) has its mirror
//    (j, i, -v); checked in O(E) with an order-independent hash of the two edge multisets);
//  - kVerifiedRows rows and kVerifiedEdges edges agree with the collision predicate on the input's
//    sphere sets (spheresCollide, exactly as the build decides; no offset-0 edge between two variants).
// The input must be valid (validateGhostTileInput).
bool verifyGhostTileAgainstInput(const GhostTile& tile, const GhostTileInput& input, std::string* why);

}  // namespace ug
