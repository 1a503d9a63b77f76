#include "scene/material_json.h"

#include <cmath>

#include "scene/field_json.h"

namespace ug {

using nlohmann::json;

namespace {
// The bounds are checked on the double; the float it becomes must still be inside them.
bool scaleIsPositive(JsonReader& r, const std::string& p, const Material& m) {
    return m.texture_scale_m >= kMinTextureScaleM || r.fail(p + "/texture_scale_m", "must be >= 0.001");
}
}  // namespace

bool readMaterial(JsonReader& r, const json& j, const std::string& p, Material* out) {
    if (!r.expectObject(j, p) ||
        !r.onlyKeys(j, p, {"base_color", "roughness", "texture", "texture_scale_m", "texture_rotation_deg",
                           "tint_variation", "alpha_cutout"}))
        return false;
    Material m = *out;
    if (auto it = j.find("base_color"); it != j.end()) {
        const std::string cp = p + "/base_color";
        if (!it->is_array() || it->size() != 3) return r.fail(cp, "expected [r, g, b] (linear, each in [0, 1])");
        glm::vec3 c;
        for (int k = 0; k < 3; ++k) {
            const json& v = (*it)[size_t(k)];
            const std::string kp = cp + "/" + std::to_string(k);
            if (!v.is_number()) return r.fail(kp, "expected a number, got " + JsonReader::typeName(v));
            const double x = v.get<double>();
            if (!std::isfinite(x)) return r.fail(kp, "not a finite number");
            if (x < 0.0 || x > 1.0) {
                char buf[96];
                std::snprintf(buf, sizeof(buf), "%g is out of range [0, 1] (linear colour)", x);
                return r.fail(kp, buf);
            }
            c[k] = float(x);
        }
        m.base_color = c;
    }
    if (!r.number(j, p, "roughness", &m.roughness, 0.0, 1.0) ||
        !r.number(j, p, "texture_scale_m", &m.texture_scale_m, 1e-3, 1e3) ||  // kMin/kMaxTextureScaleM
        !scaleIsPositive(r, p, m) ||
        !r.number(j, p, "texture_rotation_deg", &m.texture_rotation_deg, -kMaxTextureRotationDeg, kMaxTextureRotationDeg) ||
        !r.number(j, p, "tint_variation", &m.tint_variation, 0.0, 1.0) ||
        !r.boolean(j, p, "alpha_cutout", &m.alpha_cutout))
        return false;
    std::string texture = textureKindName(m.texture);
    if (!r.string(j, p, "texture", &texture)) return false;
    if (!parseTextureKind(texture, &m.texture))
        return r.fail(p + "/texture", "unknown texture '" + texture + "' (" + textureKindNames() + ")");
    *out = m;
    return true;
}

json materialToJson(const Material& m) {
    json out = json::object();
    if (m.base_color)
        out["base_color"] = json::array({jsonFloat(m.base_color->x), jsonFloat(m.base_color->y), jsonFloat(m.base_color->z)});
    out["roughness"] = jsonFloat(m.roughness);
    out["texture"] = textureKindName(m.texture);
    out["texture_scale_m"] = jsonFloat(m.texture_scale_m);
    if (m.texture_rotation_deg != 0.0f) out["texture_rotation_deg"] = jsonFloat(m.texture_rotation_deg);
    out["tint_variation"] = jsonFloat(m.tint_variation);
    out["alpha_cutout"] = m.alpha_cutout;
    return out;
}

}  // namespace ug
