// The Ghost Tile (Guérin et al. 2016, §4): a cubic tile of size s holding many overlapping candidate
// objects (detail model + frame) and the collision graph between them, including collisions with the
// copies of candidates in the 26 neighbour tiles. Built once per set of inputs, cached on disk
// (ghost_tile_cache.h), then instantiated everywhere (engine/instancer).
//
// Usage:
//     GhostTileInput input;
//     input.settings = {.tile_size_m = 0.5f, .delta_m = -0.002f, .seed = 7};
//     input.types.push_back({.name = "rock", .candidate_count = 320, .scale_min = 0.8f, .scale_max = 1.2f});
//     input.models.push_back(&rock_model);             // DetailModel from mesh/detail_model.h
//     GhostTile tile;
//     std::string error;
//     if (!buildGhostTile(input, {}, &tile, &error)) fail(error);
//     tile.graph.forEachNeighbor(i, [&](uint32_t j, uint32_t offset) { ... });
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "ghosttile/collision_graph.h"
#include "mesh/detail_model.h"

namespace ug {

// A weighted range of tilt angles: the angle between the object's +Z and the world's +Z.
struct TiltRange {
    float min_deg = 0.0f;  // in [0, 180]
    float max_deg = 30.0f;  // in [min_deg, 180]
    float weight = 1.0f;   // > 0; ranges are chosen in proportion to their weights
};

enum class OrientationMode : uint8_t {
    UniformRandom,  // uniform over all rotations (piles, pebbles)
    Tilt,           // tilt drawn from tilt_ranges, uniform by solid angle inside a range; random yaw
};

struct OrientationDistribution {
    OrientationMode mode = OrientationMode::UniformRandom;
    std::vector<TiltRange> tilt_ranges;  // used by Tilt; e.g. {{0,30,0.75},{45,60,0.25}} (paper Fig. 7)
};

enum class PositionMode : uint8_t {
    Uniform,   // independent uniform positions in the tile
    Jittered,  // one position per cell of a regular grid, jittered inside its cell (fewer clumps)
};

// One detail type as the Ghost Tile sees it. The model (sphere set) comes separately.
struct DetailTypeSettings {
    std::string name;
    uint32_t candidate_count = 300;  // in [1, kMaxCandidatesPerTile]
    OrientationDistribution orientation;
    float scale_min = 1.0f;  // uniform scale range, 0 < scale_min <= scale_max <= 100
    float scale_max = 1.0f;
    PositionMode position = PositionMode::Uniform;
};

// At most this many variants (GhostTileSettings::variants).
constexpr uint32_t kMaxTileVariants = 64;

struct GhostTileSettings {
    float tile_size_m = 0.5f;  // edge of the cubic tile; paper: 1-3x the largest object (~50 cm)
    float delta_m = 0.0f;      // collision threshold δ: d(A,B) <= δ collides; < 0 lets objects interpenetrate
    uint64_t seed = 7;
    // Independent draws of every type's candidates in a tile (docs/architecture.md "No period"); each tile of
    // the world uses one of them (tileVariant() in instancer/instantiator.h), so an arrangement does not
    // repeat one tile away. In [1, kMaxTileVariants]; 1 is the paper's single tile.
    uint32_t variants = 1;
};

struct GhostTileInput {
    GhostTileSettings settings;
    std::vector<DetailTypeSettings> types;
    std::vector<const DetailModel*> models;  // one per type, same order; not owned
};

// Candidates as structure of arrays, grouped by type: type t owns [type_begin[t], type_begin[t+1]), which
// holds `variants` equal sub-ranges, variant v of type t being [variantBegin(t, v), variantEnd(t, v)).
// Grouping by type first keeps a type's candidates together for the per-type passes of the instantiator;
// variant 0 of every type is the single-variant tile's candidates, bit for bit.
struct CandidateSet {
    std::vector<uint32_t> type_begin;    // type count + 1 entries
    std::vector<uint16_t> type;          // per candidate
    std::vector<glm::vec3> position;     // tile space, in [0, s)^3
    std::vector<glm::quat> rotation;     // unit quaternions
    std::vector<float> scale;            // uniform scale
    uint32_t variants = 1;               // every type range is a multiple of it

