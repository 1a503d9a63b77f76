// The scene of particle sculpting (Beneš & Espinosa 2000; docs/particles.md): generators that seed
// particles on a surface, attractors whose charge pulls or pushes them, cutters whose threshold triggers
// an action, and the settings of the directed random walk. Plain values only: growStrands()
// (strand_growth.h) turns a scene into strands, as a pure function of the scene and its seed.
//
// Every field is checked by validateParticleScene() before anything is allocated, so a hostile scene
// (NaN charges, a billion particles, a zero step) is refused with the field named instead of running.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "field/bounds.h"
#include "field/height_field.h"
#include "mesh/triangle_mesh.h"

namespace ug {

// What a strand does in a critical state (§5.2).
enum class StrandActionKind : uint8_t {
    Stop,       // the strand ends where it is (its points stay)
    Kill,       // the strand is removed from the output
    Split,      // the strand ends and split_count children continue from its last point
    Countdown,  // the strand goes on for countdown_steps more steps, then countdown_then (kill or stop)
    // The strand goes on with its heading turned by turn_angle_deg about a hashed axis across it (§5.2's
    // "changing the direction of the motion"), and its age starts again (an age turn meanders).
    Turn,
};

// How a state's table of actions (StrandAction::table) picks one when the state occurs.
enum class ActionChoice : uint8_t {
    Priority,  // the first that can act (a split needs a moved strand under the depth limit, a countdown a
               // strand not counting yet); the last when none can
    Random,    // one drawn in proportion to the weights by a hashed number (seed, strand, step, state)
};

struct StrandAction {
    StrandActionKind kind = StrandActionKind::Stop;
    uint32_t split_count = 2;        // Split: children, in [1, 16]
    float split_angle_deg = 30.0f;   // Split: children's headings perturbed in this cone, [0, 180)
    uint32_t countdown_steps = 4;    // Countdown: >= 1
    // Countdown: what ends the strand when the count runs out, Kill (removed) or Stop (its points stay:
    // the paper's "eliminated" in Fig. 8, where the strands reaching the outer sphere remain visible).
    StrandActionKind countdown_then = StrandActionKind::Kill;
    float turn_angle_deg = 45.0f;    // Turn: in (0, 180]
    // A table (§5.2: "the action can be either taken randomly or according to user defined priority"):
    // when not empty, the state acts by one of these (their own tables empty, at most 16) chosen by
    // `choice`, and this entry's kind and fields are unused. `weight` (> 0) counts in a Random table.
    std::vector<StrandAction> table;
    ActionChoice choice = ActionChoice::Priority;
    float weight = 1.0f;

