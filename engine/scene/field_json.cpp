// Reading density fields from the project file. The flat DensityField wants children before parents;
// a post-order walk of the JSON tree gives exactly that, so the reader appends primitives and nodes as
// it meets them and never has to reorder. Writing is the same walk from the root, which is why a saved
// and reloaded field has identical arrays (and therefore identical values, bit for bit: evaluation order
// is the array order, density_field.h).
#include "scene/field_json.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace ug {

namespace {

using nlohmann::json;

std::string fmt(double v) {
    char buf[48];
    std::snprintf(buf, sizeof(buf), "%g", v);
    return buf;
}

class FieldReader {
  public:
    FieldReader(JsonReader& r, bool has_terrain, DensityField* field)
        : r_(r), has_terrain_(has_terrain), f_(field) {}

    bool node(const json& j, const std::string& p, int depth, uint32_t* ref) {
        if (depth > kMaxFieldDepth)
            return r_.fail(p, "field nodes nested deeper than " + std::to_string(kMaxFieldDepth) + " levels");
        if (!j.is_object())
            return r_.fail(
                p, "expected a field node such as {\"point\": {...}}, got " + JsonReader::typeName(j));
        if (j.size() != 1)
            return r_.fail(
                p,
                "a field node has exactly one key, its kind (point, segment, disc, box, half_space, "
                "terrain_layer, terrain_solid, polyline, blend, union, intersection, difference); "
                "got " +
                    std::to_string(j.size()));
        const std::string kind = j.begin().key();
        const json& v = j.begin().value();
        const std::string kp = p + "/" + kind;
        if (kind == "blend") return op(FieldOp::Blend, v, kp, depth, ref);
        if (kind == "union") return op(FieldOp::Union, v, kp, depth, ref);
        if (kind == "intersection") return op(FieldOp::Intersection, v, kp, depth, ref);
        if (kind == "difference") return op(FieldOp::Difference, v, kp, depth, ref);
        if (kind == "polyline") return polyline(v, kp, ref);
        Primitive prim;
        if (kind == "point") {
            glm::vec3 c;
            float radius = 0.0f, weight = 1.0f;
            if (!r_.expectObject(v, kp) || !r_.onlyKeys(v, kp, {"center", "radius", "weight", "stroke"}) ||
                !vec3(v, kp, "center", &c) || !radiusField(v, kp, "radius", &radius) ||
                !number(v, kp, "weight", &weight, false))
                return false;
            prim = makePoint(c, radius, weight);
        } else if (kind == "segment") {
            glm::vec3 a, b;
            float radius = 0.0f, weight = 1.0f;
            if (!r_.expectObject(v, kp) ||
                !r_.onlyKeys(v, kp, {"a", "b", "radius", "end_radius", "weight", "stroke"}) || !vec3(v, kp, "a", &a) ||
                !vec3(v, kp, "b", &b) || !radiusField(v, kp, "radius", &radius) ||
                !number(v, kp, "weight", &weight, false))
                return false;
            float end_radius = radius;
            if (v.contains("end_radius") && !radiusField(v, kp, "end_radius", &end_radius)) return false;
            prim = makeCone(a, radius, b, end_radius, weight);
        } else if (kind == "disc") {
            glm::vec3 c, n;
            float disc_radius = 0.0f, radius = 0.0f, weight = 1.0f;
            if (!r_.expectObject(v, kp) ||
                !r_.onlyKeys(v, kp, {"center", "normal", "disc_radius", "radius", "weight", "stroke"}) ||
                !vec3(v, kp, "center", &c) || !normal(v, kp, "normal", &n) ||
                !nonNegative(v, kp, "disc_radius", &disc_radius) || !radiusField(v, kp, "radius", &radius) ||
                !number(v, kp, "weight", &weight, false))
                return false;
            prim = makeDisc(c, n, disc_radius, radius, weight);
            prim.normal = n;
        } else if (kind == "box") {
            glm::vec3 c, half;
            float radius = 0.0f, weight = 1.0f;
            if (!r_.expectObject(v, kp) ||
                !r_.onlyKeys(v, kp, {"center", "half_extents", "radius", "weight", "stroke"}) ||
                !vec3(v, kp, "center", &c) || !vec3(v, kp, "half_extents", &half) ||
                !radiusField(v, kp, "radius", &radius) || !number(v, kp, "weight", &weight, false))
                return false;
            if (half.x < 0.0f || half.y < 0.0f || half.z < 0.0f)
                return r_.fail(kp + "/half_extents", "must be >= 0 on every axis");
            prim = makeBox(c, half, radius, weight);
        } else if (kind == "half_space") {
            glm::vec3 c, n;
            float radius = 0.0f, weight = 1.0f;
            if (!r_.expectObject(v, kp) || !r_.onlyKeys(v, kp, {"point", "normal", "radius", "weight", "stroke"}) ||
                !vec3(v, kp, "point", &c) || !normal(v, kp, "normal", &n) ||
                !radiusField(v, kp, "radius", &radius) || !number(v, kp, "weight", &weight, false))
                return false;
            prim = makeHalfSpace(c, n, radius, weight);
            prim.normal = n;
        } else if (kind == "terrain_layer") {
            float thickness = 0.0f, radius = 0.0f, weight = 1.0f;
            if (!r_.expectObject(v, kp) || !r_.onlyKeys(v, kp, {"thickness", "radius", "weight", "stroke"}))
                return false;
            if (!has_terrain_) return r_.fail(kp, "the project has no terrain (add a top-level \"terrain\")");
            if (!nonNegative(v, kp, "thickness", &thickness) || !radiusField(v, kp, "radius", &radius) ||
                !number(v, kp, "weight", &weight, false))
                return false;
            prim = makeTerrainLayer(0, thickness, radius, weight);
        } else if (kind == "terrain_solid") {
            float radius = 0.0f, weight = kSolidWeight;
            if (!r_.expectObject(v, kp) || !r_.onlyKeys(v, kp, {"radius", "weight", "stroke"})) return false;
            if (!has_terrain_) return r_.fail(kp, "the project has no terrain (add a top-level \"terrain\")");
            if (!radiusField(v, kp, "radius", &radius) || !number(v, kp, "weight", &weight, false))
                return false;
            prim = makeTerrainSolid(0, radius, weight);
        } else {
            return r_.fail(kp, "unknown field node kind '" + kind +
                                   "' (point, segment, disc, box, half_space, terrain_layer, terrain_solid, "
                                   "polyline, blend, union, intersection, difference)");
        }
        if (!r_.integer(v, kp, "stroke", &prim.stroke, 1, UINT32_MAX)) return false;
        // The checks above give the precise member; this backstop keeps the reader and the field's own
        // rules from drifting apart.
        std::string why;
        if (!validatePrimitive(prim, f_->primitives.size(), has_terrain_ ? 1 : 0, &why))
            return r_.fail(kp, why);
        if (!room(kp, 1, 0)) return false;
        *ref = primitiveChild(addPrimitive(f_, prim));
        return true;
    }