    uint32_t size() const { return uint32_t(type.size()); }
    uint32_t typeCount() const { return type_begin.empty() ? 0 : uint32_t(type_begin.size() - 1); }

    // Candidates of one variant of type t (the type's candidate_count).
    uint32_t perVariant(uint32_t t) const { return (type_begin[t + 1] - type_begin[t]) / variants; }
    // Candidates of one variant, all types: what one tile of the world holds.
    uint32_t perVariantSize() const { return size() / variants; }
    uint32_t variantBegin(uint32_t t, uint32_t v) const { return type_begin[t] + v * perVariant(t); }
    uint32_t variantEnd(uint32_t t, uint32_t v) const { return type_begin[t] + (v + 1) * perVariant(t); }
    uint32_t variantOf(uint32_t id) const {
        const uint32_t t = type[id];
        return (id - type_begin[t]) / perVariant(t);
    }
};

struct GhostTileStats {
    uint32_t candidate_count = 0;  // #N
    uint64_t pair_count = 0;       // #E/2: colliding pairs (each stored as two directed edges)
    double rho = 0.0;              // #E / (2 #N), the paper's average collisions per candidate
    double build_seconds = 0.0;
    uint64_t graph_bytes = 0;      // collision graph storage (row offsets + packed edges)
    uint64_t total_bytes = 0;      // graph + candidate frames
    double bytes_per_pair = 0.0;   // graph_bytes / pair_count (0 when there are no pairs)
};

struct GhostTile {
    uint64_t key = 0;  // hash of every input that shapes the tile (ghostTileKey)
    GhostTileSettings settings;
    CandidateSet candidates;
    CollisionGraph graph;
    GhostTileStats stats;
};

// Refused before any memory is taken: more candidates than this in one tile (all variants together).
constexpr uint32_t kMaxCandidatesPerTile = 1u << 20;
// Refused during the build: a collision graph larger than this (bytes).
constexpr uint64_t kMaxGraphBytes = 2ull << 30;

struct BuildOptions {
    int threads = 0;                            // 0 = all hardware threads
    const std::atomic<bool>* cancel = nullptr;  // set to true to stop early (build returns false)
    std::function<void(float fraction)> progress;  // called from the building thread, in [0, 1]
};

// Checks settings, types and models; the message names the offending type and field.
bool validateGhostTileInput(const GhostTileInput& input, std::string* error);

// A 64-bit key over everything that determines the tile's content (settings, types, sphere sets,
// the builder's format version). Equal keys mean equal tiles.
uint64_t ghostTileKey(const GhostTileInput& input);

// Generates candidates and the collision graph. Deterministic: the same input gives a bit-identical tile
// for any thread count. With several variants, the graph holds offset-0 edges only between candidates of
// the same variant (a tile holds one variant) and, at the 26 other offsets, edges between any two variants
// (a neighbour tile may hold any); every edge still has its mirror.
bool buildGhostTile(const GhostTileInput& input, const BuildOptions& options, GhostTile* out,
                    std::string* error);

// Only the candidate frames (step 1 of §4.2); exposed for tests and previews. Variant v of type t is an
// independent draw seeded from (seed, t, v); variant 0 is the draw a single-variant tile makes.
bool generateCandidates(const GhostTileInput& input, CandidateSet* out, std::string* error);

// The collision predicate of §4.3 between sphere i of candidate A (at tile offset 0) and sphere j of
// candidate B at tile offset v: ||(cb - ca) + s v|| - (ra + rb) <= δ, with sphere centres in tile space.
// Written so that swapping A and B and negating v gives exactly the same answer in floating point, which
// is what makes every edge's mirror exist.
inline bool spheresCollide(const glm::vec3& ca, float ra, const glm::vec3& cb, float rb, const glm::vec3& shift,
                           float delta_m) {
    glm::vec3 d = (cb - ca) + shift;
    float reach = (ra + rb) + delta_m;
    if (reach < 0.0f) return false;
    return d.x * d.x + d.y * d.y + d.z * d.z <= reach * reach;
}

// World-space (tile-space) spheres of one candidate: centre = p + R (s c), radius = s r.
void candidateSpheres(const CandidateSet& candidates, uint32_t index, const DetailModel& model,
                      std::vector<Sphere>* out);

}  // namespace ug
