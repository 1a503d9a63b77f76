#include "env/snow_joints.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "core/parallel.h"

namespace ug {

namespace {

// How near an object's box another's must come for any of their sides to meet (world metres).
constexpr float kNearM = kSnowJointGapM + kSnowJointHeightM + 0.001f;
// Budgets: a few object pairs per object, a few hundred sides per object near another one and a few dozen
// side pairs per side in a real scene (the road's 2,725 objects: 260 k sides near another object);
// every pair in a hostile one (a thousand objects stacked in one place). Past them the remaining seams stay
// borders; together they bound the search's memory to about 400 MB.
constexpr uint64_t kMaxObjectPairs = 4'000'000;
constexpr uint64_t kMaxSides = 2'000'000;
constexpr uint64_t kMaxCellEntries = 4'000'000;
constexpr uint64_t kMaxSidePairs = 20'000'000;

Bounds grown(const Bounds& b, float by) { return Bounds{b.lo - glm::vec3(by), b.hi + glm::vec3(by)}; }

// The sides of every distinct (type, mode, settings) among the objects with geometry or box snow, and which
// one each object uses (UINT32_MAX: none).
struct TypeSides {
    std::vector<std::vector<SnowBorderSide>> sides;
    std::vector<uint32_t> of_object;
};

TypeSides typeSides(const EnvScene& scene, int threads) {
    using Key = std::tuple<uint32_t, uint32_t, float, float, float, float>;
    std::map<Key, uint32_t> index;
    struct Todo {
        uint32_t type;
        SnowMode mode;
        SnowSettings settings;
    };
    std::vector<Todo> todo;  // per distinct key
    TypeSides out;
    out.of_object.assign(scene.objects().size(), UINT32_MAX);
    for (size_t o = 0; o < scene.objects().size(); ++o) {
        const EnvObject& obj = scene.objects()[o];
        if (obj.snow.mode != SnowMode::Geometry && obj.snow.mode != SnowMode::Box) continue;
        const SnowSettings s = objectSnowSettings(scene, obj);
        const Key key{obj.type, uint32_t(obj.snow.mode), s.up.x, s.up.y, s.up.z, s.max_face_angle_deg};
        auto [it, fresh] = index.emplace(key, uint32_t(todo.size()));
        if (fresh) todo.push_back({obj.type, obj.snow.mode, s});
        out.of_object[o] = it->second;
    }
    out.sides.resize(todo.size());
    parallelFor(todo.size(), threads, 1, [&](size_t b, size_t e, int) {
        for (size_t k = b; k < e; ++k) {
            const EnvObjectType& type = scene.types()[todo[k].type];
            if (todo[k].mode == SnowMode::Box) {
                const SnowBox box = snowBoxOf(type);
                out.sides[k] = snowBoxSides(box.center, box.half_extents, todo[k].settings);
            } else {
                out.sides[k] = snowBorderSides(*type.mesh, todo[k].settings);
            }
        }
    });
    return out;
}

// Pairs of objects with sides whose boxes come within kNearM of each other, as neighbour lists.
std::vector<std::vector<uint32_t>> nearObjects(const EnvScene& scene, const TypeSides& ts) {
    const auto& objects = scene.objects();
    std::vector<uint32_t> order;
    for (uint32_t o = 0; o < objects.size(); ++o)
        if (ts.of_object[o] != UINT32_MAX && !ts.sides[ts.of_object[o]].empty()) order.push_back(o);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return objects[a].bounds.lo.x != objects[b].bounds.lo.x ? objects[a].bounds.lo.x < objects[b].bounds.lo.x : a < b;
    });
    std::vector<std::vector<uint32_t>> near(objects.size());
    uint64_t pairs = 0;
    for (size_t i = 0; i < order.size() && pairs <= kMaxObjectPairs; ++i) {
        const Bounds a = grown(objects[order[i]].bounds, kNearM);
        for (size_t j = i + 1; j < order.size() && objects[order[j]].bounds.lo.x <= a.hi.x; ++j) {
            if (++pairs > kMaxObjectPairs) break;
            if (!overlaps(a, objects[order[j]].bounds)) continue;
            near[order[i]].push_back(order[j]);
            near[order[j]].push_back(order[i]);
        }
    }
    return near;
}

// Sides meet only within kSnowJointHeightM of each other's height: they are sorted into layers that thick,
// so a side's partners lie in its own layer or the next one up or down.
constexpr float kLayerM = kSnowJointHeightM;

struct WorldSide {
    int64_t layer;  // floor(height of a / kLayerM)
    uint32_t object, side;
    SnowBorderSide geo;        // world space
    glm::vec3 local_centroid;  // its face's centroid in object space, where the builder tests shelter
    float lo_x, hi_x;
};

