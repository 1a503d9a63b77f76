#include "scene/project.h"

#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "scene/json_reader.h"

namespace ug {

namespace {

using nlohmann::json;

const char* anchorModeName(AnchorMode m) {
    switch (m) {
        case AnchorMode::Authored: return "authored";
        case AnchorMode::Center: return "center";
        case AnchorMode::SphereCenters: return "sphere_centers";
        case AnchorMode::Surface: return "surface";
    }
    return "sphere_centers";
}

bool readVec3(JsonReader& r, const json& j, const std::string& p, glm::vec3* out) {
    if (!j.is_array() || j.size() != 3) return r.fail(p, "expected [x, y, z]");
    for (int a = 0; a < 3; ++a) {
        if (!j[a].is_number() || !std::isfinite(j[a].get<double>())) return r.fail(p + "/" + std::to_string(a), "expected a finite number");
        (*out)[a] = j[a].get<float>();
    }
    return true;
}

bool readModel(JsonReader& r, const json& j, const std::string& p, DetailModelSource* m) {
    if (!r.expectObject(j, p) || !r.onlyKeys(j, p, {"mesh", "scale", "y_up", "spheres", "anchors"})) return false;
    if (!r.string(j, p, "mesh", &m->mesh_path, true) || !r.number(j, p, "scale", &m->scale, 1e-6, 1e6) ||
        !r.boolean(j, p, "y_up", &m->y_up))
        return false;
    if (auto it = j.find("spheres"); it != j.end()) {
        const std::string sp = p + "/spheres";
        if (it->is_array()) {
            for (size_t k = 0; k < it->size(); ++k) {
                const json& s = (*it)[k];
                const std::string kp = sp + "/" + std::to_string(k);
                if (!s.is_array() || s.size() != 4) return r.fail(kp, "expected [x, y, z, radius]");
                Sphere sphere;
                if (!readVec3(r, json::array({s[0], s[1], s[2]}), kp, &sphere.center)) return false;
                if (!s[3].is_number() || !(s[3].get<double>() > 0.0) || !std::isfinite(s[3].get<double>()))
                    return r.fail(kp + "/3", "radius must be a finite number > 0");
                sphere.radius = s[3].get<float>();
                m->authored_spheres.push_back(sphere);
            }
        } else {
            if (!r.expectObject(*it, sp) ||
                !r.onlyKeys(*it, sp, {"max_spheres", "tolerance_m", "tolerance_rel", "surface_samples", "seed"}) ||
                !r.integer(*it, sp, "max_spheres", &m->fit.max_spheres, 1, 4096) ||
                !r.number(*it, sp, "tolerance_m", &m->fit.tolerance_m, 0.0, 10.0) ||
                !r.number(*it, sp, "tolerance_rel", &m->fit.tolerance_rel, 1e-4, 1.0) ||
                !r.integer(*it, sp, "surface_samples", &m->fit.surface_samples, 16, 1000000) ||
                !r.integer(*it, sp, "seed", &m->fit.seed, 0, UINT64_MAX))
                return false;
        }
    }
    if (auto it = j.find("anchors"); it != j.end()) {
        const std::string ap = p + "/anchors";
        if (!r.expectObject(*it, ap) || !r.onlyKeys(*it, ap, {"mode", "count", "points"})) return false;
        std::string mode = anchorModeName(m->anchor_mode);
        if (!r.string(*it, ap, "mode", &mode)) return false;
        if (mode == "authored") m->anchor_mode = AnchorMode::Authored;
        else if (mode == "center") m->anchor_mode = AnchorMode::Center;
        else if (mode == "sphere_centers") m->anchor_mode = AnchorMode::SphereCenters;
        else if (mode == "surface") m->anchor_mode = AnchorMode::Surface;
        else return r.fail(ap + "/mode", "unknown anchor mode '" + mode + "' (authored, center, sphere_centers, surface)");
        if (!r.integer(*it, ap, "count", &m->anchor_count, 1, 4096)) return false;
        if (auto pts = it->find("points"); pts != it->end()) {
            if (!r.expectArray(*pts, ap + "/points")) return false;
            for (size_t k = 0; k < pts->size(); ++k) {
                glm::vec3 v;
                if (!readVec3(r, (*pts)[k], ap + "/points/" + std::to_string(k), &v)) return false;
                m->authored_anchors.push_back(v);
            }
        }
        if (m->anchor_mode == AnchorMode::Authored && m->authored_anchors.empty())
            return r.fail(ap + "/points", "mode 'authored' needs at least one point");
    }
    return true;
}

bool readCandidates(JsonReader& r, const json& j, const std::string& p, DetailTypeSettings* d) {
    if (!r.expectObject(j, p) || !r.onlyKeys(j, p, {"count", "orientation", "scale", "position"})) return false;
    if (!r.integer(j, p, "count", &d->candidate_count, 1, kMaxCandidatesPerTile)) return false;
    if (auto it = j.find("scale"); it != j.end()) {
        if (!it->is_array() || it->size() != 2 || !(*it)[0].is_number() || !(*it)[1].is_number())
            return r.fail(p + "/scale", "expected [min, max]");
        double lo = (*it)[0].get<double>(), hi = (*it)[1].get<double>();
        if (!(lo > 0.0) || !(hi >= lo) || hi > 100.0)
            return r.fail(p + "/scale", "expected [min, max] with 0 < min <= max <= 100");
        d->scale_min = float(lo);
        d->scale_max = float(hi);
    }
    std::string position = d->position == PositionMode::Jittered ? "jittered" : "uniform";
    if (!r.string(j, p, "position", &position)) return false;
    if (position == "uniform") d->position = PositionMode::Uniform;
    else if (position == "jittered") d->position = PositionMode::Jittered;
    else return r.fail(p + "/position", "unknown position mode '" + position + "' (uniform, jittered)");
    if (auto it = j.find("orientation"); it != j.end()) {
        const std::string op = p + "/orientation";
        if (!r.expectObject(*it, op) || !r.onlyKeys(*it, op, {"mode", "tilt_ranges"})) return false;
        std::string mode = "uniform";
        if (!r.string(*it, op, "mode", &mode)) return false;
        if (mode == "uniform") {
            d->orientation.mode = OrientationMode::UniformRandom;
        } else if (mode == "tilt") {
            d->orientation.mode = OrientationMode::Tilt;
            auto ranges = it->find("tilt_ranges");
            if (ranges == it->end() || !ranges->is_array() || ranges->empty())
                return r.fail(op + "/tilt_ranges", "mode 'tilt' needs a non-empty list of [min_deg, max_deg, weight]");
            for (size_t k = 0; k < ranges->size(); ++k) {
                const json& t = (*ranges)[k];
                const std::string kp = op + "/tilt_ranges/" + std::to_string(k);
                if (!t.is_array() || t.size() != 3 || !t[0].is_number() || !t[1].is_number() || !t[2].is_number())
                    return r.fail(kp, "expected [min_deg, max_deg, weight]");
                TiltRange tr{t[0].get<float>(), t[1].get<float>(), t[2].get<float>()};
                if (!(tr.min_deg >= 0.0f) || !(tr.max_deg <= 180.0f) || !(tr.min_deg <= tr.max_deg) || !(tr.weight > 0.0f))
                    return r.fail(kp, "needs 0 <= min_deg <= max_deg <= 180 and weight > 0");
                d->orientation.tilt_ranges.push_back(tr);
            }
        } else {
            return r.fail(op + "/mode", "unknown orientation mode '" + mode + "' (uniform, tilt)");
        }
    }
    return true;
}

}  // namespace

bool parseProject(const std::string& text, const std::string& source_name, Project* out, std::string* error) {
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::parse_error& e) {
        // nlohmann's message already carries "line L, column C".
        *error = source_name + ": invalid JSON: " + e.what();
        return false;
    }
    JsonReader r(source_name, error);
    if (!r.expectObject(doc, "") ||
        !r.onlyKeys(doc, "", {"format", "format_version", "name", "ghost_tile", "detail_types"}))
        return false;
    std::string format;
    if (!r.string(doc, "", "format", &format, true)) return false;
    if (format != "undergrowth-project") return r.fail("/format", "expected \"undergrowth-project\", got \"" + format + "\"");
    int version = 0;
    if (!r.require(doc, "", "format_version") || !r.integer(doc, "", "format_version", &version, 1, 1000000))
        return false;
    if (version > kProjectFormatVersion)
        return r.fail("/format_version", "version " + std::to_string(version) + " is newer than this program reads (" +
                                             std::to_string(kProjectFormatVersion) + "); update Undergrowth");
    Project p;
    if (!r.string(doc, "", "name", &p.name)) return false;
    if (auto it = doc.find("ghost_tile"); it != doc.end()) {
        if (!r.expectObject(*it, "/ghost_tile") || !r.onlyKeys(*it, "/ghost_tile", {"tile_size_m", "delta_m", "seed"}) ||
            !r.number(*it, "/ghost_tile", "tile_size_m", &p.ghost_tile.tile_size_m, 1e-4, 1000.0) ||
            !r.number(*it, "/ghost_tile", "delta_m", &p.ghost_tile.delta_m, -10.0, 10.0) ||
            !r.integer(*it, "/ghost_tile", "seed", &p.ghost_tile.seed, 0, UINT64_MAX))
            return false;
    }
    if (!r.require(doc, "", "detail_types")) return false;
    const json& types = doc["detail_types"];
    if (!r.expectArray(types, "/detail_types")) return false;
    if (types.empty()) return r.fail("/detail_types", "at least one detail type is needed");
    for (size_t t = 0; t < types.size(); ++t) {
        const std::string tp = "/detail_types/" + std::to_string(t);
        const json& jt = types[t];
        if (!r.expectObject(jt, tp) || !r.onlyKeys(jt, tp, {"name", "model", "candidates"})) return false;
        DetailTypeDesc d;
        if (!r.string(jt, tp, "name", &d.model.name, true)) return false;
        if (d.model.name.empty()) return r.fail(tp + "/name", "must not be empty");
        for (const DetailTypeDesc& other : p.detail_types)
            if (other.model.name == d.model.name) return r.fail(tp + "/name", "duplicate detail type '" + d.model.name + "'");
        if (!r.require(jt, tp, "model") || !readModel(r, jt["model"], tp + "/model", &d.model)) return false;
        d.ghost.name = d.model.name;
        if (auto it = jt.find("candidates"); it != jt.end() && !readCandidates(r, *it, tp + "/candidates", &d.ghost))
            return false;
        p.detail_types.push_back(std::move(d));
    }
    *out = std::move(p);
    return true;
}

