#include "editor/markers.h"

#include <algorithm>
#include <cmath>

#include "instancer/tile_coord.h"

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

// A unit basis (a, b) of the plane orthogonal to n.
void planeBasis(glm::vec3 n, glm::vec3* a, glm::vec3* b) {
    *a = glm::normalize(std::abs(n.z) < 0.9f ? glm::cross(n, glm::vec3(0, 0, 1)) : glm::cross(n, glm::vec3(1, 0, 0)));
    *b = glm::cross(n, *a);
}

void addTriangle(glm::vec3 p, glm::vec3 q, glm::vec3 r, glm::vec3 color, std::vector<MarkerVertex>* out) {
    out->push_back({p, color});
    out->push_back({q, color});
    out->push_back({r, color});
}

// Hulls are coarse on purpose: a translucent shell reads as a volume with a few hundred triangles, and
// a scene may hold dozens of primitives (every paint stamp is one).
constexpr int kHullSlices = 16;
constexpr int kHullStacks = 8;

void addSphereHull(glm::vec3 c, float r, glm::vec3 color, std::vector<MarkerVertex>* out) {
    auto at = [&](int i, int k) {
        const float theta = 3.14159265f * float(k) / kHullStacks, phi = 6.2831853f * float(i) / kHullSlices;
        return c + r * glm::vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    };
    for (int k = 0; k < kHullStacks; ++k)
        for (int i = 0; i < kHullSlices; ++i) {
            if (k > 0) addTriangle(at(i, k), at(i + 1, k), at(i, k + 1), color, out);
            if (k + 1 < kHullStacks) addTriangle(at(i + 1, k), at(i + 1, k + 1), at(i, k + 1), color, out);
        }
}

// The side of a truncated cone from (a, ra) to (b, rb); with spheres at both ends: the segment's support.
void addConeSide(glm::vec3 a, float ra, glm::vec3 b, float rb, glm::vec3 color, std::vector<MarkerVertex>* out) {
    const glm::vec3 axis = b - a;
    if (glm::length(axis) < 1e-6f) return;
    glm::vec3 u, v;
    planeBasis(glm::normalize(axis), &u, &v);
    for (int i = 0; i < kHullSlices; ++i) {
        const float t0 = 6.2831853f * float(i) / kHullSlices, t1 = 6.2831853f * float(i + 1) / kHullSlices;
        const glm::vec3 d0 = std::cos(t0) * u + std::sin(t0) * v, d1 = std::cos(t1) * u + std::sin(t1) * v;
        addTriangle(a + ra * d0, a + ra * d1, b + rb * d0, color, out);
        addTriangle(a + ra * d1, b + rb * d1, b + rb * d0, color, out);
    }
}

// A disc's support: the points within R of the flat disc, a puck with a rounded rim (half a torus of
// minor radius R around the rim, flat caps R above and below). Drawn whole, so on the ground the upper cap
// shows where the painted slab reaches instead of a flat disc half buried in the terrain.
void addDiscHull(glm::vec3 c, glm::vec3 n, float disc_r, float r, glm::vec3 color, std::vector<MarkerVertex>* out) {
    n = glm::normalize(n);
    glm::vec3 u, v;
    planeBasis(n, &u, &v);
    constexpr int kRimSteps = kHullStacks;  // from the bottom cap's edge to the top cap's
    auto at = [&](int i, int k) {
        const float theta = 6.2831853f * float(i) / float(2 * kHullSlices);
        const float phi = 3.14159265f * (float(k) / float(kRimSteps) - 0.5f);
        const glm::vec3 radial = std::cos(theta) * u + std::sin(theta) * v;
        return c + (disc_r + r * std::cos(phi)) * radial + r * std::sin(phi) * n;
    };
    for (int i = 0; i < 2 * kHullSlices; ++i) {
        for (int k = 0; k < kRimSteps; ++k) {
            addTriangle(at(i, k), at(i + 1, k), at(i + 1, k + 1), color, out);
            addTriangle(at(i, k), at(i + 1, k + 1), at(i, k + 1), color, out);
        }
        if (disc_r > 0.0f) {
            addTriangle(c + r * n, at(i, kRimSteps), at(i + 1, kRimSteps), color, out);
            addTriangle(c - r * n, at(i + 1, 0), at(i, 0), color, out);
        }
    }
}

