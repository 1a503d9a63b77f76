#include "scene/project.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "env/env_json.h"
#include "scene/field_json.h"
#include "scene/json_parse.h"
#include "scene/json_reader.h"
#include "scene/material_json.h"

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

// Fixed-size arrays of finite numbers; finite as floats too (1e300 is a finite double but not a float).
template <int N>
bool readFloats(JsonReader& r, const json& j, const std::string& p, float* out, const char* shape) {
    if (!j.is_array() || j.size() != size_t(N)) return r.fail(p, std::string("expected ") + shape);
    for (int a = 0; a < N; ++a) {
        if (!j[a].is_number() || !std::isfinite(j[a].get<float>()))
            return r.fail(p + "/" + std::to_string(a), "expected a finite number");
        out[a] = j[a].get<float>();
    }
    return true;
}

bool readVec3(JsonReader& r, const json& j, const std::string& p, glm::vec3* out) {
    return readFloats<3>(r, j, p, &out->x, "[x, y, z]");
}

bool readVec2(JsonReader& r, const json& j, const std::string& p, glm::vec2* out) {
    return readFloats<2>(r, j, p, &out->x, "[x, y]");
}

std::string fmt(double v) {
    char buf[48];
    std::snprintf(buf, sizeof(buf), "%g", v);
    return buf;
}

// An optional number > 0 (and <= hi); absent keeps *out.
bool positiveNumber(JsonReader& r, const json& obj, const std::string& p, const char* key, float* out,
                    double hi) {
    if (!r.number(obj, p, key, out, 0.0, hi)) return false;
    return *out > 0.0f || r.fail(p + "/" + key, "must be > 0");
}

// Keys of this object valid in the file's format version; a key only a newer version knows is named as
// such, so an old file edited by hand gets told what to change rather than "unknown field".
// "particles": [{"file": "grass.json", "name": "grass_a", "offset_m": [x, y, z]}, ...]; the files are read
// when the scene loads (scene/scene_particles.h), so that an error there names this entry too.
bool readParticleRefs(JsonReader& r, const json& j, const std::string& p, std::vector<ParticleSystemRef>* out) {
    if (!r.expectArray(j, p)) return false;
    if (j.size() > kMaxParticleSystems)
        return r.fail(p, std::to_string(j.size()) + " particle systems; at most " + std::to_string(kMaxParticleSystems));
    out->clear();
    for (size_t i = 0; i < j.size(); ++i) {
        const std::string ip = p + "/" + std::to_string(i);
        ParticleSystemRef ref;
        if (!r.expectObject(j[i], ip) || !r.onlyKeys(j[i], ip, {"file", "name", "offset_m"}) ||
            !r.string(j[i], ip, "file", &ref.file, true) || !r.string(j[i], ip, "name", &ref.name) ||
            // The particle files' own coordinate limit (particle_scene.h, kMaxParticleCoordinate_m).
            !r.vec3(j[i], ip, "offset_m", &ref.offset_m, 1.0e5))
            return false;
        if (ref.file.empty()) return r.fail(ip + "/file", "expected a particle system file, got \"\"");
        out->push_back(std::move(ref));
    }
    return true;
}

bool versionedKeys(JsonReader& r, const json& j, const std::string& p, int version,
                   const std::set<std::string>& v1_keys, const std::set<std::string>& v2_keys,
                   const std::set<std::string>& v3_keys = {}, const std::set<std::string>& v4_keys = {}) {
    for (auto it = j.begin(); it != j.end(); ++it) {
        if (v1_keys.count(it.key())) continue;
        const int needs = v2_keys.count(it.key())   ? 2
                          : v3_keys.count(it.key()) ? 3
                          : v4_keys.count(it.key()) ? 4
                                                    : 0;
        if (needs > 0) {
            if (version >= needs) continue;
            return r.fail(p + "/" + it.key(), "needs format_version " + std::to_string(needs) + " (this file says " +
                                                  std::to_string(version) + ")");
        }
        return r.fail(p + "/" + it.key(), "unknown field");
    }
    return true;
}