    bool operator==(const StrandAction&) const = default;
};
constexpr size_t kMaxActionTable = 16;

// Surfaces particles are seeded on. Each has an area-preserving parameterisation, so equal strata in
// parameter space are equal areas on the surface (§3: "equal areas ... arc length parameterisation").
enum class GeneratorKind : uint8_t {
    Rectangle,  // center_m + s·axis_u_m + t·axis_v_m, s, t in [-1, 1]; axes orthogonal; normal u × v
    Sphere,     // center_m, radius_m; normal outward
    Box,        // center_m, half_extents_m (axis-aligned, each > 0); normals outward, faces by area
    // A triangle mesh (a model file), scaled by `scale` about its origin and moved to center_m; normals by
    // its winding. Strata are equal slices of the cumulative area over the triangles in file order.
    Mesh,
    // The surfaces of the project's environmental objects of one type (`object_type`), optionally only
    // below max_height_m in each object's frame and only its sides (faces within 60° of vertical): vines
    // from a shelter's foot. The project that places the system gathers them into `mesh` in world
    // coordinates (scene/scene_particles.h; center_m 0, scale 1), seeded as a mesh is, `count` over all
    // the objects; without a project (or with no such object) it seeds nothing.
    Objects,
    // The instances of one detail type (`detail_type`) whose origins lie in the box center_m ±
    // half_extents_m, as the project instantiates and settles them (moss on a rock pile's rocks): their
    // faces whose world normal has z >= min_normal_z, gathered by the project that places the system
    // (scene/scene_particles.h placeOnDetails) into `mesh` relative to center_m (scale 1), seeded as a mesh
    // is, `count` over them all; the instances themselves become solids (ParticleScene::detail_obstacles).
    // Without a project (or with no such instance in the box) it seeds nothing.
    Details,
};

struct ParticleGenerator {
    GeneratorKind kind = GeneratorKind::Rectangle;
    glm::vec3 center_m{0.0f};
    glm::vec3 axis_u_m{1.0f, 0.0f, 0.0f};  // Rectangle: half-extent vectors
    glm::vec3 axis_v_m{0.0f, 1.0f, 0.0f};
    float radius_m = 1.0f;                  // Sphere
    glm::vec3 half_extents_m{0.5f};         // Box
    uint32_t count = 0;                     // particles, one per stratum
    float heading_cone_deg = 0.0f;          // initial heading: the normal perturbed in this cone, [0, 180)
    // Rectangle with horizontal axes only: each seed is dropped onto the scene's terrain (z = h(x, y),
    // the normal the terrain's), so grass grows from the ground of a project. The strata stay equal in
    // plan view, not on the slope (within 1/cos of the steepest slope of each other).
    bool on_terrain = false;
    // Mesh: the model file as the particle file names it (relative to it), its triangles once loaded
    // (particle_json.h loads them), and its scale.
    std::string mesh_file;
    std::shared_ptr<const TriangleMesh> mesh;
    float scale = 1.0f;
    // Objects: the type's name, the height band (0: the whole object) and whether only the sides seed.
    std::string object_type;
    float max_height_m = 0.0f;
    bool sides_only = false;
    // Details: the detail type's name and the lowest normal z of the faces that seed (-1: every face; 0.3:
    // faces within about 70 degrees of up, the tops and upper flanks of rocks).
    std::string detail_type;
    float min_normal_z = -1.0f;

    bool operator==(const ParticleGenerator&) const = default;
};

// Whether the generator seeds on surfaces the project gathers for it (objects' or detail instances').
inline bool seedsOnPlacedSurfaces(const ParticleGenerator& g) {
    return g.kind == GeneratorKind::Objects || g.kind == GeneratorKind::Details;
}

// Whether the generator seeds on a triangle mesh (a model's, or surfaces the project gathered).
inline bool seedsOnMesh(const ParticleGenerator& g) { return g.kind == GeneratorKind::Mesh || seedsOnPlacedSurfaces(g); }

// A generator on gathered surfaces that found none (grown alone, or nothing of its kind in reach).
inline bool hasNoPlacedSurface(const ParticleGenerator& g) {
    return seedsOnPlacedSurfaces(g) && (!g.mesh || g.mesh->triangleCount() == 0);
}

// Attractor charge keyframes: a(t) is piecewise linear in the step index t between keys (strictly
// increasing steps), constant before the first and after the last.
struct ChargeKey {
    uint32_t step = 0;
    float charge = 1.0f;  // a > 0 attracts, a < 0 repels; finite

    bool operator==(const ChargeKey&) const = default;
};

enum class AttractorKind : uint8_t {
    Point,    // a_m
    Segment,  // a_m to b_m
    Sphere,   // the surface of the sphere at a_m with radius_m
    // Points on a mesh's surface (Fig. 10-11's attracting points on the bust): point_count of them, one per
    // stratum of its area as a mesh generator seeds (a fixed seed), the mesh scaled by `scale` about its
    // origin and moved to a_m; the distance is to the nearest point.
    Mesh,
    // Points on the surfaces of the project's environmental objects of one type (`object_type`): point_count
    // per object, taken as a mesh attractor takes them and placed with each object. The project that places
    // the system fills `points` in world coordinates (scene/scene_particles.h; a_m and scale are unused);
    // without them (a system grown alone, or no such object within reach) the attractor pulls nowhere.
    Objects,
};

constexpr uint32_t kMaxAttractorPoints = 1024;
// An Objects attractor's points over all its objects: the distance is brute force over them.
constexpr size_t kMaxObjectAttractorPoints = 16384;

struct Attractor {
    AttractorKind kind = AttractorKind::Point;
    glm::vec3 a_m{0.0f};
    glm::vec3 b_m{0.0f};
    float radius_m = 1.0f;      // Sphere, > 0
    float influence_m = 0.0f;   // 0 = everywhere; else the distance is clamped to it (see attractorTerm)
    std::vector<ChargeKey> charge{ChargeKey{}};  // at least one key
    // Mesh: the model file as the particle file names it, its triangles once loaded, the scale, how many
    // surface points, and the points themselves in the mesh's own frame (unscaled; meshAttractorPoints).
    std::string mesh_file;
    std::shared_ptr<const TriangleMesh> mesh;
    float scale = 1.0f;
    uint32_t point_count = 64;
    std::shared_ptr<const std::vector<glm::vec3>> points;
    std::string object_type;  // Objects: the environmental-object type's name

