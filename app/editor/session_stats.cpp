#include "editor/session_stats.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "editor/render_data.h"
#include "instancer/tile_coord.h"

namespace ug::editor {

using nlohmann::json;

// A finished sculpt stroke's pile as the user would judge it (tools.h measureSculptedPile), around the
// ground point of its first stamp, and how many primitives the stroke left (one per cone).
json pileRecord(const Document& doc, const BrushStroke& st) {
    const size_t type = st.sculptType();
    const Bounds& b = st.changedBounds();
    const glm::vec2 at(st.stampPoints().front());
    const float search = std::max({b.hi.x - at.x, at.x - b.lo.x, b.hi.y - at.y, at.y - b.lo.y, 0.1f});
    const PileMeasure m = measureSculptedPile(doc, type, at, search, search / 40.0f, b.hi.z + 0.1f);
    const float angle =
        type < doc.project().detail_types.size() ? doc.project().detail_types[type].angle_of_repose_deg : 35.0f;
    return {{"found", m.found},
            {"type", type},
            {"ground_point", {at.x, at.y}},
            {"centroid", {m.centroid_m.x, m.centroid_m.y}},
            {"height", m.height_m},
            {"radius", m.radius_m},
            {"volume", m.volume_m3},
            {"angle_of_repose_deg", angle},
            {"stamps", st.stamps()},
            {"primitives", st.pileIds().size()},
            {"ids", st.pileIds()}};
}

// The pile as its instances show it: the sculpt type's instances whose origin lies within 1.25 pile radii
// (horizontally) of the ground point: how many, their centroid, and the highest origin above the ground.
json pileInstancesJson(const Document& doc, const InstanceStore& store, const json& pile) {
    const size_t type = pile["type"].get<size_t>();
    const glm::vec2 at(pile["ground_point"][0].get<float>(), pile["ground_point"][1].get<float>());
    const float reach = 1.25f * pile["radius"].get<float>();
    const CandidateSet& c = doc.ghostTile().candidates;
    const float s = doc.ghostTile().settings.tile_size_m;
    uint64_t count = 0;
    glm::dvec2 sum(0.0);
    float top = 0.0f;
    store.forEach([&](uint64_t key, uint32_t id) {
        if (c.type[id] != type) return;
        const glm::vec3 o = tileOrigin(unpackTile(key), s) + c.position[id];
        if (glm::length(glm::vec2(o) - at) > reach) return;
        ++count;
        sum += glm::dvec2(o.x, o.y);
        const SurfaceHit ground = pickGround(doc, rayDownOnto(doc, glm::vec2(o)));
        if (ground.hit) top = std::max(top, o.z - ground.point_m.z);
    });
    const glm::dvec2 centre = count ? sum / double(count) : glm::dvec2(at);
    return {{"count", count}, {"centroid", {centre.x, centre.y}}, {"top", top}};
}

json perTypeJson(const std::vector<std::string>& names, const std::vector<uint64_t>& counts) {
    json j = json::object();
    for (size_t i = 0; i < names.size(); ++i) j[names[i]] = i < counts.size() ? counts[i] : 0;
    return j;
}

std::vector<uint64_t> perTypeCounts(const InstanceStore& store, const CandidateSet& candidates) {
    std::vector<uint64_t> counts(candidates.typeCount(), 0);
    store.forEach([&](uint64_t, uint32_t id) { ++counts[candidates.type[id]]; });
    return counts;
}

// How far an instance's collision spheres reach from its origin, at most, over all types.
float largestReach(const Document& doc) {
    const CandidateSet& c = doc.ghostTile().candidates;
    float reach = 0.0f;
    for (size_t i = 0; i < doc.models().size() && i < c.typeCount(); ++i) {
        const DetailModel& m = doc.models()[i];
        reach = std::max(reach, candidateScaleMax(c, i) * (glm::length(m.bounds.center) + m.bounds.radius));
    }
    return reach;
}

json vec3Json(glm::vec3 v) { return {v.x, v.y, v.z}; }

// Where a world point lands on screen, in pixels from the top left (NaN behind the eye).
glm::vec2 projectToPixel(const glm::mat4& view_proj, float width, float height, glm::vec3 p) {
    const glm::vec4 c = view_proj * glm::vec4(p, 1.0f);
    if (c.w <= 0.0f) return glm::vec2(NAN);
    return {(c.x / c.w * 0.5f + 0.5f) * width, (0.5f - c.y / c.w * 0.5f) * height};
}

}  // namespace ug::editor
