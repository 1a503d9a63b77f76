// Automatic icicle anchors: the base mesh's drip edges (icicles.h has the criterion), chained into
// polylines and sampled every spacing_m. An own edge map (sorted arrays) rather than OpenMesh, because
// input meshes are often split-vertex, non-manifold or open, and sorting gives a canonical order for free.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "env/icicles.h"

namespace ug {
namespace {

// Face normals pointing below this (n·up) make an underside that water cannot follow.
constexpr float kUndersideUp = -0.2f;
// A face within 5° of horizontal drains over every side: sin(5°).
constexpr float kFlatSlope = 0.0871557f;
// A rim is downhill when its outward direction is within 60° of the steepest descent: cos(60°).
constexpr float kDownhillCos = 0.5f;
// Chains continue through a vertex only when the drip edge turns by at most 30° there: cos(30°).
constexpr float kChainTurnCos = 0.8660254f;

struct Welded {
    std::vector<uint32_t> id;        // per input vertex: welded vertex id (rank of its position)
    std::vector<glm::vec3> position; // per welded vertex
};

// Welds vertices of exactly equal position; welded ids follow the position order (x, then y, then z), so
// everything built on them is independent of the input's vertex order.
Welded weldByPosition(const std::vector<glm::vec3>& positions) {
    struct Keyed {
        glm::vec3 p;
        uint32_t index;
    };
    std::vector<Keyed> sorted(positions.size());
    for (uint32_t i = 0; i < positions.size(); ++i) sorted[i] = {positions[i], i};
    std::sort(sorted.begin(), sorted.end(), [](const Keyed& a, const Keyed& b) {
        if (a.p.x != b.p.x) return a.p.x < b.p.x;
        if (a.p.y != b.p.y) return a.p.y < b.p.y;
        if (a.p.z != b.p.z) return a.p.z < b.p.z;
        return a.index < b.index;
    });
    Welded w;
    w.id.resize(positions.size());
    for (size_t k = 0; k < sorted.size(); ++k) {
        if (k == 0 || sorted[k].p != sorted[k - 1].p) w.position.push_back(sorted[k].p);
        w.id[sorted[k].index] = uint32_t(w.position.size() - 1);
    }
    return w;
}

// One side of an edge: the face and its vertex opposite the edge.
struct HalfEdge {
    uint32_t a, b;      // welded ids, a < b
    uint32_t face;      // triangle index
    uint32_t opposite;  // welded id of the face's third vertex
};

struct FaceFrame {
    glm::vec3 normal{0.0f};  // unit; zero for a degenerate face
};

struct EdgeMap {
    std::vector<HalfEdge> half;     // sorted by (a, b, face)
    std::vector<FaceFrame> faces;   // per triangle
};

// Orders half-edges by (a, b, face) in linear time: a counting sort by a (stable, and the input comes in
// face order), then each bucket (the few edges of one vertex) by b, stably. A comparison sort of all
// half-edges was the bottleneck on facade-sized meshes.
void sortHalfEdges(std::vector<HalfEdge>* half, size_t vertex_count) {
    std::vector<uint32_t> first(vertex_count + 1, 0);
    for (const HalfEdge& h : *half) ++first[h.a + 1];
    for (size_t v = 1; v <= vertex_count; ++v) first[v] += first[v - 1];
    std::vector<HalfEdge> sorted(half->size());
    std::vector<uint32_t> fill(first.begin(), first.end() - 1);
    for (const HalfEdge& h : *half) sorted[fill[h.a]++] = h;
    for (size_t v = 0; v < vertex_count; ++v)  // insertion sort: stable, no allocation, buckets are small
        for (uint32_t i = first[v] + 1; i < first[v + 1]; ++i) {
            const HalfEdge h = sorted[i];
            uint32_t j = i;
            for (; j > first[v] && sorted[j - 1].b > h.b; --j) sorted[j] = sorted[j - 1];
            sorted[j] = h;
        }
    *half = std::move(sorted);
}

EdgeMap buildEdgeMap(const TriangleMesh& base, const Welded& w) {
    EdgeMap m;
    const size_t tri_count = base.triangleCount();
    m.faces.resize(tri_count);
    m.half.reserve(tri_count * 3);
    for (size_t t = 0; t < tri_count; ++t) {
        const uint32_t v[3] = {w.id[base.indices[3 * t]], w.id[base.indices[3 * t + 1]], w.id[base.indices[3 * t + 2]]};
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;
        const glm::vec3 n = glm::cross(w.position[v[1]] - w.position[v[0]], w.position[v[2]] - w.position[v[0]]);
        const float len = glm::length(n);
        if (!(len > 1e-20f) || !std::isfinite(len)) continue;  // degenerate: no slope, no side
        m.faces[t].normal = n / len;
        for (int k = 0; k < 3; ++k) {
            const uint32_t p = v[k], q = v[(k + 1) % 3];
            m.half.push_back({std::min(p, q), std::max(p, q), uint32_t(t), v[(k + 2) % 3]});
        }
    }
    sortHalfEdges(&m.half, w.position.size());
    return m;
}

// Does water on this face flow over the edge (a, b)? (icicles.h: "downhill rim")
bool isDownhillRim(const HalfEdge& h, const glm::vec3& normal, const Welded& w, const glm::vec3& up) {
    const glm::vec3 descent = -up + glm::dot(up, normal) * normal;  // -up projected on the face plane
    const float slope = glm::length(descent);
    if (slope < kFlatSlope) return true;
    const glm::vec3 pa = w.position[h.a], pb = w.position[h.b];
    const glm::vec3 along = glm::normalize(pb - pa);
    glm::vec3 outward = pa - w.position[h.opposite];
    outward -= glm::dot(outward, along) * along;
    const float out_len = glm::length(outward);
    if (!(out_len > 0.0f)) return false;
    return glm::dot(outward / out_len, descent / slope) > kDownhillCos;
}

bool isDripEdge(const HalfEdge* sides, size_t count, const EdgeMap& m, const Welded& w, const IcicleSettings& s,
                float sharp_cos) {
    if (count == 1) return isDownhillRim(sides[0], m.faces[sides[0].face].normal, w, s.up);
    if (count != 2) return false;
    const glm::vec3 n0 = m.faces[sides[0].face].normal, n1 = m.faces[sides[1].face].normal;
    if (!(glm::dot(n0, n1) < sharp_cos)) return false;
    const bool under0 = glm::dot(n0, s.up) < kUndersideUp, under1 = glm::dot(n1, s.up) < kUndersideUp;
    return (under1 && isDownhillRim(sides[0], n0, w, s.up)) || (under0 && isDownhillRim(sides[1], n1, w, s.up));
}

struct DripEdge {
    uint32_t a, b;  // welded ids
};

std::vector<DripEdge> findDripEdges(const EdgeMap& m, const Welded& w, const IcicleSettings& s) {
    const float sharp_cos = std::cos(glm::radians(s.sharp_angle_deg));
    std::vector<DripEdge> drips;
    for (size_t i = 0; i < m.half.size();) {
        size_t j = i + 1;
        while (j < m.half.size() && m.half[j].a == m.half[i].a && m.half[j].b == m.half[i].b) ++j;
        if (isDripEdge(&m.half[i], j - i, m, w, s, sharp_cos)) drips.push_back({m.half[i].a, m.half[i].b});
        i = j;
    }
    return drips;
}

// Drip edges grouped into polylines (vertex lists, welded ids); `closed` marks loops.
struct Chain {
    std::vector<uint32_t> vertices;
    bool closed = false;
};

class Chainer {
public:
    Chainer(const std::vector<DripEdge>& edges, const Welded& w) : edges_(edges), w_(w) {
        // CSR adjacency: vertex -> incident drip edges, in edge order.
        first_.assign(w.position.size() + 1, 0);
        for (const DripEdge& e : edges) ++first_[e.a + 1], ++first_[e.b + 1];
        for (size_t v = 1; v < first_.size(); ++v) first_[v] += first_[v - 1];
        incident_.resize(edges.size() * 2);
        std::vector<uint32_t> fill(first_.begin(), first_.end() - 1);
        for (uint32_t e = 0; e < edges.size(); ++e) {
            incident_[fill[edges[e].a]++] = e;
            incident_[fill[edges[e].b]++] = e;
        }
        used_.assign(edges.size(), false);
    }