// The sides of objects with neighbours, in world space, that come near one of those neighbours.
std::vector<WorldSide> sidesNearNeighbours(const EnvScene& scene, const TypeSides& ts,
                                           const std::vector<std::vector<uint32_t>>& near) {
    const auto& objects = scene.objects();
    std::vector<WorldSide> out;
    for (uint32_t o = 0; o < objects.size(); ++o) {
        if (near[o].empty()) continue;
        const EnvPlacement& pl = objects[o].placement;
        const std::vector<SnowBorderSide>& sides = ts.sides[ts.of_object[o]];
        for (uint32_t k = 0; k < sides.size(); ++k) {
            const SnowBorderSide& s = sides[k];
            WorldSide w{0, o, k, {pl.toWorld(s.a), pl.toWorld(s.b), glm::vec3(0.0f), pl.toWorld(s.face_centroid)},
                        s.face_centroid, 0, 0};
            w.geo.inward = glm::normalize(pl.toWorld(s.a + s.inward) - w.geo.a);
            const Bounds box = grown(Bounds{glm::min(w.geo.a, w.geo.b), glm::max(w.geo.a, w.geo.b)}, kNearM);
            bool meets = false;
            for (uint32_t n : near[o]) meets = meets || overlaps(box, objects[n].bounds);
            if (!meets) continue;
            if (out.size() >= kMaxSides) return out;
            // By vertical height, as snowSidesMeet compares them (not along a wind's slanting `up`, which
            // would put the two ends of one cobble joint layers apart).
            const double layer = std::floor(double(w.geo.a.z) / kLayerM);
            if (!(std::fabs(layer) < 1e15)) continue;  // a non-finite placement meets nothing
            w.layer = int64_t(layer);
            w.lo_x = std::min(w.geo.a.x, w.geo.b.x);
            w.hi_x = std::max(w.geo.a.x, w.geo.b.x);
            out.push_back(w);
        }
    }
    return out;
}

// Pairs of sides of two objects that meet across a joint (indices into `sides`). Every side is entered in
// the cells of a grid (kCellM squares, per layer) that its box grown by the gap covers; a cell's sides are
// paired with each other and with the same cell one layer up, each pair only in the first cell both boxes
// share. A row of small tiles puts thousands of sides at one x, which a sweep along x pairs all with each
// other; a cell holds a few dozen.
constexpr float kCellM = 0.125f;

struct CellEntry {
    int64_t layer, ix, iy;
    uint32_t side;
    bool operator<(const CellEntry& o) const {
        return std::tie(layer, ix, iy, side) < std::tie(o.layer, o.ix, o.iy, o.side);
    }
};

std::vector<std::pair<uint32_t, uint32_t>> meetingSides(const std::vector<WorldSide>& sides) {
    const float reach = kSnowJointGapM + kSnowJointOverlapM;
    auto cellRange = [&](const WorldSide& w, int64_t* x0, int64_t* x1, int64_t* y0, int64_t* y1) {
        const float ylo = std::min(w.geo.a.y, w.geo.b.y), yhi = std::max(w.geo.a.y, w.geo.b.y);
        *x0 = int64_t(std::floor((w.lo_x - reach) / kCellM)), *x1 = int64_t(std::floor((w.hi_x + reach) / kCellM));
        *y0 = int64_t(std::floor((ylo - reach) / kCellM)), *y1 = int64_t(std::floor((yhi + reach) / kCellM));
    };
    std::vector<CellEntry> entries;
    std::vector<std::pair<int64_t, int64_t>> first_cell(sides.size());  // each side's lowest (ix, iy)
    for (uint32_t k = 0; k < sides.size(); ++k) {
        int64_t x0, x1, y0, y1;
        cellRange(sides[k], &x0, &x1, &y0, &y1);
        first_cell[k] = {x0, y0};
        if (double(x1 - x0 + 1) * double(y1 - y0 + 1) + double(entries.size()) > double(kMaxCellEntries)) continue;
        for (int64_t iy = y0; iy <= y1; ++iy)
            for (int64_t ix = x0; ix <= x1; ++ix) entries.push_back({sides[k].layer, ix, iy, k});
    }
    std::sort(entries.begin(), entries.end());
    // The run of entries of one cell (empty when it holds none).
    auto cellRun = [&](int64_t layer, int64_t ix, int64_t iy) {
        const CellEntry lo{layer, ix, iy, 0};
        const auto b = std::lower_bound(entries.begin(), entries.end(), lo);
        auto e = b;
        while (e != entries.end() && e->layer == layer && e->ix == ix && e->iy == iy) ++e;
        return std::pair{b, e};
    };
    std::vector<std::pair<uint32_t, uint32_t>> meeting;
    uint64_t pairs = 0;
    auto test = [&](uint32_t i, uint32_t j, int64_t ix, int64_t iy) {
        const WorldSide &p = sides[i], &q = sides[j];
        if (p.object == q.object || q.lo_x > p.hi_x + reach || p.lo_x > q.hi_x + reach) return;
        if (ix != std::max(first_cell[i].first, first_cell[j].first) ||
            iy != std::max(first_cell[i].second, first_cell[j].second))
            return;  // met in an earlier cell
        if (snowSidesMeet(p.geo, q.geo, kSnowJointOverlapM)) meeting.emplace_back(std::min(i, j), std::max(i, j));
    };
    for (size_t b = 0; b < entries.size() && pairs <= kMaxSidePairs;) {
        size_t e = b;
        while (e < entries.size() && entries[e].layer == entries[b].layer && entries[e].ix == entries[b].ix &&
               entries[e].iy == entries[b].iy)
            ++e;
        const auto [ub, ue] = cellRun(entries[b].layer + 1, entries[b].ix, entries[b].iy);
        for (size_t i = b; i < e && pairs <= kMaxSidePairs; ++i) {
            for (size_t j = i + 1; j < e && ++pairs <= kMaxSidePairs; ++j)
                test(entries[i].side, entries[j].side, entries[b].ix, entries[b].iy);
            for (auto it = ub; it != ue && ++pairs <= kMaxSidePairs; ++it)
                test(entries[i].side, it->side, entries[b].ix, entries[b].iy);
        }
        b = e;
    }
    return meeting;
}

}  // namespace

