#include "particles/particle_seeding.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/hash.h"

namespace ug {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMargin = 1.0 / 1024.0;  // of a cell's width, see the header
constexpr uint64_t kSeedTag = 0x5eed'9a27'1c1e'0000ull;

// A rectangle of the surface in the area parameterisation: point(s, t) for s, t in [0, 1].
struct Face {
    glm::dvec3 origin, u, v;  // point = origin + s·u + t·v (rectangles, box faces)
    glm::dvec3 normal;
    uint32_t first = 0, count = 0;  // strata of this face
    uint32_t rows = 1;
};

// floor(r · n / rows): the first cell of row r.
uint32_t rowStart(uint32_t r, uint32_t n, uint32_t rows) { return uint32_t(uint64_t(r) * n / rows); }

uint32_t rowsFor(uint32_t n, double width, double height) {
    if (n == 0) return 1;
    const double r = std::round(std::sqrt(double(n) * height / width));
    return uint32_t(std::clamp(r, 1.0, double(n)));
}

// The faces of a generator: one for a rectangle and a sphere (whose (s, t) map is not planar, see
// spherePoint), six for a box with counts in proportion to their areas.
std::vector<Face> facesOf(const ParticleGenerator& g) {
    std::vector<Face> faces;
    const glm::dvec3 c(g.center_m);
    if (g.kind == GeneratorKind::Rectangle) {
        const glm::dvec3 u(g.axis_u_m), v(g.axis_v_m);
        Face f{c - u - v, 2.0 * u, 2.0 * v, glm::normalize(glm::cross(u, v)), 0, g.count, 1};
        f.rows = rowsFor(g.count, glm::length(f.u), glm::length(f.v));
        faces.push_back(f);
    } else if (g.kind == GeneratorKind::Sphere) {
        Face f{c, {}, {}, {}, 0, g.count, rowsFor(g.count, 2.0 * kPi, 2.0)};
        faces.push_back(f);
    } else {
        const glm::dvec3 h(g.half_extents_m);
        double area[6], total = 0.0;
        for (int a = 0; a < 3; ++a) {
            const int b = (a + 1) % 3, d = (a + 2) % 3;
            area[2 * a] = area[2 * a + 1] = 4.0 * h[b] * h[d];
            total += 2.0 * area[2 * a];
        }
        double running = 0.0;
        uint32_t first = 0;
        for (int k = 0; k < 6; ++k) {
            const int a = k / 2, b = (a + 1) % 3, d = (a + 2) % 3;
            const double sign = (k % 2 == 0) ? 1.0 : -1.0;
            running += area[k];
            const uint32_t end = k == 5 ? g.count : uint32_t(std::floor(running / total * double(g.count)));
            glm::dvec3 n(0.0), u(0.0), v(0.0);
            n[a] = sign;
            u[b] = 2.0 * h[b];
            v[d] = 2.0 * h[d] * sign;  // keeps u × v along the outward normal
            const glm::dvec3 origin = c + n * h[a] - 0.5 * u - 0.5 * v;
            Face f{origin, u, v, n, first, end - first, 1};
            f.rows = rowsFor(f.count, glm::length(u), glm::length(v));
            faces.push_back(f);
            first = end;
        }
    }
    return faces;
}

void spherePoint(const ParticleGenerator& g, double s, double t, glm::dvec3* p, glm::dvec3* n) {
    const double phi = 2.0 * kPi * s, z = 1.0 - 2.0 * t, rho = std::sqrt(std::max(0.0, 1.0 - z * z));
    *n = glm::dvec3(rho * std::cos(phi), rho * std::sin(phi), z);
    *p = glm::dvec3(g.center_m) + double(g.radius_m) * *n;
}

// The cell of stratum j (face-local) as [s0, s1] × [t0, t1].
void cellOf(const Face& f, uint32_t j, double* s0, double* s1, double* t0, double* t1) {
    uint32_t r = uint32_t(uint64_t(j) * f.rows / f.count);
    while (r + 1 < f.rows && rowStart(r + 1, f.count, f.rows) <= j) ++r;
    while (r > 0 && rowStart(r, f.count, f.rows) > j) --r;
    const uint32_t a = rowStart(r, f.count, f.rows), b = rowStart(r + 1, f.count, f.rows);
    const uint32_t cells = b - a, col = j - a;
    *t0 = double(a) / f.count;
    *t1 = double(b) / f.count;
    *s0 = double(col) / cells;
    *s1 = double(col + 1) / cells;
}

// Face-local stratum of parameters (s, t), the inverse of cellOf.
uint32_t stratumAt(const Face& f, double s, double t) {
    if (f.count == 0) return 0;
    s = std::clamp(s, 0.0, 1.0);
    t = std::clamp(t, 0.0, 1.0);
    uint32_t r = std::min(f.rows - 1, uint32_t(t * f.rows));
    while (r + 1 < f.rows && double(rowStart(r + 1, f.count, f.rows)) / f.count <= t) ++r;
    while (r > 0 && double(rowStart(r, f.count, f.rows)) / f.count > t) --r;
    const uint32_t a = rowStart(r, f.count, f.rows), b = rowStart(r + 1, f.count, f.rows);
    return a + std::min(b - a - 1, uint32_t(s * double(b - a)));
}

// A mesh generator's area parameterisation: u in [0, 1) is the fraction of the total area before the
// point, triangles in file order; inside triangle k (corners a, b, c) a point at area fraction r of it lies
// on the segment between a + √r·(b − a) and a + √r·(c − a) (the sub-triangle at a of that size has area
// r · area_k), at the fraction w of that segment.
struct MeshAreas {
    std::vector<double> before;  // area before triangle k, scaled; before.back() = the total
    double total = 0.0;
};

MeshAreas meshAreas(const ParticleGenerator& g) {
    MeshAreas m;
    const size_t n = g.mesh->indices.size() / 3;
    m.before.resize(n + 1, 0.0);
    const double s2 = double(g.scale) * double(g.scale);
    for (size_t k = 0; k < n; ++k) m.before[k + 1] = m.before[k] + s2 * meshTriangleArea(*g.mesh, k);
    m.total = m.before[n];
    return m;
}

glm::dvec3 meshCorner(const ParticleGenerator& g, size_t k, int corner) {
    return glm::dvec3(g.center_m) + double(g.scale) * glm::dvec3(g.mesh->positions[g.mesh->indices[3 * k + corner]]);
}

// The point at area fraction u (and w across), and its triangle's normal.
void meshPoint(const ParticleGenerator& g, const MeshAreas& m, double u, double w, glm::dvec3* p, glm::dvec3* n) {
    const double target = u * m.total;
    // The triangle whose slice holds target: the last with before[k] <= target and a positive area.
    size_t k = size_t(std::upper_bound(m.before.begin(), m.before.end() - 1, target) - m.before.begin());
    k = k > 0 ? k - 1 : 0;
    while (k + 1 < m.before.size() - 1 && !(m.before[k + 1] > m.before[k])) ++k;
    const double area = m.before[k + 1] - m.before[k];
    const double r = area > 0.0 ? std::clamp((target - m.before[k]) / area, 0.0, 1.0) : 0.0;
    const glm::dvec3 a = meshCorner(g, k, 0), b = meshCorner(g, k, 1), c = meshCorner(g, k, 2);
    const double s = std::sqrt(r);
    *p = a + s * ((1.0 - w) * (b - a) + w * (c - a));
    *n = glm::cross(b - a, c - a);
}

}  // namespace

