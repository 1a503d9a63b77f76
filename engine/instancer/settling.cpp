#include "instancer/settling.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <unordered_set>

#include "core/parallel.h"
#include "core/xy_grid.h"
#include "instancer/tile_coord.h"

namespace ug {

std::span<const uint16_t> SettledDrops::tile(uint64_t tile_key) const {
    auto it = std::lower_bound(keys_.begin(), keys_.end(), tile_key);
    if (it == keys_.end() || *it != tile_key) return {};
    const size_t t = size_t(it - keys_.begin());
    return std::span<const uint16_t>(drops_.data() + offsets_[t], offsets_[t + 1] - offsets_[t]);
}

void SettledDrops::append(uint64_t tile_key, std::span<const uint16_t> drops) {
    if (drops.empty()) return;
    keys_.push_back(tile_key);
    drops_.insert(drops_.end(), drops.begin(), drops.end());
    offsets_.push_back(uint32_t(drops_.size()));
}

void SettledDrops::clear() {
    keys_.clear();
    offsets_.assign(1, 0);
    drops_.clear();
}

bool validateSettleInput(const SettleInput& in, std::string* error) {
    auto fail = [&](const std::string& what) {
        if (error) *error = "settling: " + what;
        return false;
    };
    if (!in.tile) return fail("no Ghost Tile");
    if (in.models.size() != in.tile->candidates.typeCount()) return fail("one model per detail type is needed");
    for (const DetailModel* m : in.models)
        if (!m) return fail("a detail type has no model");
    const SettleSettings& s = in.settings;
    if (s.passes < 1 || s.passes > kMaxSettlePasses)
        return fail("passes must be in [1, " + std::to_string(kMaxSettlePasses) + "]");
    if (!std::isfinite(s.max_drop_m) || s.max_drop_m < 0.0f || s.max_drop_m > kMaxSettleDropM)
        return fail("max_drop_m must be in [0, " + std::to_string(kMaxSettleDropM) + "]");
    if (!in.support.terrain && std::isnan(in.support.ground_z)) return fail("ground_z is not a number");
    return true;
}

namespace {

struct Identity {
    uint64_t tile;
    uint32_t j;
};

// The instances of one computation (the whole store, or a window of it) and their world spheres.
struct Window {
    std::vector<Identity> id;
    std::vector<uint32_t> sphere_begin;  // per instance; size + 1
    std::vector<glm::vec3> center;       // unsettled, world
    std::vector<float> radius;
    std::vector<uint32_t> owner;
    std::vector<float> instance_max_radius;  // per instance: its largest sphere
    std::vector<glm::vec3> origin;           // per instance: unsettled, world
    float max_radius = 0.0f;
};

// Every candidate's spheres relative to its origin (rotated and scaled) by ascending height, made the first
// time a window meets the candidate: the same in every tile, so adding an instance only offsets them (the
// world centre is origin + offset, the very sum a direct computation makes). An instance's order of
// spheres by height is what the pair search walks; within equal heights it means nothing.
class CandidateSpheres {
public:
    explicit CandidateSpheres(const SettleInput& in) : in_(in), first_(in.tile->candidates.position.size(), kNone) {}
    struct Span {
        const glm::vec3* offset;
        const float* radius;
        uint32_t count;
        float largest;
    };
    Span get(uint32_t j) {
        if (first_[j] == kNone) make(j);
        const uint32_t f = first_[j];
        return {offset_.data() + f, radius_.data() + f, count_[j], largest_[j]};
    }
    uint32_t sphereCount(uint32_t j) const { return uint32_t(in_.models[in_.tile->candidates.type[j]]->spheres.size()); }

private:
    static constexpr uint32_t kNone = ~0u;
    void make(uint32_t j) {
        const CandidateSet& c = in_.tile->candidates;
        const DetailModel& m = *in_.models[c.type[j]];
        if (count_.size() < first_.size()) {
            count_.resize(first_.size(), 0);
            largest_.resize(first_.size(), 0.0f);
        }
        std::vector<uint32_t> order(m.spheres.size());
        std::vector<glm::vec3> rel(m.spheres.size());
        float largest = 0.0f;
        for (uint32_t k = 0; k < order.size(); ++k) {
            order[k] = k;
            rel[k] = c.rotation[j] * (c.scale[j] * m.spheres[k].center);
            largest = std::max(largest, c.scale[j] * m.spheres[k].radius);
        }
        std::stable_sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) { return rel[x].z < rel[y].z; });
        first_[j] = uint32_t(offset_.size());
        for (uint32_t k : order) {
            offset_.push_back(rel[k]);
            radius_.push_back(c.scale[j] * m.spheres[k].radius);
        }
        count_[j] = uint32_t(order.size());
        largest_[j] = largest;
    }
    const SettleInput& in_;
    std::vector<uint32_t> first_, count_;
    std::vector<float> largest_;
    std::vector<glm::vec3> offset_;
    std::vector<float> radius_;
};