    bool operator==(const Attractor&) const = default;
};

// Whether two attractors act at the same places (their charges and reach may differ).
bool sameAttractorPlace(const Attractor& a, const Attractor& b);

// Cutters: a signed function g(p) and a threshold; a strand triggers the cutter when its next point
// would enter the trigger side, and its point is then placed on the threshold instead (never beyond).
enum class CutterKind : uint8_t {
    Plane,   // g = dot(p - center_m, normal)
    Sphere,  // g = |p - center_m| - radius_m
    Box,     // g = signed distance to the axis-aligned box center_m ± half_extents_m
};

enum class CutterSide : uint8_t {
    Above,  // triggers where g >= threshold_m (grass too far from the ground, Fig. 6, 9)
    Below,  // triggers where g <= threshold_m (reaching a sphere from outside, Fig. 7)
};

struct Cutter {
    CutterKind kind = CutterKind::Plane;
    glm::vec3 center_m{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};  // Plane: unit length
    float radius_m = 1.0f;               // Sphere, >= 0
    glm::vec3 half_extents_m{0.5f};      // Box, >= 0
    float threshold_m = 0.0f;
    CutterSide side = CutterSide::Above;
    StrandAction action;

    bool operator==(const Cutter&) const = default;
};

struct WalkSettings {
    uint64_t seed = 1;
    uint32_t steps = 32;             // synchronous steps, <= kMaxParticleSteps
    uint32_t trials = 8;             // n trial moves per step, in [1, 256]
    float cone_deg = 30.0f;          // φ: trials in a cone of this half-angle around the heading, (0, 180)
    float step_length_m = 0.01f;     // > 0
    float strand_radius_m = 0.001f;  // tube radius r of every strand point, > 0
    bool collisions = true;          // strands keep 2r apart (the tubes never overlap)
    StrandAction on_collision;       // the move is refused first; a countdown keeps trying from that point
    uint32_t max_age_steps = 0;      // 0 = no age limit; else a strand acts on_age after this many steps
    StrandAction on_age;
    uint32_t max_split_depth = 4;    // a Split beyond this many generations acts as Stop; <= 64
    uint64_t max_points = 50'000'000;  // refuse (not truncate) a run that would need more, <= kMaxStrandPoints
    // Solids (§5.2's collision with an object): a move that would end under the scene's terrain (a system
    // grown in a project with one) or cross a mesh generator's surface is refused like a collision
    // (on_collision), counted apart (StrandStats::solid_hits).
    bool solids = true;
    // Distance keeping (§5.2's "keeping distance from another particles"): > 0 makes a strand prefer, of
    // its trials, the fittest whose end stays keep_distance_m clear of every other family's earlier
    // segments (a strand's family is its root and every strand split from it: a split's children start
    // together). When no trial can, the strand is crowded: it does not move and acts on_distance (stop by
    // default; a turn steers it away, a countdown lets it try again). 0 = off.
    float keep_distance_m = 0.0f;
    StrandAction on_distance;
    // The paper keeps "the best [trial] according to the conditions": with retry_refused a move that a
    // solid or an earlier segment would refuse gives way to the next-fittest trial that neither refuses
    // (a vine pressed against a wall slides along it). Only when every trial is refused does the state
    // act (on_collision, with the fittest's verdict). Off: the fittest alone is tried (a countdown keeps
    // it trying at later steps).
    bool retry_refused = false;