glm::vec3 coneDirection(float cone_rad, float u, float v) { return coneDirectionCos(std::cos(cone_rad), u, v); }

glm::vec3 coneDirectionCos(float cos_cone, float u, float v) {
    const float cos_t = 1.0f - u * (1.0f - cos_cone);
    const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
    const float psi = 2.0f * float(kPi) * v;
    return glm::vec3(sin_t * std::cos(psi), sin_t * std::sin(psi), cos_t);
}

glm::quat turnFrameTo(const glm::quat& from, glm::vec3 d) {
    const glm::vec3 h = from * glm::vec3(0.0f, 0.0f, 1.0f);
    const float c = glm::dot(h, d);
    glm::quat turn;
    if (c < -0.999999f) {
        // Opposite: any half turn about an axis orthogonal to h; the frame's own x is one.
        turn = glm::angleAxis(float(kPi), glm::normalize(from * glm::vec3(1.0f, 0.0f, 0.0f)));
    } else {
        // The shortest arc from h to d, (1 + c, h × d) normalised.
        const glm::vec3 axis = glm::cross(h, d);
        turn = glm::normalize(glm::quat(1.0f + c, axis.x, axis.y, axis.z));
    }
    return glm::normalize(turn * from);
}

void seedGenerator(const ParticleGenerator& gen, uint32_t generator_index, uint64_t seed, ParticleSeeds* out,
                   const HeightField* terrain) {
    const float cone = glm::radians(gen.heading_cone_deg);
    const glm::quat identity(1.0f, 0.0f, 0.0f, 0.0f);
    // A generator on gathered surfaces without them (grown alone) has nothing to seed on.
    if (hasNoPlacedSurface(gen)) return;
    // A mesh's strata are slices of its cumulative area: one face of `count` strata in one row, whose s
    // is the area fraction and t the place across the slice's triangle.
    const MeshAreas areas = seedsOnMesh(gen) ? meshAreas(gen) : MeshAreas{};
    std::vector<Face> faces;
    if (seedsOnMesh(gen))
        faces.push_back(Face{{}, {}, {}, {}, 0, gen.count, 1});
    else
        faces = facesOf(gen);
    for (const Face& f : faces)
        for (uint32_t j = 0; j < f.count; ++j) {
            const uint32_t stratum = f.first + j;
            const uint64_t h = hashWords(seed, kSeedTag + generator_index, stratum);
            double s0, s1, t0, t1;
            cellOf(f, j, &s0, &s1, &t0, &t1);
            const double js = kMargin + (1.0 - 2.0 * kMargin) * unitDouble(h);
            const double jt = kMargin + (1.0 - 2.0 * kMargin) * unitDouble(mix64(h));
            const double s = s0 + (s1 - s0) * js, t = t0 + (t1 - t0) * jt;
            glm::dvec3 p, n;
            if (gen.kind == GeneratorKind::Sphere) {
                spherePoint(gen, s, t, &p, &n);
            } else if (seedsOnMesh(gen)) {
                meshPoint(gen, areas, s, t, &p, &n);
            } else {
                p = f.origin + s * f.u + t * f.v;
                n = f.normal;
                if (gen.on_terrain) {
                    const glm::vec3 hg = terrain->sampleWithGradient(float(p.x), float(p.y));
                    p.z = double(hg.x);
                    n = glm::dvec3(-hg.y, -hg.z, 1.0);
                }
            }
            const glm::vec3 normal = glm::normalize(glm::vec3(n));
            const glm::quat on_normal = turnFrameTo(identity, normal);
            glm::vec3 heading = normal;
            if (cone > 0.0f) {
                const uint64_t hh = mix64(mix64(h));
                heading = glm::normalize(on_normal * coneDirection(cone, unitFloat(hh), unitFloat(mix64(hh))));
            }
            out->positions.push_back(glm::vec3(p));
            out->normals.push_back(normal);
            out->frames.push_back(turnFrameTo(on_normal, heading));
        }
}

