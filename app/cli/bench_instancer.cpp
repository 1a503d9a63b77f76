// Instantiation rows: the paper's Table 2 mirrored with our scenes (global instantiations and local brush
// stamps in the meadow), and the named target rows.
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "cli/bench.h"
#include "cli/scene_job.h"
#include "core/hash.h"

namespace ug::cli {

namespace {

struct GlobalCase {
    const char* row;     // instantiate.<row>.*
    const char* scene;   // assets/scenes/<scene>.json
    const char* only;    // when set, only this detail type keeps its field (a Table 2 row of the same figure)
    double paper_instances, paper_rejected, paper_seconds;
};

// Table 2 of the Ghost Tile paper: #I, #R, seconds.
const GlobalCase kGlobalCases[] = {
    {"field", "haystack_field", nullptr, 1990e3, 35000e3, 54.6},
    {"haystack", "haystack_field", "hay", 81e3, 10400e3, 6.8},
    {"beaver", "beaver_dam", nullptr, 36e3, 26300e3, 10.7},
    {"stone_hut", "stone_hut", nullptr, 63e3, 33800e3, 16.8},
    {"rock_pile", "rock_pile", nullptr, 0, 0, 0},
    {"meadow", "meadow", nullptr, 50e3, 0, 0},
};

bool loadJob(const BenchContext& ctx, const std::string& scene, SceneJob* job, std::string* error) {
    return loadSceneJob(ctx.assets_dir + "/scenes/" + scene + ".json", ctx.cache_dir, ctx.threads, true, job, error);
}

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// Brush stamps in the meadow: add a ball of density under the brush, or move one the brush added before,
// then update until the instance set is final. The time covers compiling the edited field too.
bool benchMeadowStamps(const BenchContext& ctx, SceneJob& job, Instantiator& inst, std::vector<BenchRow>* rows,
                       std::string* error) {
    const Bounds extent = job.compiled.extent;
    const int stamps = ctx.quick ? 40 : 200;
    std::vector<double> ms;
    std::vector<uint64_t> changed_counts, instances_after;
    std::vector<std::pair<size_t, uint32_t>> brush_prims;  // (type, primitive index) the brush added
    const SettleInput settle = settleInput(job.project, job.compiled.terrain, job.tile, job.models, job.environment.get());
    SettledDrops drops;
    SettleHistory history;  // as the live instancer keeps it
    std::vector<double> settle_ms;
    if (settle.settings.enabled) settleAll(settle, inst.store(), ctx.threads, &drops, &history);
    for (int k = 0; k < stamps; ++k) {
        const uint64_t h = hashWords(0xbe9c4, uint64_t(k));
        const size_t type = size_t(h % job.project.detail_types.size());
        const glm::vec2 xy = glm::mix(glm::vec2(extent.lo) + 2.0f, glm::vec2(extent.hi) - 2.0f,
                                      glm::vec2(unitFloat(hashWords(h, 1)), unitFloat(hashWords(h, 2))));
        const float ground = job.compiled.terrain ? job.compiled.terrain->sample(xy.x, xy.y) : 0.0f;
        const glm::vec3 centre(xy, ground + 0.05f);
        const auto t0 = Clock::now();
        DensityField& doc = job.project.detail_types[type].density;
        std::vector<Bounds> dirty;
        const bool move = !brush_prims.empty() && (k % 2 == 1);
        size_t edited = type;
        if (move) {
            const auto [t, p] = brush_prims[size_t(h >> 8) % brush_prims.size()];
            DensityField& d = job.project.detail_types[t].density;
            dirty.push_back(primitiveBounds(d.primitives[p], nullptr));
            d.primitives[p].center_m += glm::vec3(0.3f, -0.2f, 0.0f);
            dirty.push_back(primitiveBounds(d.primitives[p], nullptr));
            edited = t;
        } else {
            const Primitive ball = makePoint(centre, 0.6f, 1.0f);
            const uint32_t p = addPrimitive(&doc, ball);
            const uint32_t refs[2] = {nodeChild(doc.root), primitiveChild(p)};
            doc.root = doc.root == kNoNode ? addNode(&doc, FieldOp::Blend, std::span<const uint32_t>(refs + 1, 1))
                                           : addNode(&doc, FieldOp::Blend, refs);
            brush_prims.push_back({type, p});
            dirty.push_back(primitiveBounds(ball, nullptr));
        }
        std::vector<InstanceTypeSettings> types = inst.input().types;
        if (!compileDetailType(job.project, edited, job.compiled.terrain, &types[edited], error, job.compiled.environment)) return false;
        std::vector<uint64_t> changed;
        InstanceStats st;
        if (!inst.update(std::move(types), dirty, {.threads = ctx.threads}, &st, &changed, error)) return false;
        changed_counts.push_back(changed.size());
        ms.push_back(msSince(t0));
        instances_after.push_back(inst.store().instanceCount());
        if (settle.settings.enabled) {  // the drops of the changed neighbourhood, after the selection
            const auto t1 = Clock::now();
            settleUpdate(settle, inst.store(), changed, ctx.threads, &drops, nullptr, &history);
            settle_ms.push_back(msSince(t1));
        }
    }
    // The stamps' final state must equal instantiating the edited scene from scratch.
    InstancerInput fresh_input = inst.input();
    for (size_t t = 0; t < job.project.detail_types.size(); ++t)
        if (!compileDetailType(job.project, t, job.compiled.terrain, &fresh_input.types[t], error, job.compiled.environment)) return false;
    Instantiator fresh;
    InstanceStats fresh_stats;
    if (!fresh.setInput(fresh_input, error) || !fresh.instantiateAll({.threads = ctx.threads}, &fresh_stats, error))
        return false;
    if (!(fresh.store() == inst.store())) {
        *error = "meadow stamps: the incremental result differs from a full instantiation of the edited scene";
        return false;
    }
    if (settle.settings.enabled) {
        SettledDrops full;
        SettleHistory full_history;
        settleAll(settle, fresh.store(), ctx.threads, &full, &full_history);
        if (!(full == drops) || full_history.after_pass != history.after_pass) {
            *error = "meadow stamps: the incremental settled drops differ from settling the edited scene";
            return false;
        }
        std::vector<double> s = settle_ms;
        std::sort(s.begin(), s.end());
        rows->push_back({"edit.meadow.settle_p95_ms", s[std::min(s.size() - 1, size_t(double(s.size()) * 0.95))], "ms",
                         "", std::nullopt, "settling the stamp's neighbourhood after the selection (settleUpdate)"});
    }
    std::vector<double> sorted = ms;
    std::sort(sorted.begin(), sorted.end());
    const double p95 = sorted[std::min(sorted.size() - 1, size_t(double(sorted.size()) * 0.95))];
    const std::string note = std::to_string(stamps) + " stamps (ball r 0.6 m added, or moved 0.36 m), " +
                             std::to_string(inst.store().instanceCount()) + " instances after, equal to a full run";
    rows->push_back({"edit.meadow.stamp_p50_ms", median(ms), "ms", "", 300.0, note});
    rows->push_back({"edit.meadow.stamp_p95_ms", p95, "ms", "<= 16", 3400.0, "paper: 0.3-3.4 s per local edit"});
    std::vector<double> changed_d(changed_counts.begin(), changed_counts.end());
    rows->push_back({"edit.meadow.tiles_changed_p50", median(changed_d), "tiles", "", std::nullopt, "per stamp"});
    std::fprintf(stderr, "  meadow stamps: p50 %.2f ms, p95 %.2f ms, max %.2f ms\n", median(ms), p95, sorted.back());
    return true;
}

}  // namespace

bool benchInstancer(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error) {
    for (const GlobalCase& c : kGlobalCases) {
        SceneJob job;
        if (!loadJob(ctx, c.scene, &job, error)) return false;
        InstancerInput input = instancerInput(job, job.project.instantiation_seed);
        if (c.only) {
            bool found = false;
            for (size_t i = 0; i < job.models.size(); ++i) {
                if (job.models[i].name == c.only) found = true;
                else input.types[i].field = nullptr;
            }
            if (!found) {
                *error = std::string(c.scene) + ": no detail type '" + c.only + "'";
                return false;
            }
        }
        Instantiator inst;
        if (!inst.setInput(input, error)) return false;
        const bool big = std::string(c.row) == "field";
        const int reps = big ? std::max(1, ctx.repetitions() - 2) : ctx.repetitions();
        std::vector<double> seconds;
        InstanceStats st;
        for (int r = 0; r < reps; ++r) {
            if (!inst.instantiateAll({.threads = ctx.threads}, &st, error)) return false;
            seconds.push_back(st.seconds);
        }
        const std::string prefix = std::string("instantiate.") + c.row;
        const std::string note = "median of " + std::to_string(reps) + ", " + std::to_string(st.tiles_touched) +
                                 " tiles, " + std::to_string(st.candidates_tested) + " candidates tested";
        auto paper = [](double v) { return v > 0 ? std::optional<double>(v) : std::nullopt; };
        rows->push_back({prefix + ".seconds", median(seconds), "s", big ? "<= 2" : "", paper(c.paper_seconds), note});
        rows->push_back({prefix + ".instances", double(st.instances), "#I", big ? ">= 1500000" : "",
                         paper(c.paper_instances), ""});
        rows->push_back({prefix + ".rejected", double(st.rejected), "#R", "", paper(c.paper_rejected),
                         "tested - selected"});
        if (big)
            rows->push_back({"instances.bytes_per_instance", st.bytes_per_instance, "B/instance", "<= 4", std::nullopt,
                             "instance store (tile keys + varint candidate ids)"});
        std::fprintf(stderr, "  %-10s %9llu instances %11llu rejected  %.3f s\n", c.row,
                     static_cast<unsigned long long>(st.instances), static_cast<unsigned long long>(st.rejected),
                     median(seconds));
        if (std::string(c.row) == "meadow" && !benchMeadowStamps(ctx, job, inst, rows, error)) return false;
    }
    return true;
}

}  // namespace ug::cli