void addBoxHull(glm::vec3 lo, glm::vec3 hi, glm::vec3 color, std::vector<MarkerVertex>* out) {
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            glm::vec3 q[4];
            for (int k = 0; k < 4; ++k) {
                q[k][axis] = side ? hi[axis] : lo[axis];
                q[k][u] = (k == 1 || k == 2) ? hi[u] : lo[u];
                q[k][v] = (k >= 2) ? hi[v] : lo[v];
            }
            addTriangle(q[0], q[1], q[2], color, out);
            addTriangle(q[0], q[2], q[3], color, out);
        }
}

void addBoxEdges(glm::vec3 lo, glm::vec3 hi, glm::vec3 color, MarkerGeometry* out) {
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
}

glm::vec3 typeDisplayColor(const std::vector<DetailLodMesh>& meshes, size_t type) {
    const glm::vec3 base = type < meshes.size() ? meshes[type].color : glm::vec3(0.6f);
    // Mesh colours are dark linear values; lighten them so the lines read against the ground.
    return glm::mix(glm::sqrt(glm::clamp(base, 0.0f, 1.0f)), glm::vec3(1.0f), 0.35f);
}

glm::vec3 rotate(const glm::quat& q, glm::vec3 v) { return q * v; }

// The selection in kSelectedColor, negative (erasing) weights in red, the rest in their type's colour.
glm::vec3 primitiveColor(bool selected, const Primitive& p, glm::vec3 type_color) {
    if (selected) return kSelectedColor;
    return p.weight < 0.0f ? glm::vec3(0.9f, 0.3f, 0.3f) : type_color;
}

// Calls fn(primitive, display colour) for every user primitive of every type; the selected one's whole
// brush stroke is drawn selected (it is selected, moved and deleted as one).
template <typename Fn>
void forEachUserPrimitive(const Document& doc, const std::vector<DetailLodMesh>& meshes, uint64_t selected, Fn fn) {
    Primitive chosen;
    const uint32_t stroke = selected != 0 && doc.findPrimitive(selected, nullptr, &chosen) ? chosen.stroke : 0;
    for (size_t type = 0; type < doc.project().detail_types.size(); ++type) {
        const glm::vec3 type_color = typeDisplayColor(meshes, type);
        for (uint64_t id : doc.primitiveIds(type)) {
            Primitive p;
            if (doc.findPrimitive(id, nullptr, &p))
                fn(p, primitiveColor(id == selected || (stroke != 0 && p.stroke == stroke), p, type_color));
        }
    }
}

}  // namespace

void addPrimitiveMarkers(const Document& doc, const std::vector<DetailLodMesh>& meshes, uint64_t selected,
                         MarkerGeometry* out) {
    forEachUserPrimitive(doc, meshes, selected, [&](const Primitive& p, glm::vec3 color) {
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
            case PrimitiveKind::Box:
                addBoxEdges(p.center_m - p.half_extents_m, p.center_m + p.half_extents_m, color, out);
                out->points.push_back({p.center_m, color});
                break;
            case PrimitiveKind::HalfSpace:
                out->points.push_back({p.center_m, color});
                out->lines.push_back({p.center_m, color});
                out->lines.push_back({p.center_m + p.normal * p.radius_m, color});
                break;
            case PrimitiveKind::TerrainLayer:
            case PrimitiveKind::TerrainSolid:
            case PrimitiveKind::External:
                break;
        }
    });
}

namespace {

void addGreatCircles(glm::vec3 c, float r, glm::vec3 color, MarkerGeometry* out) {
    for (const glm::vec3 n : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)}) addCircle(c, n, r, color, out);
}

void addLine(glm::vec3 a, glm::vec3 b, glm::vec3 color, MarkerGeometry* out) {
    out->lines.push_back({a, color});
    out->lines.push_back({b, color});
}

}  // namespace

