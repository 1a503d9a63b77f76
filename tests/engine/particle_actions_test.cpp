// The turn action and action tables (§5.2: "changing the direction of the motion"; "the action can be
// either taken randomly or according to user defined priority"): a turn at an age bends the strand by its
// angle and starts the age again, a turn at a cutter sends it along the threshold, a random table acts in
// proportion to its weights and the same for any thread count, a priority table falls through to the
// first action that can act; files round-trip their tables and bad ones are refused naming the place.
#include <gtest/gtest.h>

#include <cmath>

#include "particle_test_util.h"
#include "particles/particle_json.h"
#include "particles/strand_growth.h"

namespace ug {
namespace {

// Strands from a square on the ground, straight up (a cone of 0.5 degrees, no attractor).
ParticleScene straightGrass(uint32_t count, uint32_t steps) {
    ParticleScene s;
    ParticleGenerator g;
    g.axis_u_m = {0.5f, 0.0f, 0.0f};
    g.axis_v_m = {0.0f, 0.5f, 0.0f};
    g.count = count;
    s.generators.push_back(g);
    s.walk.steps = steps;
    s.walk.trials = 2;
    s.walk.cone_deg = 0.5f;
    s.walk.step_length_m = 0.01f;
    s.walk.strand_radius_m = 0.0005f;
    s.walk.collisions = false;
    return s;
}

float angleDeg(glm::vec3 a, glm::vec3 b) {
    return glm::degrees(std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0f, 1.0f)));
}

Strands grow(const ParticleScene& scene, int threads = 2) {
    Strands out;
    std::string error;
    EXPECT_TRUE(growStrands(scene, {.threads = threads}, &out, &error)) << error;
    return out;
}

TEST(ParticleActions, AnAgeTurnBendsTheStrandByItsAngleAndStartsTheAgeAgain) {
    ParticleScene scene = straightGrass(40, 30);
    scene.walk.max_age_steps = 10;
    scene.walk.on_age.kind = StrandActionKind::Turn;
    scene.walk.on_age.turn_angle_deg = 70.0f;
    const Strands s = grow(scene);
    ASSERT_EQ(s.size(), 40u);
    for (size_t k = 0; k < s.size(); ++k) {
        ASSERT_EQ(s.offsets[k + 1] - s.offsets[k], 31u);
        const glm::vec3* p = s.points.data() + s.offsets[k];
        // Segment i is move i + 1; the turns follow moves 10 and 20 (the age counts moves).
        for (uint32_t i = 0; i + 1 < 30; ++i) {
            const float bend = angleDeg(p[i + 1] - p[i], p[i + 2] - p[i + 1]);
            if (i == 9 || i == 19)
                EXPECT_NEAR(bend, 70.0f, 1.5f) << "strand " << k << " after move " << i + 1;
            else
                EXPECT_LT(bend, 1.5f) << "strand " << k << " at move " << i + 1;
        }
    }
}

TEST(ParticleActions, ACutterTurnSendsTheStrandAlongTheThresholdAndItGoesOn) {
    ParticleScene scene = straightGrass(60, 25);
    Cutter c;
    c.threshold_m = 0.05f;
    c.action.kind = StrandActionKind::Turn;
    c.action.turn_angle_deg = 90.0f;
    scene.cutters.push_back(c);
    const Strands s = grow(scene);
    ASSERT_EQ(s.size(), 60u);
    EXPECT_EQ(s.stats.cutter_hits, 60u);
    for (size_t k = 0; k < s.size(); ++k) {
        EXPECT_EQ(s.offsets[k + 1] - s.offsets[k], 26u) << "strand " << k << " stopped";
        float top = 0.0f;
        for (uint32_t i = s.offsets[k]; i < s.offsets[k + 1]; ++i) top = std::max(top, s.points[i].z);
        // Clipped at 5 cm on the 5th move, then turned level: each move is within half a degree of a
        // heading that itself drifts by at most that much a move, so 20 moves of 1 cm rise at most
        // sum 0.01 sin(0.5 i deg) < 1.9 cm, and they go at least 15 cm across.
        EXPECT_LE(top, 0.05f + 0.019f) << "strand " << k;
        EXPECT_GE(top, 0.05f - 1e-5f) << "strand " << k;
        const glm::vec3 cut = s.points[s.offsets[k] + 5], tip = s.points[s.offsets[k + 1] - 1];
        EXPECT_NEAR(cut.z, 0.05f, 1e-5f) << "strand " << k;
        EXPECT_GT(glm::length(glm::vec2(tip - cut)), 0.15f) << "strand " << k;
    }
}