bool loadProject(const std::string& path, Project* out, std::string* error) {
    std::string text;
    if (!readTextFile(path, &text, error)) return false;
    if (!parseProject(text, path, out, error)) return false;
    out->base_dir = std::filesystem::path(path).parent_path().string();
    return true;
}

std::string projectToJson(const Project& project) {
    json doc;
    doc["format"] = "undergrowth-project";
    doc["format_version"] = kProjectFormatVersion;
    doc["name"] = project.name;
    doc["ghost_tile"] = {{"tile_size_m", project.ghost_tile.tile_size_m},
                         {"delta_m", project.ghost_tile.delta_m},
                         {"seed", project.ghost_tile.seed}};
    json types = json::array();
    for (const DetailTypeDesc& d : project.detail_types) {
        json model = {{"mesh", d.model.mesh_path}, {"scale", d.model.scale}, {"y_up", d.model.y_up}};
        if (!d.model.authored_spheres.empty()) {
            json spheres = json::array();
            for (const Sphere& s : d.model.authored_spheres)
                spheres.push_back({s.center.x, s.center.y, s.center.z, s.radius});
            model["spheres"] = spheres;
        } else {
            model["spheres"] = {{"max_spheres", d.model.fit.max_spheres},
                                {"tolerance_m", d.model.fit.tolerance_m},
                                {"tolerance_rel", d.model.fit.tolerance_rel},
                                {"surface_samples", d.model.fit.surface_samples},
                                {"seed", d.model.fit.seed}};
        }
        json anchors = {{"mode", anchorModeName(d.model.anchor_mode)}, {"count", d.model.anchor_count}};
        if (!d.model.authored_anchors.empty()) {
            json pts = json::array();
            for (const glm::vec3& a : d.model.authored_anchors) pts.push_back({a.x, a.y, a.z});
            anchors["points"] = pts;
        }
        model["anchors"] = anchors;
        json orientation = {{"mode", d.ghost.orientation.mode == OrientationMode::Tilt ? "tilt" : "uniform"}};
        if (d.ghost.orientation.mode == OrientationMode::Tilt) {
            json ranges = json::array();
            for (const TiltRange& tr : d.ghost.orientation.tilt_ranges) ranges.push_back({tr.min_deg, tr.max_deg, tr.weight});
            orientation["tilt_ranges"] = ranges;
        }
        types.push_back({{"name", d.model.name},
                         {"model", model},
                         {"candidates",
                          {{"count", d.ghost.candidate_count},
                           {"orientation", orientation},
                           {"scale", {d.ghost.scale_min, d.ghost.scale_max}},
                           {"position", d.ghost.position == PositionMode::Jittered ? "jittered" : "uniform"}}}});
    }
    doc["detail_types"] = types;
    return doc.dump(2) + "\n";
}

