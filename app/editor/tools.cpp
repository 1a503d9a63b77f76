#include "editor/tools.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/edit_commands.h"
#include "scene/sculpt_pile.h"

namespace ug::editor {

const char* toolName(ToolKind tool) {
    switch (tool) {
        case ToolKind::Select:
            return "select";
        case ToolKind::Paint:
            return "paint";
        case ToolKind::Sculpt:
            return "sculpt";
        case ToolKind::Erase:
            return "erase";
    }
    return "?";
}

BrushSettings defaultBrush(const Document& doc) {
    BrushSettings b;
    const size_t n = doc.project().detail_types.size();
    b.type_mix.assign(n, 0.0f);
    if (n > 0) b.type_mix[0] = 1.0f;
    for (size_t i = 0; i < n; ++i)
        if (doc.project().detail_types[i].instancing.strategy == PriorityStrategy::Elevation) {
            b.sculpt_type = i;
            break;
        }
    return b;
}

namespace {

constexpr float kMaxRay_m = 1.0e5f;

// The plane the renderer draws as the ground grid when there is no terrain.
float groundPlaneZ(const Bounds& extent) {
    if (extent.empty()) return 0.0f;
    return (extent.lo.z <= 0.0f && extent.hi.z >= 0.0f) ? 0.0f : extent.lo.z;
}

}  // namespace

float groundHeightAt(const Document& doc, glm::vec2 xy) {
    return doc.terrain() ? doc.terrain()->sample(xy.x, xy.y) : groundPlaneZ(doc.compiled().extent);
}

SurfaceHit pickGround(const Document& doc, const Ray& ray) {
    SurfaceHit out;
    float t = 0.0f;
    if (doc.terrain()) {
        if (!rayHeightField(*doc.terrain(), ray, kMaxRay_m, &t)) return out;
        out.hit = true;
        out.point_m = ray.at(t);
        const glm::vec2 g = doc.terrain()->gradient(out.point_m.x, out.point_m.y);
        out.normal = glm::normalize(glm::vec3(-g.x, -g.y, 1.0f));
        return out;
    }
    const float z = groundPlaneZ(doc.compiled().extent);
    if (std::abs(ray.direction.z) < 1e-6f) return out;
    t = (z - ray.origin_m.z) / ray.direction.z;
    if (!(t >= 0.0f && t < kMaxRay_m)) return out;
    out.hit = true;
    out.point_m = ray.at(t);
    return out;
}

SurfaceHit pickPile(const Document& doc, size_t type, const Ray& ray) {
    SurfaceHit ground = pickGround(doc, ray);
    if (type >= doc.compiled().types.size() || !doc.compiled().types[type].field) return ground;
    const DensityField& field = *doc.compiled().types[type].field;
    const float max_t = ground.hit ? glm::length(ground.point_m - ray.origin_m) + 1e-3f : kMaxRay_m;
    // 2 cm steps: thinner than the smallest ball the sculpt brush makes (its radius slider starts at 0.1 m).
    float t = 0.0f;
    if (!rayDensityIsosurface(field, ray, kSculptIso, max_t, 0.02f, &t)) return ground;
    SurfaceHit out;
    out.hit = true;
    out.on_pile = true;
    out.point_m = ray.at(t);
    const glm::vec4 g = evaluateWithGradient(field, out.point_m);
    const float len = glm::length(glm::vec3(g));
    out.normal = len > 0.0f ? -glm::vec3(g) / len : glm::vec3(0.0f, 0.0f, 1.0f);
    return out;
}

SurfaceHit pickBrushSurface(const Document& doc, const BrushSettings& brush, const Ray& ray) {
    return pickPile(doc, brush.sculpt_type, ray);
}

Ray rayDownOnto(const Document& doc, glm::vec2 xy) {
    float top = 100.0f;
    const Bounds& e = doc.compiled().extent;
    if (!e.empty() && std::isfinite(e.hi.z)) top = std::max(top, e.hi.z + 100.0f);
    if (doc.terrain()) top = std::max(top, doc.terrain()->maxHeight() + 100.0f);
    return Ray{glm::vec3(xy, top), glm::vec3(0.0f, 0.0f, -1.0f)};
}

SurfaceHit sculptLanding(const Document& doc, size_t type, const Ray& ray) {
    const SurfaceHit ground = pickGround(doc, ray);
    if (!ground.hit) return ground;
    return pickPile(doc, type, rayDownOnto(doc, glm::vec2(ground.point_m)));
}

PileMeasure measureSculptedPile(const Document& doc, size_t type, glm::vec2 centre_xy, float search_radius_m,
                                float cell_m, float top_z) {
    return measurePile(
        [&](glm::vec2 xy) {
            const Ray down{glm::vec3(xy, top_z), glm::vec3(0.0f, 0.0f, -1.0f)};
            const SurfaceHit pile = pickPile(doc, type, down);
            if (!pile.hit || !pile.on_pile) return 0.0f;
            const SurfaceHit ground = pickGround(doc, rayDownOnto(doc, xy));
            return ground.hit ? pile.point_m.z - ground.point_m.z : 0.0f;
        },
        centre_xy, search_radius_m, cell_m);
}

SurfaceHit BrushStroke::pick(const Ray& ray) const {
    if (tool_ == ToolKind::Sculpt) return sculptLanding(*doc_, brush_.sculpt_type, ray);
    return pickBrushSurface(*doc_, brush_, ray);
}

bool BrushStroke::begin(Document* doc, ToolKind tool, const BrushSettings& brush, const Ray& ray,
                        double now_s, std::string* error) {
    if (active()) end();
    doc_ = doc;
    tool_ = tool;
    brush_ = brush;
    stamps_ = 0;
    changed_ = Bounds{};
    points_.clear();
    pile_ids_.clear();
    pile_volume_m3_ = 0.0f;
    stroke_tag_ = doc->newStrokeTag();
    const char* names[] = {"Select", "Paint", "Sculpt", "Erase"};
    doc_->beginStroke(names[int(tool)]);
    const SurfaceHit hit = pick(ray);
    if (!hit.hit) return true;  // off the ground: nothing yet, the drag may come onto it
    return stamp(hit, now_s, error);
}

bool BrushStroke::drag(const Ray& ray, double now_s, std::string* error) {
    if (!active()) return true;
    if (tool_ == ToolKind::Sculpt && stamps_ > 0) {
        // Held still over the same ground point, the cone under it takes more material; the landing is
        // not picked again, since the growing cone would be under the brush and lift it.
        const SurfaceHit ground = pickGround(*doc_, ray);
        if (!ground.hit) return true;
        const float travel = glm::length(glm::vec2(ground.point_m) - glm::vec2(last_point_));
        if (travel >= brush_.radius_m / 3.0f) {
            const SurfaceHit landing = pick(ray);
            return !landing.hit || stamp(landing, now_s, error);
        }
        if (now_s - last_time_s_ >= kSculptHoldInterval_s - 1e-9) return growPile(now_s, error);
        return true;
    }
    const SurfaceHit hit = pick(ray);
    if (!hit.hit) return true;
    if (stamps_ == 0) return stamp(hit, now_s, error);
    // Travel over the ground, in XY: growing a pile moves the hit point up without the brush moving.
    const float travel = glm::length(glm::vec2(hit.point_m - last_point_));
    if (travel < brush_.radius_m / 3.0f) return true;
    return stamp(hit, now_s, error);
}

Primitive BrushStroke::pileCone(float volume_m3) const {
    Primitive prim =
        pileConePrimitive(pileConeOnBed(pile_base_, pile_bed_, volume_m3, pileAngleDeg()), pileWeight(), kSculptIso);
    prim.stroke = stroke_tag_;
    return prim;
}

PileBed samplePileBed(const Document& doc, size_t type, glm::vec3 base_m, float radius_m) {
    // 25 x 25 columns: the bed only corrects the cone's height, so its cells may be coarse (a tenth of the
    // cone's radius), and a stamp stays a few hundred short ray casts.
    constexpr int kHalfCells = 12;
    PileBed bed;
    bed.centre_m = glm::vec2(base_m);
    bed.half_cells = kHalfCells;
    bed.cell_m = radius_m / float(kHalfCells);
    bed.height_m.assign(size_t(2 * kHalfCells + 1) * size_t(2 * kHalfCells + 1), 0.0f);
    size_t k = 0;
    for (int j = -kHalfCells; j <= kHalfCells; ++j)
        for (int i = -kHalfCells; i <= kHalfCells; ++i, ++k) {
            const glm::vec2 xy = bed.centre_m + bed.cell_m * glm::vec2(i, j);
            // The pile, or the ground where there is none: on a slope the ground uphill of the base is a
            // bed too, since the cone's material cannot be inside it.
            const SurfaceHit top = pickPile(doc, type, rayDownOnto(doc, xy));
            if (top.hit) bed.height_m[k] = std::max(0.0f, top.point_m.z - base_m.z);
        }
    return bed;
}

float BrushStroke::pileWeight() const { return kSculptPileWeight * std::max(1.0f, brush_.strength); }

float BrushStroke::stampVolume() const {
    return sculptStampVolume(std::max(brush_.radius_m, 1e-3f), std::max(1.0f, brush_.strength), kSculptIso);
}

float BrushStroke::pileAngleDeg() const {
    return brush_.sculpt_type < doc_->project().detail_types.size()
               ? doc_->project().detail_types[brush_.sculpt_type].angle_of_repose_deg
               : 35.0f;
}

bool BrushStroke::startPile(const SurfaceHit& landing, double now_s, std::string* error) {
    // The cone stands on the ground under the landing and rises through the pile there (pileConeOnBed).
    pile_base_ = glm::vec3(glm::vec2(landing.point_m), groundHeightAt(*doc_, glm::vec2(landing.point_m)));
    pile_volume_m3_ = stampVolume();
    const PileCone lone = pileConeForVolume(pile_base_, pile_volume_m3_, pileAngleDeg());
    const float slope = lone.height_m / std::max(lone.base_radius_m, 1e-6f);
    const float under = landing.on_pile ? std::max(0.0f, landing.point_m.z - pile_base_.z) : 0.0f;
    // Wide enough for the cone a held brush grows to in a few seconds on top of what is there; a longer
    // hold's cone reaches past it, where the bed counts as empty and the cone rises a little less.
    const float reach = std::min(8.0f, 2.0f * (under + 2.0f * lone.height_m) / std::max(slope, 1e-3f));
    pile_bed_ = samplePileBed(*doc_, brush_.sculpt_type, pile_base_, reach);
    const Primitive prim = pileCone(pile_volume_m3_);
    const uint64_t id = doc_->addPrimitive(brush_.sculpt_type, prim, error);
    if (id == 0) return false;
    pile_ids_.push_back(id);
    changed_ = unite(changed_, editBounds(prim));
    last_point_ = landing.point_m;
    last_time_s_ = now_s;
    ++stamps_;
    points_.push_back(landing.point_m);
    return true;
}

bool BrushStroke::growPile(double now_s, std::string* error) {
    if (pile_ids_.empty()) return true;
    const float volume = pile_volume_m3_ + stampVolume();
    const Primitive cone = pileCone(volume);
    if (!doc_->setPrimitive(pile_ids_.back(), cone, error)) return false;
    pile_volume_m3_ = volume;
    // The cone only grows, so its new support holds the old one.
    changed_ = unite(changed_, editBounds(cone));
    last_time_s_ = now_s;
    ++stamps_;
    const glm::vec3 landed = points_.back();  // held still: the same spot again
    points_.push_back(landed);
    return true;
}

void BrushStroke::end() {
    if (!active()) return;
    doc_->endStroke();
    doc_ = nullptr;
}

bool BrushStroke::stamp(const SurfaceHit& hit, double now_s, std::string* error) {
    std::vector<std::pair<size_t, Primitive>> prims;
    const size_t types = doc_->project().detail_types.size();
    const float r = std::max(brush_.radius_m, 1e-3f);
    switch (tool_) {
        case ToolKind::Select:
            return true;
        case ToolKind::Paint:
            for (size_t i = 0; i < types && i < brush_.type_mix.size(); ++i) {
                if (!(brush_.type_mix[i] > 0.0f)) continue;
                const float w = brush_.strength * brush_.type_mix[i] * (brush_.subtract ? -1.0f : 1.0f);
                prims.emplace_back(
                    i, makeDisc(hit.point_m, hit.normal, r, std::max(brush_.falloff_m, 1e-3f), w));
            }
            break;
        case ToolKind::Sculpt:
            if (brush_.sculpt_type < types) return startPile(hit, now_s, error);
            break;
        case ToolKind::Erase:
            for (size_t i = 0; i < types && i < brush_.type_mix.size(); ++i) {
                if (!(brush_.type_mix[i] > 0.0f)) continue;
                prims.emplace_back(
                    i, makePoint(hit.point_m, r, -kEraseWeight * brush_.strength * brush_.type_mix[i]));
            }
            break;
    }
    for (auto& [type, prim] : prims) {
        prim.stroke = stroke_tag_;
        if (doc_->addPrimitive(type, prim, error) == 0) return false;
        changed_ = unite(changed_, editBounds(prim));
    }
    last_point_ = hit.point_m;
    last_time_s_ = now_s;
    ++stamps_;
    if (!prims.empty()) points_.push_back(hit.point_m);
    return true;
}

namespace {

bool isTerrainKind(const Primitive& prim) {
    return prim.kind == PrimitiveKind::TerrainLayer || prim.kind == PrimitiveKind::TerrainSolid;
}

// Where the ray meets the plane through `point` with normal `n`; false when parallel or behind.
bool rayPlane(const Ray& ray, glm::vec3 point, glm::vec3 n, glm::vec3* hit) {
    const float denom = glm::dot(ray.direction, n);
    if (std::abs(denom) < 1e-6f) return false;
    const float t = glm::dot(point - ray.origin_m, n) / denom;
    if (!(t >= 0.0f && t < kMaxRay_m)) return false;
    *hit = ray.at(t);
    return true;
}

}  // namespace

bool standsOnGround(const Document& doc, const Primitive& prim) {
    return isPileCone(prim) && std::abs(prim.center_m.z - groundHeightAt(doc, glm::vec2(prim.center_m))) < 0.01f;
}

glm::vec3 groundFollowingOffset(const Document& doc, const Primitive& prim, bool on_ground, glm::vec3 offset_m) {
    if (!on_ground) return offset_m;
    const glm::vec2 xy = glm::vec2(prim.center_m) + glm::vec2(offset_m);
    return glm::vec3(glm::vec2(offset_m), groundHeightAt(doc, xy) + offset_m.z - prim.center_m.z);
}

std::vector<uint64_t> duplicateStroke(Document* doc, uint64_t id, std::string* error) {
    Primitive picked;
    if (!doc->findPrimitive(id, nullptr, &picked)) {
        *error = "no primitive with id " + std::to_string(id);
        return {};
    }
    const glm::vec3 along(std::max(picked.radius_m, picked.disc_radius_m), 0.0f, 0.0f);
    const std::vector<uint64_t> members = doc->strokeMembers(id);
    std::vector<glm::vec3> offsets;
    for (uint64_t member : members) {
        Primitive p;
        offsets.push_back(doc->findPrimitive(member, nullptr, &p) ? groundFollowingOffset(*doc, p, standsOnGround(*doc, p), along)
                                                                  : along);
    }
    return doc->duplicatePrimitives(members, offsets, error);
}

bool MoveDrag::begin(Document* doc, uint64_t id, const Ray& ray) {
    if (active()) end();
    Primitive prim;
    if (!doc->findPrimitive(id, nullptr, &prim) || isTerrainKind(prim)) return false;
    // The whole stroke the primitive belongs to moves with it; its terrain layers (a paint stroke never
    // makes one, a file may tag one) follow their height field and stay.
    start_.clear();
    grounded_.clear();
    for (uint64_t member : doc->strokeMembers(id)) {
        Primitive p;
        if (!doc->findPrimitive(member, nullptr, &p) || isTerrainKind(p)) continue;
        start_.emplace_back(member, p);
        grounded_.push_back(standsOnGround(*doc, p));
    }
    doc_ = doc;
    id_ = id;
    grab_m_ = dragGrab(ray, prim.center_m);
    applied_offset_m_ = glm::vec3(0.0f);
    moves_ = 0;
    doc_->beginStroke(start_.size() > 1 ? "Move stroke" : "Move");
    return true;
}

bool dragOffset(const Ray& ray, glm::vec3 grab, glm::vec3 applied, bool vertical, glm::vec3* offset) {
    glm::vec3 hit;
    if (vertical) {
        // The upright plane through the grab point that faces the ray; only the height changes.
        const glm::vec3 n(ray.direction.x, ray.direction.y, 0.0f);
        if (glm::length(n) < 1e-4f || !rayPlane(ray, grab, glm::normalize(n), &hit)) return false;
        *offset = glm::vec3(applied.x, applied.y, hit.z - grab.z);
        return true;
    }
    if (!rayPlane(ray, grab + glm::vec3(0.0f, 0.0f, applied.z), glm::vec3(0.0f, 0.0f, 1.0f), &hit)) return false;
    *offset = glm::vec3(hit.x - grab.x, hit.y - grab.y, applied.z);
    return true;
}

glm::vec3 dragGrab(const Ray& ray, glm::vec3 centre) {
    glm::vec3 grab;
    return rayPlane(ray, centre, glm::vec3(0.0f, 0.0f, 1.0f), &grab) ? grab : centre;
}

bool MoveDrag::drag(const Ray& ray, bool vertical, std::string* error) {
    if (!active()) return true;
    glm::vec3 offset;
    if (!dragOffset(ray, grab_m_, applied_offset_m_, vertical, &offset)) return true;
    // A millimetre of motion is below anything a density change shows; skipping it keeps a still mouse
    // from flooding the live instancer.
    if (glm::length(offset - applied_offset_m_) < 1e-3f) return true;
    std::vector<std::pair<uint64_t, Primitive>> moved;
    moved.reserve(start_.size());
    for (size_t k = 0; k < start_.size(); ++k) {
        const auto& [member, start] = start_[k];
        moved.emplace_back(member, translatedPrimitive(start, groundFollowingOffset(*doc_, start, grounded_[k], offset)));
    }
    if (!doc_->setPrimitives(moved, "Move", error)) return false;
    applied_offset_m_ = offset;
    ++moves_;
    return true;
}

void MoveDrag::end() {
    if (!active()) return;
    doc_->endStroke();
    doc_ = nullptr;
}

std::vector<std::pair<uint64_t, Primitive>> strokeEdit(const Document& doc, uint64_t id, const Primitive& edited) {
    Primitive before;
    if (!doc.findPrimitive(id, nullptr, &before)) return {};
    const glm::vec3 offset = edited.center_m - before.center_m;
    const float radius_factor = before.radius_m > 0.0f ? edited.radius_m / before.radius_m : 1.0f;
    std::vector<std::pair<uint64_t, Primitive>> edits;
    for (uint64_t member : doc.strokeMembers(id)) {
        Primitive p;
        if (!doc.findPrimitive(member, nullptr, &p)) continue;
        if (member == id) {
            edits.emplace_back(member, edited);
            continue;
        }
        if (!isTerrainKind(p)) p = translatedPrimitive(p, offset);
        p.weight = before.weight != 0.0f ? p.weight * (edited.weight / before.weight)
                                         : p.weight + (edited.weight - before.weight);
        p.radius_m *= radius_factor;
        p.end_radius_m *= radius_factor;
        edits.emplace_back(member, p);
    }
    return edits;
}

Ray rayThroughPixel(const glm::mat4& view_proj, float width, float height, glm::vec2 cursor) {
    const glm::mat4 inv = glm::inverse(view_proj);
    const float x = 2.0f * cursor.x / width - 1.0f;
    const float y = 1.0f - 2.0f * cursor.y / height;
    glm::vec4 a = inv * glm::vec4(x, y, -1.0f, 1.0f);
    glm::vec4 b = inv * glm::vec4(x, y, 1.0f, 1.0f);
    a /= a.w;
    b /= b.w;
    return Ray{glm::vec3(a), glm::normalize(glm::vec3(b - a))};
}

size_t nearestOnScreen(const std::vector<glm::vec3>& points, const glm::mat4& view_proj, float width, float height,
                       glm::vec2 cursor, float max_px) {
    size_t best = SIZE_MAX;
    float best_d = max_px;
    for (size_t i = 0; i < points.size(); ++i) {
        const glm::vec4 c = view_proj * glm::vec4(points[i], 1.0f);
        if (c.w <= 0.0f) continue;  // behind the eye
        const glm::vec2 px((c.x / c.w * 0.5f + 0.5f) * width, (0.5f - c.y / c.w * 0.5f) * height);
        const float d = glm::length(px - cursor);
        if (d <= best_d) {
            best_d = d;
            best = i;
        }
    }
    return best;
}

uint64_t pickPrimitive(const Document& doc, const glm::mat4& view_proj, float width, float height,
                       glm::vec2 cursor, float max_px) {
    std::vector<glm::vec3> centres;
    std::vector<uint64_t> ids;
    for (size_t type = 0; type < doc.project().detail_types.size(); ++type)
        for (uint64_t id : doc.primitiveIds(type)) {
            Primitive prim;
            if (!doc.findPrimitive(id, nullptr, &prim)) continue;
            if (isTerrainKind(prim)) continue;
            centres.push_back(prim.center_m);
            ids.push_back(id);
        }
    const size_t best = nearestOnScreen(centres, view_proj, width, height, cursor, max_px);
    return best == SIZE_MAX ? 0 : ids[best];
}

}  // namespace ug::editor