void addInstance(const SettleInput& in, uint64_t tile_key, uint32_t j, CandidateSpheres* spheres, Window* w) {
    const glm::vec3 origin =
        tileOrigin(unpackTile(tile_key), in.tile->settings.tile_size_m) + in.tile->candidates.position[j];
    const uint32_t self = uint32_t(w->id.size());
    w->id.push_back({tile_key, j});
    w->sphere_begin.push_back(uint32_t(w->center.size()));
    const CandidateSpheres::Span own = spheres->get(j);
    for (uint32_t k = 0; k < own.count; ++k) {
        w->center.push_back(origin + own.offset[k]);
        w->radius.push_back(own.radius[k]);
        w->owner.push_back(self);
    }
    w->max_radius = std::max(w->max_radius, own.largest);
    w->instance_max_radius.push_back(own.largest);
    w->origin.push_back(origin);
}

// Room for `instances` instances of `spheres` spheres in all (a window's arrays hold millions of spheres:
// growing them by doubling copied and faulted in most of a settling's memory again).
void reserveWindow(size_t instances, size_t spheres, Window* w) {
    w->id.reserve(instances);
    w->sphere_begin.reserve(instances + 1);
    w->instance_max_radius.reserve(instances);
    w->origin.reserve(instances);
    w->center.reserve(spheres);
    w->radius.reserve(spheres);
    w->owner.reserve(spheres);
}

// Sphere e (of instance b) lies below sphere a (of instance a): a fixed order whatever the window.
bool below(const Window& w, uint32_t e, uint32_t a) {
    if (w.center[e].z != w.center[a].z) return w.center[e].z < w.center[a].z;
    const Identity& ie = w.id[w.owner[e]];
    const Identity& ia = w.id[w.owner[a]];
    if (ie.tile != ia.tile) return ie.tile < ia.tile;
    if (ie.j != ia.j) return ie.j < ia.j;
    return e < a;  // the same instance's spheres are never paired
}

struct Pair {
    uint32_t lower;  // instance
    float offset;    // clearance when the lower instance has not moved
};

uint16_t toUnits(float drop_m) {
    const float u = std::floor(drop_m / kSettleQuantumM);  // down: never deeper than the contact
    return u <= 0.0f ? 0 : u >= 65535.0f ? 65535 : uint16_t(u);
}

// The highest the support reaches under a disc (centre, radius) in XY: bilinear heights lie within the
// range of their cells' samples; the surfaces give their own bound.
float supportTop(const RestSupport& support, glm::vec3 center, float radius) {
    const glm::vec2 c(center);
    const float ground = support.terrain ? support.terrain->heightRange(c - radius, c + radius).y + 1e-4f : support.ground_z;
    return support.surfaces ? std::max(ground, support.surfaces->surfaceTopIn(c - radius, c + radius) + 1e-4f) : ground;
}

float gapOf(const SettleInput& in) { return std::max(0.0f, in.tile->settings.delta_m); }

