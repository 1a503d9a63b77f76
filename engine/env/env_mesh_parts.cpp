// Flat-shaded closed parts for the environmental starter models (see env_mesh_parts.h for why).
#include "env/env_mesh_parts.h"

#include <cassert>
#include <cmath>
#include <functional>

namespace ug::envparts {
namespace {

constexpr float kPi = 3.14159265358979f;

// The 6 faces of a lattice box: point(i, j, k) is lattice vertex (i, j, k), 0 <= i <= cells.x etc.;
// axis(k) is the world direction of lattice axis k. Corners shared by two faces come from the same
// call, so they are bit-identical and the box is closed once welded.
void addLatticeBox(MeshBuilder* b, const glm::ivec3& cells,
                   const std::function<glm::vec3(int, int, int)>& point,
                   const std::function<glm::vec3(int)>& axis) {
    for (int k = 0; k < 3; ++k) {
        const int a1 = (k + 1) % 3, a2 = (k + 2) % 3;
        for (int side = 0; side < 2; ++side) {
            const glm::vec3 outward = side ? axis(k) : -axis(k);
            const int nu = cells[a1], nv = cells[a2];
            std::vector<uint32_t> ids;
            ids.reserve(size_t(nu + 1) * size_t(nv + 1));
            for (int i = 0; i <= nu; ++i)
                for (int j = 0; j <= nv; ++j) {
                    glm::ivec3 l(0);
                    l[k] = side * cells[k];
                    l[a1] = i;
                    l[a2] = j;
                    ids.push_back(b->vertex(point(l.x, l.y, l.z)));
                }
            auto at = [&](int i, int j) { return ids[size_t(i) * size_t(nv + 1) + size_t(j)]; };
            for (int i = 0; i < nu; ++i)
                for (int j = 0; j < nv; ++j) {
                    b->tri(at(i, j), at(i + 1, j), at(i + 1, j + 1), outward);
                    b->tri(at(i, j), at(i + 1, j + 1), at(i, j + 1), outward);
                }
        }
    }
}

// i/n of the way from lo to hi, exactly hi at i = n.
float lattice(float lo, float hi, int i, int n) {
    return i == n ? hi : lo + (hi - lo) * (float(i) / float(n));
}

}  // namespace

uint32_t MeshBuilder::vertex(const glm::vec3& p) {
    mesh_.positions.push_back(p);
    return uint32_t(mesh_.positions.size() - 1);
}

void MeshBuilder::tri(uint32_t a, uint32_t b, uint32_t c, const glm::vec3& outward) {
    const glm::vec3 n =
        glm::cross(mesh_.positions[b] - mesh_.positions[a], mesh_.positions[c] - mesh_.positions[a]);
    if (glm::dot(n, outward) < 0.0f) std::swap(b, c);
    mesh_.indices.insert(mesh_.indices.end(), {a, b, c});
}

void MeshBuilder::face(const std::vector<glm::vec3>& polygon, const glm::vec3& outward) {
    assert(polygon.size() >= 3);
    std::vector<uint32_t> ids;
    for (const glm::vec3& p : polygon) ids.push_back(vertex(p));
    for (size_t k = 1; k + 1 < ids.size(); ++k) tri(ids[0], ids[k], ids[k + 1], outward);
}

TriangleMesh MeshBuilder::finish(const glm::vec3& color) {
    TriangleMesh m = std::move(mesh_);
    mesh_ = TriangleMesh();
    m.base_color = color;
    computeNormals(&m);
    return m;
}

void addBox(MeshBuilder* b, const Box& box) {
    auto coord = [&](int k, int i) { return lattice(-box.half[k], box.half[k], i, box.cells[k]); };
    addLatticeBox(
        b, box.cells,
        [&](int i, int j, int k) {
            return box.centre + box.axes[0] * coord(0, i) + box.axes[1] * coord(1, j) +
                   box.axes[2] * coord(2, k);
        },
        [&](int k) { return box.axes[k]; });
}

void addBox(MeshBuilder* b, const glm::vec3& lo, const glm::vec3& hi, const glm::ivec3& cells) {
    assert(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z);
    addLatticeBox(
        b, cells,
        [&](int i, int j, int k) {
            return glm::vec3(lattice(lo.x, hi.x, i, cells.x), lattice(lo.y, hi.y, j, cells.y),
                             lattice(lo.z, hi.z, k, cells.z));
        },
        [](int k) {
            glm::vec3 a(0.0f);
            a[k] = 1.0f;
            return a;
        });
}

void addPrism(MeshBuilder* b, const std::vector<glm::vec2>& convex_profile, const glm::vec3& origin,
              const glm::vec3& U, const glm::vec3& V, float depth) {
    assert(convex_profile.size() >= 3 && depth > 0.0f);
    const glm::vec3 W = glm::cross(U, V) * depth;
    std::vector<glm::vec3> front, back;
    glm::vec2 centroid(0.0f);
    for (const glm::vec2& q : convex_profile) {
        front.push_back(origin + q.x * U + q.y * V);
        back.push_back(front.back() + W);
        centroid += q / float(convex_profile.size());
    }
    b->face(front, -W);
    b->face(back, W);
    const glm::vec3 c = origin + centroid.x * U + centroid.y * V;
    for (size_t k = 0; k < front.size(); ++k) {
        const size_t n = (k + 1) % front.size();
        const glm::vec3 mid = 0.5f * (front[k] + front[n]);
        b->face({front[k], front[n], back[n], back[k]}, mid - c);
    }
}

void addLathe(MeshBuilder* b, const glm::vec3& base, const std::vector<glm::vec2>& profile, int segments) {
    assert(profile.size() >= 3 && segments >= 3);
    auto point = [&](const glm::vec2& rz, int j) {
        const float a = 2.0f * kPi * float(j % segments) / float(segments);
        return base + glm::vec3(rz.x * std::cos(a), rz.x * std::sin(a), rz.y);
    };
    // The ring of a profile point: `segments` vertices, or the one vertex on the axis.
    auto ring = [&](const glm::vec2& rz) {
        std::vector<uint32_t> ids;
        if (rz.x <= 0.0f) return std::vector<uint32_t>{b->vertex(base + glm::vec3(0, 0, rz.y))};
        for (int j = 0; j < segments; ++j) ids.push_back(b->vertex(point(rz, j)));
        return ids;
    };
    for (size_t e = 0; e < profile.size(); ++e) {
        const glm::vec2 p0 = profile[e], p1 = profile[(e + 1) % profile.size()];
        if (p0.x <= 0.0f && p1.x <= 0.0f) continue;  // on the axis: nothing to close
        const glm::vec2 d = p1 - p0;
        const glm::vec2 n(d.y, -d.x);  // outward: right of the direction of a counter-clockwise profile
        const std::vector<uint32_t> r0 = ring(p0), r1 = ring(p1);
        auto at = [&](const std::vector<uint32_t>& r, int j) {
            return r[r.size() == 1 ? 0 : size_t(j % segments)];
        };
        for (int j = 0; j < segments; ++j) {
            const float a = 2.0f * kPi * (float(j) + 0.5f) / float(segments);
            const glm::vec3 outward(n.x * std::cos(a), n.x * std::sin(a), n.y);
            if (r0.size() > 1) b->tri(at(r0, j), at(r0, j + 1), at(r1, j + 1), outward);
            if (r1.size() > 1) b->tri(at(r0, j), at(r1, j + 1), at(r1, j), outward);
        }
    }
}

void addTube(MeshBuilder* b, const std::vector<glm::vec3>& line, const std::vector<float>& radii, int sides) {
    assert(line.size() >= 2 && radii.size() == line.size() && sides >= 3);
    // Parallel transport keeps the rings from twisting along the line.
    const glm::vec3 t0 = glm::normalize(line[1] - line[0]);
    glm::vec3 n1 = std::abs(t0.z) < 0.9f ? glm::normalize(glm::cross(t0, glm::vec3(0, 0, 1)))
                                         : glm::normalize(glm::cross(t0, glm::vec3(1, 0, 0)));
    std::vector<glm::vec3> rings;
    for (size_t k = 0; k < line.size(); ++k) {
        const glm::vec3 t =
            glm::normalize(k + 1 < line.size() ? line[k + 1] - line[k] : line[k] - line[k - 1]);
        const glm::vec3 tk = k > 0 && k + 1 < line.size() ? glm::normalize(line[k + 1] - line[k - 1]) : t;
        n1 = glm::normalize(n1 - glm::dot(n1, tk) * tk);
        const glm::vec3 n2 = glm::cross(tk, n1);
        for (int j = 0; j < sides; ++j) {
            const float a = 2.0f * kPi * float(j) / float(sides);
            rings.push_back(line[k] + radii[k] * (std::cos(a) * n1 + std::sin(a) * n2));
        }
    }
    auto pos = [&](size_t k, int j) { return rings[k * size_t(sides) + size_t(j % sides)]; };
    // Sides: one smooth group, the vertices shared between segments.
    std::vector<uint32_t> ids;
    for (const glm::vec3& p : rings) ids.push_back(b->vertex(p));
    auto id = [&](size_t k, int j) { return ids[k * size_t(sides) + size_t(j % sides)]; };
    for (size_t k = 0; k + 1 < line.size(); ++k)
        for (int j = 0; j < sides; ++j) {
            const glm::vec3 mid = 0.5f * (pos(k, j) + pos(k + 1, j + 1));
            const glm::vec3 axis_point = 0.5f * (line[k] + line[k + 1]);
            b->tri(id(k, j), id(k, j + 1), id(k + 1, j), mid - axis_point);
            b->tri(id(k, j + 1), id(k + 1, j + 1), id(k + 1, j), mid - axis_point);
        }
    // Caps: flat fans with vertices of their own (a hard edge all around).
    const size_t last = line.size() - 1;
    for (const size_t k : {size_t(0), last}) {
        const glm::vec3 outward = k == 0 ? line[0] - line[1] : line[last] - line[last - 1];
        const uint32_t c = b->vertex(line[k]);
        std::vector<uint32_t> cap;
        for (int j = 0; j < sides; ++j) cap.push_back(b->vertex(pos(k, j)));
        for (int j = 0; j < sides; ++j) b->tri(c, cap[size_t(j)], cap[size_t((j + 1) % sides)], outward);
    }
}

void addCylinder(MeshBuilder* b, const glm::vec3& from, const glm::vec3& to, float radius, int sides) {
    addTube(b, {from, to}, {radius, radius}, sides);
}

}  // namespace ug::envparts
