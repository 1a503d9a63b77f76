#include "editor/markers.h"

#include <cmath>

namespace ug::editor {

namespace {

constexpr int kCircleSegments = 32;

void addCircle(glm::vec3 c, glm::vec3 n, float r, glm::vec3 color, MarkerGeometry* out) {
    // Any two unit vectors orthogonal to n span the circle's plane.
    const glm::vec3 a = glm::normalize(std::abs(n.z) < 0.9f ? glm::cross(n, glm::vec3(0, 0, 1))
                                                            : glm::cross(n, glm::vec3(1, 0, 0)));
    const glm::vec3 b = glm::cross(n, a);
    for (int k = 0; k < kCircleSegments; ++k) {
        const float t0 = 6.2831853f * float(k) / kCircleSegments,
                    t1 = 6.2831853f * float(k + 1) / kCircleSegments;
        out->lines.push_back({c + r * (std::cos(t0) * a + std::sin(t0) * b), color});
        out->lines.push_back({c + r * (std::cos(t1) * a + std::sin(t1) * b), color});
    }
}

}  // namespace

void addPrimitiveMarkers(const Document& doc, const std::vector<DetailLodMesh>& meshes, uint64_t selected,
                         MarkerGeometry* out) {
    for (size_t type = 0; type < doc.project().detail_types.size(); ++type) {
        const glm::vec3 base = type < meshes.size() ? meshes[type].color : glm::vec3(0.6f);
        // Mesh colours are dark linear values; lighten them so the lines read against the ground.
        const glm::vec3 type_color =
            glm::mix(glm::sqrt(glm::clamp(base, 0.0f, 1.0f)), glm::vec3(1.0f), 0.35f);
        for (uint64_t id : doc.primitiveIds(type)) {
            Primitive p;
            if (!doc.findPrimitive(id, nullptr, &p)) continue;
            const glm::vec3 color = id == selected    ? kSelectedColor
                                    : p.weight < 0.0f ? glm::vec3(0.9f, 0.3f, 0.3f)
                                                      : type_color;
            switch (p.kind) {
                case PrimitiveKind::Point:
                    out->points.push_back({p.center_m, color});
                    addCircle(p.center_m, glm::vec3(0, 0, 1), p.radius_m, color, out);
                    break;
                case PrimitiveKind::Segment:
                    out->lines.push_back({p.center_m, color});
                    out->lines.push_back({p.end_m, color});
                    out->points.push_back({p.center_m, color});
                    out->points.push_back({p.end_m, color});
                    break;
                case PrimitiveKind::Disc:
                    out->points.push_back({p.center_m, color});
                    addCircle(p.center_m, p.normal, std::max(p.disc_radius_m, 0.02f), color, out);
                    break;
                case PrimitiveKind::Box: {
                    const glm::vec3 lo = p.center_m - p.half_extents_m, hi = p.center_m + p.half_extents_m;
                    for (int axis = 0; axis < 3; ++axis)
                        for (int k = 0; k < 4; ++k) {
                            glm::vec3 a = lo, b = lo;
                            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
                            a[u] = b[u] = (k & 1) ? hi[u] : lo[u];
                            a[v] = b[v] = (k & 2) ? hi[v] : lo[v];
                            b[axis] = hi[axis];
                            out->lines.push_back({a, color});
                            out->lines.push_back({b, color});
                        }
                    out->points.push_back({p.center_m, color});
                    break;
                }
                case PrimitiveKind::HalfSpace:
                    out->points.push_back({p.center_m, color});
                    out->lines.push_back({p.center_m, color});
                    out->lines.push_back({p.center_m + p.normal * p.radius_m, color});
                    break;
                case PrimitiveKind::TerrainLayer:
                case PrimitiveKind::TerrainSolid:
                    break;
            }
        }
    }
}

void addBrushMarker(const Document& doc, glm::vec3 center, float r, MarkerGeometry* out) {
    for (int k = 0; k < kCircleSegments; ++k) {
        glm::vec3 p[2];
        for (int e = 0; e < 2; ++e) {
            const float t = 6.2831853f * float(k + e) / kCircleSegments;
            p[e] = center + r * glm::vec3(std::cos(t), std::sin(t), 0.0f);
            // Draped 3 cm over the ground so the ground does not hide it.
            if (doc.terrain()) p[e].z = doc.terrain()->sample(p[e].x, p[e].y) + 0.03f;
        }
        out->lines.push_back({p[0], kBrushColor});
        out->lines.push_back({p[1], kBrushColor});
    }
    out->points.push_back({center, kBrushColor});
}

}  // namespace ug::editor
