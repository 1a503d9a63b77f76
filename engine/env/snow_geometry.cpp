// Geometry-controlled snow (§5.1): extraction of the up-facing, open faces of a base mesh, their grouping
// into patches, and the refinement of every face by uniform subdivision with shared edges split
// identically (vertices welded by construction: an edge owns its inner points, a face its inner points).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include "env/snow.h"
#include "env/snow_detail.h"

namespace ug {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

bool fail(std::string* error, const std::string& why) {
    if (error) *error = why;
    return false;
}

// Base vertices at exactly the same position become one (meshes split at UV or normal seams still give
// one patch). Sorting, not hashing, keeps the numbering a pure function of the input.
void weldVertices(const TriangleMesh& base, std::vector<uint32_t>* weld, std::vector<glm::vec3>* welded) {
    const size_t n = base.positions.size();
    std::vector<uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    auto less = [&](uint32_t a, uint32_t b) {
        const glm::vec3 &p = base.positions[a], &q = base.positions[b];
        if (p.x != q.x) return p.x < q.x;
        if (p.y != q.y) return p.y < q.y;
        if (p.z != q.z) return p.z < q.z;
        return a < b;
    };
    std::sort(order.begin(), order.end(), less);
    weld->assign(n, 0);
    welded->clear();
    for (size_t k = 0; k < n; ++k) {
        const uint32_t v = order[k];
        if (k == 0 || base.positions[order[k - 1]] != base.positions[v]) welded->push_back(base.positions[v]);
        (*weld)[v] = uint32_t(welded->size() - 1);
    }
}

// One extracted face: welded corners, its edges and how it meets them.
struct SnowFace {
    uint32_t base_face = 0;
    uint32_t v[3] = {0, 0, 0};             // welded corner ids, the base's winding
    uint32_t edge[3] = {0, 0, 0};          // edge k joins v[k] and v[(k + 1) % 3]
    bool forward[3] = {true, true, true};  // edge k runs lo -> hi from v[k]
    uint32_t n = 1;                        // grid segments per side (the largest of its edges' counts)
    uint32_t patch = 0;
    uint32_t interior_first = 0;  // first id of its (n-1)(n-2)/2 inner vertices
};

struct SnowEdge {
    uint32_t lo = 0, hi = 0;   // welded ids, lo < hi
    uint32_t n = 1;            // segments
    uint32_t face0 = 0;        // the first extracted face using it
    bool border = false;       // used by one extracted face, or by more than two (non-manifold)
    bool joint = false;        // a border across a narrow joint from another patch (markJoints): not a
                               // border for g(d)
    glm::vec3 joint_shift{0.0f};  // a joint's points move by this: half way across it
    uint32_t inner_first = 0;  // first id of its n-1 inner points