  private:
    bool room(const std::string& p, size_t primitives, size_t nodes) {
        if (f_->primitives.size() + primitives > kMaxFieldPrimitives)
            return r_.fail(p,
                           "more than " + std::to_string(kMaxFieldPrimitives) + " primitives in one field");
        if (f_->nodes.size() + nodes > kMaxFieldNodes)
            return r_.fail(p, "more than " + std::to_string(kMaxFieldNodes) + " operator nodes in one field");
        return true;
    }

    bool op(FieldOp o, const json& v, const std::string& p, int depth, uint32_t* ref) {
        if (!v.is_array())
            return r_.fail(p, "expected an array of field nodes, got " + JsonReader::typeName(v));
        std::vector<uint32_t> refs;
        refs.reserve(v.size());
        for (size_t k = 0; k < v.size(); ++k) {
            uint32_t child = 0;
            if (!node(v[k], p + "/" + std::to_string(k), depth + 1, &child)) return false;
            refs.push_back(child);
        }
        if (!room(p, 0, 1)) return false;
        *ref = nodeChild(addNode(f_, o, refs));
        return true;
    }

    bool polyline(const json& v, const std::string& p, uint32_t* ref) {
        float weight = 1.0f;
        if (!r_.expectObject(v, p) || !r_.onlyKeys(v, p, {"vertices", "weight"}) ||
            !r_.require(v, p, "vertices") || !number(v, p, "weight", &weight, false))
            return false;
        const json& verts = v["vertices"];
        const std::string vp = p + "/vertices";
        if (!r_.expectArray(verts, vp)) return false;
        if (verts.size() < 2)
            return r_.fail(vp, "a polyline needs at least 2 vertices, got " + std::to_string(verts.size()));
        if (!room(p, verts.size() - 1, 1)) return false;  // before reading a million vertices for nothing
        std::vector<glm::vec4> vertices;
        vertices.reserve(verts.size());
        for (size_t k = 0; k < verts.size(); ++k) {
            const json& q = verts[k];
            const std::string qp = vp + "/" + std::to_string(k);
            if (!q.is_array() || q.size() != 4) return r_.fail(qp, "expected [x, y, z, radius]");
            glm::vec4 vert;
            for (int a = 0; a < 4; ++a)
                if (!finiteFloat(q[a], qp + "/" + std::to_string(a), &vert[a])) return false;
            if (!(vert.w > 0.0f)) return r_.fail(qp + "/3", "radius must be > 0, got " + fmt(vert.w));
            vertices.push_back(vert);
        }
        std::string why;
        if (!addPolyline(f_, vertices, weight, ref, &why)) return r_.fail(p, why);
        return true;
    }

