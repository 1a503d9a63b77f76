#include "ghosttile/ghost_tile_verify.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "core/hash.h"

namespace ug {

namespace {

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

template <typename T>
bool sameBitsArray(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// The first index where two arrays of frames differ (byte-wise), for the message.
template <typename T>
size_t firstDifference(const std::vector<T>& a, const std::vector<T>& b) {
    const size_t n = std::min(a.size(), b.size());
    for (size_t i = 0; i < n; ++i)
        if (std::memcmp(&a[i], &b[i], sizeof(T)) != 0) return i;
    return n;
}

bool fail(std::string* why, const std::string& text) {
    *why = text;
    return false;
}

// Does candidate i (offset 0) collide with candidate j at tile offset v? The build's answer by
// definition: some pair of their spheres satisfies spheresCollide.
bool candidatesCollide(const std::vector<Sphere>& a, const std::vector<Sphere>& b, const glm::vec3& shift,
                       float delta) {
    for (const Sphere& sa : a)
        for (const Sphere& sb : b)
            if (spheresCollide(sa.center, sa.radius, sb.center, sb.radius, shift, delta)) return true;
    return false;
}

// A bounding sphere of a candidate's spheres, padded so that rounding can never make it exclude one.
Sphere boundOf(const std::vector<Sphere>& spheres) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const Sphere& s : spheres) {
        lo = glm::min(lo, s.center - s.radius);
        hi = glm::max(hi, s.center + s.radius);
    }
    const glm::vec3 c = 0.5f * (lo + hi);
    float r = 0.0f;
    for (const Sphere& s : spheres) r = std::max(r, glm::length(s.center - c) + s.radius);
    return {c, r * (1.0f + 1e-5f) + 1e-6f};
}

}  // namespace

