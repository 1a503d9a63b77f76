// Incremental re-growth of particle strands (StrandRegrower, docs/particles.md "Incremental re-growth"):
// after any sequence of edits the strands are a full growth's, bit for bit, on any thread count; an edit
// of an attractor with a radius of influence or of a cutter re-grows only part of the strands; any other
// edit grows in full.
#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <random>

#include "particles/growth_record.h"
#include "particles/strand_growth.h"

namespace ug {
namespace {

Attractor pointAttractor(glm::vec3 at, float charge, float influence) {
    Attractor a;
    a.kind = AttractorKind::Point;
    a.a_m = at;
    a.influence_m = influence;
    a.charge = {ChargeKey{0, charge}};
    return a;
}

// A crowded patch of grass: strands that collide and split on collision, a cutter that splits them at
// a height, and three attractors (one keyed, one that reaches only part of the patch).
ParticleScene crowdedSplittingGrass() {
    ParticleScene scene;
    ParticleGenerator g;
    g.axis_u_m = {0.6f, 0.0f, 0.0f};
    g.axis_v_m = {0.0f, 0.6f, 0.0f};
    g.count = 1500;
    g.heading_cone_deg = 15.0f;
    scene.generators.push_back(g);
    scene.attractors.push_back(pointAttractor({0.0f, 0.0f, 3.0f}, 1.0f, 0.0f));
    scene.attractors.push_back(pointAttractor({0.3f, 0.2f, 0.25f}, 2.0f, 0.25f));
    Attractor keyed = pointAttractor({-0.3f, -0.2f, 0.2f}, 0.0f, 0.3f);
    keyed.charge = {ChargeKey{0, 0.0f}, ChargeKey{10, -1.5f}};
    scene.attractors.push_back(keyed);
    Cutter c;
    c.threshold_m = 0.2f;
    c.action.kind = StrandActionKind::Split;
    c.action.split_count = 2;
    c.action.split_angle_deg = 35.0f;
    scene.cutters.push_back(c);
    scene.walk.seed = 3;
    scene.walk.steps = 28;
    scene.walk.trials = 6;
    scene.walk.cone_deg = 30.0f;
    scene.walk.step_length_m = 0.012f;
    scene.walk.strand_radius_m = 0.004f;
    scene.walk.on_collision.kind = StrandActionKind::Split;
    scene.walk.on_collision.split_count = 2;
    scene.walk.on_collision.split_angle_deg = 60.0f;
    scene.walk.max_split_depth = 3;
    return scene;
}

Strands fullGrowth(const ParticleScene& scene) {
    Strands s;
    std::string error;
    EXPECT_TRUE(growStrands(scene, {.threads = 2}, &s, &error)) << error;
    return s;
}

void expectIdentical(const Strands& a, const Strands& b, const std::string& context) {
    ASSERT_EQ(a.offsets, b.offsets) << context;
    ASSERT_EQ(a.parent, b.parent) << context;
    ASSERT_EQ(a.particle, b.particle) << context;
    ASSERT_EQ(a.points.size(), b.points.size()) << context;
    EXPECT_EQ(std::memcmp(a.points.data(), b.points.data(), a.points.size() * sizeof(glm::vec3)), 0) << context;
    EXPECT_EQ(a.radii, b.radii) << context;
    EXPECT_EQ(a.stats.seeded, b.stats.seeded) << context;
    EXPECT_EQ(a.stats.strands, b.stats.strands) << context;
    EXPECT_EQ(a.stats.moves, b.stats.moves) << context;
    EXPECT_EQ(a.stats.collisions, b.stats.collisions) << context;
    EXPECT_EQ(a.stats.cutter_hits, b.stats.cutter_hits) << context;
    EXPECT_EQ(a.stats.splits, b.stats.splits) << context;
    EXPECT_EQ(a.stats.killed, b.stats.killed) << context;
    EXPECT_EQ(a.stats.dropped, b.stats.dropped) << context;
    EXPECT_EQ(a.stats.solid_hits, b.stats.solid_hits) << context;
    EXPECT_EQ(a.stats.crowded, b.stats.crowded) << context;
}

// One random edit of the attractors: a move (small or across the patch), a new shape, new charge keys.
std::string editAttractor(ParticleScene* scene, std::mt19937* rng) {
    std::uniform_int_distribution<size_t> which(0, scene->attractors.size() - 1);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    Attractor& a = scene->attractors[which(*rng)];
    switch (std::uniform_int_distribution<int>(0, 4)(*rng)) {
        case 0: a.a_m += glm::vec3(unit(*rng), unit(*rng), unit(*rng)) * 0.02f; return "nudged";
        case 1: a.a_m = glm::vec3(unit(*rng) * 0.6f, unit(*rng) * 0.6f, 0.1f + 0.2f * (unit(*rng) + 1.0f)); return "moved";
        case 2:
            a.kind = AttractorKind::Segment;
            a.b_m = a.a_m + glm::vec3(0.2f, unit(*rng) * 0.2f, 0.0f);
            return "made a segment";
        case 3: {
            const uint32_t at = uint32_t(std::uniform_int_distribution<int>(1, 25)(*rng));
            a.charge = {ChargeKey{0, a.charge.front().charge}, ChargeKey{at, unit(*rng) * 2.0f}};
            return "re-keyed";
        }
        default: a.charge.back().charge *= -1.0f; return "flipped";
    }
}

// `edits` random attractor edits (editAttractor), each re-grown from the record on 1 or 8 threads in turn
// and compared with a full growth; returns the moves taken from the records. `first` checks the first
// growth (what the scene must show for the test to test anything).
template <typename CheckFirst>
uint64_t regrowAfterRandomEdits(ParticleScene scene, uint32_t rng_seed, int edits, const std::string& context,
                                CheckFirst&& first) {
    StrandRegrower regrower;
    std::mt19937 rng(rng_seed);
    Strands out;
    std::string error;
    EXPECT_TRUE(regrower.grow(scene, {.threads = 2}, &out, &error)) << error;
    expectIdentical(out, fullGrowth(scene), context + "first growth");
    first(out);
    uint64_t reused = 0;
    for (int e = 0; e < edits; ++e) {
        const std::string what = editAttractor(&scene, &rng);
        EXPECT_TRUE(regrower.grow(scene, {.threads = e % 2 ? 8 : 1}, &out, &error)) << error;
        EXPECT_TRUE(regrower.lastReport().incremental) << what;
        reused += regrower.lastReport().reused;
        expectIdentical(out, fullGrowth(scene), context + "edit " + std::to_string(e) + ": " + what);
    }
    return reused;
}

TEST(ParticleRegrowth, IncrementalEqualsFullAfterRandomEdits) {
    ParticleScene scene = crowdedSplittingGrass();
    StrandRegrower regrower;
    std::mt19937 rng(14);
    Strands out;
    std::string error;
    ASSERT_TRUE(regrower.grow(scene, {.threads = 2}, &out, &error)) << error;
    EXPECT_FALSE(regrower.lastReport().incremental);
    expectIdentical(out, fullGrowth(scene), "first growth");
    ASSERT_GT(out.stats.splits, 100u);
    ASSERT_GT(out.stats.collisions, 100u);
    uint64_t reused = 0;
    for (int e = 0; e < 16; ++e) {
        const std::string what = editAttractor(&scene, &rng);
        const int threads = e % 3 == 0 ? 1 : e % 3 == 1 ? 2 : 8;
        ASSERT_TRUE(regrower.grow(scene, {.threads = threads}, &out, &error)) << error;
        EXPECT_TRUE(regrower.lastReport().incremental) << what;
        reused += regrower.lastReport().reused;
        expectIdentical(out, fullGrowth(scene), "edit " + std::to_string(e) + ": " + what);
    }
    // Most edits touch an attractor with a radius of influence at unchanged charges: part of each growth
    // is taken from the record, or the test would not test the replay.
    EXPECT_GT(reused, 0u);
}

// The same edits with turns and action tables (the turn's hashed axis and the table's hashed draw are a
// strand's own state, so a replayed strand turns and draws as its record did).
TEST(ParticleRegrowth, IncrementalEqualsFullWithTurnsAndActionTables) {
    ParticleScene scene = crowdedSplittingGrass();
    scene.generators[0].count = 800;
    StrandAction split = scene.walk.on_collision, turn;
    turn.kind = StrandActionKind::Turn;
    turn.turn_angle_deg = 60.0f;
    turn.weight = 2.0f;
    scene.walk.on_collision = StrandAction{};
    scene.walk.on_collision.choice = ActionChoice::Random;
    scene.walk.on_collision.table = {split, turn};
    scene.walk.max_age_steps = 8;
    scene.walk.on_age.kind = StrandActionKind::Turn;
    scene.walk.on_age.turn_angle_deg = 30.0f;
    StrandAction cut = scene.cutters[0].action;
    scene.cutters[0].action = StrandAction{};
    scene.cutters[0].action.table = {cut, turn};  // by priority: a split where it can, else a turn
    const uint64_t reused =
        regrowAfterRandomEdits(scene, 41, 8, "", [](const Strands& out) { EXPECT_GT(out.stats.splits, 50u); });
    EXPECT_GT(reused, 0u);
}

// Keeping distance, a proposal reads the earlier segments near its trials: a strand whose neighbours
// changed proposes again, one whose neighbourhood is the record's takes its recorded move.
TEST(ParticleRegrowth, IncrementalEqualsFullWithDistanceKeeping) {
    ParticleScene scene = crowdedSplittingGrass();
    scene.generators[0].count = 700;
    scene.walk.keep_distance_m = 0.012f;
    scene.walk.on_distance.kind = StrandActionKind::Turn;
    scene.walk.on_distance.turn_angle_deg = 50.0f;
    for (const bool collisions : {true, false}) {
        scene.walk.collisions = collisions;
        const uint64_t reused = regrowAfterRandomEdits(scene, collisions ? 5 : 6, 8, collisions ? "collisions, " : "",
                                                       [](const Strands& out) { EXPECT_GT(out.stats.crowded, 50u); });
        EXPECT_GT(reused, 0u);
    }
}

// Retrying refused moves, a proposal reads the earlier segments near its trials too.
TEST(ParticleRegrowth, IncrementalEqualsFullWhenRetryingRefusedMoves) {
    ParticleScene scene = crowdedSplittingGrass();
    scene.generators[0].count = 700;
    scene.walk.retry_refused = true;
    const uint64_t reused = regrowAfterRandomEdits(scene, 8, 8, "retrying, ",
                                                   [](const Strands& out) { EXPECT_GT(out.stats.collisions, 20u); });
    EXPECT_GT(reused, 0u);
}

TEST(ParticleRegrowth, AMovedAttractorReGrowsOnlyWhatItReaches) {
    ParticleScene scene = crowdedSplittingGrass();
    StrandRegrower regrower;
    Strands out;
    std::string error;
    ASSERT_TRUE(regrower.grow(scene, {.threads = 2}, &out, &error)) << error;
    scene.attractors[1].a_m.x += 0.03f;
    ASSERT_TRUE(regrower.grow(scene, {.threads = 2}, &out, &error)) << error;
    const RegrowReport report = regrower.lastReport();
    ASSERT_TRUE(report.incremental);
    // The attractor reaches a disc of about 0.3 m radius in a 1.2 m square (a fifth of it), and the
    // strands it bends reach their neighbours: well under half of the moves are proposed again.
    EXPECT_GT(report.recomputed, 0u);
    EXPECT_LT(double(report.recomputed), 0.5 * double(report.recomputed + report.reused));
    expectIdentical(out, fullGrowth(scene), "moved");
    // Moved back: the record of the first growth is gone, yet the result is the first growth's again.
    scene.attractors[1].a_m.x -= 0.03f;
    ASSERT_TRUE(regrower.grow(scene, {.threads = 1}, &out, &error)) << error;
    expectIdentical(out, fullGrowth(scene), "moved back");
}

TEST(ParticleRegrowth, ACancelledGrowthKeepsTheRecordOfTheLastFinishedOne) {
    ParticleScene scene = crowdedSplittingGrass();
    StrandRegrower regrower;
    Strands out;
    std::string error;
    std::atomic<uint32_t> steps_done{0};
    ASSERT_TRUE(regrower.grow(scene, {.threads = 2, .steps_done = &steps_done}, &out, &error)) << error;
    EXPECT_EQ(steps_done.load(), scene.walk.steps);
    // An edit whose growth is cancelled (the editor's Cancel): refused as "cancelled", before a step.
    ParticleScene edited = scene;
    edited.attractors[1].a_m.x += 0.03f;
    std::atomic<bool> cancel{true};
    steps_done = 0;
    EXPECT_FALSE(regrower.grow(edited, {.threads = 2, .cancel = &cancel, .steps_done = &steps_done}, &out, &error));
    EXPECT_EQ(error, kGrowthCancelled);
    EXPECT_EQ(steps_done.load(), 0u);
    // The edit undone: grown from the record kept, nothing proposed again, the first growth's strands.
    ASSERT_TRUE(regrower.grow(scene, {.threads = 2}, &out, &error)) << error;
    EXPECT_TRUE(regrower.lastReport().incremental);
    EXPECT_EQ(regrower.lastReport().recomputed, 0u);
    expectIdentical(out, fullGrowth(scene), "cancelled, then undone");
    EXPECT_FALSE(growStrands(scene, {.threads = 2, .cancel = &cancel}, &out, &error));
    EXPECT_EQ(error, kGrowthCancelled);
}

// One random edit of a cutter: moved, its threshold, its side, its action, its kind.
std::string editCutter(ParticleScene* scene, std::mt19937* rng) {
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    Cutter& c = scene->cutters[std::uniform_int_distribution<size_t>(0, scene->cutters.size() - 1)(*rng)];
    switch (std::uniform_int_distribution<int>(0, 4)(*rng)) {
        case 0: c.threshold_m += unit(*rng) * 0.03f; return "threshold";
        case 1: c.center_m += glm::vec3(unit(*rng), unit(*rng), unit(*rng) * 0.1f) * 0.2f; return "moved";
        case 2: c.action.kind = c.action.kind == StrandActionKind::Stop ? StrandActionKind::Split : StrandActionKind::Stop; return "action";
        case 3:
            c.kind = CutterKind::Sphere;
            c.center_m = glm::vec3(unit(*rng) * 0.4f, unit(*rng) * 0.4f, 0.25f);
            c.radius_m = 0.08f;
            c.threshold_m = 0.0f;
            c.side = CutterSide::Below;
            return "a sphere";
        default:
            c.kind = CutterKind::Plane;
            c.normal = glm::vec3(0.0f, 0.0f, 1.0f);
            c.side = CutterSide::Above;
            c.threshold_m = 0.15f + 0.1f * (unit(*rng) + 1.0f);
            return "a plane";
    }
}

// A cutter edit re-grows only the strands that come within a step of a changed cutter, old or new (its g
// is a signed distance), and the moves it clips: the same strands as a full growth after any sequence.
TEST(ParticleRegrowth, IncrementalEqualsFullAfterRandomCutterEdits) {
    ParticleScene scene = crowdedSplittingGrass();
    scene.generators[0].count = 900;
    Cutter sphere;
    sphere.kind = CutterKind::Sphere;
    sphere.center_m = {0.25f, -0.2f, 0.12f};
    sphere.radius_m = 0.06f;
    sphere.side = CutterSide::Below;
    sphere.action.kind = StrandActionKind::Stop;
    scene.cutters.push_back(sphere);
    StrandRegrower regrower;
    std::mt19937 rng(23);
    Strands out;
    std::string error;
    ASSERT_TRUE(regrower.grow(scene, {.threads = 2}, &out, &error)) << error;
    uint64_t reused = 0;
    for (int e = 0; e < 12; ++e) {
        const std::string what = e % 3 == 2 ? editAttractor(&scene, &rng) : editCutter(&scene, &rng);
        ASSERT_TRUE(regrower.grow(scene, {.threads = e % 2 ? 8 : 1}, &out, &error)) << error;
        EXPECT_TRUE(regrower.lastReport().incremental) << what;
        reused += regrower.lastReport().reused;
        expectIdentical(out, fullGrowth(scene), "edit " + std::to_string(e) + ": " + what);
    }
    EXPECT_GT(out.stats.cutter_hits, 0u);
    EXPECT_GT(reused, 0u);
}

TEST(ParticleRegrowth, AMovedCutterReGrowsOnlyWhatComesNearIt) {
    ParticleScene scene = crowdedSplittingGrass();
    Cutter sphere;  // a small stone that stops what reaches it, in one corner of the patch
    sphere.kind = CutterKind::Sphere;
    sphere.center_m = {0.45f, 0.45f, 0.1f};
    sphere.radius_m = 0.05f;
    sphere.side = CutterSide::Below;
    scene.cutters.push_back(sphere);
    StrandRegrower regrower;
    Strands out;
    std::string error;
    ASSERT_TRUE(regrower.grow(scene, {.threads = 2}, &out, &error)) << error;
    scene.cutters[1].center_m.x -= 0.04f;
    ASSERT_TRUE(regrower.grow(scene, {.threads = 2}, &out, &error)) << error;
    const RegrowReport report = regrower.lastReport();
    ASSERT_TRUE(report.incremental);
    EXPECT_GT(report.recomputed, 0u);
    EXPECT_LT(double(report.recomputed), 0.25 * double(report.recomputed + report.reused));
    expectIdentical(out, fullGrowth(scene), "the stone moved");
}

// A cutter whose action alone changes (its children gone, or new ones): the moves it clips part from the
// record, so the children the record had are not taken for unchanged neighbours.
TEST(ParticleRegrowth, ACuttersNewActionPartsTheMovesItClips) {
    ParticleScene scene = crowdedSplittingGrass();
    // A small sphere in the crowd that splits what reaches it: its children grow among strands that never
    // touch it, whose records were refused by those children's segments.
    scene.cutters[0].threshold_m = 1.0f;  // the plane out of reach
    Cutter sphere;
    sphere.kind = CutterKind::Sphere;
    sphere.center_m = {0.05f, 0.0f, 0.0f};
    sphere.radius_m = 0.2f;
    sphere.side = CutterSide::Below;
    sphere.action = crowdedSplittingGrass().cutters[0].action;  // a split
    scene.cutters.insert(scene.cutters.begin(), sphere);
    StrandRegrower regrower;
    Strands out;
    std::string error;
    ASSERT_TRUE(regrower.grow(scene, {.threads = 2}, &out, &error)) << error;
    const uint64_t splits = out.stats.splits;
    for (const StrandActionKind kind : {StrandActionKind::Stop, StrandActionKind::Split, StrandActionKind::Kill}) {
        scene.cutters[0].action.kind = kind;
        ASSERT_TRUE(regrower.grow(scene, {.threads = 2}, &out, &error)) << error;
        EXPECT_TRUE(regrower.lastReport().incremental);
        expectIdentical(out, fullGrowth(scene), std::string("the cutter's action became ") + strandActionName(kind));
        if (kind == StrandActionKind::Stop) {
            EXPECT_LT(out.stats.splits, splits);
        }
    }
}

TEST(ParticleRegrowth, OtherEditsGrowInFullAndFailuresDropTheRecord) {
    ParticleScene scene = crowdedSplittingGrass();
    StrandRegrower regrower;
    Strands out;
    std::string error;
    ASSERT_TRUE(regrower.grow(scene, {.threads = 2}, &out, &error)) << error;
    scene.walk.trials = 5;  // the walk changes every move
    ASSERT_TRUE(regrower.grow(scene, {.threads = 2}, &out, &error)) << error;
    EXPECT_FALSE(regrower.lastReport().incremental);
    expectIdentical(out, fullGrowth(scene), "trials changed");
    scene.attractors[1].influence_m = 0.4f;  // a new radius changes the term everywhere: all proposed again
    ASSERT_TRUE(regrower.grow(scene, {.threads = 2}, &out, &error)) << error;
    EXPECT_TRUE(regrower.lastReport().incremental);
    EXPECT_EQ(regrower.lastReport().reused, 0u);
    expectIdentical(out, fullGrowth(scene), "radius changed");

    ParticleScene bad = scene;
    bad.attractors[0].charge[0].charge = std::nanf("");
    EXPECT_FALSE(regrower.grow(bad, {.threads = 2}, &out, &error));
    EXPECT_NE(error.find("attractors[0].charge[0].charge"), std::string::npos) << error;
    scene.attractors[1].a_m.y += 0.05f;
    ASSERT_TRUE(regrower.grow(scene, {.threads = 2}, &out, &error)) << error;
    EXPECT_FALSE(regrower.lastReport().incremental);
    expectIdentical(out, fullGrowth(scene), "after a refused scene");
}

// A regrower keeps its working arrays from one growth to the next (the first edit finds them in memory).
// Nothing of one scene may leak into the next: a patch grown after a coarser and a finer one, and edited,
// is a fresh growth's, bit for bit.
TEST(ParticleRegrowth, WorkingMemoryCarriesNothingFromOneSceneToTheNext) {
    const ParticleScene crowded = crowdedSplittingGrass();
    ParticleScene coarse = crowded;  // thicker strands, longer steps: the grids' cells are wider
    coarse.walk.step_length_m = 0.03f;
    coarse.walk.strand_radius_m = 0.01f;
    coarse.generators[0].count = 3000;
    ParticleScene fine = crowded;  // a sparser, finer patch: every array shorter
    fine.walk.step_length_m = 0.006f;
    fine.walk.strand_radius_m = 0.002f;
    fine.generators[0].count = 400;
    StrandRegrower regrower;
    Strands out;
    std::string error;
    for (const ParticleScene* scene : std::vector<const ParticleScene*>{&crowded, &coarse, &crowded, &fine, &crowded}) {
        ASSERT_TRUE(regrower.grow(*scene, {.threads = 2}, &out, &error)) << error;
        EXPECT_FALSE(regrower.lastReport().incremental);
        expectIdentical(out, fullGrowth(*scene), "step " + std::to_string(scene->walk.step_length_m));
    }
    ParticleScene edited = crowded;
    edited.attractors[1].a_m.x -= 0.1f;
    ASSERT_TRUE(regrower.grow(edited, {.threads = 2}, &out, &error)) << error;
    EXPECT_TRUE(regrower.lastReport().incremental);
    expectIdentical(out, fullGrowth(edited), "edited after the other scenes");
}

TEST(ParticleRegrowth, WarmArrayGivesRoomOnceAndThenLeavesTheArrayAlone) {
    std::vector<uint32_t> a{7, 8, 9};
    warmArray(a, 100);
    EXPECT_TRUE(a.empty());
    EXPECT_GE(a.capacity(), 125u);  // a quarter more than asked, against small growths
    const uint32_t* memory = a.data();
    for (uint32_t i = 0; i < 120; ++i) a.push_back(i);
    EXPECT_EQ(a.data(), memory);  // filled without growing again
    warmArray(a, 110);  // room enough: left alone, contents and all
    EXPECT_EQ(a.size(), 120u);
    EXPECT_EQ(a.data(), memory);
    warmArray(a, 1000);
    EXPECT_TRUE(a.empty());
    EXPECT_GE(a.capacity(), 1000u);
}

}  // namespace
}  // namespace ug
