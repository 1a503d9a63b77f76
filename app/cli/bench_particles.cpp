// Particle sculpting rows (issue 14): a fur ball after Beneš & Espinosa 2000 (their PII ran ten thousand
// particles interactively without collisions; the `paper` column has no figure for this work). 100,000
// strands on a sphere, 64 synchronous steps of 8 trials each, collisions between all strands on.
#include <chrono>
#include <cstdio>

#include "cli/bench.h"
#include "particles/strand_growth.h"

namespace ug::cli {

namespace {

// A ball of fur 10 cm across: the centre repels (the fur stands), a point below attracts weakly and
// only within its reach (it combs the lower half down), the strands keep two radii apart.
ParticleScene furBall(uint32_t strands, uint32_t steps) {
    ParticleScene scene;
    ParticleGenerator skin;
    skin.kind = GeneratorKind::Sphere;
    skin.radius_m = 0.05f;
    skin.count = strands;
    skin.heading_cone_deg = 15.0f;
    scene.generators.push_back(skin);
    Attractor core;
    core.kind = AttractorKind::Point;
    core.charge = {ChargeKey{0, -1.0f}};
    scene.attractors.push_back(core);
    Attractor comb;
    comb.kind = AttractorKind::Point;
    comb.a_m = {0.0f, 0.0f, -0.12f};
    comb.influence_m = 0.1f;
    comb.charge = {ChargeKey{0, 0.0f}, ChargeKey{16, 0.8f}};
    scene.attractors.push_back(comb);
    scene.walk.seed = 14;
    scene.walk.steps = steps;
    scene.walk.trials = 8;
    scene.walk.cone_deg = 25.0f;
    scene.walk.step_length_m = 0.0005f;
    scene.walk.strand_radius_m = 0.00005f;
    scene.walk.collisions = true;
    scene.walk.on_collision.kind = StrandActionKind::Stop;
    return scene;
}

}  // namespace

bool benchParticles(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error) {
    const uint32_t strands = ctx.quick ? 10000 : 100000, steps = ctx.quick ? 32 : 64;
    const ParticleScene scene = furBall(strands, steps);
    const int reps = ctx.quick ? 1 : 5;
    std::vector<double> seconds;
    Strands out;
    for (int r = 0; r < reps; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        if (!growStrands(scene, {.threads = ctx.threads}, &out, error)) return false;
        seconds.push_back(since(t0));
    }
    const std::string size = std::to_string(strands / 1000) + "k strands x " + std::to_string(steps) + " steps x 8 trials";
    rows->push_back({"particles.fur.seconds", median(seconds), "s", ctx.quick ? "" : "<= 1.5", std::nullopt,
                     (reps > 1 ? "median of 5: " : "one run: ") + size + ", collisions on"});
    rows->push_back({"particles.fur.strand_steps", double(out.stats.moves), "steps", "", std::nullopt,
                     std::to_string(out.stats.collisions) + " moves refused by collisions, " +
                         std::to_string(out.size()) + " strands out"});
    return true;
}

}  // namespace ug::cli