bool readTerrain(JsonReader& r, const json& j, const std::string& p, TerrainDesc* t) {
    if (!r.expectObject(j, p)) return false;
    const size_t shapes = j.size() - (j.contains("material") ? 1 : 0);
    if (shapes != 1 || !(j.contains("procedural") || j.contains("image")))
        return r.fail(p, "expected {\"procedural\": {...}} or {\"image\": {...}}, and optionally \"material\"");
    if (auto m = j.find("material"); m != j.end() && !readMaterial(r, *m, p + "/material", &t->material))
        return false;
    if (auto it = j.find("procedural"); it != j.end()) {
        const std::string pp = p + "/procedural";
        ProceduralTerrainDesc& d = t->procedural;
        if (!r.expectObject(*it, pp) ||
            !r.onlyKeys(*it, pp,
                        {"origin", "cell_size_m", "width", "height", "seed", "octaves", "base_height_m",
                         "amplitude_m", "feature_size_m", "lacunarity", "gain"}))
            return false;
        if (auto o = it->find("origin"); o != it->end() && !readVec2(r, *o, pp + "/origin", &d.origin_m))
            return false;
        if (!positiveNumber(r, *it, pp, "cell_size_m", &d.cell_size_m, 1e4) ||
            !r.integer(*it, pp, "width", &d.width, kMinTerrainSide, kMaxHeightFieldSide) ||
            !r.integer(*it, pp, "height", &d.height, kMinTerrainSide, kMaxHeightFieldSide) ||
            !r.integer(*it, pp, "seed", &d.seed, 0, UINT64_MAX) ||
            !r.integer(*it, pp, "octaves", &d.octaves, 1, 16) ||
            !r.number(*it, pp, "base_height_m", &d.base_height_m, -1e6, 1e6) ||
            !r.number(*it, pp, "amplitude_m", &d.amplitude_m, 0.0, 1e6) ||
            !positiveNumber(r, *it, pp, "feature_size_m", &d.feature_size_m, 1e7) ||
            !positiveNumber(r, *it, pp, "lacunarity", &d.lacunarity, 1e3) ||
            !positiveNumber(r, *it, pp, "gain", &d.gain, 1.0))
            return false;
        // Refused here, before anything is loaded: the grid's samples are computed (and held) one by one.
        if (uint64_t(d.width) * uint64_t(d.height) > kMaxHeightFieldSamples)
            return r.fail(pp + "/width", std::to_string(d.width) + "x" + std::to_string(d.height) +
                                             " samples exceed the limit of " +
                                             std::to_string(kMaxHeightFieldSamples) + " samples per terrain");
        t->kind = TerrainKind::Procedural;
        return true;
    }
    const json& im = j["image"];
    const std::string ip = p + "/image";
    HeightFieldImageDesc& d = t->image;
    if (!r.expectObject(im, ip) ||
        !r.onlyKeys(im, ip, {"path", "origin", "cell_size_m", "min_height_m", "max_height_m"}) ||
        !r.string(im, ip, "path", &t->image_path, true))
        return false;
    if (t->image_path.empty()) return r.fail(ip + "/path", "must not be empty");
    if (auto o = im.find("origin"); o != im.end() && !readVec2(r, *o, ip + "/origin", &d.origin_m))
        return false;
    if (!positiveNumber(r, im, ip, "cell_size_m", &d.cell_size_m, 1e4) ||
        !r.number(im, ip, "min_height_m", &d.min_height_m, -1e6, 1e6) ||
        !r.number(im, ip, "max_height_m", &d.max_height_m, -1e6, 1e6))
        return false;
    if (!(d.min_height_m <= d.max_height_m))
        return r.fail(ip + "/max_height_m", "must be >= min_height_m (" + fmt(d.min_height_m) + ")");
    t->kind = TerrainKind::Image;
    return true;
}

bool readExtent(JsonReader& r, const json& j, const std::string& p, Bounds* out) {
    if (!r.expectObject(j, p) || !r.onlyKeys(j, p, {"min", "max"}) || !r.require(j, p, "min") ||
        !r.require(j, p, "max") || !readVec3(r, j["min"], p + "/min", &out->lo) ||
        !readVec3(r, j["max"], p + "/max", &out->hi))
        return false;
    for (int a = 0; a < 3; ++a)
        if (!(out->lo[a] < out->hi[a]))
            return r.fail(p, std::string("min must be < max on every axis (") + "xyz"[a] + ": " +
                                 fmt(out->lo[a]) + " >= " + fmt(out->hi[a]) + ")");
    return true;
}

