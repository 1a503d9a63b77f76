#include "particles/particle_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "particles/particle_seeding.h"

namespace ug {

namespace {

bool fail(std::string* error, const std::string& field, const char* reason) {
    if (error) *error = field + ": " + reason;
    return false;
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// A position the spatial hash can index: finite and within kMaxParticleCoordinate_m.
bool checkPosition(glm::vec3 p, const std::string& field, std::string* error) {
    if (!finite(p)) return fail(error, field, "not finite");
    for (int a = 0; a < 3; ++a)
        if (std::abs(p[a]) > kMaxParticleCoordinate_m) return fail(error, field, "beyond 1e5 m");
    return true;
}

bool checkLength(float v, const std::string& field, bool allow_zero, std::string* error) {
    if (!std::isfinite(v)) return fail(error, field, "not finite");
    if (allow_zero ? v < 0.0f : !(v > 0.0f)) return fail(error, field, allow_zero ? "must be >= 0" : "must be > 0");
    if (v > kMaxParticleCoordinate_m) return fail(error, field, "beyond 1e5 m");
    return true;
}

bool checkCone(float deg, const std::string& field, bool allow_zero, std::string* error) {
    if (!std::isfinite(deg)) return fail(error, field, "not finite");
    if (allow_zero ? deg < 0.0f : !(deg > 0.0f))
        return fail(error, field, allow_zero ? "must be in [0, 180) degrees" : "must be in (0, 180) degrees");
    if (deg >= 180.0f) return fail(error, field, allow_zero ? "must be in [0, 180) degrees" : "must be in (0, 180) degrees");
    return true;
}

bool checkAction(const StrandAction& a, const std::string& field, std::string* error, bool in_table = false) {
    if (!a.table.empty()) {
        if (in_table) return fail(error, field + ".table", "an action in a table has no table of its own");
        if (a.table.size() > kMaxActionTable) return fail(error, field + ".table", "at most 16 actions");
        for (size_t i = 0; i < a.table.size(); ++i) {
            const std::string f = field + ".table[" + std::to_string(i) + "]";
            if (!checkAction(a.table[i], f, error, true)) return false;
            if (!std::isfinite(a.table[i].weight) || !(a.table[i].weight > 0.0f) || a.table[i].weight > 1e6f)
                return fail(error, f + ".weight", "must be in (0, 1e6]");
        }
        return true;
    }
    if (a.kind == StrandActionKind::Turn && !(a.turn_angle_deg > 0.0f && a.turn_angle_deg <= 180.0f))
        return fail(error, field + ".turn_angle_deg", "must be in (0, 180] degrees");
    if (a.kind == StrandActionKind::Split) {
        if (a.split_count < 1 || a.split_count > 16) return fail(error, field + ".split_count", "must be in [1, 16]");
        if (!checkCone(a.split_angle_deg, field + ".split_angle_deg", true, error)) return false;
    }
    if (a.kind == StrandActionKind::Countdown && a.countdown_steps < 1)
        return fail(error, field + ".countdown_steps", "must be >= 1");
    if (a.kind == StrandActionKind::Countdown && a.countdown_then != StrandActionKind::Kill &&
        a.countdown_then != StrandActionKind::Stop)
        return fail(error, field + ".countdown_then", "must be kill or stop");
    return true;
}

// Segment ab's closest point to p, as a distance.
float segmentDistance(glm::vec3 a, glm::vec3 b, glm::vec3 p) {
    const glm::vec3 ab = b - a;
    const float len2 = glm::dot(ab, ab);
    const float s = len2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
    return glm::length(p - (a + s * ab));
}

// Brute force: at most kMaxObjectAttractorPoints, and the points stay in cache.
float nearestSquared(const std::vector<glm::vec3>& points, glm::vec3 q) {
    float best = INFINITY;
    for (const glm::vec3& s : points) {
        const glm::vec3 d = q - s;
        best = std::min(best, glm::dot(d, d));
    }
    return best;
}

}  // namespace

double meshTriangleArea(const TriangleMesh& mesh, size_t triangle) {
    const glm::dvec3 a(mesh.positions[mesh.indices[3 * triangle]]), b(mesh.positions[mesh.indices[3 * triangle + 1]]),
        c(mesh.positions[mesh.indices[3 * triangle + 2]]);
    return 0.5 * glm::length(glm::cross(b - a, c - a));
}

bool sameAttractorPlace(const Attractor& a, const Attractor& b) {
    const bool same_points = a.points == b.points || (a.points && b.points && *a.points == *b.points);
    return a.kind == b.kind && a.a_m == b.a_m && a.b_m == b.b_m && a.radius_m == b.radius_m &&
           a.scale == b.scale && same_points;
}

glm::vec3 ParticleObstacle::toWorld(glm::vec3 local) const {
    const glm::vec3 q = rotation * (local * scale);
    return translation + glm::vec3(cos_yaw * q.x - sin_yaw * q.y, sin_yaw * q.x + cos_yaw * q.y, q.z);
}

glm::vec3 ParticleObstacle::toLocal(glm::vec3 world) const { return directionToLocal(world - translation) / scale; }

glm::vec3 ParticleObstacle::directionToLocal(glm::vec3 d) const {
    const glm::vec3 unturned(cos_yaw * d.x + sin_yaw * d.y, -sin_yaw * d.x + cos_yaw * d.y, d.z);
    return glm::conjugate(rotation) * unturned;
}

Bounds particleReach(const ParticleScene& scene) {
    Bounds b;
    for (const ParticleGenerator& g : scene.generators) {
        glm::vec3 half(0.0f);
        glm::vec3 center = g.center_m;
        switch (g.kind) {
            case GeneratorKind::Rectangle: half = glm::abs(g.axis_u_m) + glm::abs(g.axis_v_m); break;
            case GeneratorKind::Sphere: half = glm::vec3(g.radius_m); break;
            case GeneratorKind::Box: half = g.half_extents_m; break;
            case GeneratorKind::Mesh:
            case GeneratorKind::Objects:
            case GeneratorKind::Details:
                if (g.mesh && !g.mesh->positions.empty()) {
                    Bounds m;
                    for (const glm::vec3& p : g.mesh->positions) m = unite(m, Bounds{p, p});
                    center += 0.5f * (m.lo + m.hi) * g.scale;
                    half = 0.5f * (m.hi - m.lo) * g.scale;
                }
                break;
        }
        Bounds gb = Bounds::fromCenterHalf(center, half);
        if (g.on_terrain) {
            gb.lo.z = -std::numeric_limits<float>::infinity();
            gb.hi.z = std::numeric_limits<float>::infinity();
        }
        b = unite(b, gb);
    }
    if (b.empty()) return b;
    const float walk = float(scene.walk.steps) * scene.walk.step_length_m + scene.walk.strand_radius_m;
    return Bounds{b.lo - glm::vec3(walk), b.hi + glm::vec3(walk)};
}

std::shared_ptr<const std::vector<glm::vec3>> meshAttractorPoints(std::shared_ptr<const TriangleMesh> mesh,
                                                                 uint32_t count) {
    // The mesh generator's stratified seeding (particle_seeding.h), at the origin, unscaled.
    ParticleGenerator g;
    g.kind = GeneratorKind::Mesh;
    g.mesh = std::move(mesh);
    g.count = count;
    ParticleSeeds seeds;
    seedGenerator(g, 0, 0x6d657368u /* "mesh" */, &seeds);
    return std::make_shared<const std::vector<glm::vec3>>(std::move(seeds.positions));
}

void translateParticleScene(ParticleScene* scene, glm::vec3 offset) {
    for (ParticleGenerator& g : scene->generators) g.center_m += offset;
    for (Attractor& a : scene->attractors) {
        a.a_m += offset;
        a.b_m += offset;
    }
    for (Cutter& c : scene->cutters) c.center_m += offset;
}

const char* strandActionName(StrandActionKind kind) {
    switch (kind) {
        case StrandActionKind::Stop: return "stop";
        case StrandActionKind::Kill: return "kill";
        case StrandActionKind::Split: return "split";
        case StrandActionKind::Countdown: return "countdown";
        case StrandActionKind::Turn: return "turn";
    }
    return "?";
}

bool validateParticleScene(const ParticleScene& scene, std::string* error) {
    const WalkSettings& w = scene.walk;
    if (w.steps > kMaxParticleSteps) return fail(error, "walk.steps", "must be <= 100000");
    if (w.trials < 1 || w.trials > 256) return fail(error, "walk.trials", "must be in [1, 256]");
    if (!checkCone(w.cone_deg, "walk.cone_deg", false, error)) return false;
    if (!checkLength(w.step_length_m, "walk.step_length_m", false, error)) return false;
    if (!checkLength(w.strand_radius_m, "walk.strand_radius_m", false, error)) return false;
    if (!checkAction(w.on_collision, "walk.on_collision", error) || !checkAction(w.on_age, "walk.on_age", error) ||
        !checkAction(w.on_distance, "walk.on_distance", error))
        return false;
    // The segment grids' cells grow with the distance looked for: a keep far beyond the step would make
    // every query visit most of the system.
    if (!(w.keep_distance_m >= 0.0f) || !(w.keep_distance_m <= 100.0f * w.step_length_m))
        return fail(error, "walk.keep_distance_m", "must be in [0, 100 x step_length_m]");
    if (w.max_points > kMaxStrandPoints) return fail(error, "walk.max_points", "must be <= 50000000");
    if (w.max_split_depth > 64) return fail(error, "walk.max_split_depth", "must be <= 64");

    uint64_t particles = 0;
    for (size_t i = 0; i < scene.generators.size(); ++i) {
        const ParticleGenerator& g = scene.generators[i];
        const std::string f = "generators[" + std::to_string(i) + "]";
        if (!checkPosition(g.center_m, f + ".center_m", error)) return false;
        if (!checkCone(g.heading_cone_deg, f + ".heading_cone_deg", true, error)) return false;
        if (g.kind == GeneratorKind::Rectangle) {
            if (!checkPosition(g.axis_u_m, f + ".axis_u_m", error) || !checkPosition(g.axis_v_m, f + ".axis_v_m", error))
                return false;
            const float lu = glm::length(g.axis_u_m), lv = glm::length(g.axis_v_m);
            if (!(lu > 0.0f) || !(lv > 0.0f)) return fail(error, f + ".axis_u_m", "the axes must not be zero");
            if (std::abs(glm::dot(g.axis_u_m, g.axis_v_m)) > 1e-4f * lu * lv)
                return fail(error, f + ".axis_v_m", "must be orthogonal to axis_u_m");
            if (g.on_terrain && (g.axis_u_m.z != 0.0f || g.axis_v_m.z != 0.0f))
                return fail(error, f + ".on_terrain", "needs horizontal axes (axis_u_m and axis_v_m with z = 0)");
        } else if (g.on_terrain) {
            return fail(error, f + ".on_terrain", "only a rectangle can be dropped onto the terrain");
        } else if (g.kind == GeneratorKind::Objects) {
            if (g.object_type.empty()) return fail(error, f + ".object_type", "names no environmental-object type");
            if (!std::isfinite(g.max_height_m) || g.max_height_m < 0.0f || g.max_height_m > kMaxParticleCoordinate_m)
                return fail(error, f + ".max_height_m", "must be in [0, 1e5] m");
        } else if (g.kind == GeneratorKind::Details) {
            if (g.detail_type.empty()) return fail(error, f + ".detail_type", "names no detail type");
            for (int a = 0; a < 3; ++a)
                if (!checkLength(g.half_extents_m[a], f + ".half_extents_m", false, error)) return false;
            if (!(g.min_normal_z >= -1.0f && g.min_normal_z <= 1.0f))
                return fail(error, f + ".min_normal_z", "must be in [-1, 1]");
        } else if (g.kind == GeneratorKind::Mesh) {
            if (!std::isfinite(g.scale) || !(g.scale > 0.0f) || g.scale > 1e4f)
                return fail(error, f + ".scale", "must be in (0, 10000]");
            if (!g.mesh) return fail(error, f + ".mesh", "no mesh loaded");
            double area = 0.0;
            for (size_t t = 0; t + 2 < g.mesh->indices.size(); t += 3)
                area += meshTriangleArea(*g.mesh, t / 3);
            if (!(area > 0.0)) return fail(error, f + ".mesh", "the mesh has no area to seed on");
        } else if (g.kind == GeneratorKind::Sphere) {
            if (!checkLength(g.radius_m, f + ".radius_m", false, error)) return false;
        } else {
            for (int a = 0; a < 3; ++a)
                if (!checkLength(g.half_extents_m[a], f + ".half_extents_m", false, error)) return false;
        }
        particles += g.count;
        if (particles > kMaxParticles) return fail(error, f + ".count", "the generators seed more than 10000000 particles");
    }

    for (size_t i = 0; i < scene.attractors.size(); ++i) {
        const Attractor& a = scene.attractors[i];
        const std::string f = "attractors[" + std::to_string(i) + "]";
        if (!checkPosition(a.a_m, f + ".a_m", error)) return false;
        if (a.kind == AttractorKind::Segment && !checkPosition(a.b_m, f + ".b_m", error)) return false;
        if (a.kind == AttractorKind::Sphere && !checkLength(a.radius_m, f + ".radius_m", false, error)) return false;
        if (a.kind == AttractorKind::Objects) {
            if (a.object_type.empty()) return fail(error, f + ".object_type", "names no environmental-object type");
            if (a.point_count < 1 || a.point_count > kMaxAttractorPoints)
                return fail(error, f + ".points", "must be in [1, 1024]");
            if (a.points && a.points->size() > kMaxObjectAttractorPoints)
                return fail(error, f + ".points",
                            "the objects within reach times their points exceed 16384 (take fewer points)");
            if (a.points)
                for (const glm::vec3& q : *a.points)
                    if (!checkPosition(q, f + ".points", error)) return false;
        }
        if (a.kind == AttractorKind::Mesh) {
            if (!std::isfinite(a.scale) || !(a.scale > 0.0f) || a.scale > 1e4f)
                return fail(error, f + ".scale", "must be in (0, 10000]");
            if (a.point_count < 1 || a.point_count > kMaxAttractorPoints)
                return fail(error, f + ".points", "must be in [1, 1024]");
            if (!a.mesh || !a.points || a.points->size() != a.point_count)
                return fail(error, f + ".mesh", "no mesh loaded (or its points not taken)");
        }
        if (!checkLength(a.influence_m, f + ".influence_m", true, error)) return false;
        if (a.charge.empty()) return fail(error, f + ".charge", "needs at least one key");
        for (size_t k = 0; k < a.charge.size(); ++k) {
            const std::string fk = f + ".charge[" + std::to_string(k) + "]";
            if (!std::isfinite(a.charge[k].charge)) return fail(error, fk + ".charge", "not finite");
            if (std::abs(a.charge[k].charge) > 1e6f) return fail(error, fk + ".charge", "beyond ±1e6");
            if (k > 0 && a.charge[k].step <= a.charge[k - 1].step)
                return fail(error, fk + ".step", "steps must increase strictly");
        }
    }

    for (const auto& [list, name] : {std::pair{&scene.obstacles, "obstacles"}, {&scene.detail_obstacles, "detail_obstacles"}})
        for (size_t i = 0; i < list->size(); ++i) {
            const ParticleObstacle& o = (*list)[i];
            const std::string f = std::string(name) + "[" + std::to_string(i) + "]";
            if (!o.mesh) return fail(error, f + ".mesh", "no mesh loaded");
            if (!std::isfinite(o.scale) || !(o.scale > 0.0f)) return fail(error, f + ".scale", "must be > 0");
            if (!checkPosition(o.translation, f + ".translation", error)) return false;
        }

    if (scene.cutters.size() > kMaxCutters) return fail(error, "cutters", "at most 32");
    for (size_t i = 0; i < scene.cutters.size(); ++i) {
        const Cutter& c = scene.cutters[i];
        const std::string f = "cutters[" + std::to_string(i) + "]";
        if (!checkPosition(c.center_m, f + ".center_m", error)) return false;
        if (!std::isfinite(c.threshold_m) || std::abs(c.threshold_m) > kMaxParticleCoordinate_m)
            return fail(error, f + ".threshold_m", "not finite or beyond 1e5 m");
        if (c.kind == CutterKind::Plane) {
            if (!finite(c.normal) || std::abs(glm::length(c.normal) - 1.0f) > 1e-4f)
                return fail(error, f + ".normal", "must be a unit vector");
        } else if (c.kind == CutterKind::Sphere) {
            if (!checkLength(c.radius_m, f + ".radius_m", true, error)) return false;
        } else {
            for (int a = 0; a < 3; ++a)
                if (!checkLength(c.half_extents_m[a], f + ".half_extents_m", true, error)) return false;
        }
        if (!checkAction(c.action, f + ".action", error)) return false;
    }

    // The points a run without splits needs: a bound known before anything is allocated. Splits add
    // strands during the run; growStrands refuses those runs when they reach max_points.
    const uint64_t points = particles * (uint64_t(w.steps) + 1);
    if (points > w.max_points)
        return fail(error, "walk.max_points", "the generators' particles times (steps + 1) exceed it");
    return true;
}

float chargeAt(const std::vector<ChargeKey>& keys, uint32_t step) {
    if (step <= keys.front().step) return keys.front().charge;
    if (step >= keys.back().step) return keys.back().charge;
    const auto hi = std::upper_bound(keys.begin(), keys.end(), step,
                                     [](uint32_t s, const ChargeKey& k) { return s < k.step; });
    const ChargeKey& b = *hi;
    const ChargeKey& a = *(hi - 1);
    const float s = float(step - a.step) / float(b.step - a.step);
    return a.charge + (b.charge - a.charge) * s;
}

float attractorDistance(const Attractor& a, glm::vec3 p) {
    switch (a.kind) {
        case AttractorKind::Point: return glm::length(p - a.a_m);
        case AttractorKind::Segment: return segmentDistance(a.a_m, a.b_m, p);
        case AttractorKind::Sphere: return std::abs(glm::length(p - a.a_m) - a.radius_m);
        case AttractorKind::Mesh:
            // Brute force over at most kMaxAttractorPoints: in the mesh's frame, then scaled back.
            return std::sqrt(nearestSquared(*a.points, (p - a.a_m) / a.scale)) * a.scale;
        case AttractorKind::Objects:
            // Nowhere to pull to: a constant term, which no trial prefers.
            if (!a.points || a.points->empty()) return 0.0f;
            return std::sqrt(nearestSquared(*a.points, p));
    }
    return 0.0f;
}

float cutterValue(const Cutter& c, glm::vec3 p) {
    switch (c.kind) {
        case CutterKind::Plane: return glm::dot(p - c.center_m, c.normal);
        case CutterKind::Sphere: return glm::length(p - c.center_m) - c.radius_m;
        case CutterKind::Box: {
            const glm::vec3 q = glm::abs(p - c.center_m) - c.half_extents_m;
            const float outside = glm::length(glm::max(q, glm::vec3(0.0f)));
            const float inside = std::min(std::max(q.x, std::max(q.y, q.z)), 0.0f);
            return outside + inside;
        }
    }
    return 0.0f;
}

}  // namespace ug
