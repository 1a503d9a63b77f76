#include "particles/strand_mesh.h"

#include <cmath>

#include "core/hash.h"

namespace ug {

namespace {

// Any unit vector perpendicular to unit t.
glm::vec3 perpendicular(glm::vec3 t) {
    const glm::vec3 axis = std::fabs(t.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    return glm::normalize(glm::cross(t, axis));
}

// The tangent at point i: the mean of the segments meeting there (the segment itself at the ends);
// `previous` where the segments cancel or vanish.
glm::vec3 tangentAt(const glm::vec3* p, size_t n, size_t i, glm::vec3 previous) {
    const glm::vec3 d = p[std::min(i + 1, n - 1)] - p[i > 0 ? i - 1 : 0];
    const float len = glm::length(d);
    return len > 1e-12f ? d / len : previous;
}

}  // namespace

uint64_t strandTubeTriangles(const Strands& strands, uint32_t sides) {
    uint64_t total = 0;
    for (size_t s = 0; s < strands.size(); ++s) {
        const uint64_t n = strands.offsets[s + 1] - strands.offsets[s];
        if (n >= 2) total += 2ull * sides * (n - 1) + 2ull * (sides - 2);
    }
    return total;
}

bool strandTubeMesh(const Strands& strands, const StrandMeshSettings& settings, TriangleMesh* out,
                    std::string* error) {
    const uint32_t k = settings.sides;
    if (k < 3 || k > 32) {
        if (error) *error = "mesh.sides: " + std::to_string(k) + " is out of range [3, 32]";
        return false;
    }
    const uint64_t triangles = strandTubeTriangles(strands, k);
    if (triangles > settings.max_triangles) {
        if (error)
            *error = "mesh.max_triangles: the tubes need " + std::to_string(triangles) + " triangles, more than " +
                     std::to_string(settings.max_triangles) + "; use fewer sides, strands or steps";
        return false;
    }
    *out = TriangleMesh{};
    out->positions.reserve(size_t(strands.points.size()) * k);
    out->normals.reserve(size_t(strands.points.size()) * k);
    out->indices.reserve(size_t(triangles) * 3);
    const float turn = 2.0f * float(M_PI) / float(k);
    for (size_t s = 0; s < strands.size(); ++s) {
        const size_t first = strands.offsets[s], n = strands.offsets[s + 1] - first;
        if (n < 2) continue;
        const glm::vec3* p = strands.points.data() + first;
        const uint32_t base = uint32_t(out->positions.size());
        glm::vec3 t = tangentAt(p, n, 0, glm::vec3(0.0f, 0.0f, 1.0f));
        glm::vec3 normal = perpendicular(t);
        for (size_t i = 0; i < n; ++i) {
            const glm::vec3 next = tangentAt(p, n, i, t);
            // Parallel transport: the normal loses its component along the new tangent.
            glm::vec3 m = normal - glm::dot(normal, next) * next;
            normal = glm::length(m) > 1e-6f ? glm::normalize(m) : perpendicular(next);
            t = next;
            const glm::vec3 binormal = glm::cross(t, normal);
            const float r = strands.radii[first + i];
            for (uint32_t j = 0; j < k; ++j) {
                const glm::vec3 radial = std::cos(turn * float(j)) * normal + std::sin(turn * float(j)) * binormal;
                out->positions.push_back(p[i] + r * radial);
                out->normals.push_back(radial);
            }
        }
        // Around: quads between rings i and i + 1, wound outward (counter-clockwise seen from outside).
        for (uint32_t i = 0; i + 1 < uint32_t(n); ++i)
            for (uint32_t j = 0; j < k; ++j) {
                const uint32_t a = base + i * k + j, b = base + i * k + (j + 1) % k;
                const uint32_t c = a + k, d = b + k;
                out->indices.insert(out->indices.end(), {a, b, d, a, d, c});
            }
        // Ends: fans over the first ring (facing back) and the last (facing forward).
        const uint32_t last = base + uint32_t(n - 1) * k;
        for (uint32_t j = 1; j + 1 < k; ++j) {
            out->indices.insert(out->indices.end(), {base, base + j + 1, base + j});
            out->indices.insert(out->indices.end(), {last, last + j, last + j + 1});
        }
    }
    return true;
}

}  // namespace ug

namespace ug {

namespace {

constexpr uint64_t kBladeTurnTag = 0xb1ade'0000'0000ull;

// The first segment's unit direction, or up for a strand whose first segment vanishes.
glm::vec3 firstTangent(const glm::vec3* p, size_t n) { return tangentAt(p, n, 0, glm::vec3(0.0f, 0.0f, 1.0f)); }

bool refuseTriangles(uint64_t triangles, const StrandMeshSettings& settings, const char* what, std::string* error) {
    if (triangles <= settings.max_triangles) return true;
    if (error)
        *error = std::string("mesh.max_triangles: the ") + what + " need " + std::to_string(triangles) +
                 " triangles, more than " + std::to_string(settings.max_triangles) + "; use fewer strands or steps";
    return false;
}

}  // namespace

uint64_t strandBladeTriangles(const Strands& strands) {
    uint64_t total = 0;
    for (size_t s = 0; s < strands.size(); ++s) {
        const uint64_t n = strands.offsets[s + 1] - strands.offsets[s];
        if (n >= 2) total += 4ull * (n - 1);
    }
    return total;
}

bool strandBladeMesh(const Strands& strands, const StrandMeshSettings& settings, TriangleMesh* out,
                     std::string* error) {
    if (!(settings.blade_width_m >= 0.0f) || !(settings.blade_tip >= 0.0f && settings.blade_tip <= 1.0f)) {
        if (error) *error = "mesh.blade_width_m / mesh.blade_tip: out of range";
        return false;
    }
    const uint64_t triangles = strandBladeTriangles(strands);
    if (!refuseTriangles(triangles, settings, "blades", error)) return false;
    *out = TriangleMesh{};
    out->positions.reserve(size_t(strands.points.size()) * 4);
    out->normals.reserve(size_t(strands.points.size()) * 4);
    out->indices.reserve(size_t(triangles) * 3);
    for (size_t s = 0; s < strands.size(); ++s) {
        const size_t first = strands.offsets[s], n = strands.offsets[s + 1] - first;
        if (n < 2) continue;
        const glm::vec3* p = strands.points.data() + first;
        glm::vec3 t = firstTangent(p, n);
        // The across-direction: any perpendicular turned about the strand by a hashed angle.
        const glm::vec3 u = perpendicular(t), v = glm::cross(t, u);
        const uint64_t id = s < strands.particle.size() ? strands.particle[s] : s;
        const float angle = 2.0f * float(M_PI) * unitFloat(hashWords(kBladeTurnTag, id));
        glm::vec3 across = std::cos(angle) * u + std::sin(angle) * v;
        const uint32_t base = uint32_t(out->positions.size());
        for (size_t i = 0; i < n; ++i) {
            const glm::vec3 next = tangentAt(p, n, i, t);
            const glm::vec3 m = across - glm::dot(across, next) * next;
            across = glm::length(m) > 1e-6f ? glm::normalize(m) : perpendicular(next);
            t = next;
            const float root = settings.blade_width_m > 0.0f ? settings.blade_width_m : 4.0f * strands.radii[first + i];
            const float share = 1.0f + (settings.blade_tip - 1.0f) * float(i) / float(n - 1);
            const glm::vec3 half = 0.5f * root * share * across;
            // cross(across, t) is the face that (left, right, next right) winds counter-clockwise around.
            const glm::vec3 face = glm::normalize(glm::cross(across, t));
            for (const glm::vec3& normal : {face, -face}) {
                out->positions.push_back(p[i] - half);
                out->positions.push_back(p[i] + half);
                out->normals.push_back(normal);
                out->normals.push_back(normal);
            }
        }
        // Vertices per point: front left, front right, back left, back right.
        for (uint32_t i = 0; i + 1 < uint32_t(n); ++i) {
            const uint32_t a = base + 4 * i, c = a + 4;
            out->indices.insert(out->indices.end(), {a, a + 1, c + 1, a, c + 1, c});
            out->indices.insert(out->indices.end(), {a + 2, c + 3, a + 3, a + 2, c + 2, c + 3});
        }
    }
    return true;
}

bool strandMesh(const Strands& strands, const StrandMeshSettings& settings, TriangleMesh* out, std::string* error) {
    return settings.shape == StrandShape::Blade ? strandBladeMesh(strands, settings, out, error)
                                                : strandTubeMesh(strands, settings, out, error);
}

namespace {

float distanceToSegment(glm::vec3 p, glm::vec3 a, glm::vec3 b) {
    const glm::vec3 ab = b - a;
    const float len2 = glm::dot(ab, ab);
    const float t = len2 > 0.0f ? glm::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
    return glm::distance(p, a + t * ab);
}

// The points a level keeps of a strand of n points: every stride-th and the last.
uint32_t nextKept(uint32_t i, uint32_t stride, uint32_t n) { return std::min(i + stride, n - 1); }

}  // namespace

void strandMeshLevels(const Strands& strands, const StrandMeshSettings& settings, std::vector<MeshLodLevel>* out) {
    out->clear();
    const bool blades = settings.shape == StrandShape::Blade;
    const uint32_t k = settings.sides;
    size_t previous = 0;  // the previous level's indices (level 0's: the mesh's)
    for (size_t s = 0; s < strands.size(); ++s) {
        const uint32_t n = strands.offsets[s + 1] - strands.offsets[s];
        if (n >= 2) previous += 3 * (blades ? 4ull * (n - 1) : 2ull * k * (n - 1) + 2ull * (k - 2));
    }
    for (uint32_t stride : {2u, 4u, 8u}) {
        MeshLodLevel level;
        uint32_t base = 0;  // the strand's first vertex, as strandMesh lays them out
        for (size_t s = 0; s < strands.size(); ++s) {
            const uint32_t first = strands.offsets[s], n = strands.offsets[s + 1] - first;
            if (n < 2) continue;
            const glm::vec3* p = strands.points.data() + first;
            for (uint32_t i = 0; i + 1 < n; i = nextKept(i, stride, n)) {
                const uint32_t j = nextKept(i, stride, n);
                for (uint32_t m = i + 1; m < j; ++m) level.error_m = std::max(level.error_m, distanceToSegment(p[m], p[i], p[j]));
                if (blades) {
                    const uint32_t a = base + 4 * i, c = base + 4 * j;
                    level.indices.insert(level.indices.end(), {a, a + 1, c + 1, a, c + 1, c});
                    level.indices.insert(level.indices.end(), {a + 2, c + 3, a + 3, a + 2, c + 2, c + 3});
                } else {
                    for (uint32_t r = 0; r < k; ++r) {
                        const uint32_t a = base + i * k + r, b = base + i * k + (r + 1) % k;
                        const uint32_t c = base + j * k + r, d = base + j * k + (r + 1) % k;
                        level.indices.insert(level.indices.end(), {a, b, d, a, d, c});
                    }
                }
            }
            if (!blades) {
                const uint32_t last = base + (n - 1) * k;
                for (uint32_t r = 1; r + 1 < k; ++r) {
                    level.indices.insert(level.indices.end(), {base, base + r + 1, base + r});
                    level.indices.insert(level.indices.end(), {last, last + r, last + r + 1});
                }
            }
            base += n * (blades ? 4 : k);
        }
        if (10 * level.indices.size() > 9 * previous) break;
        if (!out->empty()) level.error_m = std::max(level.error_m, out->back().error_m);
        previous = level.indices.size();
        out->push_back(std::move(level));
    }
}

}  // namespace ug