bool readInstancing(JsonReader& r, const json& j, const std::string& p, bool has_terrain, InstancingDesc* d) {
    if (!r.expectObject(j, p) || !r.onlyKeys(j, p, {"strategy", "layer_m", "orientation", "size"}))
        return false;
    std::string strategy = priorityStrategyName(d->strategy);
    if (!r.string(j, p, "strategy", &strategy)) return false;
    if (strategy == "random")
        d->strategy = PriorityStrategy::Random;
    else if (strategy == "elevation")
        d->strategy = PriorityStrategy::Elevation;
    else if (strategy == "distance_to_boundary")
        d->strategy = PriorityStrategy::DistanceToBoundary;
    else
        return r.fail(p + "/strategy",
                      "unknown strategy '" + strategy + "' (random, elevation, distance_to_boundary)");
    if (!positiveNumber(r, j, p, "layer_m", &d->layer_m, 1e3)) return false;

    if (auto it = j.find("orientation"); it != j.end()) {
        const std::string op = p + "/orientation";
        OrientationDesc& o = d->orientation;
        if (!r.expectObject(*it, op) || !r.onlyKeys(*it, op, {"direction", "max_angle_deg"})) return false;
        o.enabled = true;
        if (auto dir = it->find("direction"); dir != it->end()) {
            const std::string dp = op + "/direction";
            if (dir->is_string()) {
                if (dir->get<std::string>() != "gradient")
                    return r.fail(dp, "unknown direction '" + dir->get<std::string>() +
                                          "' (expected [x, y, z] or \"gradient\")");
                o.kind = DirectionFieldKind::Gradient;
            } else {
                if (!dir->is_array())
                    return r.fail(dp,
                                  "expected [x, y, z] or \"gradient\", got " + JsonReader::typeName(*dir));
                glm::vec3 v;
                if (!readVec3(r, *dir, dp, &v)) return false;
                if (v == glm::vec3(0.0f)) return r.fail(dp, "must not be zero");
                v = documentUnitVector(v);
                if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
                    return r.fail(dp, "too large to normalize");
                o.kind = DirectionFieldKind::Constant;
                o.direction = v;
            }
        }
        if (!r.number(*it, op, "max_angle_deg", &o.max_angle_deg, 0.0, 180.0)) return false;
    }

    if (auto it = j.find("size"); it != j.end()) {
        const std::string sp = p + "/size";
        SizeDesc& s = d->size;
        if (!r.expectObject(*it, sp) || !r.onlyKeys(*it, sp, {"target", "tolerance"}) ||
            !r.require(*it, sp, "target"))
            return false;
        s.enabled = true;
        const json& target = (*it)["target"];
        const std::string tp = sp + "/target";
        if (target.is_number()) {
            s.kind = SizeFieldKind::Constant;
            if (!positiveNumber(r, *it, sp, "target", &s.target, 100.0)) return false;
        } else if (target.is_object()) {
            s.kind = SizeFieldKind::Ramp;
            if (!r.onlyKeys(target, tp, {"field", "value_lo", "value_hi", "scale_lo", "scale_hi"}) ||
                !r.require(target, tp, "field") ||
                !readDensityField(r, target["field"], tp + "/field", has_terrain, &s.field) ||
                !r.number(target, tp, "value_lo", &s.value_lo, -1e30, 1e30) ||
                !r.number(target, tp, "value_hi", &s.value_hi, -1e30, 1e30) ||
                !positiveNumber(r, target, tp, "scale_lo", &s.scale_lo, 100.0) ||
                !positiveNumber(r, target, tp, "scale_hi", &s.scale_hi, 100.0))
                return false;
            if (!(s.value_lo < s.value_hi))
                return r.fail(tp + "/value_hi", "must be > value_lo (" + fmt(s.value_lo) + ")");
        } else {
            return r.fail(
                tp,
                "expected a scale > 0 or {\"field\": ..., \"value_lo\", \"value_hi\", \"scale_lo\", "
                "\"scale_hi\"}, got " +
                    JsonReader::typeName(target));
        }
        if (!r.number(*it, sp, "tolerance", &s.tolerance, 0.0, 100.0)) return false;
    }
    return true;
}