    std::vector<Chain> chains() {
        std::vector<Chain> out;
        // Open chains first, each started from its break vertex found first in edge order ...
        for (uint32_t e = 0; e < edges_.size(); ++e)
            for (uint32_t start : {edges_[e].a, edges_[e].b})
                if (!used_[e] && isBreak(start)) out.push_back(walk(start, e));
        // ... then the loops that remain, each from its first edge's lower vertex.
        for (uint32_t e = 0; e < edges_.size(); ++e)
            if (!used_[e]) {
                Chain c = walk(edges_[e].a, e);
                c.closed = true;
                out.push_back(std::move(c));
            }
        return out;
    }

private:
    const std::vector<DripEdge>& edges_;
    const Welded& w_;
    std::vector<uint32_t> first_, incident_;
    std::vector<bool> used_;

    uint32_t other(uint32_t e, uint32_t v) const { return edges_[e].a == v ? edges_[e].b : edges_[e].a; }

    // A chain ends at v unless exactly two drip edges meet there with a gentle turn.
    bool isBreak(uint32_t v) const {
        if (first_[v + 1] - first_[v] != 2) return true;
        const uint32_t e0 = incident_[first_[v]], e1 = incident_[first_[v] + 1];
        const glm::vec3 in = glm::normalize(w_.position[v] - w_.position[other(e0, v)]);
        const glm::vec3 out = glm::normalize(w_.position[other(e1, v)] - w_.position[v]);
        return !(glm::dot(in, out) >= kChainTurnCos);
    }