bool saveProject(const std::string& path, const Project& project, std::string* error) {
    return writeTextFileAtomically(path, projectToJson(project), error);
}

std::string resolveProjectPath(const Project& project, const std::string& path) {
    std::filesystem::path p(path);
    if (p.is_absolute() || project.base_dir.empty()) return path;
    return (std::filesystem::path(project.base_dir) / p).lexically_normal().string();
}

bool loadProjectModels(const Project& project, std::vector<DetailModel>* models, std::string* error) {
    models->clear();
    models->resize(project.detail_types.size());
    for (size_t t = 0; t < project.detail_types.size(); ++t) {
        DetailModelSource source = project.detail_types[t].model;
        source.mesh_path = resolveProjectPath(project, source.mesh_path);
        std::string model_error;
        if (!loadDetailModel(source, &(*models)[t], &model_error)) {
            *error = "detail type '" + source.name + "': " + model_error;
            return false;
        }
    }
    return true;
}

GhostTileInput ghostTileInput(const Project& project, const std::vector<DetailModel>& models) {
    GhostTileInput input;
    input.settings = project.ghost_tile;
    for (size_t t = 0; t < project.detail_types.size(); ++t) {
        input.types.push_back(project.detail_types[t].ghost);
        input.models.push_back(t < models.size() ? &models[t] : nullptr);
    }
    return input;
}

}  // namespace ug