void addParticleMarkers(const ParticleSystemFile& system, ParticleHandle selected, MarkerGeometry* out) {
    const ParticleScene& scene = system.scene;
    for (size_t i = 0; i < scene.attractors.size(); ++i) {
        const Attractor& a = scene.attractors[i];
        const glm::vec3 color = selected == ParticleHandle{ParticlePart::Attractor, i} ? kSelectedColor
                                : chargeAt(a.charge, 0) < 0.0f                    ? kRepelColor
                                                                                  : kAttractColor;
        if (a.kind == AttractorKind::Segment) {
            addLine(a.a_m, a.b_m, color, out);
            out->points.push_back({a.b_m, color});
        }
        if (a.kind == AttractorKind::Sphere) addGreatCircles(a.a_m, a.radius_m, color, out);
        if (a.kind == AttractorKind::Mesh && a.points)
            for (const glm::vec3& p : *a.points) out->points.push_back({a.a_m + a.scale * p, color * 0.8f});
        if (a.kind == AttractorKind::Objects && a.points)
            for (const glm::vec3& p : *a.points) out->points.push_back({p, color * 0.8f});
        if (a.influence_m > 0.0f && a.kind != AttractorKind::Objects)
            addGreatCircles(a.a_m, a.influence_m, color * 0.7f, out);
    }
    for (const ParticleGenerator& g : scene.generators) {
        switch (g.kind) {
            case GeneratorKind::Rectangle: {
                const glm::vec3 c = g.center_m, u = g.axis_u_m, v = g.axis_v_m;
                const glm::vec3 corners[4] = {c - u - v, c + u - v, c + u + v, c - u + v};
                // Seeds on the terrain: the outline follows the ground they grow from.
                const HeightField* ground = g.on_terrain ? scene.terrain.get() : nullptr;
                const int pieces = ground ? 16 : 1;
                for (int k = 0; k < 4; ++k)
                    for (int i = 0; i < pieces; ++i) {
                        glm::vec3 p = glm::mix(corners[k], corners[(k + 1) % 4], float(i) / float(pieces));
                        glm::vec3 q = glm::mix(corners[k], corners[(k + 1) % 4], float(i + 1) / float(pieces));
                        if (ground) {
                            p.z = ground->sample(p.x, p.y) + 0.01f;
                            q.z = ground->sample(q.x, q.y) + 0.01f;
                        }
                        addLine(p, q, kGeneratorColor, out);
                    }
                break;
            }
            case GeneratorKind::Sphere: addGreatCircles(g.center_m, g.radius_m, kGeneratorColor, out); break;
            case GeneratorKind::Box:
                addBoxEdges(g.center_m - g.half_extents_m, g.center_m + g.half_extents_m, kGeneratorColor, out);
                break;
            case GeneratorKind::Details:  // the box its instances' origins lie in
                addBoxEdges(g.center_m - g.half_extents_m, g.center_m + g.half_extents_m, kGeneratorColor, out);
                [[fallthrough]];
            case GeneratorKind::Mesh:
            case GeneratorKind::Objects:  // its gathered surfaces: world coordinates, center 0, scale 1
                if (g.mesh && !g.mesh->positions.empty()) {
                    glm::vec3 lo = g.mesh->positions[0], hi = lo;
                    for (const glm::vec3& p : g.mesh->positions) {
                        lo = glm::min(lo, p);
                        hi = glm::max(hi, p);
                    }
                    addBoxEdges(g.center_m + lo * g.scale, g.center_m + hi * g.scale, kGeneratorColor, out);
                }
                break;
        }
    }
    for (const Cutter& c : scene.cutters) {
        switch (c.kind) {
            case CutterKind::Plane: {
                glm::vec3 a, b;
                planeBasis(c.normal, &a, &b);
                const glm::vec3 o = c.center_m + c.normal * c.threshold_m;  // where it triggers
                const glm::vec3 corners[4] = {o - 0.5f * a - 0.5f * b, o + 0.5f * a - 0.5f * b, o + 0.5f * a + 0.5f * b,
                                              o - 0.5f * a + 0.5f * b};
                for (int k = 0; k < 4; ++k) addLine(corners[k], corners[(k + 1) % 4], kCutterColor, out);
                addLine(o, o + 0.1f * c.normal, kCutterColor, out);
                break;
            }
            case CutterKind::Sphere:
                addGreatCircles(c.center_m, std::max(c.radius_m + c.threshold_m, 0.001f), kCutterColor, out);
                break;
            case CutterKind::Box: {
                const glm::vec3 h = glm::max(c.half_extents_m + glm::vec3(c.threshold_m), glm::vec3(0.001f));
                addBoxEdges(c.center_m - h, c.center_m + h, kCutterColor, out);
                break;
            }
        }
    }
    // The dots the Select tool picks and drags (particle_tools.h), in the part's colour.
    for (const ParticleHandlePoint& h : particleHandlePoints(scene)) {
        glm::vec3 color = h.handle.part == ParticlePart::Generator ? kGeneratorColor
                          : h.handle.part == ParticlePart::Cutter  ? kCutterColor
                          : chargeAt(scene.attractors[h.handle.index].charge, 0) < 0.0f ? kRepelColor
                                                                                      : kAttractColor;
        if (h.handle == selected) color = kSelectedColor;
        out->points.push_back({h.position_m, color});
    }
}