    bool finiteFloat(const json& v, const std::string& p, float* out) {
        if (!v.is_number()) return r_.fail(p, "expected a number, got " + JsonReader::typeName(v));
        const float f = float(v.get<double>());
        if (!std::isfinite(f)) return r_.fail(p, "not a finite number (single precision)");
        *out = f;
        return true;
    }

    bool number(const json& obj, const std::string& p, const char* key, float* out, bool required) {
        auto it = obj.find(key);
        if (it == obj.end()) return !required || r_.fail(p + "/" + key, "missing (required)");
        return finiteFloat(*it, p + "/" + key, out);
    }

    bool radiusField(const json& obj, const std::string& p, const char* key, float* out) {
        if (!number(obj, p, key, out, true)) return false;
        return *out > 0.0f || r_.fail(p + "/" + key, "must be > 0, got " + fmt(*out));
    }

    bool nonNegative(const json& obj, const std::string& p, const char* key, float* out) {
        if (!number(obj, p, key, out, true)) return false;
        return *out >= 0.0f || r_.fail(p + "/" + key, "must be >= 0, got " + fmt(*out));
    }

    bool vec3(const json& obj, const std::string& p, const char* key, glm::vec3* out) {
        auto it = obj.find(key);
        const std::string kp = p + "/" + key;
        if (it == obj.end()) return r_.fail(kp, "missing (required)");
        if (!it->is_array() || it->size() != 3) return r_.fail(kp, "expected [x, y, z]");
        for (int a = 0; a < 3; ++a)
            if (!finiteFloat((*it)[a], kp + "/" + std::to_string(a), &(*out)[a])) return false;
        return true;
    }

    bool normal(const json& obj, const std::string& p, const char* key, glm::vec3* out) {
        if (!vec3(obj, p, key, out)) return false;
        if (*out == glm::vec3(0.0f)) return r_.fail(p + "/" + key, "must not be zero");
        *out = documentUnitVector(*out);
        if (!std::isfinite(out->x) || !std::isfinite(out->y) || !std::isfinite(out->z))
            return r_.fail(p + "/" + key, "too large to normalize");
        return true;
    }

