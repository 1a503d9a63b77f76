#include "material/material.h"

#include <algorithm>

#include "material/procedural_texture.h"

namespace ug {
namespace {

constexpr TextureKind kKinds[] = {TextureKind::None,  TextureKind::Rock,   TextureKind::Leaf, TextureKind::Bark,
                                  TextureKind::Grass, TextureKind::Ground, TextureKind::Hay};

}  // namespace

const char* textureKindName(TextureKind kind) {
    switch (kind) {
        case TextureKind::None: return "none";
        case TextureKind::Rock: return "rock";
        case TextureKind::Leaf: return "leaf";
        case TextureKind::Bark: return "bark";
        case TextureKind::Grass: return "grass";
        case TextureKind::Ground: return "ground";
        case TextureKind::Hay: return "hay";
    }
    return "none";
}

bool parseTextureKind(const std::string& name, TextureKind* out) {
    for (TextureKind k : kKinds)
        if (name == textureKindName(k)) {
            *out = k;
            return true;
        }
    return false;
}

std::string textureKindNames() {
    std::string out;
    for (TextureKind k : kKinds) out += std::string(out.empty() ? "" : ", ") + textureKindName(k);
    return out;
}

float materialGloss(float roughness) {
    if (!(roughness < kGlossyRoughness)) return 0.0f;  // NaN too
    return std::clamp(1.0f - roughness / kGlossyRoughness, 0.0f, 1.0f);
}

SurfaceMaterial resolveMaterial(const Material& m, glm::vec3 surface_color) {
    SurfaceMaterial s;
    s.base_color = glm::clamp(m.base_color.value_or(surface_color), 0.0f, 1.0f);
    s.roughness = m.roughness;
    s.texture_kind = m.texture;
    s.texture_scale_m = m.texture_scale_m;
    s.texture_rotation_deg = m.texture_rotation_deg;
    s.tint_variation = m.tint_variation;
    s.alpha_cutout = m.alpha_cutout;
    if (m.texture != TextureKind::None)
        s.texture = std::make_shared<const TextureImage>(bakeMaterialTexture(m.texture, m.alpha_cutout, s.base_color));
    return s;
}

uint32_t lowbias32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

glm::vec3 instanceTint(float variation, uint32_t key) {
    const uint32_t h = lowbias32(key);
    const float a = float(h & 0xffffu) / 65535.0f, b = float(h >> 16) / 65535.0f;
    const float brightness = 1.0f + variation * 0.5f * (2.0f * a - 1.0f);
    const float warmth = variation * 0.25f * (2.0f * b - 1.0f);
    return brightness * glm::vec3(1.0f + warmth, 1.0f, 1.0f - warmth);
}

}  // namespace ug