SnowBox snowBoxOf(const EnvObjectType& type) {
    const Bounds3& b = type.bounds;
    return SnowBox{(b.min + b.max) * 0.5f, (b.max - b.min) * 0.5f};
}

SnowSettings objectSnowSettings(const EnvScene& scene, const EnvObject& o) {
    SnowSettings s;
    // Faces take snow when they face back along the snowfall, turned into the object's space.
    const glm::vec3 up = -scene.desc().snow_direction;
    s.up = glm::normalize(glm::vec3(o.placement.c * up.x + o.placement.s * up.y,
                                    -o.placement.s * up.x + o.placement.c * up.y, up.z));
    s.max_face_angle_deg = o.snow.max_face_angle_deg;
    s.min_open = scene.snowMinOpen();
    s.d0_m = o.snow.d0_m / o.placement.scale;
    s.target_edge_m = o.snow.target_edge_m / o.placement.scale;
    return s;
}

std::vector<std::vector<SnowSegment>> findSnowJoints(const EnvScene& scene, int threads) {
    const auto& objects = scene.objects();
    std::vector<std::vector<SnowSegment>> out(objects.size());
    const TypeSides ts = typeSides(scene, threads);
    std::vector<WorldSide> sides = sidesNearNeighbours(scene, ts, nearObjects(scene, ts));
    const std::vector<std::pair<uint32_t, uint32_t>> meeting = meetingSides(sides);
    // Both faces must take snow: open at their centroid, as the builder tests them (one query per object).
    std::vector<uint32_t> involved;
    for (auto [i, j] : meeting) involved.insert(involved.end(), {i, j});
    std::sort(involved.begin(), involved.end(), [&](uint32_t a, uint32_t b) {
        return std::tie(sides[a].object, a) < std::tie(sides[b].object, b);
    });
    involved.erase(std::unique(involved.begin(), involved.end()), involved.end());
    std::vector<size_t> runs;  // starts of each object's run in `involved`
    for (size_t k = 0; k < involved.size(); ++k)
        if (k == 0 || sides[involved[k]].object != sides[involved[k - 1]].object) runs.push_back(k);
    runs.push_back(involved.size());
    std::vector<char> open(sides.size(), 0);
    const float min_open = scene.snowMinOpen();
    parallelFor(runs.size() - 1, threads, 1, [&](size_t b, size_t e, int) {
        for (size_t r = b; r < e; ++r) {
            const uint32_t o = sides[involved[runs[r]]].object;
            std::vector<glm::vec3> at;
            for (size_t k = runs[r]; k < runs[r + 1]; ++k)
                at.push_back(sides[involved[k]].local_centroid);
            std::vector<EnvSample> e_at(at.size());
            scene.objectQuery(o)(at.data(), at.size(), e_at.data());
            for (size_t k = runs[r]; k < runs[r + 1]; ++k) open[involved[k]] = e_at[k - runs[r]].shelter >= min_open;
        }
    });
    // Per object, (side, joint width in its own units); a side facing two others keeps the wider joint.
    std::vector<std::vector<std::pair<uint32_t, float>>> bridged(objects.size());
    // The width in 0.1 mm steps: pieces whose joints differ by rounding alone still share one snow mesh.
    auto bridge = [&](const WorldSide& p, const WorldSide& q) {
        const float gap = std::round(snowJointGap(p.geo, q.geo) * 1e4f) * 1e-4f;
        bridged[p.object].emplace_back(p.side, gap / objects[p.object].placement.scale);
    };
    for (auto [i, j] : meeting)
        if (open[i] && open[j]) bridge(sides[i], sides[j]), bridge(sides[j], sides[i]);
    for (uint32_t o = 0; o < objects.size(); ++o) {
        auto& list = bridged[o];
        if (list.empty()) continue;
        std::sort(list.begin(), list.end());
        const std::vector<SnowBorderSide>& type_sides = ts.sides[ts.of_object[o]];
        for (size_t k = 0; k < list.size(); ++k)
            if (k + 1 == list.size() || list[k + 1].first != list[k].first)  // the widest of the side's joints
                out[o].push_back(SnowSegment{type_sides[list[k].first].a, type_sides[list[k].first].b, list[k].second});
    }
    return out;
}

}  // namespace ug