    JsonReader& r_;
    bool has_terrain_;
    DensityField* f_;
};

json vec3Json(glm::vec3 v) {
    return json::array({jsonFloat(v.x), jsonFloat(v.y), jsonFloat(v.z)});
}

json primitiveJson(const Primitive& p) {
    switch (p.kind) {
        case PrimitiveKind::Point:
            return {{"point",
                     {{"center", vec3Json(p.center_m)},
                      {"radius", jsonFloat(p.radius_m)},
                      {"weight", jsonFloat(p.weight)}}}};
        case PrimitiveKind::Segment: {
            json s = {{"a", vec3Json(p.center_m)},
                      {"b", vec3Json(p.end_m)},
                      {"radius", jsonFloat(p.radius_m)},
                      {"weight", jsonFloat(p.weight)}};
            if (p.end_radius_m != p.radius_m) s["end_radius"] = jsonFloat(p.end_radius_m);
            return {{"segment", s}};
        }
        case PrimitiveKind::Disc:
            return {{"disc",
                     {{"center", vec3Json(p.center_m)},
                      {"normal", vec3Json(p.normal)},
                      {"disc_radius", jsonFloat(p.disc_radius_m)},
                      {"radius", jsonFloat(p.radius_m)},
                      {"weight", jsonFloat(p.weight)}}}};
        case PrimitiveKind::Box:
            return {{"box",
                     {{"center", vec3Json(p.center_m)},
                      {"half_extents", vec3Json(p.half_extents_m)},
                      {"radius", jsonFloat(p.radius_m)},
                      {"weight", jsonFloat(p.weight)}}}};
        case PrimitiveKind::HalfSpace:
            return {{"half_space",
                     {{"point", vec3Json(p.center_m)},
                      {"normal", vec3Json(p.normal)},
                      {"radius", jsonFloat(p.radius_m)},
                      {"weight", jsonFloat(p.weight)}}}};
        case PrimitiveKind::TerrainLayer:
            return {{"terrain_layer",
                     {{"thickness", jsonFloat(p.thickness_m)},
                      {"radius", jsonFloat(p.radius_m)},
                      {"weight", jsonFloat(p.weight)}}}};
        case PrimitiveKind::TerrainSolid:
            return {{"terrain_solid", {{"radius", jsonFloat(p.radius_m)}, {"weight", jsonFloat(p.weight)}}}};
        case PrimitiveKind::External:
            break;  // compiled from a type's scatter settings (scene_compile.h), never part of a document
    }
    return nullptr;
}

// With its stroke tag, when it has one: {"segment": {..., "stroke": 3}}.
json taggedPrimitiveJson(const Primitive& p) {
    json j = primitiveJson(p);
    if (p.stroke != 0 && j.is_object()) j.begin().value()["stroke"] = p.stroke;
    return j;
}

json childJson(const DensityField& f, uint32_t ref) {
    if (isPrimitiveChild(ref)) return taggedPrimitiveJson(f.primitives[childIndex(ref)]);
    const FieldNode& n = f.nodes[ref];
    json children = json::array();
    for (uint32_t c = 0; c < n.child_count; ++c)
        children.push_back(childJson(f, f.children[n.first_child + c]));
    return {{fieldOpName(n.op), std::move(children)}};
}

}  // namespace

bool readDensityField(JsonReader& r, const json& j, const std::string& pointer, bool has_terrain,
                      DensityField* out) {
    DensityField field;
    FieldReader reader(r, has_terrain, &field);
    uint32_t ref = 0;
    if (!reader.node(j, pointer, 1, &ref)) return false;
    if (isPrimitiveChild(ref)) ref = addNode(&field, FieldOp::Blend, std::span<const uint32_t>(&ref, 1));
    field.root = ref;
    *out = std::move(field);
    return true;
}

json densityFieldToJson(const DensityField& field) {
    if (field.root == kNoNode) return nullptr;
    return childJson(field, nodeChild(field.root));
}

glm::vec3 documentUnitVector(glm::vec3 v) {
    const float len = glm::length(v);
    if (std::abs(len - 1.0f) <= 1e-6f) return v;
    return len > 0.0f && std::isfinite(len) ? v / len : v;
}

json jsonFloat(float v) {
    if (!std::isfinite(v)) return json(double(v));  // not reached for valid documents (written as null)
    char buf[32];
    for (int precision = 1; precision <= 9; ++precision) {  // 9 significant digits always round-trip a float
        std::snprintf(buf, sizeof(buf), "%.*g", precision, double(v));
        const double d = std::strtod(buf, nullptr);
        if (float(d) == v) return json(d);
    }
    return json(double(v));  // not reached
}

}  // namespace ug