    // g(d) falls to 0 here: the snow's border (d measures the distance to these edges).
    bool bounds() const { return border && !joint; }
};

// Faces facing `up` within the angle, non-degenerate, in base order.
std::vector<SnowFace> upFacingFaces(const TriangleMesh& base, const std::vector<uint32_t>& weld,
                                    const SnowSettings& s) {
    const glm::vec3 up = snow_detail::unitUp(s);
    const float cos_max = std::cos(glm::radians(s.max_face_angle_deg));
    std::vector<SnowFace> faces;
    for (size_t f = 0; f < base.triangleCount(); ++f) {
        const uint32_t* t = &base.indices[3 * f];
        const glm::vec3 &a = base.positions[t[0]], &b = base.positions[t[1]], &c = base.positions[t[2]];
        const glm::vec3 cr = glm::cross(b - a, c - a);
        const float len = glm::length(cr);
        if (!(len > 0.0f) || !std::isfinite(len)) continue;
        if (glm::dot(cr, up) < cos_max * len) continue;
        SnowFace sf;
        sf.base_face = uint32_t(f);
        for (int k = 0; k < 3; ++k) sf.v[k] = weld[t[k]];
        if (sf.v[0] == sf.v[1] || sf.v[1] == sf.v[2] || sf.v[2] == sf.v[0]) continue;
        faces.push_back(sf);
    }
    return faces;
}

// Keeps the faces whose centroid is open enough (one batched query).
void keepOpenFaces(const std::vector<glm::vec3>& welded, const SnowSettings& s, const EnvQuery& env,
                   std::vector<SnowFace>* faces) {
    if (faces->empty()) return;
    std::vector<glm::vec3> centroids(faces->size());
    for (size_t f = 0; f < faces->size(); ++f) {
        const SnowFace& sf = (*faces)[f];
        centroids[f] = (welded[sf.v[0]] + welded[sf.v[1]] + welded[sf.v[2]]) / 3.0f;
    }
    std::vector<EnvSample> e(faces->size());
    env(centroids.data(), centroids.size(), e.data());
    size_t w = 0;
    for (size_t f = 0; f < faces->size(); ++f)
        if (e[f].shelter >= s.min_open) (*faces)[w++] = (*faces)[f];
    faces->resize(w);
}

double faceArea(const std::vector<glm::vec3>& welded, const SnowFace& f) {
    const glm::dvec3 a(welded[f.v[0]]), b(welded[f.v[1]]), c(welded[f.v[2]]);
    return 0.5 * glm::length(glm::cross(b - a, c - a));
}

// Unique edges of the extracted faces (sorted by welded ids), their face counts and each face's edge slots.
std::vector<SnowEdge> buildEdges(std::vector<SnowFace>* faces) {
    struct Slot {
        uint64_t key;
        uint32_t slot;  // face * 3 + k
    };
    std::vector<Slot> slots;
    slots.reserve(faces->size() * 3);
    for (size_t f = 0; f < faces->size(); ++f)
        for (uint32_t k = 0; k < 3; ++k) {
            const uint32_t a = (*faces)[f].v[k], b = (*faces)[f].v[(k + 1) % 3];
            slots.push_back({(uint64_t(std::min(a, b)) << 32) | std::max(a, b), uint32_t(f * 3 + k)});
        }
    std::sort(slots.begin(), slots.end(),
              [](const Slot& x, const Slot& y) { return x.key != y.key ? x.key < y.key : x.slot < y.slot; });
    std::vector<SnowEdge> edges;
    for (size_t i = 0; i < slots.size();) {
        size_t j = i;
        while (j < slots.size() && slots[j].key == slots[i].key) ++j;
        SnowEdge e;
        e.lo = uint32_t(slots[i].key >> 32);
        e.hi = uint32_t(slots[i].key & 0xffffffffu);
        e.face0 = slots[i].slot / 3;
        e.border = (j - i) != 2;
        const uint32_t id = uint32_t(edges.size());
        for (size_t k = i; k < j; ++k) {
            SnowFace& f = (*faces)[slots[k].slot / 3];
            const uint32_t local = slots[k].slot % 3;
            f.edge[local] = id;
            f.forward[local] = f.v[local] == e.lo;
        }
        edges.push_back(e);
        i = j;
    }
    return edges;
}

uint32_t findRoot(std::vector<uint32_t>& parent, uint32_t x) {
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

// Connected components through interior (two-face) edges, numbered in order of their first face.
size_t assignPatches(const std::vector<SnowEdge>& edges, std::vector<SnowFace>* faces) {
    std::vector<uint32_t> parent(faces->size());
    std::iota(parent.begin(), parent.end(), 0u);
    for (size_t f = 0; f < faces->size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const SnowEdge& e = edges[(*faces)[f].edge[k]];
            if (e.border) continue;
            const uint32_t a = findRoot(parent, uint32_t(f)), b = findRoot(parent, e.face0);
            if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the smaller face stays the root
        }
    std::vector<uint32_t> patch_of_root(faces->size(), UINT32_MAX);
    size_t count = 0;
    for (size_t f = 0; f < faces->size(); ++f) {
        const uint32_t r = findRoot(parent, uint32_t(f));
        if (patch_of_root[r] == UINT32_MAX) patch_of_root[r] = uint32_t(count++);
        (*faces)[f].patch = patch_of_root[r];
    }
    return count;
}

// One border edge's side, for the joint search: its edge id and the side's geometry.
struct Side {
    uint32_t edge;
    SnowBorderSide geo;
    float lo_x, hi_x;
};

// The sides of the border edges (edge order), each with the direction across it toward its face.
std::vector<Side> borderSides(const std::vector<glm::vec3>& welded, const std::vector<SnowFace>& faces,
                              const std::vector<SnowEdge>& edges, glm::vec3 up) {
    std::vector<Side> sides;
    for (uint32_t e = 0; e < edges.size(); ++e) {
        const SnowEdge& se = edges[e];
        if (!se.border) continue;
        const glm::vec3 a = welded[se.lo], b = welded[se.hi], d = b - a;
        // Ends further apart in height than this never meet another side (snowSidesMeet): a tree's
        // branches have thousands of such edges. Vertical height, as snowSidesMeet measures it.
        if (std::fabs(d.z) > 2.0f * kSnowJointHeightM) continue;
        const SnowFace& f = faces[se.face0];
        const glm::vec3 c = (welded[f.v[0]] + welded[f.v[1]] + welded[f.v[2]]) / 3.0f;
        glm::vec3 across = (c - a) - d * (glm::dot(c - a, d) / glm::dot(d, d));
        across -= up * glm::dot(across, up);
        const float len = glm::length(across);
        if (!(len > 0.0f)) continue;
        sides.push_back({e, {a, b, across / len, c}, std::min(a.x, b.x), std::max(a.x, b.x)});
    }
    return sides;
}

// Joints within the mesh: a border edge facing another patch's border edge (snowSidesMeet; a paving
// slab's 8 mm joints, the slabs of one model being patches of their own). Snow bridges such a gap, so
// neither is a border for g(d): the snow keeps its depth up to the joint instead of falling to nothing on
// both sides, which drew a dark groove two d0 wide around every slab of a snowy pavement. Then the
// border edges the caller says another object's snow continues beyond (SnowSettings::bridged_borders).
// The sweep below looks at pairs whose x ranges meet: a handful per edge in real models, but every pair in
// a hostile strip of tiny faces along y. Past this many pairs the remaining borders stay borders.
constexpr uint64_t kMaxJointPairs = 20'000'000;

bool lessPoint(glm::vec3 p, glm::vec3 q) {
    if (p.x != q.x) return p.x < q.x;
    if (p.y != q.y) return p.y < q.y;
    return p.z < q.z;
}

// A joint edge's points move half way across the gap (the widest of its joints).
void setShift(SnowEdge* e, const SnowBorderSide& side, float gap) {
    const glm::vec3 shift = -side.inward * (0.5f * gap);
    if (glm::dot(shift, shift) > glm::dot(e->joint_shift, e->joint_shift)) e->joint_shift = shift;
    e->joint = true;
}

void markBridged(const std::vector<glm::vec3>& welded, const std::vector<Side>& sides,
                 const std::vector<SnowSegment>& bridged, std::vector<SnowEdge>* edges) {
    if (bridged.empty()) return;
    using Key = std::pair<glm::vec3, glm::vec3>;
    auto ordered = [](glm::vec3 a, glm::vec3 b) { return lessPoint(b, a) ? Key(b, a) : Key(a, b); };
    auto less = [](const Key& x, const Key& y) {
        return lessPoint(x.first, y.first) || (x.first == y.first && lessPoint(x.second, y.second));
    };
    std::vector<std::pair<Key, float>> keys;  // (ends, gap)
    keys.reserve(bridged.size());
    for (const SnowSegment& g : bridged) keys.emplace_back(ordered(g.a, g.b), g.gap_m);
    std::sort(keys.begin(), keys.end(), [&](const auto& x, const auto& y) {
        return less(x.first, y.first) || (!less(y.first, x.first) && x.second < y.second);
    });
    for (const Side& side : sides) {
        SnowEdge& e = (*edges)[side.edge];
        const Key k = ordered(welded[e.lo], welded[e.hi]);
        auto it = std::lower_bound(keys.begin(), keys.end(), k,
                                   [&](const std::pair<Key, float>& x, const Key& y) { return less(x.first, y); });
        for (; it != keys.end() && !less(k, it->first); ++it) setShift(&e, side.geo, std::max(0.0f, it->second));
    }
}

void markJoints(const std::vector<glm::vec3>& welded, const std::vector<SnowFace>& faces, const SnowSettings& s,
                std::vector<SnowEdge>* edges) {
    const glm::vec3 up = snow_detail::unitUp(s);
    std::vector<Side> sides = borderSides(welded, faces, *edges, up);
    // A sweep along x: pairs whose x ranges come within the gap.
    std::vector<uint32_t> order(sides.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t p, uint32_t q) {
        return sides[p].lo_x != sides[q].lo_x ? sides[p].lo_x < sides[q].lo_x : sides[p].edge < sides[q].edge;
    });
    uint64_t pairs = 0;
    for (size_t i = 0; i < order.size() && pairs <= kMaxJointPairs; ++i)
        for (size_t j = i + 1; j < order.size() && sides[order[j]].lo_x <= sides[order[i]].hi_x + kSnowJointGapM; ++j) {
            if (++pairs > kMaxJointPairs) break;
            const Side &p = sides[order[i]], &q = sides[order[j]];
            if (faces[(*edges)[p.edge].face0].patch == faces[(*edges)[q.edge].face0].patch) continue;
            if (!snowSidesMeet(p.geo, q.geo, 1e-6f)) continue;
            setShift(&(*edges)[p.edge], p.geo, snowJointGap(p.geo, q.geo));
            setShift(&(*edges)[q.edge], q.geo, snowJointGap(q.geo, p.geo));
        }
    markBridged(welded, sides, s.bridged_borders, edges);
}

// Segment counts. A face wants n0 = ceil(longest edge / target); an edge takes the larger n0 of the faces
// sharing it (so both split it identically), and a face's grid the largest count of its edges. Where
// neighbours want the same n0 (regular meshes: quads split in two, uniform grids) no grid node is
// snapped and every edge is <= target. A face's count is at most the largest n0 among itself and its
// (at most three, manifold) neighbours, so the total is at most 4 Σ n0². Returns the exact number of
// sub-triangles before allocating any (a double: it may be astronomically large).
double assignCounts(const std::vector<glm::vec3>& welded, const SnowSettings& s, std::vector<SnowEdge>* edges,
                    std::vector<SnowFace>* faces) {
    for (SnowEdge& e : *edges) e.n = 1;
    for (SnowFace& f : *faces) {
        double longest = 0.0;
        for (int k = 0; k < 3; ++k)
            longest = std::max(
                longest, glm::length(glm::dvec3(welded[f.v[(k + 1) % 3]]) - glm::dvec3(welded[f.v[k]])));
        const double n0 = std::max(1.0, std::ceil(longest / double(s.target_edge_m)));
        const uint32_t n = n0 > 1e9 ? uint32_t(1e9) : uint32_t(n0);  // 1e18 triangles: refused below anyway
        for (int k = 0; k < 3; ++k) (*edges)[f.edge[k]].n = std::max((*edges)[f.edge[k]].n, n);
    }
    double triangles = 0.0;
    for (SnowFace& f : *faces) {
        f.n = std::max({(*edges)[f.edge[0]].n, (*edges)[f.edge[1]].n, (*edges)[f.edge[2]].n});
        triangles += double(f.n) * double(f.n);
    }
    return triangles;
}

// Border edges each face may be within d0 of (its patch's border edges whose box meets the face's box
// grown by d0), as CSR lists in increasing edge order.
struct Candidates {
    std::vector<uint32_t> first;  // per face, size faces + 1
    std::vector<uint32_t> edges;
};

struct Box {
    glm::vec3 lo, hi;
};

bool boxesMeet(const Box& a, const Box& b) {
    return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
           b.lo.z <= a.hi.z;
}

// A uniform grid over the border edges, so a face looks at the border edges near it rather than at its
// whole patch's (a large patch has many). Cells are sorted (cell, patch, edge) entries: no hashing.
// Edges spanning too many cells, and faces covering too many, fall back to the patch's full list.
class BorderGrid {
    struct Cell3 {
        uint64_t x, y, z;
    };