// How far apart two instances' origins can be and still act on each other in one pass: twice the largest
// distance from a candidate's origin to the far side of one of its spheres, plus the gap. Every relation a
// pass reads (a sphere pair, a held instance's neighbour beside it) lies within it, so the update windows
// and region halos, which are this reach per pass, stay exact.
float passReachMetres(const SettleInput& in) {
    float bound = 0.0f;
    const CandidateSet& c = in.tile->candidates;
    for (uint32_t t = 0; t < c.typeCount(); ++t) {
        float scale = 0.0f;
        for (uint32_t j = c.type_begin[t]; j < c.type_begin[t + 1]; ++j) scale = std::max(scale, c.scale[j]);
        const DetailModel& m = *in.models[t];
        for (const Sphere& s : m.spheres) bound = std::max(bound, scale * (glm::length(s.center) + s.radius));
    }
    return 2.0f * bound + gapOf(in);
}

// What a window's passes read and record besides computing drops. fixed (optional): per instance, 1
// where its drops are given rather than computed (the ring an update reads from a history);
// given[k][i] its drops after pass k + 1, for every pass, the last included. record (optional):
// receives every instance's drops after each pass but the last.
struct WindowPasses {
    const std::vector<uint8_t>* fixed = nullptr;
    const std::vector<std::vector<uint16_t>>* given = nullptr;
    std::vector<std::vector<uint16_t>>* record = nullptr;
};