bool verifyGhostTileAgainstInput(const GhostTile& tile, const GhostTileInput& input, std::string* why) {
    const GhostTileSettings& s = tile.settings;
    if (!sameBits(s.tile_size_m, input.settings.tile_size_m))
        return fail(why, "tile size " + std::to_string(s.tile_size_m) + " m, the scene asks for " +
                             std::to_string(input.settings.tile_size_m) + " m");
    if (!sameBits(s.delta_m, input.settings.delta_m))
        return fail(why, "delta " + std::to_string(s.delta_m) + " m, the scene asks for " +
                             std::to_string(input.settings.delta_m) + " m");
    if (s.seed != input.settings.seed)
        return fail(why, "seed " + std::to_string(s.seed) + ", the scene asks for " + std::to_string(input.settings.seed));
    if (s.variants != input.settings.variants || tile.candidates.variants != input.settings.variants)
        return fail(why, "variants " + std::to_string(s.variants) + " (candidates: " +
                             std::to_string(tile.candidates.variants) + "), the scene asks for " +
                             std::to_string(input.settings.variants));

    CandidateSet expected;
    if (!generateCandidates(input, &expected, why)) return false;
    const CandidateSet& c = tile.candidates;
    if (c.type_begin != expected.type_begin) {
        const size_t t = firstDifference(c.type_begin, expected.type_begin);
        return fail(why, "candidate counts per type disagree with the scene (at type range boundary " +
                             std::to_string(t) + ")");
    }
    if (!sameBitsArray(c.type, expected.type)) return fail(why, "candidate types disagree with the scene");
    if (!sameBitsArray(c.position, expected.position))
        return fail(why, "candidate " + std::to_string(firstDifference(c.position, expected.position)) +
                             ": position differs from the scene's candidate");
    if (!sameBitsArray(c.rotation, expected.rotation))
        return fail(why, "candidate " + std::to_string(firstDifference(c.rotation, expected.rotation)) +
                             ": rotation differs from the scene's candidate");
    if (!sameBitsArray(c.scale, expected.scale))
        return fail(why, "candidate " + std::to_string(firstDifference(c.scale, expected.scale)) +
                             ": scale differs from the scene's candidate");

    const uint32_t n = c.size();
    const CollisionGraph& g = tile.graph;
    if (g.nodeCount() != n)
        return fail(why, "collision graph has " + std::to_string(g.nodeCount()) + " rows for " + std::to_string(n) +
                             " candidates");

    // Symmetry: the multiset of edges (i, j, v) equals the multiset of mirrors (j, i, -v). Summing a strong
    // hash of each side is order independent and O(E).
    uint64_t forward = 0, mirrored = 0;
    for (uint32_t i = 0; i < n; ++i) {
        g.forEachNeighbor(i, [&](uint32_t j, uint32_t v) {
            forward += hashWords(i, j, v, 0x65646765ull);
            mirrored += hashWords(j, i, mirrorOffset(v), 0x65646765ull);
        });
    }
    if (forward != mirrored) return fail(why, "collision graph is not symmetric (an edge lacks its mirror)");
    if (n == 0) return true;

    // Re-derive sampled rows and edges from the sphere sets.
    std::vector<std::vector<Sphere>> spheres(n);
    std::vector<Sphere> bounds(n);
    for (uint32_t i = 0; i < n; ++i) {
        candidateSpheres(c, i, *input.models[c.type[i]], &spheres[i]);
        bounds[i] = boundOf(spheres[i]);
    }
    const float tile_m = s.tile_size_m, delta = s.delta_m, delta_pos = std::max(0.0f, delta);
    auto collide = [&](uint32_t i, uint32_t j, uint32_t v) {
        const glm::vec3 shift = glm::vec3(offsetVector(v)) * tile_m;
        const glm::vec3 d = (bounds[j].center + shift) - bounds[i].center;
        const float r = bounds[i].radius + bounds[j].radius + delta_pos;
        if (glm::dot(d, d) > r * r) return false;  // conservative: padded bounds enclose every sphere
        return candidatesCollide(spheres[i], spheres[j], shift, delta);
    };
    // A tile holds one variant, so the graph has no offset-0 edge between two variants.
    auto sameVariant = [&](uint32_t i, uint32_t j) { return c.variants == 1 || c.variantOf(i) == c.variantOf(j); };
    const uint32_t rows = std::min(n, kVerifiedRows);
    std::vector<uint32_t> stored, derived;
    for (uint32_t k = 0; k < rows; ++k) {
        const uint32_t i = uint32_t(hashWords(tile.key, k, 0x726f77ull) % n);
        stored.clear();
        derived.clear();
        g.forEachNeighbor(i, [&](uint32_t j, uint32_t v) { stored.push_back(j * kOffsetCount + v); });
        for (uint32_t j = 0; j < n; ++j)
            for (uint32_t v = 0; v < kOffsetCount; ++v)
                if (!(v == kCenterOffset && (j == i || !sameVariant(i, j))) && collide(i, j, v))
                    derived.push_back(j * kOffsetCount + v);
        if (stored != derived)
            return fail(why, "collision graph row " + std::to_string(i) + " has " + std::to_string(stored.size()) +
                                 " edges, the sphere sets give " + std::to_string(derived.size()));
    }
    const uint64_t edges = g.edgeCount();
    if (edges == 0) return true;
    // Single edges: pick stored edges by rank, walking the rows once.
    std::vector<uint64_t> ranks(std::min<uint64_t>(edges, kVerifiedEdges));
    for (size_t k = 0; k < ranks.size(); ++k) ranks[k] = hashWords(tile.key, k, 0x65ull) % edges;
    std::sort(ranks.begin(), ranks.end());
    uint64_t rank = 0;
    size_t next = 0;
    std::string bad;
    for (uint32_t i = 0; i < n && next < ranks.size() && bad.empty(); ++i) {
        g.forEachNeighbor(i, [&](uint32_t j, uint32_t v) {
            while (next < ranks.size() && ranks[next] == rank) {
                if (bad.empty() && !collide(i, j, v))
                    bad = "collision graph edge " + std::to_string(i) + " - " + std::to_string(j) +
                          " does not collide on the scene's sphere sets";
                if (bad.empty() && v == kCenterOffset && !sameVariant(i, j))
                    bad = "collision graph edge " + std::to_string(i) + " - " + std::to_string(j) +
                          " joins two variants in the same tile";
                ++next;
            }
            ++rank;
        });
    }
    if (!bad.empty()) return fail(why, bad);
    return true;
}

}  // namespace ug