  public:
    static constexpr uint64_t kMaxCellsPerItem = 64;

    BorderGrid(const std::vector<Box>& edge_box, const std::vector<std::pair<uint32_t, uint32_t>>& patch_edge,
               float d0) {
        Box all{glm::vec3(INFINITY), glm::vec3(-INFINITY)};
        double total = 0.0;
        for (const auto& pe : patch_edge) {
            const Box& b = edge_box[pe.second];
            all.lo = glm::min(all.lo, b.lo);
            all.hi = glm::max(all.hi, b.hi);
            total += double(glm::length(b.hi - b.lo));
        }
        origin_ = all.lo;
        const glm::vec3 size = patch_edge.empty() ? glm::vec3(0.0f) : all.hi - all.lo;
        const float extent = std::max({size.x, size.y, size.z});
        const float mean = patch_edge.empty() ? 0.0f : float(total / double(patch_edge.size()));
        cell_ = std::max({d0, mean, extent / float(kAxisCells - 1)});
        for (const auto& pe : patch_edge) {
            const Cell3 a = cellOf(edge_box[pe.second].lo), b = cellOf(edge_box[pe.second].hi);
            if (cellCount(a, b) > kMaxCellsPerItem) {
                big_.push_back(pe);
                continue;
            }
            for (uint64_t x = a.x; x <= b.x; ++x)
                for (uint64_t y = a.y; y <= b.y; ++y)
                    for (uint64_t z = a.z; z <= b.z; ++z)
                        entries_.push_back({key(x, y, z), pe.first, pe.second});
        }
        std::sort(entries_.begin(), entries_.end());
        std::sort(big_.begin(), big_.end());
    }