// The passes over one window; drops[i] for instance i of the window.
std::vector<uint16_t> settleWindow(const SettleInput& in, const Window& w, int threads, const WindowPasses& io = {}) {
    const size_t n = w.id.size();
    const int passes = in.settings.passes;
    std::vector<uint16_t> drops(n, 0);
    if (io.record) io.record->assign(size_t(passes - 1), drops);
    if (n == 0) return drops;
    auto isFixed = [&](size_t i) { return io.fixed && (*io.fixed)[i] != 0; };
    const float gap = gapOf(in);
    const float max_drop = in.settings.max_drop_m;
    const float pass_reach = passReachMetres(in);
    // Per instance: a bounding sphere and the height range of its sphere centres (broad phase).
    std::vector<glm::vec3> bound_center(n);
    std::vector<float> bound_radius(n), zlo(n), zhi(n);
    float max_bound = 0.0f;
    for (size_t i = 0; i < n; ++i) {
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        for (uint32_t a = w.sphere_begin[i]; a < w.sphere_begin[i + 1]; ++a) {
            lo = glm::min(lo, w.center[a] - w.radius[a]);
            hi = glm::max(hi, w.center[a] + w.radius[a]);
            zlo[i] = a == w.sphere_begin[i] ? w.center[a].z : std::min(zlo[i], w.center[a].z);
            zhi[i] = a == w.sphere_begin[i] ? w.center[a].z : std::max(zhi[i], w.center[a].z);
        }
        bound_center[i] = 0.5f * (lo + hi);
        bound_radius[i] = 0.5f * glm::length(hi - lo);
        max_bound = std::max(max_bound, bound_radius[i]);
    }
    const XyGrid columns(std::span<const glm::vec3>(bound_center), std::max(2.0f * max_bound + gap, 1e-3f));

    // Fixed per instance: the bound from the support and the max drop, and per lower neighbour the
    // smallest clearance over their sphere pairs (drop_B adds to every pair of A and B alike); for a held
    // instance, the neighbours whose least drop it follows.
    std::vector<float> bound(n);
    std::vector<std::vector<Pair>> pairs(n);
    std::vector<std::vector<uint32_t>> beside(n);
    parallelFor(n, threads, 128, [&](size_t b, size_t e, int) {
        std::vector<uint32_t> near_o;  // scratch: a neighbour's spheres that can meet the instance's
        for (size_t i = b; i < e; ++i) {
            if (isFixed(i)) continue;  // its drops are given: it is only a neighbour here
            // Spheres come by ascending height: once even the largest sphere that high could not reach
            // the highest ground under the instance sooner, the rest cannot either.
            float limit = max_drop;
            const float ground_top = supportTop(in.support, bound_center[i], bound_radius[i]);
            for (uint32_t a = w.sphere_begin[i]; a < w.sphere_begin[i + 1] && limit > 0.0f; ++a) {
                if (w.center[a].z - w.instance_max_radius[i] - ground_top >= limit) break;
                limit = std::min(limit, std::max(0.0f, supportClearance(in.support, w.center[a], w.radius[a])));
            }
            bound[i] = limit;
            // A pair whose clearance is not below the support's bound can never lower the drop (a drop
            // is min(bound, clearance + the lower one's drop >= 0)), so the search looks only for
            // clearances below it, and an instance resting on the support has no pair to look for.
            // With nothing within max_drop (limit == max_drop) a pair at exactly max_drop still counts:
            // it decides whether the instance is held.
            const float wanted = limit < max_drop ? limit : std::nextafter(max_drop, std::numeric_limits<float>::infinity());
            std::vector<Pair>& mine = pairs[i];
            auto pairWith = [&](uint32_t o) {
                if (o == i || zlo[o] > zhi[i]) return;  // no sphere of o lies below one of i
                const float dx = bound_center[i].x - bound_center[o].x, dy = bound_center[i].y - bound_center[o].y;
                const float far = bound_radius[i] + bound_radius[o] + gap;
                if (dx * dx + dy * dy >= far * far) return;
                // o's spheres horizontally within reach of i's bounding sphere, still by height: no other
                // can meet a sphere of i (|s - i's centre| <= |s - a| + |a - i's centre| < rs + ra + gap +
                // i's radius - ra; grown a little against rounding). Two stones touching at one face share
                // a few of their spheres' reaches, not all.
                near_o.clear();
                for (uint32_t s = w.sphere_begin[o]; s < w.sphere_begin[o + 1]; ++s) {
                    const float sx = w.center[s].x - bound_center[i].x, sy = w.center[s].y - bound_center[i].y;
                    const float reach = (bound_radius[i] + w.radius[s] + gap) * 1.001f + 1e-5f;
                    if (sx * sx + sy * sy < reach * reach) near_o.push_back(s);
                }
                if (near_o.empty()) return;
                float best = wanted;
                const float widest_any = w.instance_max_radius[i] + w.instance_max_radius[o] + gap;
                for (uint32_t a = w.sphere_begin[i]; a < w.sphere_begin[i + 1]; ++a) {
                    const glm::vec3 ca = w.center[a];
                    const float ra = w.radius[a];
                    // Spheres of i come by ascending height: once even o's highest sphere at the widest
                    // reach is too far below to beat the best, the higher spheres of i cannot either.
                    if (ca.z - zhi[o] - widest_any >= best) break;
                    const float ax = ca.x - bound_center[o].x, ay = ca.y - bound_center[o].y;
                    const float near = ra + bound_radius[o] + gap;
                    if (ax * ax + ay * ay >= near * near || ca.z < zlo[o]) continue;
                    // Down from the highest sphere of o below a: once even the widest pair could not
                    // beat the best clearance found, the lower spheres cannot either.
                    const size_t top = size_t(std::upper_bound(near_o.begin(), near_o.end(), ca.z,
                                                               [&](float z, uint32_t t) { return z < w.center[t].z; }) -
                                              near_o.begin());
                    const float widest = ra + w.instance_max_radius[o] + gap;
                    for (size_t k = top; k-- > 0;) {
                        const uint32_t s = near_o[k];
                        if (ca.z - w.center[s].z - widest >= best) break;
                        if (!below(w, s, a)) continue;
                        const float reach = ra + w.radius[s] + gap;
                        const float hx = ca.x - w.center[s].x, hy = ca.y - w.center[s].y;
                        const float h2 = hx * hx + hy * hy;
                        if (h2 >= reach * reach) continue;
                        best = std::min(best, ca.z - w.center[s].z - std::sqrt(reach * reach - h2));
                    }
                    // Spheres at exactly a's height are below it or not by the tie-break.
                    for (size_t k = top; k < near_o.size() && w.center[near_o[k]].z == ca.z; ++k) {
                        const uint32_t s = near_o[k];
                        if (!below(w, s, a)) continue;
                        const float reach = ra + w.radius[s] + gap;
                        const float hx = ca.x - w.center[s].x, hy = ca.y - w.center[s].y;
                        const float h2 = hx * hx + hy * hy;
                        if (h2 < reach * reach) best = std::min(best, -std::sqrt(reach * reach - h2));
                    }
                }
                if (best < wanted) mine.push_back({o, best});
            };
            if (wanted > 0.0f) columns.forEachNear(glm::vec2(bound_center[i]), bound_radius[i] + max_bound + gap, pairWith);
            // Nothing to land on within max_drop where everything still is: the instance is HELD (a
            // stone of a corbelled roof, wedged between its neighbours), never dropped into the open.
            // It moves down with the wall that holds it: as far as the least of its neighbours beside
            // or below it (bounding spheres that touch, centre not higher) has fallen, never further
            // than max_drop, which its own pairs leave free. Held where it was without one. (Held at 0,
            // a stone of a dome's inner face kept the courses resting on it up while the wall beside
            // them settled: open bands tore through the stone hut's wall.) Decided once, so drops
            // still only grow from pass to pass.
            if (mine.empty() && !(limit < max_drop)) {
                columns.forEachNear(glm::vec2(bound_center[i]), bound_radius[i] + max_bound + gap, [&](uint32_t o) {
                    if (o == i || bound_center[o].z > bound_center[i].z) return;
                    const float reach = bound_radius[i] + bound_radius[o] + gap;
                    const glm::vec3 d = bound_center[i] - bound_center[o];
                    if (!(glm::dot(d, d) < reach * reach)) return;
                    // Boxes around rotated sphere sets can touch with their origins up to ~2.4 bounds apart
                    // (each box's centre off its origin): beyond one pass reach a neighbour would lie outside
                    // the halo an update reads, so it does not hold the instance.
                    const glm::vec3 o_d = w.origin[i] - w.origin[o];
                    if (glm::dot(glm::vec2(o_d), glm::vec2(o_d)) < pass_reach * pass_reach &&
                        std::abs(o_d.z) < pass_reach + max_drop)
                        beside[i].push_back(o);
                });
                if (beside[i].empty()) bound[i] = 0.0f;
            }
        }
    });

    std::vector<uint16_t> next(n);
    for (int pass = 0; pass < passes; ++pass) {
        std::atomic<bool> moved{false};
        parallelFor(n, threads, 256, [&](size_t b, size_t e, int) {
            bool any = false;
            for (size_t i = b; i < e; ++i) {
                if (isFixed(i)) {
                    next[i] = (*io.given)[size_t(pass)][i];
                    continue;
                }
                float d = bound[i];
                for (const Pair& p : pairs[i]) d = std::min(d, std::max(0.0f, p.offset + dropMetres(drops[p.lower])));
                next[i] = toUnits(d);
                // In units, not metres: a held instance keeps exactly in step with its wall.
                for (uint32_t o : beside[i]) next[i] = std::min(next[i], drops[o]);
                any = any || next[i] != drops[i];
            }
            if (any) moved.store(true, std::memory_order_relaxed);
        });
        drops.swap(next);
        if (io.record && pass + 1 < passes) (*io.record)[size_t(pass)] = drops;
        // Nothing moved: every later pass would give the same drops. (A window with a given ring runs
        // every pass: the ring may still move.)
        if (!io.fixed && !moved.load()) {
            if (io.record)
                for (int later = pass + 1; later + 1 < passes; ++later) (*io.record)[size_t(later)] = drops;
            break;
        }
    }
    return drops;
}

