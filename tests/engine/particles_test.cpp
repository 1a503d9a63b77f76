// Particle sculpting (engine/particles, docs/particles.md): seeding one particle per stratum, attractors
// that pull and push, keyframed charges, cutters that act exactly at their threshold, collisions that keep
// the strands' tubes apart, the same strands on any thread count, and bad input refused by field.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <set>

#include "core/hash.h"
#include "particles/particle_seeding.h"
#include "particles/segment_grid.h"
#include "particles/strand_growth.h"

namespace ug {
namespace {

// A patch of grass: particles on a square of side 2 at z = 0, heading up.
ParticleScene grassPatch(uint32_t count, uint32_t steps) {
    ParticleScene scene;
    ParticleGenerator g;
    g.kind = GeneratorKind::Rectangle;
    g.axis_u_m = {1.0f, 0.0f, 0.0f};
    g.axis_v_m = {0.0f, 1.0f, 0.0f};
    g.count = count;
    g.heading_cone_deg = 10.0f;
    scene.generators.push_back(g);
    scene.walk.steps = steps;
    scene.walk.trials = 8;
    scene.walk.cone_deg = 30.0f;
    scene.walk.step_length_m = 0.05f;
    scene.walk.strand_radius_m = 0.01f;
    scene.walk.seed = 7;
    return scene;
}

Attractor pointAttractor(glm::vec3 at, float charge) {
    Attractor a;
    a.kind = AttractorKind::Point;
    a.a_m = at;
    a.charge = {ChargeKey{0, charge}};
    return a;
}

Strands grow(const ParticleScene& scene, int threads = 2) {
    Strands s;
    std::string error;
    EXPECT_TRUE(growStrands(scene, {.threads = threads}, &s, &error)) << error;
    return s;
}

glm::vec3 point(const Strands& s, size_t strand, size_t i) { return s.points[s.offsets[strand] + i]; }
size_t length(const Strands& s, size_t strand) { return s.offsets[strand + 1] - s.offsets[strand]; }

// Mean distance to `at` of the strands' point i, over strands that have one.
double meanDistanceAt(const Strands& s, size_t i, glm::vec3 at) {
    double sum = 0.0;
    size_t n = 0;
    for (size_t k = 0; k < s.size(); ++k)
        if (length(s, k) > i) {
            sum += glm::length(glm::dvec3(point(s, k, i)) - glm::dvec3(at));
            ++n;
        }
    EXPECT_GT(n, 0u);
    return sum / double(n);
}

// Brute-force closest distance between segments, in double.
double segDist(glm::dvec3 p0, glm::dvec3 p1, glm::dvec3 q0, glm::dvec3 q1) {
    // Dense sampling of one segment against the exact point-segment distance: slow, independent of
    // the engine's closed form, exact enough at 1e-4 of a segment (a few micrometres here).
    double best = 1e300;
    for (int i = 0; i <= 2000; ++i) {
        const glm::dvec3 p = p0 + (p1 - p0) * (double(i) / 2000.0);
        const glm::dvec3 d = q1 - q0;
        const double l2 = glm::dot(d, d);
        const double t = l2 > 0.0 ? std::clamp(glm::dot(p - q0, d) / l2, 0.0, 1.0) : 0.0;
        best = std::min(best, glm::length(p - (q0 + t * d)));
    }
    return best;
}

bool related(const Strands& s, size_t a, size_t b) {
    return s.parent[a] == int32_t(b) || s.parent[b] == int32_t(a) || (s.parent[a] >= 0 && s.parent[a] == s.parent[b]);
}

TEST(ParticleSeeding, StratifiedJitterPutsExactlyOneParticlePerStratum) {
    for (GeneratorKind kind : {GeneratorKind::Rectangle, GeneratorKind::Sphere, GeneratorKind::Box}) {
        for (uint32_t count : {1u, 7u, 100u, 997u, 5000u}) {
            ParticleGenerator g;
            g.kind = kind;
            g.center_m = {0.5f, -1.0f, 2.0f};
            g.axis_u_m = {2.0f, 0.0f, 0.0f};
            g.axis_v_m = {0.0f, 0.0f, 0.5f};
            g.radius_m = 1.5f;
            g.half_extents_m = {1.0f, 0.5f, 0.25f};
            g.count = count;
            ParticleSeeds seeds;
            seedGenerator(g, 0, 3, &seeds);
            ASSERT_EQ(seeds.positions.size(), count);
            std::vector<int> hits(count, 0);
            for (const glm::vec3& p : seeds.positions) {
                const uint32_t s = locateStratum(g, p);
                ASSERT_LT(s, count);
                ++hits[s];
            }
            for (uint32_t s = 0; s < count; ++s)
                EXPECT_EQ(hits[s], 1) << "kind " << int(kind) << " count " << count << " stratum " << s;
        }
    }
}

// Two triangles of areas 0.5 (z = 0) and 1.5 (z = 1, facing down), scaled by 2 and moved.
ParticleGenerator twoTriangleMesh(uint32_t count) {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {3, 0, 1}, {0, 1, 1}};
    mesh->indices = {0, 1, 2, 3, 5, 4};
    ParticleGenerator g;
    g.kind = GeneratorKind::Mesh;
    g.mesh = mesh;
    g.scale = 2.0f;
    g.center_m = {1.0f, -1.0f, 0.5f};
    g.count = count;
    return g;
}

TEST(ParticleSeeding, MeshStrataAreEqualSlicesOfItsArea) {
    for (uint32_t count : {1u, 4u, 400u, 997u}) {
        const ParticleGenerator g = twoTriangleMesh(count);
        ParticleSeeds seeds;
        seedGenerator(g, 0, 13, &seeds);
        ASSERT_EQ(seeds.positions.size(), count);
        std::vector<int> hits(count, 0);
        size_t low = 0;
        for (size_t i = 0; i < seeds.positions.size(); ++i) {
            const glm::vec3 p = seeds.positions[i];
            ++hits[locateStratum(g, p)];
            // On one of the two placed triangles, with its normal (the second is wound to face down).
            const bool first = std::abs(p.z - 0.5f) < 1e-5f;
            low += first;
            EXPECT_TRUE(first || std::abs(p.z - 2.5f) < 1e-5f) << p.z;
            const glm::vec3 q = (p - g.center_m) / 2.0f;  // back in the model's space
            EXPECT_GE(q.x, -1e-5f);
            EXPECT_GE(q.y, -1e-5f);
            EXPECT_LE(first ? q.x + q.y : q.x / 3.0f + q.y, 1.0f + 1e-5f);
            EXPECT_NEAR(seeds.normals[i].z, first ? 1.0f : -1.0f, 1e-6f);
        }
        for (uint32_t s = 0; s < count; ++s) EXPECT_EQ(hits[s], 1) << "count " << count << " stratum " << s;
        // The first triangle holds a quarter of the area: the strata of the first quarter (the one
        // straddling the quarter, when count is not a multiple of 4, either way).
        EXPECT_GE(low, size_t(count / 4)) << count;
        EXPECT_LE(low, size_t((count + 3) / 4)) << count;
    }
}

TEST(ParticleSeeding, SeedsLieOnTheSurfaceAndHeadingsInTheCone) {
    ParticleGenerator g;
    g.kind = GeneratorKind::Sphere;
    g.center_m = {1.0f, 2.0f, 3.0f};
    g.radius_m = 2.0f;
    g.count = 2000;
    g.heading_cone_deg = 20.0f;
    ParticleSeeds seeds;
    seedGenerator(g, 0, 11, &seeds);
    float widest = 0.0f;
    for (size_t i = 0; i < seeds.positions.size(); ++i) {
        EXPECT_NEAR(glm::length(seeds.positions[i] - g.center_m), 2.0f, 1e-5f);
        const glm::vec3 heading = seeds.frames[i] * glm::vec3(0.0f, 0.0f, 1.0f);
        const float angle = glm::degrees(std::acos(std::clamp(glm::dot(heading, seeds.normals[i]), -1.0f, 1.0f)));
        EXPECT_LE(angle, 20.0f + 1e-2f);
        widest = std::max(widest, angle);
    }
    EXPECT_GT(widest, 15.0f);  // the cone is used, not just the normal
}

TEST(ParticleSeeding, EqualStrataAreEqualAreasOnTheSphere) {
    // The Archimedes map: as many seeds fall in the polar caps z > 0.5 (a quarter of the area, z in
    // [0.5, 1]) as area says, within the one-row slack of the strata.
    ParticleGenerator g;
    g.kind = GeneratorKind::Sphere;
    g.count = 10000;
    ParticleSeeds seeds;
    seedGenerator(g, 0, 5, &seeds);
    size_t cap = 0;
    for (const glm::vec3& p : seeds.positions) cap += p.z > 0.5f;
    EXPECT_NEAR(double(cap), 2500.0, 60.0);
}

TEST(ParticleTrials, CosSinOfTurnsStaysWithinTwoUnitsInTheLastPlace) {
    // Against the double-precision library on a fine sweep and at the quarter-reduction's seams.
    std::vector<float> turns;
    for (int i = 0; i < (1 << 16); ++i) turns.push_back(float(i) / float(1 << 16));
    for (float seam : {0.125f, 0.375f, 0.625f, 0.875f, 1.0f})
        for (float t : {std::nextafter(seam, 0.0f), seam, std::nextafter(seam, 2.0f)})
            if (t < 1.0f) turns.push_back(t);
    turns.push_back(std::nextafter(1.0f, 0.0f));
    double worst = 0.0;
    for (float t : turns) {
        float c, s;
        cosSinOfTurns(t, &c, &s);
        const double angle = 2.0 * M_PI * double(t);
        worst = std::max({worst, std::abs(double(c) - std::cos(angle)), std::abs(double(s) - std::sin(angle))});
    }
    EXPECT_LT(worst, 2.0 * 1.2e-7) << "float's unit in the last place at 1 is 1.2e-7";
}

TEST(ParticleTrials, BatchedConeDirectionsAreTheConesDirections) {
    // The walk's batched trials against the one-at-a-time construction (the C library's cosine and sine):
    // the same unit directions in the cap, to float's rounding, for every quarter of the turn.
    const float cos_cone = std::cos(glm::radians(25.0f));
    std::vector<float> u, v;
    for (uint64_t i = 0; i < 4096; ++i) {
        const uint64_t h = hashWords(3, i);
        u.push_back(unitFloat(h));
        v.push_back(unitFloat(mix64(h)));
    }
    std::vector<float> x(u.size()), y(u.size()), z(u.size());
    coneDirectionsCos(cos_cone, u.size(), u.data(), v.data(), x.data(), y.data(), z.data());
    std::array<int, 4> quarters{};
    for (size_t i = 0; i < u.size(); ++i) {
        const glm::vec3 batched(x[i], y[i], z[i]), one = coneDirectionCos(cos_cone, u[i], v[i]);
        ASSERT_LT(glm::length(batched - one), 1e-6f) << "trial " << i;
        EXPECT_NEAR(glm::length(batched), 1.0f, 1e-6f);
        EXPECT_GE(batched.z, cos_cone - 1e-6f);
        ++quarters[size_t(std::min(3.0f, 4.0f * v[i]))];
    }
    for (int q : quarters) EXPECT_GT(q, 900) << "every quarter of the turn is covered";
}

TEST(ParticleAttractors, PositiveChargePullsAndNegativePushes) {
    const glm::vec3 at(3.0f, 0.0f, 1.0f);
    for (float charge : {1.0f, -1.0f}) {
        ParticleScene scene = grassPatch(200, 20);
        scene.walk.collisions = false;
        scene.walk.cone_deg = 45.0f;
        scene.attractors.push_back(pointAttractor(at, charge));
        const Strands s = grow(scene);
        ASSERT_EQ(s.size(), 200u);
        for (size_t i = 1; i <= 20; ++i) {
            const double before = meanDistanceAt(s, i - 1, at), after = meanDistanceAt(s, i, at);
            if (charge > 0)
                EXPECT_LT(after, before) << "step " << i;
            else
                EXPECT_GT(after, before) << "step " << i;
        }
    }
}

TEST(ParticleAttractors, ChargeIsPiecewiseLinearInTheStep) {
    const std::vector<ChargeKey> keys{{2, 1.0f}, {6, -1.0f}, {10, -1.0f}};
    EXPECT_EQ(chargeAt(keys, 0), 1.0f);
    EXPECT_EQ(chargeAt(keys, 2), 1.0f);
    EXPECT_EQ(chargeAt(keys, 4), 0.0f);
    EXPECT_EQ(chargeAt(keys, 5), -0.5f);
    EXPECT_EQ(chargeAt(keys, 6), -1.0f);
    EXPECT_EQ(chargeAt(keys, 50), -1.0f);
}

TEST(ParticleAttractors, InfluenceRadiusClampsTheTerm) {
    Attractor a = pointAttractor({0.0f, 0.0f, 0.0f}, 2.0f);
    a.influence_m = 1.0f;
    EXPECT_FLOAT_EQ(attractorTerm(a, 2.0f, {0.5f, 0.0f, 0.0f}), 1.0f);
    EXPECT_FLOAT_EQ(attractorTerm(a, 2.0f, {5.0f, 0.0f, 0.0f}), 2.0f);  // continuous: no cliff at the border
    Attractor sphere = a;
    sphere.kind = AttractorKind::Sphere;
    sphere.radius_m = 2.0f;
    sphere.influence_m = 0.0f;
    EXPECT_FLOAT_EQ(attractorDistance(sphere, {0.5f, 0.0f, 0.0f}), 1.5f);
    Attractor seg = a;
    seg.kind = AttractorKind::Segment;
    seg.b_m = {4.0f, 0.0f, 0.0f};
    EXPECT_FLOAT_EQ(attractorDistance(seg, {2.0f, 3.0f, 0.0f}), 3.0f);
    EXPECT_FLOAT_EQ(attractorDistance(seg, {7.0f, 4.0f, 0.0f}), 5.0f);
}

TEST(ParticleAttractors, KeyframedSignChangeChangesBehaviourFromThatStep) {
    const glm::vec3 at(3.0f, 0.0f, 1.0f);
    const uint32_t k = 8;
    ParticleScene attract = grassPatch(150, 16);
    attract.walk.collisions = false;
    attract.walk.cone_deg = 120.0f;  // wide enough that a turned strand can move away at once
    attract.attractors.push_back(pointAttractor(at, 1.0f));
    ParticleScene flip = attract;
    flip.attractors[0].charge = {ChargeKey{k - 1, 1.0f}, ChargeKey{k, -1.0f}};
    const Strands a = grow(attract), f = grow(flip);
    ASSERT_EQ(a.size(), f.size());
    // Identical up to point k - 1 (steps 1 .. k - 1 saw a = +1 in both), different from point k on.
    size_t differ = 0;
    for (size_t s = 0; s < a.size(); ++s) {
        for (size_t i = 0; i < k; ++i) ASSERT_EQ(point(a, s, i), point(f, s, i)) << "strand " << s << " point " << i;
        differ += point(a, s, k) != point(f, s, k);
    }
    EXPECT_GT(differ, a.size() * 9 / 10);
    EXPECT_LT(meanDistanceAt(f, k - 1, at), meanDistanceAt(f, k - 2, at));  // still pulled at step k - 1
    EXPECT_GT(meanDistanceAt(f, k, at), meanDistanceAt(f, k - 1, at));      // pushed from step k
    EXPECT_LT(meanDistanceAt(a, k, at), meanDistanceAt(a, k - 1, at));
}

// Grass growing up through a plane cutter at z = 0.3 with each action.
ParticleScene grassUnderCutter(StrandActionKind action) {
    ParticleScene scene = grassPatch(100, 20);
    scene.walk.collisions = false;
    scene.attractors.push_back(pointAttractor({0.0f, 0.0f, 5.0f}, 1.0f));
    Cutter c;
    c.kind = CutterKind::Plane;
    c.normal = {0.0f, 0.0f, 1.0f};
    c.threshold_m = 0.3f;
    c.side = CutterSide::Above;
    c.action.kind = action;
    c.action.split_count = 3;
    c.action.split_angle_deg = 40.0f;
    scene.cutters.push_back(c);
    return scene;
}

TEST(ParticleCutters, StopEndsStrandsExactlyAtTheThreshold) {
    const Strands s = grow(grassUnderCutter(StrandActionKind::Stop));
    ASSERT_EQ(s.size(), 100u);
    for (size_t k = 0; k < s.size(); ++k) {
        for (size_t i = 0; i < length(s, k); ++i) EXPECT_LT(point(s, k, i).z, 0.3f);
        EXPECT_NEAR(point(s, k, length(s, k) - 1).z, 0.3f, 1e-5f);
        EXPECT_LT(length(s, k), 21u);  // stopped before the last step
    }
    EXPECT_EQ(s.stats.cutter_hits, 100u);
}

TEST(ParticleCutters, KillRemovesTheStrandsThatReachIt) {
    ParticleScene scene = grassUnderCutter(StrandActionKind::Kill);
    scene.cutters[0].threshold_m = 0.5f;
    // Half of the strands (the second generator) are too slow to reach the cutter in 20 steps.
    ParticleGenerator slow = scene.generators[0];
    slow.center_m = {10.0f, 0.0f, 0.0f};
    slow.heading_cone_deg = 0.0f;
    scene.generators.push_back(slow);
    scene.attractors[0].influence_m = 0.0f;
    scene.attractors.push_back(pointAttractor({10.0f, 0.0f, 0.2f}, 50.0f));  // holds the slow ones down
    scene.attractors[1].influence_m = 1.5f;
    const Strands s = grow(scene);
    EXPECT_GT(s.stats.killed, 0u);
    EXPECT_EQ(s.stats.killed, s.stats.cutter_hits);
    EXPECT_EQ(s.size() + s.stats.killed + s.stats.dropped, 200u);
    for (size_t k = 0; k < s.size(); ++k)
        for (size_t i = 0; i < length(s, k); ++i) EXPECT_LT(point(s, k, i).z, 0.5f);
}

TEST(ParticleCutters, CountdownGoesOnThatManyStepsThenKillsOrStops) {
    // 100 strands reach the plane at 0.3 m well before step 20; a countdown of 3 lets each go on 3 more
    // moves past it. Ending in a kill removes them all; ending in a stop keeps them, each with exactly 3
    // points beyond the threshold (the crossing move itself is clipped to it).
    ParticleScene scene = grassUnderCutter(StrandActionKind::Countdown);
    scene.cutters[0].action.countdown_steps = 3;
    const Strands killed = grow(scene);
    EXPECT_EQ(killed.size(), 0u);
    EXPECT_EQ(killed.stats.killed, 100u);
    scene.cutters[0].action.countdown_then = StrandActionKind::Stop;
    const Strands stopped = grow(scene);
    ASSERT_EQ(stopped.size(), 100u);
    EXPECT_EQ(stopped.stats.killed, 0u);
    for (size_t k = 0; k < stopped.size(); ++k) {
        size_t beyond = 0;
        for (size_t i = 0; i < length(stopped, k); ++i) beyond += point(stopped, k, i).z > 0.3f + 1e-5f;
        EXPECT_EQ(beyond, 3u) << "strand " << k;
        EXPECT_LT(length(stopped, k), 21u);  // ended before the last step
    }
}

TEST(ParticleCutters, SplitContinuesChildrenFromTheThreshold) {
    const Strands s = grow(grassUnderCutter(StrandActionKind::Split));
    size_t parents = 0, children = 0;
    for (size_t k = 0; k < s.size(); ++k) {
        if (s.parent[k] < 0) {
            ++parents;
            for (size_t i = 0; i < length(s, k); ++i) EXPECT_LT(point(s, k, i).z, 0.3f);
            EXPECT_NEAR(point(s, k, length(s, k) - 1).z, 0.3f, 1e-5f);
        } else {
            ++children;
            const size_t p = size_t(s.parent[k]);
            EXPECT_EQ(point(s, k, 0), point(s, p, length(s, p) - 1));  // from the split point
            EXPECT_GT(point(s, k, length(s, k) - 1).z, 0.3f);           // and past it: it fires once
        }
    }
    EXPECT_EQ(parents, 100u);
    EXPECT_EQ(children, 300u);
    EXPECT_EQ(s.stats.splits, 100u);
}

TEST(ParticleCutters, SplitChildrenLeaveTheSplitPointWithCollisionsOn) {
    // The cutter clips the parent's last move, often to less than the strands' reach: the children
    // start within 2r of the parent's previous segment, which must not count as a collision (it stopped
    // up to half of them on the spot). A child that then bends back into its parent still collides:
    // the brute-force test of ParticleCollisions covers that.
    ParticleScene scene = grassUnderCutter(StrandActionKind::Split);
    scene.walk.collisions = true;
    scene.walk.on_collision.kind = StrandActionKind::Stop;
    const Strands s = grow(scene);
    ASSERT_GT(s.stats.splits, 90u);  // a few parents meet another before the cutter
    size_t children = 0, clipped_short = 0;
    for (size_t k = 0; k < s.size(); ++k) {
        if (s.parent[k] < 0) {
            const size_t n = length(s, k);
            clipped_short += glm::length(point(s, k, n - 1) - point(s, k, n - 2)) < 2.0f * scene.walk.strand_radius_m;
            continue;
        }
        ++children;
    }
    // Children that never move are dropped from the output. Before the exemption 294 of 297 were; the
    // few left may meet a neighbour's strand, as any strand may.
    EXPECT_GE(children, 3 * s.stats.splits - 3) << s.stats.collisions << " collisions";
    EXPECT_GT(clipped_short, 10u);  // the case arises
}

TEST(ParticleCutters, SphereAndBoxCuttersHoldTheirThreshold) {
    for (CutterKind kind : {CutterKind::Sphere, CutterKind::Box}) {
        ParticleScene scene = grassPatch(80, 30);
        scene.walk.collisions = false;
        scene.attractors.push_back(pointAttractor({0.0f, 0.0f, 2.0f}, 1.0f));
        Cutter c;
        c.kind = kind;
        c.center_m = {0.0f, 0.0f, 2.0f};
        c.radius_m = 0.8f;
        c.half_extents_m = {1.5f, 1.5f, 0.6f};
        c.threshold_m = 0.1f;
        c.side = CutterSide::Below;  // reaching it from outside
        c.action.kind = StrandActionKind::Stop;
        scene.cutters.push_back(c);
        const Strands s = grow(scene);
        ASSERT_GT(s.stats.cutter_hits, 0u);
        for (size_t k = 0; k < s.size(); ++k) {
            for (size_t i = 0; i < length(s, k); ++i) EXPECT_GT(cutterValue(c, point(s, k, i)), 0.1f);
            if (length(s, k) < 31) {
                EXPECT_NEAR(cutterValue(c, point(s, k, length(s, k) - 1)), 0.1f, 1e-5f);
            }
        }
    }
}

// Dense grass bent toward a few attractors so strands crowd and collide, with splits on collision.
ParticleScene crowdedGrass() {
    ParticleScene scene = grassPatch(300, 30);
    scene.generators[0].axis_u_m = {0.4f, 0.0f, 0.0f};
    scene.generators[0].axis_v_m = {0.0f, 0.4f, 0.0f};
    scene.walk.strand_radius_m = 0.012f;
    scene.walk.on_collision.kind = StrandActionKind::Split;
    scene.walk.on_collision.split_count = 2;
    scene.walk.on_collision.split_angle_deg = 60.0f;
    scene.walk.max_split_depth = 2;
    scene.attractors.push_back(pointAttractor({0.0f, 0.0f, 1.0f}, 1.0f));
    scene.attractors.push_back(pointAttractor({0.6f, 0.6f, 0.8f}, 0.5f));
    Attractor push = pointAttractor({0.0f, 0.0f, 0.4f}, -1.0f);
    push.charge = {ChargeKey{0, 0.0f}, ChargeKey{15, -2.0f}};
    scene.attractors.push_back(push);
    Cutter c;
    c.threshold_m = 1.2f;
    c.action.kind = StrandActionKind::Countdown;
    c.action.countdown_steps = 3;
    scene.cutters.push_back(c);
    return scene;
}

// Brute force over every pair of segments of different strands (a split's children may share their
// split point with their family): none closer than 2r. Returns how many near pairs it measured.
size_t expectTwiceTheRadiusApart(const Strands& s, float radius) {
    const double reach = 2.0 * double(radius) - 1e-6;
    size_t pairs = 0;
    for (size_t a = 0; a < s.size(); ++a)
        for (size_t b = a + 1; b < s.size(); ++b)
            for (size_t i = 0; i + 1 < length(s, a); ++i)
                for (size_t j = 0; j + 1 < length(s, b); ++j) {
                    const glm::dvec3 p0(point(s, a, i)), p1(point(s, a, i + 1));
                    const glm::dvec3 q0(point(s, b, j)), q1(point(s, b, j + 1));
                    // Cheap reject before the slow distance.
                    if (glm::length(0.5 * (p0 + p1) - 0.5 * (q0 + q1)) >
                        0.5 * glm::length(p1 - p0) + 0.5 * glm::length(q1 - q0) + reach + 1e-6)
                        continue;
                    if (related(s, a, b) && (p0 == q0 || p0 == q1 || p1 == q0 || p1 == q1)) continue;
                    ++pairs;
                    EXPECT_GE(segDist(p0, p1, q0, q1), reach) << "strands " << a << ", " << b << " segments " << i << ", " << j;
                }
    return pairs;
}

TEST(ParticleCollisions, StrandsNeverComeCloserThanTwiceTheirRadius) {
    const ParticleScene scene = crowdedGrass();
    const Strands s = grow(scene);
    ASSERT_GT(s.stats.collisions, 100u);  // the scene does crowd
    ASSERT_GT(s.stats.splits, 10u);
    EXPECT_GT(expectTwiceTheRadiusApart(s, scene.walk.strand_radius_m), 1000u);  // many near pairs were checked
}

// walk.retry_refused: a refused fittest trial gives way to the next-fittest that is not refused, so the
// strands still keep 2r apart, fewer strands stop on a collision and they grow further; the same for any
// thread count.
TEST(ParticleCollisions, RetryingTakesTheNextFittestTrialAndStillKeepsTwiceTheRadius) {
    ParticleScene scene = crowdedGrass();
    scene.walk.on_collision.kind = StrandActionKind::Stop;
    const Strands once = grow(scene);
    scene.walk.retry_refused = true;
    const Strands retried = grow(scene, 1);
    ASSERT_GT(once.stats.collisions, 100u);
    // Each collision stops a strand; a same-step conflict (a lower id's move) is not retried.
    EXPECT_LT(retried.stats.collisions, once.stats.collisions);
    EXPECT_GT(retried.stats.moves, once.stats.moves + once.stats.moves / 10) << once.stats.moves;
    EXPECT_GT(expectTwiceTheRadiusApart(retried, scene.walk.strand_radius_m), 1000u);
    for (const int threads : {2, 8}) {
        const Strands other = grow(scene, threads);
        EXPECT_EQ(other.offsets, retried.offsets) << threads;
        EXPECT_EQ(other.points, retried.points) << threads;
    }
}

TEST(ParticleCollisions, WithoutCollisionsTheSameSceneOverlaps) {
    // The check above can fail: the same scene with collisions off has strands within 2r.
    ParticleScene scene = crowdedGrass();
    scene.walk.collisions = false;
    const Strands s = grow(scene);
    const float reach2 = 4.0f * scene.walk.strand_radius_m * scene.walk.strand_radius_m;
    size_t close = 0;
    for (size_t a = 0; a < s.size() && close == 0; ++a)
        for (size_t b = a + 1; b < s.size() && close == 0; ++b)
            for (size_t i = 1; i + 1 < length(s, a); ++i)
                for (size_t j = 1; j + 1 < length(s, b); ++j)
                    close += segmentSegmentDistance2(point(s, a, i), point(s, a, i + 1), point(s, b, j),
                                                     point(s, b, j + 1)) < reach2;
    EXPECT_GT(close, 0u);
}

// A closed cube of side 2 centred at the origin, wound outward.
std::shared_ptr<TriangleMesh> cubeMesh() {
    auto m = std::make_shared<TriangleMesh>();
    for (int i = 0; i < 8; ++i) m->positions.push_back(glm::vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
    m->indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                  2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    return m;
}

TEST(ParticleSolids, StrandsPulledIntoAMeshStopAtItsSurface) {
    // Strands seeded on a cube (scaled to side 0.5) and pulled to its centre: with solids on, no point
    // ever lies inside; with them off, the same scene goes in.
    ParticleScene scene;
    ParticleGenerator g;
    g.kind = GeneratorKind::Mesh;
    g.mesh = cubeMesh();
    g.scale = 0.25f;
    g.center_m = {0.3f, -0.2f, 1.0f};
    g.count = 300;
    g.heading_cone_deg = 80.0f;
    scene.generators.push_back(g);
    scene.attractors.push_back(pointAttractor(g.center_m, 1.0f));
    scene.walk.steps = 12;
    scene.walk.cone_deg = 60.0f;
    scene.walk.step_length_m = 0.02f;
    scene.walk.strand_radius_m = 0.001f;
    scene.walk.collisions = false;
    auto inside = [&](const Strands& s) {
        size_t n = 0;
        for (const glm::vec3& p : s.points) {
            const glm::vec3 q = glm::abs(p - g.center_m);
            n += std::max(q.x, std::max(q.y, q.z)) < 0.25f - 1e-4f;
        }
        return n;
    };
    const Strands solid = grow(scene);
    EXPECT_GT(solid.stats.solid_hits, 100u);
    EXPECT_EQ(inside(solid), 0u);
    // Retrying, a strand pressed against the surface slides along it: more moves, still never inside.
    scene.walk.retry_refused = true;
    const Strands sliding = grow(scene);
    EXPECT_EQ(inside(sliding), 0u);
    EXPECT_GT(sliding.stats.moves, solid.stats.moves);
    EXPECT_LT(sliding.stats.solid_hits, solid.stats.solid_hits);
    scene.walk.retry_refused = false;
    scene.walk.solids = false;
    const Strands open = grow(scene);
    EXPECT_EQ(open.stats.solid_hits, 0u);
    EXPECT_GT(inside(open), 100u);
}

TEST(ParticleSolids, StrandsPulledIntoTheTerrainStopAtTheGround) {
    std::vector<float> heights;
    for (int j = 0; j < 9; ++j)
        for (int i = 0; i < 9; ++i) heights.push_back(0.3f * (-2.0f + 0.5f * i) + 0.1f * (-2.0f + 0.5f * j));
    ParticleScene scene = grassPatch(200, 15);
    scene.terrain = std::make_shared<const HeightField>(glm::vec2(-2.0f), 0.5f, 9, 9, heights);
    scene.generators[0].on_terrain = true;
    scene.walk.collisions = false;
    scene.walk.step_length_m = 0.03f;
    // Up for five steps, then pulled down hard.
    Attractor down = pointAttractor({0.0f, 0.0f, -5.0f}, 0.0f);
    down.charge = {ChargeKey{0, 0.0f}, ChargeKey{5, 0.0f}, ChargeKey{6, 3.0f}};
    scene.attractors.push_back(pointAttractor({0.0f, 0.0f, 5.0f}, 1.0f));
    scene.attractors.push_back(down);
    auto below = [&](const Strands& s) {
        size_t n = 0;
        for (const glm::vec3& p : s.points) n += p.z < scene.terrain->sample(p.x, p.y) - 1e-4f;
        return n;
    };
    const Strands solid = grow(scene);
    EXPECT_GT(solid.stats.solid_hits, 20u);
    EXPECT_EQ(below(solid), 0u);
    scene.walk.solids = false;
    const Strands open = grow(scene);
    EXPECT_GT(below(open), 50u);
}

TEST(ParticleCollisions, GridVisitsExactlyTheSegmentsWithinReach) {
    // Midpoints scattered over a few cells and across the origin (negative cells); every query must see
    // exactly the brute-force set, including those just inside the reach at a cell's far side.
    const float reach = 0.05f;
    SegmentGrid grid(reach);
    std::vector<glm::vec3> mids;
    for (uint32_t i = 0; i < 4000; ++i) {
        const uint64_t h = hashWords(1, i);
        mids.push_back(glm::vec3(unitFloat(h), unitFloat(mix64(h)), unitFloat(mix64(mix64(h)))) * 0.6f - 0.3f);
        grid.insert(i, mids.back(), i * 3);
    }
    size_t seen_total = 0;
    for (uint32_t q = 0; q < 1500; ++q) {
        const uint64_t h = hashWords(2, q);
        const glm::vec3 m = glm::vec3(unitFloat(h), unitFloat(mix64(h)), unitFloat(mix64(mix64(h)))) * 0.7f - 0.35f;
        std::set<uint32_t> seen, expected;
        EXPECT_FALSE(grid.anyNear(m, [&](uint32_t id, uint32_t tag) {
            EXPECT_EQ(tag, id * 3);
            seen.insert(id);
            return false;
        }));
        for (uint32_t i = 0; i < mids.size(); ++i)
            if (glm::dot(mids[i] - m, mids[i] - m) <= reach * reach) expected.insert(i);
        ASSERT_EQ(seen, expected) << "query " << q;
        seen_total += seen.size();
    }
    EXPECT_GT(seen_total, 1500u * 4u);  // about 6 a query: the sets are not trivially empty
    EXPECT_TRUE(grid.anyNear(mids[7], [&](uint32_t id, uint32_t) { return id == 7; }));
}

TEST(ParticleCollisions, SegmentDistanceMatchesBruteForce) {
    const glm::vec3 cases[][4] = {
        {{0, 0, 0}, {1, 0, 0}, {0.5f, 1, 0}, {0.5f, 2, 0}},
        {{0, 0, 0}, {1, 0, 0}, {0, 1, 1}, {1, 1, 1}},       // parallel
        {{0, 0, 0}, {1, 1, 0}, {1, 0, 0.5f}, {0, 1, 0.5f}},  // crossing above
        {{0, 0, 0}, {0, 0, 0}, {2, 0, 0}, {2, 0, 3}},        // a point
        {{0, 0, 0}, {1, 0, 0}, {3, 1, 0}, {4, 3, 0}},        // ends nearest
    };
    for (const auto& c : cases)
        EXPECT_NEAR(std::sqrt(segmentSegmentDistance2(c[0], c[1], c[2], c[3])),
                    segDist(c[0], c[1], c[2], c[3]), 1e-3);
}

TEST(ParticleThreads, OneTwoAndEightThreadsGiveBitIdenticalStrands) {
    // Enough strands for many chunks of the parallel loops (512 strands each), crowded like the above.
    ParticleScene scene = crowdedGrass();
    scene.generators[0].count = 8000;
    scene.generators[0].axis_u_m = {1.6f, 0.0f, 0.0f};
    scene.generators[0].axis_v_m = {0.0f, 1.6f, 0.0f};
    scene.walk.steps = 20;
    const Strands one = grow(scene, 1), two = grow(scene, 2), eight = grow(scene, 8);
    ASSERT_GT(one.stats.collisions, 0u);
    for (const Strands* s : {&two, &eight}) {
        ASSERT_EQ(s->offsets, one.offsets);
        ASSERT_EQ(s->parent, one.parent);
        ASSERT_EQ(s->particle, one.particle);
        ASSERT_EQ(s->points.size(), one.points.size());
        EXPECT_EQ(std::memcmp(s->points.data(), one.points.data(), one.points.size() * sizeof(glm::vec3)), 0);
        EXPECT_EQ(s->stats.collisions, one.stats.collisions);
        EXPECT_EQ(s->stats.moves, one.stats.moves);
    }
}

TEST(ParticleThreads, ADifferentSeedGivesDifferentStrands) {
    ParticleScene scene = crowdedGrass();
    const Strands a = grow(scene);
    scene.walk.seed = 8;
    const Strands b = grow(scene);
    EXPECT_NE(a.points, b.points);
}

TEST(ParticleAge, MaxAgeStopsAndSplitsAtTheLimit) {
    ParticleScene scene = grassPatch(50, 20);
    scene.walk.collisions = false;
    scene.walk.max_age_steps = 5;
    scene.walk.on_age.kind = StrandActionKind::Split;
    scene.walk.on_age.split_count = 2;
    scene.walk.max_split_depth = 2;
    const Strands s = grow(scene);
    // Roots split after 5 steps, children after 5 more, grandchildren stop at 5: 50 + 100 + 200.
    ASSERT_EQ(s.size(), 350u);
    for (size_t k = 0; k < s.size(); ++k) EXPECT_EQ(length(s, k), 6u);
}

void expectRefused(const ParticleScene& scene, const std::string& field) {
    Strands s;
    std::string error;
    EXPECT_FALSE(growStrands(scene, {}, &s, &error)) << field;
    EXPECT_NE(error.find(field), std::string::npos) << "error: " << error << ", expected field " << field;
}

TEST(ParticleValidation, BadInputsAreRefusedWithTheFieldNamed) {
    const ParticleScene good = crowdedGrass();
    {
        std::string error;
        EXPECT_TRUE(validateParticleScene(good, &error)) << error;
    }
    ParticleScene s = good;
    s.attractors[1].charge[0].charge = std::nanf("");
    expectRefused(s, "attractors[1].charge[0].charge");
    s = good;
    s.attractors[2].charge[1].charge = INFINITY;
    expectRefused(s, "attractors[2].charge[1].charge");
    s = good;
    s.attractors[0].a_m.y = NAN;
    expectRefused(s, "attractors[0].a_m");
    s = good;
    s.generators[0].center_m.x = INFINITY;
    expectRefused(s, "generators[0].center_m");
    s = good;
    s.walk.trials = 0;
    expectRefused(s, "walk.trials");
    s = good;
    s.walk.cone_deg = 0.0f;
    expectRefused(s, "walk.cone_deg");
    s = good;
    s.walk.cone_deg = 180.0f;
    expectRefused(s, "walk.cone_deg");
    s = good;
    s.walk.step_length_m = 0.0f;
    expectRefused(s, "walk.step_length_m");
    s = good;
    s.walk.step_length_m = -1.0f;
    expectRefused(s, "walk.step_length_m");
    s = good;
    s.walk.strand_radius_m = NAN;
    expectRefused(s, "walk.strand_radius_m");
    s = good;
    s.attractors[2].charge[1].step = 0;
    expectRefused(s, "attractors[2].charge[1].step");
    s = good;
    s.cutters[0].normal = {0.0f, 0.0f, 2.0f};
    expectRefused(s, "cutters[0].normal");
    s = good;
    s.walk.max_split_depth = 300;  // a generation counter that would wrap
    expectRefused(s, "walk.max_split_depth");
    s = good;
    s.walk.on_collision.split_count = 0;
    expectRefused(s, "walk.on_collision.split_count");
    // Sizes are refused before anything is allocated: 4 G particles, or 10 M x 100 steps of points.
    s = good;
    s.generators[0].count = 0xffffffffu;
    expectRefused(s, "generators[0].count");
    s = good;
    s.generators[0].count = 1'000'000;
    s.walk.steps = 100;
    expectRefused(s, "walk.max_points");
    s = good;
    s.walk.max_points = 60'000'000;
    expectRefused(s, "walk.max_points");
}

TEST(ParticleValidation, SplitsBeyondMaxPointsAreRefusedNotTruncated) {
    ParticleScene scene = grassPatch(100, 40);
    scene.walk.collisions = false;
    scene.walk.max_age_steps = 2;
    scene.walk.on_age.kind = StrandActionKind::Split;
    scene.walk.on_age.split_count = 4;
    scene.walk.max_split_depth = 12;
    scene.walk.max_points = 50'000;
    Strands s;
    std::string error;
    EXPECT_FALSE(growStrands(scene, {}, &s, &error));
    EXPECT_NE(error.find("walk.max_points"), std::string::npos) << error;
}

}  // namespace
}  // namespace ug