void addPrimitiveHulls(const Document& doc, const std::vector<DetailLodMesh>& meshes, uint64_t selected,
                       MarkerGeometry* out) {
    forEachUserPrimitive(doc, meshes, selected, [&](const Primitive& p, glm::vec3 color) {
        switch (p.kind) {
            case PrimitiveKind::Point:
                addSphereHull(p.center_m, p.radius_m, color, &out->hull);
                break;
            case PrimitiveKind::Segment:
                addSphereHull(p.center_m, p.radius_m, color, &out->hull);
                addSphereHull(p.end_m, p.end_radius_m, color, &out->hull);
                addConeSide(p.center_m, p.radius_m, p.end_m, p.end_radius_m, color, &out->hull);
                break;
            case PrimitiveKind::Disc:
                addDiscHull(p.center_m, p.normal, p.disc_radius_m, p.radius_m, color, &out->hull);
                break;
            case PrimitiveKind::Box:
                // note: the support is the box rounded by R; the box grown by R bounds it.
                addBoxHull(p.center_m - p.half_extents_m - p.radius_m, p.center_m + p.half_extents_m + p.radius_m,
                           color, &out->hull);
                break;
            case PrimitiveKind::HalfSpace:
            case PrimitiveKind::TerrainLayer:
            case PrimitiveKind::TerrainSolid:
            case PrimitiveKind::External:
                break;  // unbounded or following the terrain: no hull
        }
    });
}

void nearestTiles(const ResidentTiles& tiles, glm::vec3 target, float radius_m, size_t cap, std::vector<uint32_t>* out) {
    out->clear();
    const float s = tiles.tile_size_m;
    std::vector<std::pair<float, uint32_t>> near;
    for (size_t t = 0; t < tiles.tileCount(); ++t) {
        const float d = glm::length(tileOrigin(tiles.tile_coord[t], s) + 0.5f * s - target);
        if (d <= radius_m) near.push_back({d, uint32_t(t)});
    }
    const size_t n = std::min(cap, near.size());
    std::partial_sort(near.begin(), near.begin() + long(n), near.end());
    for (size_t i = 0; i < n; ++i) out->push_back(near[i].second);
}

void addTileOverlay(const ResidentTiles& tiles, glm::vec3 target, float radius_m, MarkerGeometry* out) {
    std::vector<uint32_t> near;
    nearestTiles(tiles, target, radius_m, kOverlayTileCap, &near);
    const float s = tiles.tile_size_m;
    for (uint32_t t : near) {
        const glm::vec3 lo = tileOrigin(tiles.tile_coord[t], s);
        addBoxEdges(lo, lo + s, glm::vec3(0.45f, 0.75f, 1.0f), out);
    }
}