// Halo of one pass, in tiles: horizontally the pair reach, vertically the reach plus the largest drop.
glm::ivec3 passHaloTiles(const SettleInput& in) {
    const float s = in.tile->settings.tile_size_m;
    const float reach = passReachMetres(in);
    const int xy = int(std::ceil(reach / s));
    const int z = int(std::ceil((reach + in.settings.max_drop_m) / s));
    return glm::ivec3(xy, xy, z);
}

}  // namespace

namespace {

// Values one per instance of the store, in store order, filed by tile.
void fileByTile(const InstanceStore& store, const std::vector<uint16_t>& values, SettledDrops* out) {
    out->clear();
    size_t i = 0;
    std::vector<uint32_t> ids;
    for (size_t t = 0; t < store.tileCount(); ++t) {
        store.tileIds(t, &ids);
        out->append(store.tileKey(t), std::span<const uint16_t>(values.data() + i, ids.size()));
        i += ids.size();
    }
}

}  // namespace

void settleAll(const SettleInput& in, const InstanceStore& store, int threads, SettledDrops* out,
               SettleHistory* history) {
    Window w;
    CandidateSpheres spheres(in);
    size_t sphere_count = 0;
    store.forEach([&](uint64_t, uint32_t j) { sphere_count += spheres.sphereCount(j); });
    reserveWindow(store.instanceCount(), sphere_count, &w);
    store.forEach([&](uint64_t tile, uint32_t j) { addInstance(in, tile, j, &spheres, &w); });
    w.sphere_begin.push_back(uint32_t(w.center.size()));
    std::vector<std::vector<uint16_t>> record;
    fileByTile(store, settleWindow(in, w, threads, {.record = history ? &record : nullptr}), out);
    if (!history) return;
    history->passes = in.settings.passes;
    history->after_pass.resize(record.size());
    for (size_t k = 0; k < record.size(); ++k) fileByTile(store, record[k], &history->after_pass[k]);
}

