#include "env/env_json.h"

#include <cmath>
#include <set>

#include "field/density_field.h"
#include "scene/field_json.h"
#include "scene/material_json.h"

namespace ug {

using nlohmann::json;

namespace {

const std::set<std::string> kShapeKinds = {"point", "segment", "disc", "box"};

bool readVec3(JsonReader& r, const json& obj, const std::string& p, const char* key, glm::vec3* out) {
    return r.vec3(obj, p, key, out, 1e7);
}

bool readField(JsonReader& r, const json& j, const std::string& p, EnvFieldDesc* out) {
    if (!r.expectObject(j, p) || !r.onlyKeys(j, p, {"channel", "value", "shape"})) return false;
    std::string channel;
    if (!r.string(j, p, "channel", &channel, true)) return false;
    if (!envChannelFromName(channel, &out->channel))
        return r.fail(p + "/channel", "unknown channel \"" + channel +
                                          "\" (snow, icicles, leaves, grass, trash, occlusion, humidity, temperature)");
    if (!r.require(j, p, "value")) return false;
    const bool occlusion = out->channel == EnvChannel::Occlusion;
    if (!r.number(j, p, "value", &out->value, occlusion ? 0.0 : -1e6, occlusion ? 1.0 : 1e6)) return false;
    auto shape = j.find("shape");
    out->everywhere = shape == j.end();
    if (out->everywhere) return true;
    const std::string sp = p + "/shape";
    if (!r.expectObject(*shape, sp)) return false;
    if (shape->size() != 1 || !kShapeKinds.count(shape->begin().key()))
        return r.fail(sp, "expected one of {\"point\": ..}, {\"segment\": ..}, {\"disc\": ..}, {\"box\": ..}");
    const std::string kind = shape->begin().key();
    if (shape->begin()->is_object() && shape->begin()->contains("weight"))
        return r.fail(sp + "/" + kind + "/weight", "a field's strength is its \"value\", not a weight");
    DensityField field;
    if (!readDensityField(r, *shape, sp, false, &field)) return false;
    if (field.primitives.size() != 1) return r.fail(sp, "expected one primitive");
    out->shape = field.primitives[0];
    out->shape.weight = out->value;
    return true;
}

bool readFields(JsonReader& r, const json& obj, const std::string& p, std::vector<EnvFieldDesc>* out,
                const char* key = "fields") {
    auto it = obj.find(key);
    if (it == obj.end()) return true;
    const std::string fp = p + "/" + key;
    if (!r.expectArray(*it, fp)) return false;
    if (it->size() > kMaxEnvFields) return r.fail(fp, "more than " + std::to_string(kMaxEnvFields) + " fields");
    for (size_t i = 0; i < it->size(); ++i) {
        EnvFieldDesc f;
        if (!readField(r, (*it)[i], fp + "/" + std::to_string(i), &f)) return false;
        out->push_back(f);
    }
    return true;
}

bool readSnowMode(JsonReader& r, const json& j, const std::string& p, SnowMode* out) {
    std::string mode;
    if (!r.string(j, p, "mode", &mode)) return false;
    if (!j.contains("mode")) return true;
    for (SnowMode m : {SnowMode::None, SnowMode::Geometry, SnowMode::Box, SnowMode::Cylinder, SnowMode::Sphere})
        if (mode == snowModeName(m)) {
            *out = m;
            return true;
        }
    return r.fail(p + "/mode", "expected \"geometry\", \"box\", \"cylinder\", \"sphere\" or \"none\", got \"" + mode + "\"");
}

bool positive(JsonReader& r, const json& j, const std::string& p, const char* key, float* v, double hi) {
    if (!r.number(j, p, key, v, 0.0, hi)) return false;
    return *v > 0.0f || r.fail(p + "/" + key, "must be > 0");
}

// Snow settings: a type's (every key into *desc) or an override's (into *ov).
bool readSnow(JsonReader& r, const json& obj, const std::string& p, SnowEffectDesc* desc, EffectOverrides* ov) {
    auto it = obj.find("snow");
    if (it == obj.end()) return true;
    const std::string sp = p + "/snow";
    if (!r.expectObject(*it, sp) || !r.onlyKeys(*it, sp, {"mode", "max_face_angle_deg", "d0_m", "target_edge_m"}))
        return false;
    SnowEffectDesc d = desc ? *desc : SnowEffectDesc{};
    if (!readSnowMode(r, *it, sp, &d.mode) || !positive(r, *it, sp, "max_face_angle_deg", &d.max_face_angle_deg, 89.9) ||
        !positive(r, *it, sp, "d0_m", &d.d0_m, 1e3) || !positive(r, *it, sp, "target_edge_m", &d.target_edge_m, 1e3))
        return false;
    if (desc) *desc = d;
    if (ov) {
        if (it->contains("mode")) ov->snow_mode = d.mode;
        if (it->contains("max_face_angle_deg")) ov->snow_max_face_angle_deg = d.max_face_angle_deg;
        if (it->contains("d0_m")) ov->snow_d0_m = d.d0_m;
        if (it->contains("target_edge_m")) ov->snow_target_edge_m = d.target_edge_m;
    }
    return true;
}

bool readIcicles(JsonReader& r, const json& obj, const std::string& p, IcicleEffectDesc* desc, EffectOverrides* ov) {
    auto it = obj.find("icicles");
    if (it == obj.end()) return true;
    const std::string ip = p + "/icicles";
    const std::set<std::string> type_keys = {"enabled", "automatic_anchors", "anchors", "spacing_m", "max_length_m",
                                             "length_per_degree_m"};
    const std::set<std::string> override_keys = {"enabled", "spacing_m", "max_length_m"};
    if (!r.expectObject(*it, ip) || !r.onlyKeys(*it, ip, desc ? type_keys : override_keys)) return false;
    IcicleEffectDesc d = desc ? *desc : IcicleEffectDesc{};
    if (!r.boolean(*it, ip, "enabled", &d.enabled) || !r.boolean(*it, ip, "automatic_anchors", &d.automatic_anchors) ||
        !positive(r, *it, ip, "spacing_m", &d.spacing_m, 1e3) || !positive(r, *it, ip, "max_length_m", &d.max_length_m, 1e2) ||
        !positive(r, *it, ip, "length_per_degree_m", &d.length_per_degree_m, 1e2))
        return false;
    if (auto a = it->find("anchors"); a != it->end()) {
        const std::string ap = ip + "/anchors";
        if (!r.expectArray(*a, ap)) return false;
        d.anchors.clear();
        for (size_t k = 0; k < a->size(); ++k) {
            const json wrap = {{"p", (*a)[k]}};
            glm::vec3 v(0.0f);
            if (!r.require(wrap, ap, "p") || !readVec3(r, wrap, ap, "p", &v)) return false;
            d.anchors.push_back(v);
        }
    }
    if (desc) *desc = d;
    if (ov) {
        if (it->contains("enabled")) ov->icicles_enabled = d.enabled;
        if (it->contains("spacing_m")) ov->icicle_spacing_m = d.spacing_m;
        if (it->contains("max_length_m")) ov->icicle_max_length_m = d.max_length_m;
    }
    return true;
}

bool readPlacement(JsonReader& r, const json& j, const std::string& p, EnvTransform* t) {
    return readVec3(r, j, p, "at", &t->translation) && r.number(j, p, "yaw_deg", &t->yaw_deg, -1e6, 1e6) &&
           positive(r, j, p, "scale", &t->scale, 1e4);
}

struct TreeReader {
    JsonReader& r;
    const EnvironmentDesc& env;  // the types, for object nodes
    size_t nodes = 0;