    // Appends to *out the border edges of `patch` in the cells `box` covers, plus the patch's edges too long
    // for the grid; false (nothing appended) when the box covers too many cells to be worth it.
    bool gather(const Box& box, uint32_t patch, std::vector<uint32_t>* out) const {
        const Cell3 a = cellOf(box.lo), b = cellOf(box.hi);
        if (cellCount(a, b) > kMaxCellsPerItem) return false;
        for (uint64_t x = a.x; x <= b.x; ++x)
            for (uint64_t y = a.y; y <= b.y; ++y)
                for (uint64_t z = a.z; z <= b.z; ++z) {
                    const uint64_t k = key(x, y, z);
                    auto it = std::lower_bound(entries_.begin(), entries_.end(), Entry{k, patch, 0});
                    for (; it != entries_.end() && it->cell == k && it->patch == patch; ++it)
                        out->push_back(it->edge);
                }
        auto it = std::lower_bound(big_.begin(), big_.end(), std::pair<uint32_t, uint32_t>(patch, 0));
        for (; it != big_.end() && it->first == patch; ++it) out->push_back(it->second);
        return true;
    }

  private:
    static constexpr uint64_t kAxisCells = uint64_t(1) << 20;
    struct Entry {
        uint64_t cell;
        uint32_t patch, edge;
        bool operator<(const Entry& o) const {
            if (cell != o.cell) return cell < o.cell;
            return patch != o.patch ? patch < o.patch : edge < o.edge;
        }
    };
    Cell3 cellOf(glm::vec3 p) const {
        const glm::vec3 u = (p - origin_) / cell_;
        auto axis = [](float v) { return uint64_t(std::clamp(v, 0.0f, float(kAxisCells - 1))); };
        return {axis(u.x), axis(u.y), axis(u.z)};
    }
    static uint64_t cellCount(Cell3 a, Cell3 b) {
        return (b.x - a.x + 1) * (b.y - a.y + 1) * (b.z - a.z + 1);
    }
    static uint64_t key(uint64_t x, uint64_t y, uint64_t z) { return (x << 42) | (y << 21) | z; }