float settleHaloMetres(const SettleInput& in) {
    const glm::ivec3 h = passHaloTiles(in);
    return float(std::max(h.x, h.z) * in.settings.passes + 1) * in.tile->settings.tile_size_m;
}

namespace {

// The store's tiles, each from `values` (a window's, where fresh[t] >= 0 says its tile starts) or, where
// fresh[t] < 0, as `old` had it (a tile the window did not compute kept its instances and their values).
// Tiles the store lost are gone.
void mergeFresh(const InstanceStore& store, const std::vector<int64_t>& fresh, const std::vector<uint16_t>& values,
                const SettledDrops& old, SettledDrops* out) {
    out->clear();
    std::vector<uint32_t> ids;
    for (size_t t = 0; t < store.tileCount(); ++t) {
        const uint64_t key = store.tileKey(t);
        if (fresh[t] < 0) {
            out->append(key, old.tile(key));
            continue;
        }
        store.tileIds(t, &ids);
        out->append(key, std::span<const uint16_t>(values.data() + fresh[t], ids.size()));
    }
}

}  // namespace

void settleUpdate(const SettleInput& in, const InstanceStore& store, std::span<const uint64_t> changed_tiles,
                  int threads, SettledDrops* drops, std::vector<uint64_t>* touched, SettleHistory* history) {
    if (touched) touched->clear();
    if (changed_tiles.empty()) return;
    const int passes = in.settings.passes;
    // With the drops after every pass known outside, the window is the tiles that may change and one
    // pass's halo of neighbours read from the history; without, the neighbours' drops must be computed
    // too, from instances as far again.
    const bool narrow = history && history->passes == passes && history->after_pass.size() == size_t(passes - 1);
    if (history && !narrow) history->clear();
    const glm::ivec3 halo = passHaloTiles(in);
    const glm::ivec3 affect = halo * passes;                        // drops that may change
    const glm::ivec3 need = narrow ? affect + halo : affect * 2;    // instances those depend on
    std::vector<glm::ivec3> changed;
    glm::ivec3 lo(std::numeric_limits<int>::max()), hi(std::numeric_limits<int>::min());
    for (uint64_t k : changed_tiles) {
        changed.push_back(unpackTile(k));
        lo = glm::min(lo, changed.back());
        hi = glm::max(hi, changed.back());
    }
    auto within = [&](const glm::ivec3& t, const glm::ivec3& reach) {
        if (glm::any(glm::lessThan(t, lo - reach)) || glm::any(glm::greaterThan(t, hi + reach))) return false;
        for (const glm::ivec3& c : changed) {
            const glm::ivec3 d = glm::abs(t - c);
            if (d.x <= reach.x && d.y <= reach.y && d.z <= reach.z) return true;
        }
        return false;
    };
    Window w;
    CandidateSpheres spheres(in);
    std::vector<uint32_t> ids;
    // Per store tile: -1 keeps its old drops, else where its fresh ones start in the window.
    std::vector<int64_t> fresh(store.tileCount(), -1);
    // Narrow: per window instance whether it is read, and what (after each pass, the last included).
    std::vector<uint8_t> fixed;
    std::vector<std::vector<uint16_t>> given(narrow ? size_t(passes) : 0);
    for (size_t t = 0; t < store.tileCount(); ++t) {
        const uint64_t key = store.tileKey(t);
        const glm::ivec3 coord = unpackTile(key);
        if (!within(coord, need)) continue;
        store.tileIds(t, &ids);
        const bool compute = within(coord, affect);
        if (compute) fresh[t] = int64_t(w.id.size());
        if (narrow) {
            for (int k = 0; k < passes; ++k) {
                const std::span<const uint16_t> known =
                    compute ? std::span<const uint16_t>() : k + 1 < passes ? history->after_pass[size_t(k)].tile(key) : drops->tile(key);
                if (!compute && known.size() != ids.size()) {
                    // Not the history of these drops (a caller's mistake): start again without it.
                    history->clear();
                    settleUpdate(in, store, changed_tiles, threads, drops, touched, history);
                    return;
                }
                if (compute) given[size_t(k)].resize(given[size_t(k)].size() + ids.size(), 0);
                else given[size_t(k)].insert(given[size_t(k)].end(), known.begin(), known.end());
            }
            fixed.resize(fixed.size() + ids.size(), compute ? 0 : 1);
        }
        for (uint32_t j : ids) addInstance(in, key, j, &spheres, &w);
    }
    w.sphere_begin.push_back(uint32_t(w.center.size()));
    std::vector<std::vector<uint16_t>> record;
    const WindowPasses io = narrow ? WindowPasses{&fixed, &given, &record} : WindowPasses{};
    const std::vector<uint16_t> result = settleWindow(in, w, threads, io);
    SettledDrops next;
    mergeFresh(store, fresh, result, *drops, &next);
    if (touched) {
        // Only tiles whose drops differ need re-drawing, and the changed ones.
        for (size_t t = 0; t < store.tileCount(); ++t) {
            const uint64_t key = store.tileKey(t);
            if (fresh[t] < 0) continue;
            const std::span<const uint16_t> now = next.tile(key), before = drops->tile(key);
            if (!std::equal(now.begin(), now.end(), before.begin(), before.end())) touched->push_back(key);
        }
        for (uint64_t k : changed_tiles) touched->push_back(k);
        std::sort(touched->begin(), touched->end());
        touched->erase(std::unique(touched->begin(), touched->end()), touched->end());
    }
    *drops = std::move(next);
    if (narrow) {
        for (size_t k = 0; k + 1 < size_t(passes); ++k) {
            SettledDrops merged;
            mergeFresh(store, fresh, record[k], history->after_pass[k], &merged);
            history->after_pass[k] = std::move(merged);
        }
    }
}