    bool node(const json& j, const std::string& p, int depth, EnvNode* out) {
        if (depth > kMaxEnvTreeDepth)
            return r.fail(p, "the tree is deeper than " + std::to_string(kMaxEnvTreeDepth) + " levels");
        if (++nodes > kMaxEnvObjects) return r.fail(p, "more than " + std::to_string(kMaxEnvObjects) + " nodes");
        if (!r.expectObject(j, p)) return false;
        if (j.contains("object")) return object(j, p, out);
        if (j.contains("ref")) return reference(j, p, out);
        for (const char* kind : {"group", "lod"}) {
            auto it = j.find(kind);
            if (it == j.end()) continue;
            if (j.size() != 1) return r.fail(p, std::string("a \"") + kind + "\" node has no other keys");
            out->kind = std::string(kind) == "group" ? EnvNodeKind::Group : EnvNodeKind::Lod;
            return group(*it, p + "/" + kind, depth, out);
        }
        return r.fail(p, "expected a node: {\"object\": ..}, {\"group\": ..}, {\"lod\": ..} or {\"ref\": ..}");
    }

    bool object(const json& j, const std::string& p, EnvNode* out) {
        if (!r.onlyKeys(j, p, {"object", "at", "yaw_deg", "scale", "fields", "snow", "icicles"})) return false;
        std::string type;
        if (!r.string(j, p, "object", &type, true)) return false;
        out->kind = EnvNodeKind::Object;
        size_t t = 0;
        while (t < env.types.size() && env.types[t].name != type) ++t;
        if (t == env.types.size()) return r.fail(p + "/object", "unknown environmental-object type \"" + type + "\"");
        out->type = uint32_t(t);
        return readPlacement(r, j, p, &out->transform) && readFields(r, j, p, &out->fields) &&
               readSnow(r, j, p, nullptr, &out->overrides) && readIcicles(r, j, p, nullptr, &out->overrides);
    }