TEST(ParticleActions, ARandomTableActsInProportionToItsWeightsForAnyThreadCount) {
    ParticleScene scene = straightGrass(4000, 12);
    scene.walk.max_age_steps = 6;
    StrandAction kill, stop;
    kill.kind = StrandActionKind::Kill;
    kill.weight = 1.0f;
    stop.kind = StrandActionKind::Stop;
    stop.weight = 3.0f;
    scene.walk.on_age.choice = ActionChoice::Random;
    scene.walk.on_age.table = {kill, stop};
    const Strands one = grow(scene, 1), eight = grow(scene, 8);
    EXPECT_EQ(one.points, eight.points);
    EXPECT_EQ(one.offsets, eight.offsets);
    // Every strand reaches age 6 once: a quarter are killed, the rest stop with 7 points.
    const double killed = double(one.stats.killed) / 4000.0;
    EXPECT_NEAR(killed, 0.25, 0.03);
    EXPECT_EQ(one.size() + one.stats.killed, 4000u);
    for (size_t k = 0; k < one.size(); ++k) EXPECT_EQ(one.offsets[k + 1] - one.offsets[k], 7u);
    // Another seed draws other strands to kill, in the same proportion.
    scene.walk.seed = 99;
    const Strands other = grow(scene);
    EXPECT_NEAR(double(other.stats.killed) / 4000.0, 0.25, 0.03);
    EXPECT_NE(other.particle, one.particle);
}

TEST(ParticleActions, APriorityTableTakesTheFirstActionThatCanAct) {
    ParticleScene scene = straightGrass(50, 20);
    scene.walk.max_age_steps = 5;
    StrandAction split, turn;
    split.kind = StrandActionKind::Split;
    split.split_count = 2;
    split.split_angle_deg = 20.0f;
    turn.kind = StrandActionKind::Turn;
    turn.turn_angle_deg = 40.0f;
    scene.walk.on_age.table = {split, turn};  // Priority by default
    // Splits allowed once: the roots split at age 5, their children (depth 1) cannot and turn instead.
    scene.walk.max_split_depth = 1;
    const Strands s = grow(scene);
    EXPECT_EQ(s.stats.splits, 50u);
    EXPECT_EQ(s.size(), 150u);
    size_t turned = 0;
    for (size_t k = 0; k < s.size(); ++k) {
        if (s.parent[k] < 0) {
            EXPECT_EQ(s.offsets[k + 1] - s.offsets[k], 6u);  // the seed and 5 moves, then the split
            continue;
        }
        const glm::vec3* p = s.points.data() + s.offsets[k];
        const uint32_t n = s.offsets[k + 1] - s.offsets[k];
        ASSERT_GT(n, 8u);
        // A child's age is its own: it turns after its 5th move.
        turned += std::abs(angleDeg(p[5] - p[4], p[6] - p[5]) - 40.0f) < 1.5f;
    }
    EXPECT_EQ(turned, 100u);
}

TEST(ParticleActions, TablesRoundTripAndBadOnesAreRefusedNamingThePlace) {
    ParticleSystemFile file;
    file.name = "tables";
    file.scene = straightGrass(10, 5);
    StrandAction kill, turn;
    kill.kind = StrandActionKind::Kill;
    kill.weight = 0.5f;
    turn.kind = StrandActionKind::Turn;
    turn.turn_angle_deg = 120.0f;
    turn.weight = 2.5f;
    file.scene.walk.on_collision.choice = ActionChoice::Random;
    file.scene.walk.on_collision.table = {kill, turn};
    file.scene.walk.on_age.kind = StrandActionKind::Turn;
    file.scene.walk.on_age.turn_angle_deg = 15.0f;
    ParticleSystemFile back;
    std::string error;
    ASSERT_TRUE(parseParticleSystem(particleSystemToJson(file), "tables.json", &back, &error)) << error;
    EXPECT_EQ(back.scene.walk, file.scene.walk);

    const auto refused = test::expectWalkRefused;
    refused(R"({"on_age": {"kind": "turn", "turn_angle_deg": 0}})", "/walk/on_age/turn_angle_deg");
    refused(R"({"on_age": {"table": []}})", "/walk/on_age/table");
    refused(R"({"on_age": {"choice": "random", "table": [{"kind": "stop", "weight": 0}]}})", "/walk/on_age/table/0/weight");
    refused(R"({"on_age": {"table": [{"table": [{"kind": "stop"}]}]}})", "/walk/on_age/table/0/table");
    refused(R"({"on_age": {"choice": "sometimes", "table": [{"kind": "stop"}]}})", "/walk/on_age/choice");
    refused(R"({"on_age": {"kind": "stop", "weight": 2}})", "/walk/on_age/weight");
    // Built in code, a nested table is refused by the validation.
    ParticleScene nested = straightGrass(4, 4);
    nested.walk.on_age.table = {StrandAction{}};
    nested.walk.on_age.table[0].table = {StrandAction{}};
    EXPECT_FALSE(validateParticleScene(nested, &error));
    EXPECT_NE(error.find("walk.on_age.table[0].table"), std::string::npos) << error;
}

}  // namespace
}  // namespace ug