    glm::vec3 origin_{0.0f};
    float cell_ = 1.0f;
    std::vector<Entry> entries_;
    std::vector<std::pair<uint32_t, uint32_t>> big_;  // (patch, edge)
};

Candidates borderCandidates(const std::vector<glm::vec3>& welded, const std::vector<SnowEdge>& edges,
                            const std::vector<SnowFace>& faces, size_t patch_count, float d0) {
    // The border edges of each patch (a non-manifold edge bounds every patch that uses it).
    std::vector<std::pair<uint32_t, uint32_t>> patch_edge;
    for (const SnowFace& f : faces)
        for (int k = 0; k < 3; ++k)
            if (edges[f.edge[k]].bounds()) patch_edge.emplace_back(f.patch, f.edge[k]);
    std::sort(patch_edge.begin(), patch_edge.end());
    patch_edge.erase(std::unique(patch_edge.begin(), patch_edge.end()), patch_edge.end());
    std::vector<uint32_t> patch_first(patch_count + 1, 0);
    for (const auto& pe : patch_edge) ++patch_first[pe.first + 1];
    for (size_t p = 0; p < patch_count; ++p) patch_first[p + 1] += patch_first[p];

    std::vector<Box> edge_box(edges.size());
    for (size_t e = 0; e < edges.size(); ++e) {
        const glm::vec3 p = welded[edges[e].lo], q = welded[edges[e].hi];
        edge_box[e] = {glm::min(p, q), glm::max(p, q)};
    }
    const BorderGrid grid(edge_box, patch_edge, d0);

    Candidates c;
    c.first.reserve(faces.size() + 1);
    c.first.push_back(0);
    std::vector<uint32_t> near;
    for (const SnowFace& f : faces) {
        const glm::vec3 a = welded[f.v[0]], b = welded[f.v[1]], cc = welded[f.v[2]];
        const Box box{glm::min(a, glm::min(b, cc)) - glm::vec3(d0),
                      glm::max(a, glm::max(b, cc)) + glm::vec3(d0)};
        near.clear();
        if (grid.gather(box, f.patch, &near)) {
            std::sort(near.begin(), near.end());
            near.erase(std::unique(near.begin(), near.end()), near.end());
        } else {
            for (uint32_t i = patch_first[f.patch]; i < patch_first[f.patch + 1]; ++i)
                near.push_back(patch_edge[i].second);
        }
        for (uint32_t e : near)
            if (boxesMeet(edge_box[e], box)) c.edges.push_back(e);
        c.first.push_back(uint32_t(c.edges.size()));
    }
    return c;
}

float segmentDistance(glm::vec3 p, glm::vec3 a, glm::vec3 b) {
    const glm::vec3 ab = b - a;
    const float len2 = glm::dot(ab, ab);
    float t = len2 > 0.0f ? glm::dot(p - a, ab) / len2 : 0.0f;
    t = std::clamp(t, 0.0f, 1.0f);
    return glm::length(p - (a + ab * t));
}

// Everything the vertex layout needs to compute one vertex's border distance.
struct DistanceContext {
    const std::vector<glm::vec3>& welded;
    const std::vector<SnowEdge>& edges;
    const Candidates& cand;
    float d0;