    bool reference(const json& j, const std::string& p, EnvNode* out) {
        if (!r.onlyKeys(j, p, {"ref", "at", "yaw_deg", "scale", "snow", "icicles"})) return false;
        out->kind = EnvNodeKind::Reference;
        return r.string(j, p, "ref", &out->target, true) && readPlacement(r, j, p, &out->transform) &&
               readSnow(r, j, p, nullptr, &out->overrides) && readIcicles(r, j, p, nullptr, &out->overrides);
    }

    bool group(const json& j, const std::string& p, int depth, EnvNode* out) {
        const bool lod = out->kind == EnvNodeKind::Lod;
        if (!r.expectObject(j, p) ||
            !r.onlyKeys(j, p, lod ? std::set<std::string>{"at", "yaw_deg", "scale", "children", "fields"}
                                  : std::set<std::string>{"at", "yaw_deg", "scale", "children", "fields", "snow", "icicles"}) ||
            !readPlacement(r, j, p, &out->transform) || !readFields(r, j, p, &out->fields) ||
            !readSnow(r, j, p, nullptr, &out->overrides) || !readIcicles(r, j, p, nullptr, &out->overrides))
            return false;
        auto c = j.find("children");
        if (c == j.end()) return true;
        return children(*c, p + "/children", depth, &out->children);
    }

