// Distance keeping, §5.2's "keeping distance from another particles": a strand takes the fittest of its
// trials whose end stays walk.keep_distance_m clear of other families' earlier segments, and acts
// on_distance when none can. Checked by brute force on the polylines (a distance in double written here,
// not the engine's grid or segment distance), against the same growth without keeping, across thread
// counts, and through the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "particle_test_util.h"
#include "particles/particle_json.h"
#include "particles/strand_growth.h"

namespace ug {
namespace {

// Strands from a 0.6 m square drawn to one point 0.35 m above its centre: without keeping they crowd
// together towards it. No collisions, no splits: a root's point i is its move at step i, until it stops.
ParticleScene convergingStrands(float keep_m) {
    ParticleScene s;
    ParticleGenerator g;
    g.axis_u_m = {0.3f, 0.0f, 0.0f};
    g.axis_v_m = {0.0f, 0.3f, 0.0f};
    g.count = 160;
    g.heading_cone_deg = 10.0f;
    s.generators.push_back(g);
    Attractor a;
    a.a_m = {0.0f, 0.0f, 0.35f};
    a.charge = {ChargeKey{0, 1.0f}};
    s.attractors.push_back(a);
    s.walk.seed = 7;
    s.walk.steps = 40;
    s.walk.trials = 8;
    s.walk.cone_deg = 40.0f;
    s.walk.step_length_m = 0.01f;
    s.walk.strand_radius_m = 0.001f;
    s.walk.collisions = false;
    s.walk.keep_distance_m = keep_m;
    return s;
}

Strands grow(const ParticleScene& scene, int threads = 2) {
    Strands out;
    std::string error;
    EXPECT_TRUE(growStrands(scene, {.threads = threads}, &out, &error)) << error;
    return out;
}

double pointSegmentDistance(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b) {
    const glm::dvec3 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return glm::length(p - (a + ab * t));
}

// The smallest distance from a point of one strand to a segment another strand placed at an earlier step
// (roots without splits: point i was placed at step i, the segment ending at point i at step i).
double closestToEarlierSegments(const Strands& s) {
    double closest = std::numeric_limits<double>::infinity();
    for (size_t a = 0; a < s.size(); ++a)
        for (size_t b = 0; b < s.size(); ++b) {
            if (a == b) continue;
            for (uint32_t j = 1; s.offsets[a] + j < s.offsets[a + 1]; ++j) {
                const glm::dvec3 p(s.points[s.offsets[a] + j]);
                for (uint32_t i = 1; i < j && s.offsets[b] + i < s.offsets[b + 1]; ++i)
                    closest = std::min(closest, pointSegmentDistance(p, glm::dvec3(s.points[s.offsets[b] + i - 1]),
                                                                     glm::dvec3(s.points[s.offsets[b] + i])));
            }
        }
    return closest;
}

TEST(ParticleDistance, NoStrandComesWithinTheDistanceOfAnotherOnesEarlierSegments) {
    const float keep = 0.03f;
    const Strands loose = grow(convergingStrands(0.0f));
    const Strands kept = grow(convergingStrands(keep));
    ASSERT_EQ(loose.size(), 160u);
    // Without keeping the strands do crowd, or the check below would hold for any growth.
    EXPECT_LT(closestToEarlierSegments(loose), 0.3 * keep);
    EXPECT_EQ(loose.stats.crowded, 0u);
    EXPECT_GT(kept.stats.crowded, 0u);
    for (size_t k = 0; k < kept.size(); ++k) EXPECT_EQ(kept.parent[k], -1);
    EXPECT_GE(closestToEarlierSegments(kept), keep * (1.0 - 1e-5));
    // A crowded strand stops (the default on_distance): it never grows past the step it was crowded at.
    EXPECT_LT(kept.points.size(), loose.points.size());
}

TEST(ParticleDistance, TheFittestTrialThatKeepsTheDistanceIsTaken) {
    // Far apart strands are never crowded: keeping changes nothing, to the bit.
    ParticleScene far = convergingStrands(0.0f);
    far.generators[0].count = 4;
    far.attractors.clear();
    const Strands plain = grow(far);
    far.walk.keep_distance_m = 0.05f;
    const Strands kept = grow(far);
    EXPECT_EQ(kept.stats.crowded, 0u);
    EXPECT_EQ(kept.offsets, plain.offsets);
    EXPECT_EQ(kept.points, plain.points);

    // Crowded ones that turn away instead of stopping keep growing: more points, and still crowded at times.
    ParticleScene turning = convergingStrands(0.03f);
    turning.walk.on_distance.kind = StrandActionKind::Turn;
    turning.walk.on_distance.turn_angle_deg = 60.0f;
    const Strands turned = grow(turning), stopped = grow(convergingStrands(0.03f));
    EXPECT_GT(turned.stats.crowded, 0u);
    EXPECT_GT(turned.points.size(), stopped.points.size());
}

TEST(ParticleDistance, ASplitsChildrenAreNotCrowdedByTheirOwnFamily) {
    // A few strands far apart that split every 5 steps: siblings start at one point and parents end where
    // children begin, yet none of them is crowded by its family.
    ParticleScene s = convergingStrands(0.0f);
    s.generators[0].count = 3;
    s.attractors.clear();
    s.walk.max_age_steps = 5;
    s.walk.on_age.kind = StrandActionKind::Split;
    s.walk.on_age.split_angle_deg = 20.0f;
    s.walk.max_split_depth = 3;
    s.walk.steps = 20;
    const Strands plain = grow(s);
    s.walk.keep_distance_m = 0.02f;
    const Strands kept = grow(s);
    ASSERT_GT(plain.stats.splits, 6u);
    EXPECT_EQ(kept.stats.crowded, 0u);
    EXPECT_EQ(kept.offsets, plain.offsets);
    EXPECT_EQ(kept.points, plain.points);
}

TEST(ParticleDistance, OneTwoAndEightThreadsGrowTheSameStrands) {
    ParticleScene s = convergingStrands(0.02f);
    s.generators[0].count = 600;
    s.walk.collisions = true;
    s.walk.on_distance.kind = StrandActionKind::Countdown;
    s.walk.on_distance.countdown_steps = 3;
    const Strands one = grow(s, 1), two = grow(s, 2), eight = grow(s, 8);
    ASSERT_GT(one.stats.crowded, 0u);
    for (const Strands* other : {&two, &eight}) {
        EXPECT_EQ(other->offsets, one.offsets);
        EXPECT_EQ(other->points, one.points);
        EXPECT_EQ(other->stats.crowded, one.stats.crowded);
        EXPECT_EQ(other->stats.collisions, one.stats.collisions);
    }
}

TEST(ParticleDistance, TheDistanceRoundTripsAndBadOnesAreRefusedNamingThePlace) {
    ParticleSystemFile file;
    file.name = "keep";
    file.scene = convergingStrands(0.025f);
    file.scene.walk.on_distance.kind = StrandActionKind::Turn;
    file.scene.walk.on_distance.turn_angle_deg = 35.0f;
    file.scene.walk.retry_refused = true;
    ParticleSystemFile back;
    std::string error;
    ASSERT_TRUE(parseParticleSystem(particleSystemToJson(file), "keep.json", &back, &error)) << error;
    EXPECT_EQ(back.scene.walk, file.scene.walk);

    const auto refused = test::expectWalkRefused;
    refused(R"({"keep_distance_m": -0.01})", "/walk/keep_distance_m");
    refused(R"({"keep_distance_m": "far"})", "/walk/keep_distance_m");
    refused(R"({"on_distance": {"kind": "wander"}})", "/walk/on_distance/kind");
    refused(R"({"retry_refused": "yes"})", "/walk/retry_refused");
    // A distance far beyond the step would make every query visit the whole system.
    refused(R"({"step_length_m": 0.01, "keep_distance_m": 5})", "walk.keep_distance_m");
    ParticleScene nan = convergingStrands(std::nanf(""));
    EXPECT_FALSE(validateParticleScene(nan, &error));
    EXPECT_NE(error.find("walk.keep_distance_m"), std::string::npos) << error;
}

}  // namespace
}  // namespace ug