    // d(p) through the candidates of extracted face f; +inf at or beyond d0.
    float operator()(glm::vec3 p, uint32_t f) const {
        float best = kInf;
        for (uint32_t i = cand.first[f]; i < cand.first[f + 1]; ++i) {
            const SnowEdge& e = edges[cand.edges[i]];
            best = std::min(best, segmentDistance(p, welded[e.lo], welded[e.hi]));
        }
        return best < d0 ? best : kInf;
    }
};

// The id of grid node m (of n_face, counted along local edge k from v[k]) on a face's edge: the nearest
// of the edge's points, so both faces of an edge use exactly its points.
uint32_t edgeNode(const SnowFace& f, int k, uint32_t m, const std::vector<SnowEdge>& edges,
                  const std::vector<uint32_t>& base_id) {
    const SnowEdge& e = edges[f.edge[k]];
    const uint64_t cm = f.forward[k] ? m : f.n - m;                  // numerator along lo -> hi
    const uint64_t kk = (2 * cm * e.n + f.n) / (2 * uint64_t(f.n));  // round(cm * e.n / f.n), ties up
    if (kk == 0) return base_id[e.lo];
    if (kk >= e.n) return base_id[e.hi];
    return e.inner_first + uint32_t(kk - 1);
}

// How far each base corner moves across the joints it lies on: the sum of its joint edges' shifts, each
// direction counted once (a corner in the middle of a side lies on two edges of one joint; where four
// slabs meet it moves diagonally, to the middle of the crossing).
std::vector<glm::vec3> cornerShifts(size_t corners, const std::vector<SnowEdge>& edges) {
    std::vector<glm::vec3> shift(corners, glm::vec3(0.0f));
    std::vector<std::array<glm::vec3, 2>> seen(corners);  // the (at most two) directions already counted
    std::vector<uint8_t> count(corners, 0);
    for (const SnowEdge& e : edges) {
        if (!e.joint || e.joint_shift == glm::vec3(0.0f)) continue;
        const glm::vec3 dir = glm::normalize(e.joint_shift);
        for (uint32_t v : {e.lo, e.hi}) {
            bool counted = false;
            for (uint8_t k = 0; k < count[v]; ++k) counted = counted || glm::dot(seen[v][k], dir) > 0.9f;
            if (counted || count[v] == 2) continue;
            seen[v][count[v]++] = dir;
            shift[v] += e.joint_shift;
        }
    }
    return shift;
}

// Lays out every snow vertex (base corners, edge points, face-inner points; each computed once by its
// owner) with its border distance, then every face's sub-triangles.
snow_detail::SnowLayout layOut(const std::vector<glm::vec3>& welded, std::vector<SnowEdge>& edges,
                               std::vector<SnowFace>& faces, const Candidates& cand, float d0) {
    const DistanceContext dist{welded, edges, cand, d0};
    snow_detail::SnowLayout out;
    size_t verts = welded.size(), tris = 0;  // upper bounds, to allocate once
    for (const SnowEdge& e : edges) verts += e.n - 1;
    for (const SnowFace& f : faces) {
        verts += f.n >= 3 ? size_t(f.n - 1) * (f.n - 2) / 2 : 0;
        tris += size_t(f.n) * f.n;
    }
    out.surface.reserve(verts);
    out.border_distance.reserve(verts);
    out.indices.reserve(3 * tris);
    out.tri_face.reserve(tris);

    // Base corners used, in welded order; on the border when an endpoint of a border edge.
    std::vector<uint32_t> base_id(welded.size(), UINT32_MAX), corner_face(welded.size(), UINT32_MAX);
    std::vector<uint8_t> corner_border(welded.size(), 0);
    for (size_t f = 0; f < faces.size(); ++f)
        for (int k = 0; k < 3; ++k)
            corner_face[faces[f].v[k]] = std::min(corner_face[faces[f].v[k]], uint32_t(f));
    for (const SnowEdge& e : edges)
        if (e.bounds()) corner_border[e.lo] = corner_border[e.hi] = 1;
    const std::vector<glm::vec3> corner_shift = cornerShifts(welded.size(), edges);
    for (size_t v = 0; v < welded.size(); ++v) {
        if (corner_face[v] == UINT32_MAX) continue;
        base_id[v] = uint32_t(out.surface.size());
        out.surface.push_back(welded[v] + corner_shift[v]);
        out.border_distance.push_back(corner_border[v] ? 0.0f : dist(welded[v], corner_face[v]));
    }
    // Edge inner points, lo -> hi.
    for (SnowEdge& e : edges) {
        e.inner_first = uint32_t(out.surface.size());
        const glm::vec3 a = welded[e.lo], ab = welded[e.hi] - welded[e.lo];
        for (uint32_t k = 1; k < e.n; ++k) {
            const glm::vec3 p = a + ab * (float(k) / float(e.n));
            out.surface.push_back(p + e.joint_shift);
            out.border_distance.push_back(e.bounds() ? 0.0f : dist(p, e.face0));
        }
    }
    // Face inner points and triangles.
    std::vector<uint32_t> node;
    for (size_t fi = 0; fi < faces.size(); ++fi) {
        SnowFace& f = faces[fi];
        const uint32_t n = f.n;
        f.interior_first = uint32_t(out.surface.size());
        const glm::vec3 a = welded[f.v[0]], ab = welded[f.v[1]] - a, ac = welded[f.v[2]] - a;
        node.resize(size_t(n + 1) * (n + 2) / 2);
        size_t at = 0;
        for (uint32_t j = 0; j <= n; ++j)
            for (uint32_t i = 0; i + j <= n; ++i, ++at) {
                if (j == 0)
                    node[at] = edgeNode(f, 0, i, edges, base_id);
                else if (i + j == n)
                    node[at] = edgeNode(f, 1, j, edges, base_id);
                else if (i == 0)
                    node[at] = edgeNode(f, 2, n - j, edges, base_id);
                else {
                    const glm::vec3 p = a + ab * (float(i) / float(n)) + ac * (float(j) / float(n));
                    node[at] = uint32_t(out.surface.size());
                    out.surface.push_back(p);
                    out.border_distance.push_back(dist(p, uint32_t(fi)));
                }
            }
        auto id = [&](uint32_t i, uint32_t j) {
            return node[size_t(j) * (n + 1) - size_t(j) * (j - 1) / 2 + i];
        };
        auto emit = [&](uint32_t p, uint32_t q, uint32_t r) {
            if (p == q || q == r || r == p) return;  // collapsed in a transition strip
            out.indices.insert(out.indices.end(), {p, q, r});
            out.tri_face.push_back(f.base_face);
        };
        for (uint32_t j = 0; j < n; ++j)
            for (uint32_t i = 0; i + j < n; ++i) {
                emit(id(i, j), id(i + 1, j), id(i, j + 1));
                if (i + j + 1 < n) emit(id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            }
    }
    return out;
}

}  // namespace

namespace snow_detail {

bool layOutGeometrySnow(const TriangleMesh& base, const SnowSettings& s, const EnvQuery& env,
                        SnowLayout* layout, size_t* faces_used, size_t* patch_count, std::string* error) {
    std::string why;
    if (!validateMesh(base, &why)) return fail(error, "snow base mesh: " + why);
    if (!validateSnowSettings(s, error)) return false;
    if (!env) return fail(error, "snow: no environment query");

    std::vector<uint32_t> weld;
    std::vector<glm::vec3> welded;
    weldVertices(base, &weld, &welded);
    std::vector<SnowFace> faces = upFacingFaces(base, weld, s);
    keepOpenFaces(welded, s, env, &faces);

    double area = 0.0;
    for (const SnowFace& f : faces) area += faceArea(welded, f);
    const double t = double(s.target_edge_m);
    const double estimate = area / (t * t * std::sqrt(3.0) / 4.0) * 2.0;
    if (estimate > double(kMaxSnowTriangles))
        return fail(error, "snow: about " + std::to_string(uint64_t(std::min(estimate, 1e18))) +
                               " triangles for " + std::to_string(area) + " m² at target_edge_m " +
                               std::to_string(s.target_edge_m) + " (more than " +
                               std::to_string(kMaxSnowTriangles) + "); raise target_edge_m");

    std::vector<SnowEdge> edges = buildEdges(&faces);
    const size_t patches = assignPatches(edges, &faces);
    markJoints(welded, faces, s, &edges);
    const double exact = assignCounts(welded, s, &edges, &faces);
    if (exact > double(kMaxSnowTriangles))
        return fail(error, "snow: uniform subdivision gives " +
                               std::to_string(uint64_t(std::min(exact, 1e18))) +
                               " triangles at target_edge_m " + std::to_string(s.target_edge_m) +
                               " (more than " + std::to_string(kMaxSnowTriangles) +
                               "; thin faces subdivide into many); raise target_edge_m");

    const Candidates cand = borderCandidates(welded, edges, faces, patches, s.d0_m);
    *layout = layOut(welded, edges, faces, cand, s.d0_m);
    *faces_used = faces.size();
    *patch_count = patches;
    return true;
}

}  // namespace snow_detail

namespace {

// v's offset from the line through `a` along the unit `along` (square to it).
glm::vec3 offsetFromLine(glm::vec3 a, glm::vec3 along, glm::vec3 v) {
    const glm::vec3 off = v - a;
    return off - along * glm::dot(off, along);
}

}  // namespace

float snowJointGap(const SnowBorderSide& p, const SnowBorderSide& q) {
    // From the edge line: a wind leans `inward` along the edge, so a plain offset from p.a would add the
    // length along the edge times that lean.
    const glm::vec3 d = p.b - p.a;
    const float len = glm::length(d);
    const glm::vec3 along = len > 0.0f ? d / len : glm::vec3(0.0f);
    const float beyond_a = glm::dot(offsetFromLine(p.a, along, q.a), p.inward);
    const float beyond_b = glm::dot(offsetFromLine(p.a, along, q.b), p.inward);
    return std::max(0.0f, -0.5f * (beyond_a + beyond_b));
}

std::vector<SnowBorderSide> snowBorderSides(const TriangleMesh& base, const SnowSettings& s) {
    if (!validateMesh(base, nullptr) || !validateSnowSettings(s, nullptr)) return {};
    std::vector<uint32_t> weld;
    std::vector<glm::vec3> welded;
    weldVertices(base, &weld, &welded);
    std::vector<SnowFace> faces = upFacingFaces(base, weld, s);
    const std::vector<SnowEdge> edges = buildEdges(&faces);
    std::vector<SnowBorderSide> out;
    for (const Side& side : borderSides(welded, faces, edges, snow_detail::unitUp(s))) out.push_back(side.geo);
    return out;
}

namespace {

// q's ends beyond p's edge (away from p's face) by -overlap_m to the gap, at the height of p's edge line,
// and alongside p over at least half the shorter edge.
bool facing(const SnowBorderSide& p, const SnowBorderSide& q, float overlap_m) {
    const glm::vec3 dp = p.b - p.a, dq = q.b - q.a;
    const float lp = glm::length(dp), lq = glm::length(dq);
    if (!(lp > 0.0f && lq > 0.0f)) return false;
    if (std::fabs(glm::dot(dp, dq)) < 0.996f * lp * lq || glm::dot(p.inward, q.inward) > -0.9f) return false;
    const glm::vec3 along = dp / lp;
    for (const glm::vec3 v : {q.a, q.b}) {
        // Heights are vertical (objects turn only about Z) and taken from p's edge line, not from its end
        // along the snow's `up`: with a wind, `up` leans along every horizontal edge that runs with the
        // wind, and q's ends, a paving stone's length along that edge, seemed centimetres higher or lower
        // (the cobbles' rows were never bridged: a groove down to the stone between every two rows).
        const glm::vec3 across = offsetFromLine(p.a, along, v);
        const float gap = -glm::dot(across, p.inward);
        if (gap < -overlap_m || gap > kSnowJointGapM || std::fabs(across.z) > kSnowJointHeightM) return false;
    }
    const float t0 = glm::dot(q.a - p.a, along), t1 = glm::dot(q.b - p.a, along);
    const float overlap = std::min(lp, std::max(t0, t1)) - std::max(0.0f, std::min(t0, t1));
    return overlap >= 0.5f * std::min(lp, lq);
}

}  // namespace

bool snowSidesMeet(const SnowBorderSide& p, const SnowBorderSide& q, float overlap_m) {
    return facing(p, q, overlap_m) && facing(q, p, overlap_m);
}

bool buildGeometrySnow(const TriangleMesh& base, const SnowSettings& s, const EnvQuery& env, SnowCover* out,
                       std::string* error) {
    snow_detail::SnowLayout layout;
    size_t faces = 0, patches = 0;
    if (!snow_detail::layOutGeometrySnow(base, s, env, &layout, &faces, &patches, error)) return false;
    return snow_detail::finishSnowCover(std::move(layout), s, env, /*zero_below_min_open=*/false, faces,
                                        patches, out, error);
}

}  // namespace ug