    bool children(const json& j, const std::string& p, int depth, std::vector<EnvNode>* out) {
        if (!r.expectArray(j, p)) return false;
        out->resize(j.size());
        for (size_t i = 0; i < j.size(); ++i)
            if (!node(j[i], p + "/" + std::to_string(i), depth + 1, &(*out)[i])) return false;
        return true;
    }
};

// "receives": ["leaves", "grass", "trash"] (any subset, no repeats).
bool readReceives(JsonReader& r, const json& j, const std::string& p, uint32_t* out) {
    auto it = j.find("receives");
    if (it == j.end()) return true;
    const std::string rp = p + "/receives";
    if (!r.expectArray(*it, rp)) return false;
    uint32_t bits = 0;
    for (size_t k = 0; k < it->size(); ++k) {
        const std::string ep = rp + "/" + std::to_string(k);
        EnvChannel c;
        if (!(*it)[k].is_string() || !envChannelFromName((*it)[k].get<std::string>(), &c) ||
            !(envChannelBit(c) & kScatterChannels))
            return r.fail(ep, "expected \"leaves\", \"grass\" or \"trash\"");
        if (bits & envChannelBit(c)) return r.fail(ep, "\"" + std::string(envChannelName(c)) + "\" is listed twice");
        bits |= envChannelBit(c);
    }
    *out = bits;
    return true;
}

json receivesJson(uint32_t bits) {
    json a = json::array();
    for (EnvChannel c : {EnvChannel::Leaves, EnvChannel::Grass, EnvChannel::Trash})
        if (bits & envChannelBit(c)) a.push_back(envChannelName(c));
    return a;
}

bool readType(JsonReader& r, const json& j, const std::string& p, EnvTypeDesc* t) {
    if (!r.expectObject(j, p) ||
        !r.onlyKeys(j, p, {"name", "mesh", "scale", "y_up", "fields", "snow", "icicles", "material", "receives",
                           "shelters"}) ||
        !readReceives(r, j, p, &t->receives) || !r.boolean(j, p, "shelters", &t->shelters) ||
        !r.string(j, p, "name", &t->name, true) || !r.string(j, p, "mesh", &t->mesh_path, true) ||
        !positive(r, j, p, "scale", &t->scale, 1e4) || !r.boolean(j, p, "y_up", &t->y_up) ||
        !readFields(r, j, p, &t->fields) || !readSnow(r, j, p, &t->snow, nullptr) ||
        !readIcicles(r, j, p, &t->icicles, nullptr))
        return false;
    if (t->name.empty()) return r.fail(p + "/name", "must not be empty");
    if (auto m = j.find("material"); m != j.end() && !readMaterial(r, *m, p + "/material", &t->material)) return false;
    return true;
}

json vec3Json(glm::vec3 v) { return json::array({jsonFloat(v.x), jsonFloat(v.y), jsonFloat(v.z)}); }

json fieldJson(const EnvFieldDesc& f) {
    json j = {{"channel", envChannelName(f.channel)}, {"value", jsonFloat(f.value)}};
    if (f.everywhere) return j;
    Primitive shape = f.shape;
    shape.weight = 1.0f;
    const json tree = densityFieldToJson(makeBlendField({shape}));
    json prim = tree["blend"][0];
    prim.begin()->erase("weight");
    j["shape"] = prim;
    return j;
}

void writeFields(const std::vector<EnvFieldDesc>& fields, json* out) {
    if (fields.empty()) return;
    json a = json::array();
    for (const EnvFieldDesc& f : fields) a.push_back(fieldJson(f));
    (*out)["fields"] = a;
}

void writePlacement(const EnvTransform& t, json* out) {
    if (t.translation != glm::vec3(0.0f)) (*out)["at"] = vec3Json(t.translation);
    if (t.yaw_deg != 0.0f) (*out)["yaw_deg"] = jsonFloat(t.yaw_deg);
    if (t.scale != 1.0f) (*out)["scale"] = jsonFloat(t.scale);
}

void writeOverrides(const EffectOverrides& o, json* out) {
    json snow = json::object(), ice = json::object();
    if (o.snow_mode) snow["mode"] = snowModeName(*o.snow_mode);
    if (o.snow_max_face_angle_deg) snow["max_face_angle_deg"] = jsonFloat(*o.snow_max_face_angle_deg);
    if (o.snow_d0_m) snow["d0_m"] = jsonFloat(*o.snow_d0_m);
    if (o.snow_target_edge_m) snow["target_edge_m"] = jsonFloat(*o.snow_target_edge_m);
    if (o.icicles_enabled) ice["enabled"] = *o.icicles_enabled;
    if (o.icicle_spacing_m) ice["spacing_m"] = jsonFloat(*o.icicle_spacing_m);
    if (o.icicle_max_length_m) ice["max_length_m"] = jsonFloat(*o.icicle_max_length_m);
    if (!snow.empty()) (*out)["snow"] = snow;
    if (!ice.empty()) (*out)["icicles"] = ice;
}

json nodeJson(const EnvNode& n, const EnvironmentDesc& env) {
    json j = json::object();
    switch (n.kind) {
    case EnvNodeKind::Object:
        j["object"] = env.types[n.type].name;
        writePlacement(n.transform, &j);
        writeFields(n.fields, &j);
        writeOverrides(n.overrides, &j);
        return j;
    case EnvNodeKind::Reference:
        j["ref"] = n.target;
        writePlacement(n.transform, &j);
        writeOverrides(n.overrides, &j);
        return j;
    case EnvNodeKind::Group:
    case EnvNodeKind::Lod: {
        json g = json::object();
        writePlacement(n.transform, &g);
        writeFields(n.fields, &g);
        writeOverrides(n.overrides, &g);
        json c = json::array();
        for (const EnvNode& child : n.children) c.push_back(nodeJson(child, env));
        g["children"] = c;
        j[n.kind == EnvNodeKind::Lod ? "lod" : "group"] = g;
        return j;
    }
    }
    return j;
}

}  // namespace

bool readEnvironment(JsonReader& r, const json& j, const std::string& p, EnvironmentDesc* out) {
    if (!r.expectObject(j, p) ||
        !r.onlyKeys(j, p, {"types", "groups", "tree", "global_fields", "terrain", "use_lod_nodes", "sharing_threshold",
                           "snow_direction", "snow_spread_deg"}))
        return false;
    EnvironmentDesc env;
    if (j.contains("snow_direction")) {
        glm::vec3 d(0.0f);
        if (!readVec3(r, j, p, "snow_direction", &d)) return false;
        const float len = glm::length(d);
        if (!(len > 1e-6f)) return r.fail(p + "/snow_direction", "must not be zero");
        d = documentUnitVector(d);
        if (!(-d.z >= std::cos(kMaxSnowTiltDeg * 0.017453292519943295f) - 1e-6f))
            return r.fail(p + "/snow_direction", "must point down, at most " + std::to_string(int(kMaxSnowTiltDeg)) +
                                                     " degrees from straight down");
        env.snow_direction = d;
    }
    if (auto it = j.find("types"); it != j.end()) {
        const std::string tp = p + "/types";
        if (!r.expectArray(*it, tp)) return false;
        if (it->size() > kMaxEnvTypes) return r.fail(tp, "more than " + std::to_string(kMaxEnvTypes) + " types");
        std::set<std::string> names;
        for (size_t t = 0; t < it->size(); ++t) {
            EnvTypeDesc type;
            const std::string ep = tp + "/" + std::to_string(t);
            if (!readType(r, (*it)[t], ep, &type)) return false;
            if (!names.insert(type.name).second) return r.fail(ep + "/name", "duplicate type name \"" + type.name + "\"");
            env.types.push_back(std::move(type));
        }
    }
    TreeReader tree{r, env};
    if (auto it = j.find("groups"); it != j.end()) {
        const std::string gp = p + "/groups";
        if (!r.expectObject(*it, gp)) return false;
        for (auto g = it->begin(); g != it->end(); ++g) {
            NamedEnvGroup named;
            named.name = g.key();
            const std::string np = gp + "/" + g.key();
            if (!g->is_object() || !(g->contains("group") || g->contains("lod")))
                return r.fail(np, "expected {\"group\": ..} or {\"lod\": ..}");
            if (!tree.node(*g, np, 1, &named.group)) return false;
            env.groups.push_back(std::move(named));
        }
    }
    if (auto it = j.find("tree"); it != j.end() && !tree.children(*it, p + "/tree", 0, &env.roots)) return false;
    if (!readFields(r, j, p, &env.global_fields, "global_fields")) return false;
    if (auto it = j.find("terrain"); it != j.end()) {
        const std::string tp = p + "/terrain";
        if (!r.expectObject(*it, tp) || !r.onlyKeys(*it, tp, {"snow", "snow_cell_m", "receives"}) ||
            !r.boolean(*it, tp, "snow", &env.terrain.snow) || !readReceives(r, *it, tp, &env.terrain.receives) ||
            !positive(r, *it, tp, "snow_cell_m", &env.terrain.snow_cell_m, 100.0))
            return false;
    }
    if (!r.number(j, p, "snow_spread_deg", &env.snow_spread_deg, 0.0, kMaxSnowSpreadDeg) ||
        !r.boolean(j, p, "use_lod_nodes", &env.use_lod_nodes) ||
        !r.number(j, p, "sharing_threshold", &env.sharing_threshold, -1.0, 1e6))
        return false;
    *out = std::move(env);
    return true;
}

json environmentToJson(const EnvironmentDesc& env) {
    json j = json::object();
    if (env.snow_direction != glm::vec3(0.0f, 0.0f, -1.0f)) j["snow_direction"] = vec3Json(env.snow_direction);
    if (env.snow_spread_deg != 0.0f) j["snow_spread_deg"] = jsonFloat(env.snow_spread_deg);
    json types = json::array();
    for (const EnvTypeDesc& t : env.types) {
        json jt = {{"name", t.name}, {"mesh", t.mesh_path}, {"scale", jsonFloat(t.scale)}, {"y_up", t.y_up}};
        writeFields(t.fields, &jt);
        jt["snow"] = {{"mode", snowModeName(t.snow.mode)},
                      {"max_face_angle_deg", jsonFloat(t.snow.max_face_angle_deg)},
                      {"d0_m", jsonFloat(t.snow.d0_m)},
                      {"target_edge_m", jsonFloat(t.snow.target_edge_m)}};
        json anchors = json::array();
        for (glm::vec3 a : t.icicles.anchors) anchors.push_back(vec3Json(a));
        jt["icicles"] = {{"enabled", t.icicles.enabled},
                         {"automatic_anchors", t.icicles.automatic_anchors},
                         {"anchors", anchors},
                         {"spacing_m", jsonFloat(t.icicles.spacing_m)},
                         {"max_length_m", jsonFloat(t.icicles.max_length_m)},
                         {"length_per_degree_m", jsonFloat(t.icicles.length_per_degree_m)}};
        if (!(t.material == Material{})) jt["material"] = materialToJson(t.material);
        if (t.receives) jt["receives"] = receivesJson(t.receives);
        if (!t.shelters) jt["shelters"] = false;
        types.push_back(jt);
    }
    j["types"] = types;
    if (!env.groups.empty()) {
        json g = json::object();
        for (const NamedEnvGroup& n : env.groups) g[n.name] = nodeJson(n.group, env);
        j["groups"] = g;
    }
    json tree = json::array();
    for (const EnvNode& n : env.roots) tree.push_back(nodeJson(n, env));
    j["tree"] = tree;
    json globals = json::array();
    for (const EnvFieldDesc& f : env.global_fields) globals.push_back(fieldJson(f));
    j["global_fields"] = globals;
    j["terrain"] = {{"snow", env.terrain.snow}, {"snow_cell_m", jsonFloat(env.terrain.snow_cell_m)}};
    if (env.terrain.receives != kScatterChannels) j["terrain"]["receives"] = receivesJson(env.terrain.receives);
    j["use_lod_nodes"] = env.use_lod_nodes;
    j["sharing_threshold"] = jsonFloat(env.sharing_threshold);
    return j;
}

}  // namespace ug