    Chain walk(uint32_t start, uint32_t e) {
        Chain c;
        c.vertices.push_back(start);
        uint32_t v = start;
        while (true) {
            used_[e] = true;
            v = other(e, v);
            c.vertices.push_back(v);
            if (v == start || isBreak(v)) break;
            const uint32_t e0 = incident_[first_[v]], e1 = incident_[first_[v] + 1];
            e = used_[e0] ? e1 : e0;
            if (used_[e]) break;
        }
        return c;
    }
};

void sampleChain(const Chain& c, const Welded& w, float spacing, std::vector<IcicleAnchor>* out) {
    std::vector<float> arc(c.vertices.size(), 0.0f);
    for (size_t k = 1; k < c.vertices.size(); ++k)
        arc[k] = arc[k - 1] + glm::distance(w.position[c.vertices[k - 1]], w.position[c.vertices[k]]);
    const float length = arc.back();
    const size_t n = size_t(std::floor(length / spacing + 0.5f));
    if (n == 0) return;
    // Open chains: anchors `spacing` apart, centred. Loops: n even steps around (no seam gap).
    const float step = c.closed ? length / float(n) : spacing;
    const float first = c.closed ? 0.5f * step : 0.5f * (length - float(n - 1) * spacing);
    size_t seg = 1;
    for (size_t k = 0; k < n; ++k) {
        const float t = first + float(k) * step;
        while (seg + 1 < arc.size() && arc[seg] < t) ++seg;
        const glm::vec3 p0 = w.position[c.vertices[seg - 1]], p1 = w.position[c.vertices[seg]];
        const float seg_len = arc[seg] - arc[seg - 1];
        const float u = seg_len > 0.0f ? std::clamp((t - arc[seg - 1]) / seg_len, 0.0f, 1.0f) : 0.0f;
        out->push_back({p0 + u * (p1 - p0), glm::normalize(p1 - p0)});
    }
}

// A horizontal unit vector for authored anchors (no edge known).
glm::vec3 horizontalAxis(const glm::vec3& up) {
    const glm::vec3 ref = std::abs(up.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::normalize(ref - glm::dot(ref, up) * up);
}

bool fail(std::string* error, const std::string& reason) {
    if (error) *error = reason;
    return false;
}

bool checkBase(const TriangleMesh& base, std::string* error) {
    if (base.indices.size() % 3 != 0)
        return fail(error, "base mesh index count " + std::to_string(base.indices.size()) + " is not a multiple of 3");
    if (base.indices.empty()) return true;  // nothing to find, not an error
    std::string why;
    if (!validateMesh(base, &why)) return fail(error, "base mesh: " + why);
    return true;
}

}  // namespace

std::vector<IcicleAnchor> findIcicleAnchors(const TriangleMesh& base, const IcicleSettings& s, std::string* error) {
    std::vector<IcicleAnchor> anchors;
    if (const std::string why = validateIcicleSettings(s); !why.empty()) {
        fail(error, why);
        return {};
    }
    if (s.automatic_anchors && !base.indices.empty()) {
        if (!checkBase(base, error)) return {};
        const Welded w = weldByPosition(base.positions);
        const EdgeMap m = buildEdgeMap(base, w);
        const std::vector<DripEdge> drips = findDripEdges(m, w, s);
        double total = 0.0;
        for (const DripEdge& e : drips) total += double(glm::distance(w.position[e.a], w.position[e.b]));
        const double estimate = total / double(s.spacing_m) + double(drips.size()) + double(s.anchors.size());
        if (estimate > double(kMaxIcicleAnchors)) {
            fail(error, "about " + std::to_string(size_t(estimate)) + " icicle anchors (" + std::to_string(total) +
                            " m of drip edges every " + std::to_string(s.spacing_m) + " m) exceed the limit of " +
                            std::to_string(kMaxIcicleAnchors));
            return {};
        }
        anchors.reserve(size_t(estimate));
        for (const Chain& c : Chainer(drips, w).chains()) sampleChain(c, w, s.spacing_m, &anchors);
    }
    const glm::vec3 side = horizontalAxis(s.up);
    for (const glm::vec3& p : s.anchors) anchors.push_back({p, side});
    return anchors;
}

}  // namespace ug