void addAnchorOverlay(const ResidentTiles& tiles, const CandidateSet& c, const std::vector<DetailLodMesh>& meshes,
                      glm::vec3 target, float radius_m, MarkerGeometry* out) {
    std::vector<uint32_t> near;
    nearestTiles(tiles, target, radius_m, kOverlayAnchorTileCap, &near);
    const float s = tiles.tile_size_m;
    for (uint32_t t : near) {
        const glm::vec3 origin = tileOrigin(tiles.tile_coord[t], s);
        // Every candidate, dim: the Ghost Tile's full set at this tile.
        for (uint32_t j = 0; j < c.size(); ++j)
            out->dots.push_back({origin + c.position[j], 0.45f * typeDisplayColor(meshes, c.type[j])});
        // The selected ones (the tile's instances), bright.
        for (uint32_t type = 0; type < tiles.type_count; ++type) {
            const TileSlot slot = tiles.slot[size_t(t) * tiles.type_count + type];
            const uint32_t n = tiles.count[size_t(t) * tiles.type_count + type];
            for (uint32_t i = 0; i < n; ++i) {
                glm::ivec3 tile;
                uint32_t j = 0;
                unpackInstance(tiles.types[type].mirror[slot.offset + i], &tile, &j);
                out->points.push_back({origin + c.position[j], typeDisplayColor(meshes, type)});
            }
        }
    }
}

void addSphereOverlay(const ResidentTiles& tiles, const CandidateSet& c, const std::vector<DetailModel>& models,
                      glm::vec3 target, float radius_m, MarkerGeometry* out) {
    std::vector<uint32_t> near;
    nearestTiles(tiles, target, radius_m, kOverlaySphereInstanceCap, &near);
    const float s = tiles.tile_size_m;
    size_t drawn = 0, spheres = 0;
    const glm::vec3 color(1.0f, 0.55f, 0.85f);
    for (uint32_t t : near) {
        const glm::vec3 origin = tileOrigin(tiles.tile_coord[t], s);
        for (uint32_t type = 0; type < tiles.type_count && type < models.size(); ++type) {
            const TileSlot slot = tiles.slot[size_t(t) * tiles.type_count + type];
            const uint32_t n = tiles.count[size_t(t) * tiles.type_count + type];
            for (uint32_t i = 0; i < n; ++i) {
                if (drawn++ >= kOverlaySphereInstanceCap) return;
                if (spheres >= kOverlaySphereCap) return;
                glm::ivec3 tile;
                uint32_t j = 0;
                unpackInstance(tiles.types[type].mirror[slot.offset + i], &tile, &j);
                // The instance's frame, as the exporter and the vertex shader rebuild it.
                for (const Sphere& sp : models[type].spheres) {
                    const glm::vec3 centre = origin + c.position[j] + rotate(c.rotation[j], c.scale[j] * sp.center);
                    const float r = c.scale[j] * sp.radius;
                    // One horizontal circle per sphere: the set's footprint reads, and the cap stays cheap.
                    addCircle(centre, glm::vec3(0, 0, 1), r, color, out);
                    ++spheres;
                }
            }
        }
    }
}

void addBrushMarker(const Document& doc, glm::vec3 center, float r, bool on_ground, MarkerGeometry* out) {
    for (int k = 0; k < kCircleSegments; ++k) {
        glm::vec3 p[2];
        for (int e = 0; e < 2; ++e) {
            const float t = 6.2831853f * float(k + e) / kCircleSegments;
            p[e] = center + r * glm::vec3(std::cos(t), std::sin(t), 0.0f);
            // Draped 3 cm over the ground so the ground does not hide it.
            if (on_ground && doc.terrain()) p[e].z = doc.terrain()->sample(p[e].x, p[e].y) + 0.03f;
        }
        out->lines.push_back({p[0], kBrushColor});
        out->lines.push_back({p[1], kBrushColor});
    }
    out->points.push_back({center, kBrushColor});
}

}  // namespace ug::editor