void cropToRegion(const InstanceStore& store, const SettledDrops& drops, const GhostTile& tile, const Bounds& region,
                  InstanceStore* out_store, SettledDrops* out_drops) {
    out_store->clear();
    out_drops->clear();
    const CandidateSet& c = tile.candidates;
    std::vector<uint32_t> ids, kept_ids;
    std::vector<uint16_t> kept_drops;
    for (size_t t = 0; t < store.tileCount(); ++t) {
        const uint64_t key = store.tileKey(t);
        store.tileIds(t, &ids);
        const std::span<const uint16_t> d = drops.tile(key);
        const glm::vec3 origin = tileOrigin(unpackTile(key), tile.settings.tile_size_m);
        kept_ids.clear();
        kept_drops.clear();
        for (size_t k = 0; k < ids.size(); ++k) {
            const glm::vec3 p = origin + c.position[ids[k]];
            if (!(region.lo.x <= p.x && p.x < region.hi.x && region.lo.y <= p.y && p.y < region.hi.y &&
                  region.lo.z <= p.z && p.z < region.hi.z))
                continue;
            kept_ids.push_back(ids[k]);
            kept_drops.push_back(k < d.size() ? d[k] : 0);
        }
        out_store->appendTile(key, kept_ids);
        out_drops->append(key, kept_drops);
    }
}

}  // namespace ug
