#include "particles/particle_json.h"

#include <cmath>
#include <filesystem>
#include <memory>
#include <set>
#include <string>

#include "core/atomic_file.h"
#include "mesh/mesh_loader.h"
#include "scene/json_parse.h"
#include "scene/json_reader.h"
#include "scene/material_json.h"

namespace ug {

namespace {

using nlohmann::json;

constexpr double kMaxCoordinate = double(kMaxParticleCoordinate_m);
constexpr size_t kMaxFileBytes = size_t(64) << 20;

bool readVec3(JsonReader& r, const json& obj, const std::string& p, const char* key, glm::vec3* out) {
    return r.vec3(obj, p, key, out, kMaxCoordinate);
}

// "kind": one of `names` (in enum order).
template <typename E, size_t N>
bool readKind(JsonReader& r, const json& obj, const std::string& p, const char* key, const char* const (&names)[N],
              E* out, bool required) {
    if (!obj.contains(key)) return !required || r.fail(p + "/" + key, "missing (required)");
    std::string s;
    if (!r.string(obj, p, key, &s)) return false;
    for (size_t i = 0; i < N; ++i)
        if (s == names[i]) {
            *out = E(i);
            return true;
        }
    std::string all;
    for (size_t i = 0; i < N; ++i) all += std::string(i ? ", " : "") + names[i];
    return r.fail(p + "/" + key, "'" + s + "' is not one of " + all);
}

const char* const kActionNames[] = {"stop", "kill", "split", "countdown", "turn"};
const char* const kChoiceNames[] = {"priority", "random"};
// countdown_then takes only the first two actions (StrandActionKind's Stop and Kill, in enum order).
const char* const kCountdownEndNames[] = {"stop", "kill"};
const char* const kGeneratorNames[] = {"rectangle", "sphere", "box", "mesh", "objects", "details"};
const char* const kAttractorNames[] = {"point", "segment", "sphere", "mesh", "objects"};
const char* const kCutterNames[] = {"plane", "sphere", "box"};
const char* const kSideNames[] = {"above", "below"};
const char* const kShapeNames[] = {"tube", "blade"};

const std::set<std::string> kActionKeys = {"kind", "split_count", "split_angle_deg", "countdown_steps",
                                           "countdown_then", "turn_angle_deg"};
const std::set<std::string> kTableActionKeys = {"kind", "split_count", "split_angle_deg", "countdown_steps",
                                                "countdown_then", "turn_angle_deg", "weight"};

// One action's own fields (and its weight, in a table).
bool readActionFields(JsonReader& r, const json& j, const std::string& at, bool in_table, StrandAction* out) {
    return r.expectObject(j, at) &&
           r.onlyKeys(j, at, in_table ? kTableActionKeys : kActionKeys) &&
           readKind(r, j, at, "kind", kActionNames, &out->kind, true) &&
           r.integer(j, at, "split_count", &out->split_count, 1, 16) &&
           r.number(j, at, "split_angle_deg", &out->split_angle_deg, 0.0, 179.9) &&
           r.integer(j, at, "countdown_steps", &out->countdown_steps, 1, kMaxParticleSteps) &&
           readKind(r, j, at, "countdown_then", kCountdownEndNames, &out->countdown_then, false) &&
           r.number(j, at, "turn_angle_deg", &out->turn_angle_deg, 1e-3, 180.0) &&
           r.number(j, at, "weight", &out->weight, 1e-6, 1e6);
}

// An action: {"kind": ..., fields} or a table {"choice": "priority" | "random", "table": [actions]}.
bool readAction(JsonReader& r, const json& obj, const std::string& p, const char* key, StrandAction* out) {
    auto it = obj.find(key);
    if (it == obj.end()) return true;
    const std::string at = p + "/" + key;
    if (!r.expectObject(*it, at)) return false;
    auto table = it->find("table");
    if (table == it->end()) return readActionFields(r, *it, at, false, out);
    if (!r.onlyKeys(*it, at, {"choice", "table"}) || !readKind(r, *it, at, "choice", kChoiceNames, &out->choice, false))
        return false;
    if (!table->is_array() || table->empty() || table->size() > kMaxActionTable)
        return r.fail(at + "/table", "expected 1 to 16 actions");
    out->table.assign(table->size(), StrandAction{});
    for (size_t i = 0; i < table->size(); ++i)
        if (!readActionFields(r, (*table)[i], at + "/table/" + std::to_string(i), true, &out->table[i])) return false;
    return true;
}

bool readGenerator(JsonReader& r, const json& j, const std::string& p, ParticleGenerator* g) {
    return r.expectObject(j, p) &&
           r.onlyKeys(j, p, {"kind", "center_m", "axis_u_m", "axis_v_m", "radius_m", "half_extents_m", "count",
                             "heading_cone_deg", "on_terrain", "mesh", "scale", "object_type", "max_height_m",
                             "sides_only", "detail_type", "min_normal_z"}) &&
           r.string(j, p, "detail_type", &g->detail_type) && r.number(j, p, "min_normal_z", &g->min_normal_z, -1.0, 1.0) &&
           r.boolean(j, p, "on_terrain", &g->on_terrain) && r.string(j, p, "mesh", &g->mesh_file) &&
           r.string(j, p, "object_type", &g->object_type) && r.boolean(j, p, "sides_only", &g->sides_only) &&
           r.number(j, p, "max_height_m", &g->max_height_m, 0.0, kMaxCoordinate) &&
           r.number(j, p, "scale", &g->scale, 1e-6, 1e4) &&
           readKind(r, j, p, "kind", kGeneratorNames, &g->kind, true) && readVec3(r, j, p, "center_m", &g->center_m) &&
           readVec3(r, j, p, "axis_u_m", &g->axis_u_m) && readVec3(r, j, p, "axis_v_m", &g->axis_v_m) &&
           r.number(j, p, "radius_m", &g->radius_m, 0.0, kMaxCoordinate) &&
           readVec3(r, j, p, "half_extents_m", &g->half_extents_m) && r.require(j, p, "count") &&
           r.integer(j, p, "count", &g->count, 1, kMaxParticles) &&
           r.number(j, p, "heading_cone_deg", &g->heading_cone_deg, 0.0, 179.9);
}

bool readCharge(JsonReader& r, const json& obj, const std::string& p, std::vector<ChargeKey>* out) {
    auto it = obj.find("charge");
    if (it == obj.end()) return true;
    const std::string at = p + "/charge";
    if (it->is_number()) {
        const double a = it->get<double>();
        if (!std::isfinite(a) || std::fabs(a) > 1e6) return r.fail(at, "not a finite charge within 1e6");
        *out = {ChargeKey{0, float(a)}};
        return true;
    }
    if (!it->is_array() || it->empty() || it->size() > 1024)
        return r.fail(at, "expected a number or 1 to 1024 [step, charge] keys");
    out->clear();
    for (size_t k = 0; k < it->size(); ++k) {
        const json& key = (*it)[k];
        const std::string kp = at + "/" + std::to_string(k);
        if (!key.is_array() || key.size() != 2 || !key[0].is_number_unsigned() || !key[1].is_number())
            return r.fail(kp, "expected [step, charge] with a whole step >= 0");
        const uint64_t step = key[0].get<uint64_t>();
        const double a = key[1].get<double>();
        if (step > kMaxParticleSteps) return r.fail(kp + "/0", "step beyond " + std::to_string(kMaxParticleSteps));
        if (!std::isfinite(a) || std::fabs(a) > 1e6) return r.fail(kp + "/1", "not a finite charge within 1e6");
        out->push_back(ChargeKey{uint32_t(step), float(a)});
    }
    return true;
}

// A mesh generator's or attractor's model (`file` as the particle file names it, relative to `source`),
// loaded into *mesh; `at` is its JSON Pointer. Parts of other kinds must not name one.
bool loadPartMesh(JsonReader& r, const std::string& at, const char* part, bool is_mesh, const std::string& file,
                  const std::string& source, std::shared_ptr<const TriangleMesh>* mesh) {
    if (!is_mesh) {
        if (!file.empty()) return r.fail(at, std::string("only a \"mesh\" ") + part + " takes a mesh");
        return true;
    }
    if (file.empty()) return r.fail(at, std::string("missing (a mesh ") + part + " needs a model file)");
    std::filesystem::path path(file);
    if (path.is_relative()) path = std::filesystem::path(source).parent_path() / path;
    auto loaded = std::make_shared<TriangleMesh>();
    std::string why;
    if (!loadMeshFile(path.lexically_normal().string(), loaded.get(), &why)) return r.fail(at, why);
    *mesh = std::move(loaded);
    return true;
}

bool readAttractor(JsonReader& r, const json& j, const std::string& p, Attractor* a) {
    return r.expectObject(j, p) &&
           r.onlyKeys(j, p, {"kind", "a_m", "b_m", "radius_m", "influence_m", "charge", "mesh", "scale", "points",
                             "object_type"}) &&
           readKind(r, j, p, "kind", kAttractorNames, &a->kind, true) && readVec3(r, j, p, "a_m", &a->a_m) &&
           r.string(j, p, "object_type", &a->object_type) &&
           r.string(j, p, "mesh", &a->mesh_file) && r.number(j, p, "scale", &a->scale, 1e-6, 1e4) &&
           r.integer(j, p, "points", &a->point_count, 1, kMaxAttractorPoints) &&
           readVec3(r, j, p, "b_m", &a->b_m) && r.number(j, p, "radius_m", &a->radius_m, 0.0, kMaxCoordinate) &&
           r.number(j, p, "influence_m", &a->influence_m, 0.0, kMaxCoordinate) && readCharge(r, j, p, &a->charge);
}

bool readCutter(JsonReader& r, const json& j, const std::string& p, Cutter* c) {
    return r.expectObject(j, p) &&
           r.onlyKeys(j, p, {"kind", "center_m", "normal", "radius_m", "half_extents_m", "threshold_m", "side",
                             "action"}) &&
           readKind(r, j, p, "kind", kCutterNames, &c->kind, true) && readVec3(r, j, p, "center_m", &c->center_m) &&
           readVec3(r, j, p, "normal", &c->normal) && r.number(j, p, "radius_m", &c->radius_m, 0.0, kMaxCoordinate) &&
           readVec3(r, j, p, "half_extents_m", &c->half_extents_m) &&
           r.number(j, p, "threshold_m", &c->threshold_m, -kMaxCoordinate, kMaxCoordinate) &&
           readKind(r, j, p, "side", kSideNames, &c->side, false) && readAction(r, j, p, "action", &c->action);
}

bool readWalk(JsonReader& r, const json& obj, const std::string& pointer, WalkSettings* w) {
    auto it = obj.find("walk");
    if (it == obj.end()) return true;
    const json& j = *it;
    const std::string p = pointer + "/walk";
    return r.expectObject(j, p) &&
           r.onlyKeys(j, p, {"seed", "steps", "trials", "cone_deg", "step_length_m", "strand_radius_m", "collisions",
                             "on_collision", "max_age_steps", "on_age", "max_split_depth", "max_points", "solids",
                             "keep_distance_m", "on_distance", "retry_refused"}) &&
           r.integer(j, p, "seed", &w->seed, 0, UINT64_MAX) && r.integer(j, p, "steps", &w->steps, 1, kMaxParticleSteps) &&
           r.integer(j, p, "trials", &w->trials, 1, 256) && r.number(j, p, "cone_deg", &w->cone_deg, 0.001, 179.9) &&
           r.number(j, p, "step_length_m", &w->step_length_m, 1e-6, 1e3) &&
           r.number(j, p, "strand_radius_m", &w->strand_radius_m, 1e-7, 1e2) &&
           r.boolean(j, p, "collisions", &w->collisions) && readAction(r, j, p, "on_collision", &w->on_collision) &&
           r.integer(j, p, "max_age_steps", &w->max_age_steps, 0, kMaxParticleSteps) &&
           readAction(r, j, p, "on_age", &w->on_age) && r.integer(j, p, "max_split_depth", &w->max_split_depth, 0, 64) &&
           r.integer(j, p, "max_points", &w->max_points, 1, kMaxStrandPoints) && r.boolean(j, p, "solids", &w->solids) &&
           r.number(j, p, "keep_distance_m", &w->keep_distance_m, 0.0, 1e5) &&
           readAction(r, j, p, "on_distance", &w->on_distance) && r.boolean(j, p, "retry_refused", &w->retry_refused);
}

template <typename T, typename F>
bool readList(JsonReader& r, const json& obj, const char* key, size_t max, std::vector<T>* out, F&& read_one) {
    auto it = obj.find(key);
    if (it == obj.end()) return true;
    const std::string p = std::string("/") + key;
    if (!r.expectArray(*it, p)) return false;
    if (it->size() > max) return r.fail(p, std::to_string(it->size()) + " entries, at most " + std::to_string(max));
    out->assign(it->size(), T{});
    for (size_t i = 0; i < it->size(); ++i)
        if (!read_one(r, (*it)[i], p + "/" + std::to_string(i), &(*out)[i])) return false;
    return true;
}

json vec3Json(glm::vec3 v) { return {v.x, v.y, v.z}; }

json actionJson(const StrandAction& a, bool in_table = false) {
    if (!a.table.empty()) {
        json table = json::array();
        for (const StrandAction& t : a.table) table.push_back(actionJson(t, true));
        return {{"choice", kChoiceNames[size_t(a.choice)]}, {"table", table}};
    }
    json j = {{"kind", kActionNames[size_t(a.kind)]},
              {"split_count", a.split_count},
              {"split_angle_deg", a.split_angle_deg},
              {"countdown_steps", a.countdown_steps},
              {"countdown_then", kActionNames[size_t(a.countdown_then)]},
              {"turn_angle_deg", a.turn_angle_deg}};
    if (in_table) j["weight"] = a.weight;
    return j;
}

}  // namespace

bool parseParticleSystem(const json& j, const std::string& source, ParticleSystemFile* out, std::string* error) {
    JsonReader r(source, error);
    ParticleSystemFile s;
    std::string format;
    uint32_t version = 0;
    if (!r.expectObject(j, "") ||
        !r.onlyKeys(j, "", {"format", "format_version", "name", "generators", "attractors", "cutters", "walk", "mesh",
                            "material"}) ||
        !r.string(j, "", "format", &format, true))
        return false;
    if (format != "undergrowth-particles") return r.fail("/format", "expected \"undergrowth-particles\"");
    if (!r.require(j, "", "format_version") || !r.integer(j, "", "format_version", &version, 1, 1) ||
        !r.string(j, "", "name", &s.name) ||
        !readList(r, j, "generators", 64, &s.scene.generators, readGenerator) ||
        !readList(r, j, "attractors", 1024, &s.scene.attractors, readAttractor) ||
        !readList(r, j, "cutters", kMaxCutters, &s.scene.cutters, readCutter) || !readWalk(r, j, "", &s.scene.walk))
        return false;
    if (auto it = j.find("mesh"); it != j.end()) {
        if (!r.expectObject(*it, "/mesh") ||
            !r.onlyKeys(*it, "/mesh", {"shape", "sides", "max_triangles", "blade_width_m", "blade_tip"}) ||
            !readKind(r, *it, "/mesh", "shape", kShapeNames, &s.mesh.shape, false) ||
            !r.number(*it, "/mesh", "blade_width_m", &s.mesh.blade_width_m, 0.0, 10.0) ||
            !r.number(*it, "/mesh", "blade_tip", &s.mesh.blade_tip, 0.0, 1.0) ||
            !r.integer(*it, "/mesh", "sides", &s.mesh.sides, 3, 32) ||
            !r.integer(*it, "/mesh", "max_triangles", &s.mesh.max_triangles, 1, 200'000'000))
            return false;
    }
    if (auto it = j.find("material"); it != j.end() && !readMaterial(r, *it, "/material", &s.material)) return false;
    if (s.scene.generators.empty()) return r.fail("/generators", "at least one generator is needed");
    // Mesh generators' and mesh attractors' models, relative to the particle file; the attractors' points.
    for (size_t i = 0; i < s.scene.generators.size(); ++i) {
        ParticleGenerator& g = s.scene.generators[i];
        if (!loadPartMesh(r, "/generators/" + std::to_string(i) + "/mesh", "generator", g.kind == GeneratorKind::Mesh,
                          g.mesh_file, source, &g.mesh))
            return false;
        if (g.kind != GeneratorKind::Objects && !g.object_type.empty())
            return r.fail("/generators/" + std::to_string(i) + "/object_type", "only an \"objects\" generator takes one");
        if (g.kind != GeneratorKind::Details && !g.detail_type.empty())
            return r.fail("/generators/" + std::to_string(i) + "/detail_type", "only a \"details\" generator takes one");
    }
    for (size_t i = 0; i < s.scene.attractors.size(); ++i) {
        Attractor& a = s.scene.attractors[i];
        const std::string at = "/attractors/" + std::to_string(i) + "/mesh";
        if (!loadPartMesh(r, at, "attractor", a.kind == AttractorKind::Mesh, a.mesh_file, source, &a.mesh))
            return false;
        if (a.kind != AttractorKind::Objects && !a.object_type.empty())
            return r.fail("/attractors/" + std::to_string(i) + "/object_type", "only an \"objects\" attractor takes one");
        if (!a.mesh) continue;
        double area = 0.0;
        for (size_t t = 0; t < a.mesh->triangleCount(); ++t) area += meshTriangleArea(*a.mesh, t);
        if (!(area > 0.0)) return r.fail(at, "the mesh has no area to take points on");
        a.points = meshAttractorPoints(a.mesh, a.point_count);
    }
    std::string why;
    if (!validateParticleScene(s.scene, &why)) return r.fail("", why);
    *out = std::move(s);
    return true;
}

bool loadParticleSystem(const std::string& path, ParticleSystemFile* out, std::string* error) {
    std::string text;
    if (!readTextFile(path, &text, error, kMaxFileBytes)) return false;
    json j;
    if (!parseJsonText(text, path, &j, error)) return false;
    if (!parseParticleSystem(j, path, out, error)) return false;
    if (out->name.empty()) out->name = std::filesystem::path(path).stem().string();
    out->file_name = out->name;
    return true;
}

json particleSystemToJson(const ParticleSystemFile& s) {
    json generators = json::array(), attractors = json::array(), cutters = json::array();
    for (const ParticleGenerator& g : s.scene.generators) {
        json gj = {{"kind", kGeneratorNames[size_t(g.kind)]},
                   {"center_m", vec3Json(g.center_m)},
                   {"axis_u_m", vec3Json(g.axis_u_m)},
                   {"axis_v_m", vec3Json(g.axis_v_m)},
                   {"radius_m", g.radius_m},
                   {"half_extents_m", vec3Json(g.half_extents_m)},
                   {"count", g.count},
                   {"heading_cone_deg", g.heading_cone_deg},
                   {"on_terrain", g.on_terrain}};
        if (g.kind == GeneratorKind::Mesh) {
            gj["mesh"] = g.mesh_file;
            gj["scale"] = g.scale;
        }
        if (g.kind == GeneratorKind::Objects) {
            gj["object_type"] = g.object_type;
            gj["max_height_m"] = g.max_height_m;
            gj["sides_only"] = g.sides_only;
        }
        if (g.kind == GeneratorKind::Details) {
            gj["detail_type"] = g.detail_type;
            gj["min_normal_z"] = g.min_normal_z;
        }
        generators.push_back(std::move(gj));
    }
    for (const Attractor& a : s.scene.attractors) {
        json charge = json::array();
        for (const ChargeKey& k : a.charge) charge.push_back({k.step, k.charge});
        json aj = {{"kind", kAttractorNames[size_t(a.kind)]},
                   {"a_m", vec3Json(a.a_m)},
                   {"b_m", vec3Json(a.b_m)},
                   {"radius_m", a.radius_m},
                   {"influence_m", a.influence_m},
                   {"charge", charge}};
        if (a.kind == AttractorKind::Mesh) {
            aj["mesh"] = a.mesh_file;
            aj["scale"] = a.scale;
            aj["points"] = a.point_count;
        }
        if (a.kind == AttractorKind::Objects) {
            aj["object_type"] = a.object_type;
            aj["points"] = a.point_count;
        }
        attractors.push_back(std::move(aj));
    }
    for (const Cutter& c : s.scene.cutters)
        cutters.push_back({{"kind", kCutterNames[size_t(c.kind)]},
                           {"center_m", vec3Json(c.center_m)},
                           {"normal", vec3Json(c.normal)},
                           {"radius_m", c.radius_m},
                           {"half_extents_m", vec3Json(c.half_extents_m)},
                           {"threshold_m", c.threshold_m},
                           {"side", kSideNames[size_t(c.side)]},
                           {"action", actionJson(c.action)}});
    const WalkSettings& w = s.scene.walk;
    return {{"format", "undergrowth-particles"},
            {"format_version", 1u},
            {"name", s.name},
            {"generators", generators},
            {"attractors", attractors},
            {"cutters", cutters},
            {"walk",
             {{"seed", w.seed},
              {"steps", w.steps},
              {"trials", w.trials},
              {"cone_deg", w.cone_deg},
              {"step_length_m", w.step_length_m},
              {"strand_radius_m", w.strand_radius_m},
              {"collisions", w.collisions},
              {"on_collision", actionJson(w.on_collision)},
              {"max_age_steps", w.max_age_steps},
              {"on_age", actionJson(w.on_age)},
              {"max_split_depth", w.max_split_depth},
              {"max_points", w.max_points},
              {"solids", w.solids},
              {"keep_distance_m", w.keep_distance_m},
              {"on_distance", actionJson(w.on_distance)},
              {"retry_refused", w.retry_refused}}},
            {"mesh", {{"shape", kShapeNames[size_t(s.mesh.shape)]},
                      {"sides", s.mesh.sides},
                      {"max_triangles", s.mesh.max_triangles},
                      {"blade_width_m", s.mesh.blade_width_m},
                      {"blade_tip", s.mesh.blade_tip}}},
            {"material", materialToJson(s.material)}};
}

}  // namespace ug