bool readModel(JsonReader& r, const json& j, const std::string& p, DetailModelSource* m) {
    if (!r.expectObject(j, p) || !r.onlyKeys(j, p, {"mesh", "scale", "y_up", "spheres", "anchors"})) return false;
    if (!r.string(j, p, "mesh", &m->mesh_path, true) || !r.number(j, p, "scale", &m->scale, 1e-6, 1e6) ||
        !r.boolean(j, p, "y_up", &m->y_up))
        return false;
    // An empty path would resolve to the scene's folder and fail later with a message about a directory.
    if (m->mesh_path.empty()) return r.fail(p + "/mesh", "must name a model file (.glb, .gltf, .obj, .ply, .off or .stl)");
    if (auto it = j.find("spheres"); it != j.end()) {
        const std::string sp = p + "/spheres";
        if (it->is_array()) {
            for (size_t k = 0; k < it->size(); ++k) {
                const json& s = (*it)[k];
                const std::string kp = sp + "/" + std::to_string(k);
                if (!s.is_array() || s.size() != 4) return r.fail(kp, "expected [x, y, z, radius]");
                Sphere sphere;
                if (!readVec3(r, json::array({s[0], s[1], s[2]}), kp, &sphere.center)) return false;
                if (!s[3].is_number() || !(s[3].get<double>() > 0.0) || !(s[3].get<double>() <= 1e6))
                    return r.fail(kp + "/3", "radius must be a number in (0, 1e6] metres");
                sphere.radius = s[3].get<float>();
                m->authored_spheres.push_back(sphere);
            }
        } else {
            if (!r.expectObject(*it, sp) ||
                !r.onlyKeys(*it, sp, {"max_spheres", "tolerance_m", "tolerance_rel", "surface_samples", "seed"}) ||
                !r.integer(*it, sp, "max_spheres", &m->fit.max_spheres, 1, 4096) ||
                !r.number(*it, sp, "tolerance_m", &m->fit.tolerance_m, 0.0, 10.0) ||
                !r.number(*it, sp, "tolerance_rel", &m->fit.tolerance_rel, 1e-4, 1.0) ||
                !r.integer(*it, sp, "surface_samples", &m->fit.surface_samples, kMinSurfaceSamples, kMaxSurfaceSamples) ||
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

// "scatter" (format 3): see project.h. Variant names are checked against every type's later, when all
// are known.
bool readScatter(JsonReader& r, const json& j, const std::string& p, ScatterDesc* out) {
    ScatterDesc sc;
    sc.enabled = true;
    if (!r.expectObject(j, p) || !r.onlyKeys(j, p, {"channel", "thickness_m", "ramp_m", "sheltered", "variants"}) ||
        !r.require(j, p, "channel"))
        return false;
    std::string channel;
    if (!r.string(j, p, "channel", &channel, true)) return false;
    if (!envChannelFromName(channel, &sc.settings.channel) || !(envChannelBit(sc.settings.channel) & kScatterChannels))
        return r.fail(p + "/channel", "expected \"leaves\", \"grass\" or \"trash\", got \"" + channel + "\"");
    sc.settings.sheltered = sc.settings.channel != EnvChannel::Grass;
    if (!r.number(j, p, "thickness_m", &sc.settings.thickness_m, 1e-6, 100.0) ||
        !r.number(j, p, "ramp_m", &sc.settings.ramp_m, 1e-6, 100.0) ||
        !r.boolean(j, p, "sheltered", &sc.settings.sheltered))
        return false;
    if (auto it = j.find("variants"); it != j.end()) {
        const std::string vp = p + "/variants";
        if (!r.expectArray(*it, vp)) return false;
        for (size_t k = 0; k < it->size(); ++k) {
            const json& jv = (*it)[k];
            const std::string kp = vp + "/" + std::to_string(k);
            ScatterVariantDesc v;
            if (!r.expectObject(jv, kp) || !r.onlyKeys(jv, kp, {"name", "model", "material", "when"}) ||
                !r.require(jv, kp, "name") || !r.string(jv, kp, "name", &v.model.name, true) ||
                !r.require(jv, kp, "model") || !readModel(r, jv["model"], kp + "/model", &v.model) ||
                !r.require(jv, kp, "when"))
                return false;
            if (v.model.name.empty()) return r.fail(kp + "/name", "must not be empty");
            if (auto m = jv.find("material"); m != jv.end() && !readMaterial(r, *m, kp + "/material", &v.material))
                return false;
            const json& w = jv["when"];
            const std::string wp = kp + "/when";
            std::string wc;
            if (!r.expectObject(w, wp) || !r.onlyKeys(w, wp, {"channel", "min", "max"}) || !r.require(w, wp, "channel") ||
                !r.string(w, wp, "channel", &wc, true))
                return false;
            if (!envChannelFromName(wc, &v.when.channel)) return r.fail(wp + "/channel", "unknown channel \"" + wc + "\"");
            if (!r.number(w, wp, "min", &v.when.min, -1e30, 1e30) || !r.number(w, wp, "max", &v.when.max, -1e30, 1e30))
                return false;
            if (!(v.when.min < v.when.max)) return r.fail(wp, "min must be less than max");
            sc.variants.push_back(std::move(v));
        }
    }
    *out = std::move(sc);
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
    if (!parseJsonText(text, source_name, &doc, error)) return false;
    JsonReader r(source_name, error);
    if (!r.expectObject(doc, "")) return false;
    std::string format;
    if (!r.string(doc, "", "format", &format, true)) return false;
    if (format != "undergrowth-project") return r.fail("/format", "expected \"undergrowth-project\", got \"" + format + "\"");
    int version = 0;
    if (!r.require(doc, "", "format_version") || !r.integer(doc, "", "format_version", &version, 1, 1000000))
        return false;
    if (version > kProjectFormatVersion)
        return r.fail("/format_version", "version " + std::to_string(version) + " is newer than this program reads (" +
                                             std::to_string(kProjectFormatVersion) + "); update Undergrowth");
    if (!versionedKeys(r, doc, "", version,
                       {"format", "format_version", "name", "ghost_tile", "detail_types"},
                       {"terrain", "extent", "instantiation", "settling"}, {"environment"}, {"particles"}))
        return false;
    Project p;
    p.source = source_name;
    if (!r.string(doc, "", "name", &p.name)) return false;
    if (auto it = doc.find("ghost_tile"); it != doc.end()) {
        if (!r.expectObject(*it, "/ghost_tile") ||
            !r.onlyKeys(*it, "/ghost_tile", {"tile_size_m", "delta_m", "seed", "variants"}) ||
            !r.number(*it, "/ghost_tile", "tile_size_m", &p.ghost_tile.tile_size_m, 1e-4, 1000.0) ||
            !r.number(*it, "/ghost_tile", "delta_m", &p.ghost_tile.delta_m, -10.0, 10.0) ||
            !r.integer(*it, "/ghost_tile", "seed", &p.ghost_tile.seed, 0, UINT64_MAX))
            return false;
        // Optional (default 1) in format 2: a file without it means what it always meant.
        if (auto v = it->find("variants"); v != it->end()) {
            if (!v->is_number_unsigned() || v->get<uint64_t>() < 1 || v->get<uint64_t>() > kMaxTileVariants) {
                std::string got = v->dump();
                if (got.size() > 40) got = got.substr(0, 40) + "...";
                return r.fail("/ghost_tile/variants",
                              "expected an integer in [1, " + std::to_string(kMaxTileVariants) + "], got " + got);
            }
            p.ghost_tile.variants = uint32_t(v->get<uint64_t>());
        }
    }
    if (auto it = doc.find("terrain"); it != doc.end() && !readTerrain(r, *it, "/terrain", &p.terrain))
        return false;
    const bool has_terrain = p.terrain.kind != TerrainKind::None;
    if (auto it = doc.find("extent"); it != doc.end()) {
        Bounds b;
        if (!readExtent(r, *it, "/extent", &b)) return false;
        p.extent = b;
    }
    if (auto it = doc.find("instantiation"); it != doc.end()) {
        if (!r.expectObject(*it, "/instantiation") ||
            !r.onlyKeys(*it, "/instantiation", {"seed", "chunk_size_m"}) ||
            !r.integer(*it, "/instantiation", "seed", &p.instantiation_seed, 0, UINT64_MAX) ||
            !positiveNumber(r, *it, "/instantiation", "chunk_size_m", &p.chunk_size_m, 1e6))
            return false;
    }
    if (auto it = doc.find("settling"); it != doc.end()) {
        SettleSettings& st = p.settling.settle;
        st.enabled = true;  // the object's presence switches it on unless it says otherwise
        float ground = 0.0f;
        if (!r.expectObject(*it, "/settling") ||
            !r.onlyKeys(*it, "/settling", {"enabled", "passes", "max_drop_m", "ground_z"}) ||
            !r.boolean(*it, "/settling", "enabled", &st.enabled) ||
            !r.integer(*it, "/settling", "passes", &st.passes, 1, kMaxSettlePasses) ||
            !r.number(*it, "/settling", "max_drop_m", &st.max_drop_m, 0.0, kMaxSettleDropM) ||
            !r.number(*it, "/settling", "ground_z", &ground, -1e6, 1e6))
            return false;
        if (it->contains("ground_z")) p.settling.ground_z = ground;
    }
    if (!r.require(doc, "", "detail_types")) return false;
    const json& types = doc["detail_types"];
    if (!r.expectArray(types, "/detail_types")) return false;
    if (types.empty()) return r.fail("/detail_types", "at least one detail type is needed");
    // Refused before any type is read or any model loaded: each type costs a model load and a sphere fit.
    if (types.size() > kMaxDetailTypes)
        return r.fail("/detail_types", std::to_string(types.size()) + " detail types exceed the limit of " +
                                           std::to_string(kMaxDetailTypes));
    std::set<std::string> type_names;
    uint64_t total_candidates = 0;
    for (size_t t = 0; t < types.size(); ++t) {
        const std::string tp = "/detail_types/" + std::to_string(t);
        const json& jt = types[t];
        if (!r.expectObject(jt, tp) ||
            !versionedKeys(r, jt, tp, version, {"name", "model", "candidates"},
                           {"density", "subtract_terrain", "terrain_falloff_m", "angle_of_repose_deg", "instancing",
                            "material"},
                           {"scatter"}))
            return false;
        DetailTypeDesc d;
        if (!r.string(jt, tp, "name", &d.model.name, true)) return false;
        if (d.model.name.empty()) return r.fail(tp + "/name", "must not be empty");
        if (!type_names.insert(d.model.name).second)
            return r.fail(tp + "/name", "duplicate detail type '" + d.model.name + "'");
        if (!r.require(jt, tp, "model") || !readModel(r, jt["model"], tp + "/model", &d.model)) return false;
        d.ghost.name = d.model.name;
        if (auto it = jt.find("candidates"); it != jt.end() && !readCandidates(r, *it, tp + "/candidates", &d.ghost))
            return false;
        // The tile holds every type's candidates: the sum has the per-tile limit, checked before models load.
        total_candidates += d.ghost.candidate_count;
        if (total_candidates > kMaxCandidatesPerTile)
            return r.fail(tp + "/candidates/count", "the detail types' candidates add up to " +
                                                        std::to_string(total_candidates) + ", more than the limit of " +
                                                        std::to_string(kMaxCandidatesPerTile) + " per Ghost Tile");
        // The tile stores every variant of every type.
        const uint64_t variants = p.ghost_tile.variants;
        if (total_candidates * variants > kMaxCandidatesPerTile)
            return r.fail(tp + "/candidates/count",
                          "the detail types' candidates add up to " + std::to_string(total_candidates) + ", times " +
                              std::to_string(variants) + " variants (/ghost_tile/variants) " +
                              std::to_string(total_candidates * variants) + ", more than the limit of " +
                              std::to_string(kMaxCandidatesPerTile) + " per Ghost Tile");
        if (auto it = jt.find("density");
            it != jt.end() && !readDensityField(r, *it, tp + "/density", has_terrain, &d.density))
            return false;
        if (!r.boolean(jt, tp, "subtract_terrain", &d.subtract_terrain) ||
            !positiveNumber(r, jt, tp, "terrain_falloff_m", &d.terrain_falloff_m, 100.0) ||
            !positiveNumber(r, jt, tp, "angle_of_repose_deg", &d.angle_of_repose_deg, 89.0))
            return false;
        if (auto it = jt.find("instancing");
            it != jt.end() && !readInstancing(r, *it, tp + "/instancing", has_terrain, &d.instancing))
            return false;
        if (auto it = jt.find("material"); it != jt.end() && !readMaterial(r, *it, tp + "/material", &d.material))
            return false;
        if (auto it = jt.find("scatter"); it != jt.end() && !readScatter(r, *it, tp + "/scatter", &d.scatter))
            return false;
        p.detail_types.push_back(std::move(d));
    }
    // Variants are exported and drawn as meshes of their own, named like the types.
    for (size_t t = 0; t < p.detail_types.size(); ++t)
        for (size_t k = 0; k < p.detail_types[t].scatter.variants.size(); ++k)
            if (!type_names.insert(p.detail_types[t].scatter.variants[k].model.name).second)
                return r.fail("/detail_types/" + std::to_string(t) + "/scatter/variants/" + std::to_string(k) + "/name",
                              "'" + p.detail_types[t].scatter.variants[k].model.name +
                                  "' is already the name of a detail type or variant");
    if (auto it = doc.find("environment");
        it != doc.end() && !readEnvironment(r, *it, "/environment", &p.environment))
        return false;
    if (auto it = doc.find("particles"); it != doc.end() && !readParticleRefs(r, *it, "/particles", &p.particles))
        return false;
    *out = std::move(p);
    return true;
}

bool loadProject(const std::string& path, Project* out, std::string* error) {
    std::string text;
    // A project stores recipes, never instances: even a world's is kilobytes. The limit keeps a wrong file
    // (a dump, a model renamed .json) from becoming a parse tree many times its size.
    if (!readTextFile(path, &text, error, kMaxProjectFileBytes)) return false;
    if (!parseProject(text, path, out, error)) return false;
    out->base_dir = std::filesystem::path(path).parent_path().string();
    return true;
}

namespace {

json vec3Json(glm::vec3 v) {
    return json::array({jsonFloat(v.x), jsonFloat(v.y), jsonFloat(v.z)});
}
json vec2Json(glm::vec2 v) {
    return json::array({jsonFloat(v.x), jsonFloat(v.y)});
}

json modelJson(const DetailModelSource& m) {
    json model = {
        {"mesh", m.mesh_path}, {"scale", jsonFloat(m.scale)}, {"y_up", m.y_up}};
    if (!m.authored_spheres.empty()) {
        json spheres = json::array();
        for (const Sphere& s : m.authored_spheres)
            spheres.push_back({jsonFloat(s.center.x), jsonFloat(s.center.y), jsonFloat(s.center.z),
                               jsonFloat(s.radius)});
        model["spheres"] = spheres;
    } else {
        model["spheres"] = {{"max_spheres", m.fit.max_spheres},
                            {"tolerance_m", jsonFloat(m.fit.tolerance_m)},
                            {"tolerance_rel", jsonFloat(m.fit.tolerance_rel)},
                            {"surface_samples", m.fit.surface_samples},
                            {"seed", m.fit.seed}};
    }
    json anchors = {{"mode", anchorModeName(m.anchor_mode)}, {"count", m.anchor_count}};
    if (!m.authored_anchors.empty()) {
        json pts = json::array();
        for (const glm::vec3& a : m.authored_anchors) pts.push_back(vec3Json(a));
        anchors["points"] = pts;
    }
    model["anchors"] = anchors;
    return model;
}

json scatterJson(const ScatterDesc& sc) {
    json j = {{"channel", envChannelName(sc.settings.channel)},
              {"thickness_m", jsonFloat(sc.settings.thickness_m)},
              {"ramp_m", jsonFloat(sc.settings.ramp_m)},
              {"sheltered", sc.settings.sheltered}};
    if (sc.variants.empty()) return j;
    json variants = json::array();
    for (const ScatterVariantDesc& v : sc.variants) {
        json when = {{"channel", envChannelName(v.when.channel)}};
        if (std::isfinite(v.when.min)) when["min"] = jsonFloat(v.when.min);
        if (std::isfinite(v.when.max)) when["max"] = jsonFloat(v.when.max);
        json jv = {{"name", v.model.name}, {"model", modelJson(v.model)}, {"when", when}};
        if (v.material != Material{}) jv["material"] = materialToJson(v.material);
        variants.push_back(std::move(jv));
    }
    j["variants"] = variants;
    return j;
}

json terrainShapeJson(const TerrainDesc& t) {
    if (t.kind == TerrainKind::Procedural) {
        const ProceduralTerrainDesc& d = t.procedural;
        return {{"procedural",
                 {{"origin", vec2Json(d.origin_m)},
                  {"cell_size_m", jsonFloat(d.cell_size_m)},
                  {"width", d.width},
                  {"height", d.height},
                  {"seed", d.seed},
                  {"octaves", d.octaves},
                  {"base_height_m", jsonFloat(d.base_height_m)},
                  {"amplitude_m", jsonFloat(d.amplitude_m)},
                  {"feature_size_m", jsonFloat(d.feature_size_m)},
                  {"lacunarity", jsonFloat(d.lacunarity)},
                  {"gain", jsonFloat(d.gain)}}}};
    }
    const HeightFieldImageDesc& d = t.image;
    return {{"image",
             {{"path", t.image_path},
              {"origin", vec2Json(d.origin_m)},
              {"cell_size_m", jsonFloat(d.cell_size_m)},
              {"min_height_m", jsonFloat(d.min_height_m)},
              {"max_height_m", jsonFloat(d.max_height_m)}}}};
}

json terrainJson(const TerrainDesc& t) {
    json out = terrainShapeJson(t);
    if (t.material != Material{}) out["material"] = materialToJson(t.material);
    return out;
}

json instancingJson(const InstancingDesc& d) {
    json out = {{"strategy", priorityStrategyName(d.strategy)}, {"layer_m", jsonFloat(d.layer_m)}};
    if (d.orientation.enabled) {
        const OrientationDesc& o = d.orientation;
        out["orientation"] = {
            {"direction", o.kind == DirectionFieldKind::Gradient ? json("gradient") : vec3Json(o.direction)},
            {"max_angle_deg", jsonFloat(o.max_angle_deg)}};
    }
    if (d.size.enabled) {
        const SizeDesc& s = d.size;
        json target;
        if (s.kind == SizeFieldKind::Constant) {
            target = jsonFloat(s.target);
        } else {
            // An empty ramp field has no tree of its own; an empty blend is the same 0 everywhere.
            json field =
                s.field.root == kNoNode ? json{{"blend", json::array()}} : densityFieldToJson(s.field);
            target = {{"field", std::move(field)},
                      {"value_lo", jsonFloat(s.value_lo)},
                      {"value_hi", jsonFloat(s.value_hi)},
                      {"scale_lo", jsonFloat(s.scale_lo)},
                      {"scale_hi", jsonFloat(s.scale_hi)}};
        }
        out["size"] = {{"target", std::move(target)}, {"tolerance", jsonFloat(s.tolerance)}};
    }
    return out;
}

// nlohmann's dump(2) puts every number of every vector on its own line, which makes a density of a few
// hundred primitives thousands of lines long. This writes any value whose one-line form fits within the
// line width on one line ({"point": {"center": [0, 0, 0], "radius": 2, "weight": 1}}) and breaks the
// rest one member per line, so saved projects read like the hand-written samples.
constexpr size_t kJsonLineWidth = 110;

void writeCompact(const json& j, std::string* out) {
    if (j.is_object()) {
        *out += '{';
        bool first = true;
        for (auto it = j.begin(); it != j.end(); ++it) {
            if (!first) *out += ", ";
            first = false;
            *out += json(it.key()).dump() + ": ";
            writeCompact(it.value(), out);
        }
        *out += '}';
    } else if (j.is_array()) {
        *out += '[';
        for (size_t k = 0; k < j.size(); ++k) {
            if (k) *out += ", ";
            writeCompact(j[k], out);
        }
        *out += ']';
    } else {
        *out += j.dump();
    }
}

void writePretty(const json& j, size_t indent, size_t key_width, std::string* out) {
    std::string compact;
    writeCompact(j, &compact);
    if ((!j.is_structured() || j.empty()) || indent + key_width + compact.size() <= kJsonLineWidth) {
        *out += compact;
        return;
    }
    const bool object = j.is_object();
    *out += object ? "{\n" : "[\n";
    size_t k = 0;
    for (auto it = j.begin(); it != j.end(); ++it, ++k) {
        if (k) *out += ",\n";
        out->append(indent + 2, ' ');
        size_t width = 0;
        if (object) {
            const std::string key = json(it.key()).dump() + ": ";
            *out += key;
            width = key.size();
        }
        writePretty(it.value(), indent + 2, width, out);
    }
    *out += '\n';
    out->append(indent, ' ');
    *out += object ? '}' : ']';
}

}  // namespace

std::string projectToJson(const Project& project) {
    json doc;
    doc["format"] = "undergrowth-project";
    // A project without environmental objects is a format 2 file, which older builds still read.
    bool scatters = false;
    for (const DetailTypeDesc& d : project.detail_types) scatters = scatters || d.scatter.enabled;
    // Each format is written only when its keys are used, so older builds read what they can.
    doc["format_version"] = !project.particles.empty()                      ? 4
                            : project.environment.empty() && !scatters ? 2
                                                                         : 3;
    doc["name"] = project.name;
    doc["ghost_tile"] = {{"tile_size_m", jsonFloat(project.ghost_tile.tile_size_m)},
                         {"delta_m", jsonFloat(project.ghost_tile.delta_m)},
                         {"seed", project.ghost_tile.seed}};
    // Written only when set, so a single-variant project saves exactly as before and older builds of
    // format 2 (which refuse unknown keys) still read it.
    if (project.ghost_tile.variants != 1) doc["ghost_tile"]["variants"] = project.ghost_tile.variants;
    if (project.terrain.kind != TerrainKind::None) doc["terrain"] = terrainJson(project.terrain);
    if (project.extent)
        doc["extent"] = {{"min", vec3Json(project.extent->lo)}, {"max", vec3Json(project.extent->hi)}};
    doc["instantiation"] = {{"seed", project.instantiation_seed},
                            {"chunk_size_m", jsonFloat(project.chunk_size_m)}};
    const SettleSettings& st = project.settling.settle;
    if (st.enabled || project.settling.ground_z) {
        doc["settling"] = {{"enabled", st.enabled}, {"passes", st.passes}, {"max_drop_m", jsonFloat(st.max_drop_m)}};
        if (project.settling.ground_z) doc["settling"]["ground_z"] = jsonFloat(*project.settling.ground_z);
    }
    json types = json::array();
    for (const DetailTypeDesc& d : project.detail_types) {
        const json model = modelJson(d.model);
        json orientation = {{"mode", d.ghost.orientation.mode == OrientationMode::Tilt ? "tilt" : "uniform"}};
        if (d.ghost.orientation.mode == OrientationMode::Tilt) {
            json ranges = json::array();
            for (const TiltRange& tr : d.ghost.orientation.tilt_ranges)
                ranges.push_back({jsonFloat(tr.min_deg), jsonFloat(tr.max_deg), jsonFloat(tr.weight)});
            orientation["tilt_ranges"] = ranges;
        }
        json type = {{"name", d.model.name},
                     {"model", model},
                     {"candidates",
                      {{"count", d.ghost.candidate_count},
                       {"orientation", orientation},
                       {"scale", {jsonFloat(d.ghost.scale_min), jsonFloat(d.ghost.scale_max)}},
                       {"position", d.ghost.position == PositionMode::Jittered ? "jittered" : "uniform"}}},
                     {"subtract_terrain", d.subtract_terrain},
                     {"terrain_falloff_m", jsonFloat(d.terrain_falloff_m)},
                     {"angle_of_repose_deg", jsonFloat(d.angle_of_repose_deg)},
                     {"instancing", instancingJson(d.instancing)}};
        if (d.density.root != kNoNode) type["density"] = densityFieldToJson(d.density);
        if (d.material != Material{}) type["material"] = materialToJson(d.material);
        if (d.scatter.enabled) type["scatter"] = scatterJson(d.scatter);
        types.push_back(std::move(type));
    }
    doc["detail_types"] = types;
    if (!project.environment.empty()) doc["environment"] = environmentToJson(project.environment);
    if (!project.particles.empty()) {
        json refs = json::array();
        for (const ParticleSystemRef& ref : project.particles) {
            json e = {{"file", ref.file}};
            if (!ref.name.empty()) e["name"] = ref.name;
            if (ref.offset_m != glm::vec3(0.0f)) e["offset_m"] = vec3Json(ref.offset_m);
            refs.push_back(std::move(e));
        }
        doc["particles"] = refs;
    }
    std::string text;
    writePretty(doc, 0, 0, &text);
    return text + "\n";
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
            // The scene and the place that named the model come first: the model's own message ("detail
            // model 'rock' (path): element: reason") does not say which scene referenced it, nor where.
            *error = (project.source.empty() ? std::string() : project.source + ": ") + "/detail_types/" +
                     std::to_string(t) + "/model: " + model_error;
            return false;
        }
    }
    return true;
}

bool loadScatterVariantModels(const Project& project, std::vector<std::vector<DetailModel>>* out, std::string* error) {
    out->assign(project.detail_types.size(), {});
    for (size_t t = 0; t < project.detail_types.size(); ++t) {
        const std::vector<ScatterVariantDesc>& variants = project.detail_types[t].scatter.variants;
        (*out)[t].resize(variants.size());
        for (size_t k = 0; k < variants.size(); ++k) {
            DetailModelSource source = variants[k].model;
            source.mesh_path = resolveProjectPath(project, source.mesh_path);
            std::string model_error;
            if (!loadDetailModel(source, &(*out)[t][k], &model_error)) {
                *error = (project.source.empty() ? std::string() : project.source + ": ") + "/detail_types/" +
                         std::to_string(t) + "/scatter/variants/" + std::to_string(k) + "/model: " + model_error;
                return false;
            }
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