uint32_t locateStratum(const ParticleGenerator& gen, glm::vec3 p_f) {
    const glm::dvec3 p(p_f), c(gen.center_m);
    if (hasNoPlacedSurface(gen)) return 0;
    if (seedsOnMesh(gen)) {
        // The triangle p lies in (the nearest by its barycentric coordinates' excess), then its area fraction.
        const MeshAreas m = meshAreas(gen);
        size_t best = 0;
        double best_excess = std::numeric_limits<double>::infinity(), best_s = 0.0;
        for (size_t k = 0; k + 1 < m.before.size(); ++k) {
            if (!(m.before[k + 1] > m.before[k])) continue;
            const glm::dvec3 a = meshCorner(gen, k, 0), b = meshCorner(gen, k, 1), cc = meshCorner(gen, k, 2);
            const glm::dvec3 e1 = b - a, e2 = cc - a, d = p - a, nn = glm::cross(e1, e2);
            const double inv = 1.0 / glm::dot(nn, nn);
            const double lb = glm::dot(glm::cross(d, e2), nn) * inv, lc = glm::dot(glm::cross(e1, d), nn) * inv;
            const double off = std::abs(glm::dot(d, nn)) * std::sqrt(inv);  // distance to the plane
            const double excess = off + std::max(0.0, -lb) + std::max(0.0, -lc) + std::max(0.0, lb + lc - 1.0);
            if (excess < best_excess) {
                best_excess = excess;
                best = k;
                best_s = lb + lc;
            }
        }
        const double r = std::clamp(best_s * best_s, 0.0, 1.0);
        const double u = (m.before[best] + r * (m.before[best + 1] - m.before[best])) / m.total;
        return std::min(gen.count - 1, uint32_t(std::max(0.0, u) * double(gen.count)));
    }
    const std::vector<Face> faces = facesOf(gen);
    if (gen.kind == GeneratorKind::Sphere) {
        const glm::dvec3 d = glm::normalize(p - c);
        double phi = std::atan2(d.y, d.x);
        if (phi < 0.0) phi += 2.0 * kPi;
        return stratumAt(faces[0], phi / (2.0 * kPi), (1.0 - d.z) / 2.0);
    }
    size_t k = 0;
    if (gen.kind == GeneratorKind::Box) {
        // The face whose plane p is nearest to, relative to the box's size along it.
        const glm::dvec3 q = (p - c) / glm::dvec3(gen.half_extents_m);
        int a = 0;
        for (int b = 1; b < 3; ++b)
            if (std::abs(q[b]) > std::abs(q[a])) a = b;
        k = size_t(2 * a + (q[a] < 0.0 ? 1 : 0));
    }
    const Face& f = faces[k];
    const glm::dvec3 r = p - f.origin;
    return f.first + stratumAt(f, glm::dot(r, f.u) / glm::dot(f.u, f.u), glm::dot(r, f.v) / glm::dot(f.v, f.v));
}

}  // namespace ug