    bool operator==(const WalkSettings&) const = default;
};

// A solid the project places around a system (scene/scene_particles.h: an environmental object's base
// geometry, a detail instance's model): its mesh in its own frame, scaled, turned by `rotation` (a detail
// instance's frame; identity for objects), then about z by the yaw, and moved. walk.solids refuses a move
// that crosses its surface, as it refuses one into a mesh generator's.
struct ParticleObstacle {
    std::shared_ptr<const TriangleMesh> mesh;
    glm::vec3 translation{0.0f};
    float cos_yaw = 1.0f, sin_yaw = 0.0f;
    float scale = 1.0f;  // > 0
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // unit

    glm::vec3 toWorld(glm::vec3 local) const;
    glm::vec3 toLocal(glm::vec3 world) const;
    glm::vec3 directionToLocal(glm::vec3 d) const;  // the rotation only (lengths keep the world's)
    bool operator==(const ParticleObstacle&) const = default;
};

struct ParticleScene {
    std::vector<ParticleGenerator> generators;
    // The ground on_terrain generators seed on: set by the project that places the system
    // (scene/scene_particles.h), null for a system grown alone.
    std::shared_ptr<const HeightField> terrain;
    std::vector<Attractor> attractors;
    std::vector<Cutter> cutters;  // at most kMaxCutters (a strand remembers which it has triggered)
    WalkSettings walk;
    // The solids around the system, set by the project that places it (empty for a system grown alone):
    // the environmental objects within reach (placeAmongObjects) and the instances its details generators
    // seed on (placeOnDetails), kept apart so that placing one kind again keeps the other.
    std::vector<ParticleObstacle> obstacles;
    std::vector<ParticleObstacle> detail_obstacles;
};

constexpr uint64_t kMaxParticles = 10'000'000;
constexpr uint64_t kMaxStrandPoints = 50'000'000;
constexpr uint32_t kMaxParticleSteps = 100'000;
constexpr size_t kMaxCutters = 32;
// Coordinates beyond this are refused: the spatial hash's cells are indexed by 32-bit integers.
constexpr float kMaxParticleCoordinate_m = 1.0e5f;

// Checks every field; on failure *error names it, e.g. "attractors[1].charge[0].charge: not finite".
bool validateParticleScene(const ParticleScene& scene, std::string* error);

// a(t): the keys interpolated linearly in the step index.
float chargeAt(const std::vector<ChargeKey>& keys, uint32_t step);

// Distance from p to the attractor's skeleton.
float attractorDistance(const Attractor& a, glm::vec3 p);

// A mesh attractor's surface points (mesh and point_count set): one per stratum of the mesh's area, in
// its own frame, from a fixed seed, so the same file gives the same points.
std::shared_ptr<const std::vector<glm::vec3>> meshAttractorPoints(std::shared_ptr<const TriangleMesh> mesh,
                                                                 uint32_t count);

// The attractor's term of the fitness, a·min(d, influence) (§5.1 with the radius of influence the paper
// suggests). Clamping keeps f continuous: a term that dropped to 0 beyond the radius would make a
// positive attractor's border a cliff that pushes particles out.
// The term from the distance d: the random walk's trials compute a point's distances several at a time.
inline float attractorTermAt(const Attractor& a, float charge, float d) {
    return charge * (a.influence_m > 0.0f && d > a.influence_m ? a.influence_m : d);
}
inline float attractorTerm(const Attractor& a, float charge, glm::vec3 p) {
    // The point, the commonest kind, inline: this runs for every trial of every move.
    return attractorTermAt(a, charge, a.kind == AttractorKind::Point ? glm::length(p - a.a_m) : attractorDistance(a, p));
}

// g(p) of the cutter (see CutterKind).
float cutterValue(const Cutter& c, glm::vec3 p);
inline bool cutterTriggered(const Cutter& c, float g) {
    return c.side == CutterSide::Above ? g >= c.threshold_m : g <= c.threshold_m;
}

const char* strandActionName(StrandActionKind kind);

// Area of a mesh's triangle (unscaled), in double: the mesh generator's strata are built from these.
double meshTriangleArea(const TriangleMesh& mesh, size_t triangle);

// Where the system's strands can be: its generators' bounds grown by the longest walk (steps × step length)
// and the strand radius. A terrain-dropped rectangle's bounds are unbounded in z.
Bounds particleReach(const ParticleScene& scene);

// Moves every generator, attractor and cutter by `offset` (metres): the same system placed elsewhere.
void translateParticleScene(ParticleScene* scene, glm::vec3 offset);

}  // namespace ug
