// How a detail type (or the terrain) looks: a PBR base colour and roughness, and an optional procedural
// texture (procedural_texture.h) mapped by box projection (uv_projection.h). GL-free: the editor's
// renderer and the glTF exporter read the same values, so the viewport and the export match.
//
// Scene JSON (scene/material_json.h): "material": {"base_color": [r, g, b], "roughness", "texture",
// "texture_scale_m", "texture_rotation_deg", "tint_variation", "alpha_cutout"}, every key optional.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace ug {

enum class TextureKind : uint8_t { None, Rock, Leaf, Bark, Grass, Ground, Hay };

// "none", "rock", "leaf", "bark", "grass", "ground", "hay".
const char* textureKindName(TextureKind kind);
// False for an unknown name (*out untouched).
bool parseTextureKind(const std::string& name, TextureKind* out);
// Every kind's name, in enum order, for messages ("none, rock, leaf, ...").
std::string textureKindNames();

// Ranges the scene reader enforces (and the exporter relies on).
constexpr float kMinTextureScaleM = 1e-3f;  // one repeat per millimetre: finer is noise on any screen
constexpr float kMaxTextureScaleM = 1e3f;
constexpr float kDefaultRoughness = 0.9f;   // what exports used before materials existed
constexpr float kDefaultTextureScaleM = 0.2f;
constexpr float kMaxTextureRotationDeg = 360.0f;  // |rotation|: a full turn either way

// As the user sets it. The defaults reproduce the look before materials existed: the model's own
// base colour (the terrain's kTerrainColor), roughness 0.9, no texture.
struct Material {
    std::optional<glm::vec3> base_color;     // linear RGB, each in [0, 1]; absent: the model's colour
    float roughness = kDefaultRoughness;     // [0, 1]
    TextureKind texture = TextureKind::None;
    float texture_scale_m = kDefaultTextureScaleM;  // metres per texture repeat, [kMin, kMax]TextureScaleM
    // The texture turned in its uv plane (rotateTextureUv, uv_projection.h), degrees in
    // [-kMax, kMax]TextureRotationDeg. Bark's fibres run along u, which the box projection lays
    // horizontally on an upright trunk; 90 stands them up.
    float texture_rotation_deg = 0.0f;
    float tint_variation = 0.0f;             // [0, 1]: per-instance spread of brightness and hue
    bool alpha_cutout = false;               // the texture's alpha cuts the surface (glTF alphaMode MASK)

    bool operator==(const Material&) const = default;
};

// A tileable RGBA8 image, rows top to bottom (row 0 is v = 0 in glTF and t = 0 in GL when uploaded
// as-is), 4 bytes per pixel.
struct TextureImage {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;  // width * height * 4
};

// A material with every default resolved against its surface, plus its baked texture: what the renderer
// draws and the exporter writes.
struct SurfaceMaterial {
    glm::vec3 base_color{0.6f};  // linear RGB, the surface's average colour
    float roughness = kDefaultRoughness;
    TextureKind texture_kind = TextureKind::None;
    float texture_scale_m = kDefaultTextureScaleM;
    float texture_rotation_deg = 0.0f;
    float tint_variation = 0.0f;
    bool alpha_cutout = false;
    // Null when texture_kind is None. Otherwise the FINAL colour, sRGB-encoded (upload as
    // GL_SRGB8_ALPHA8; glTF baseColorTexture, factor 1): base_color x the kind's detail map, whose
    // linear mean is 1 per channel, so the texture's average linear colour is base_color. Alpha is
    // coverage: 255 except where an alpha_cutout texture cuts (compare with 0.5, as glTF's alphaCutoff).
    std::shared_ptr<const TextureImage> texture;
    bool operator==(const SurfaceMaterial&) const = default;  // the texture by object
};

// Every surface of a scene: one per detail look (the project's types in order, then their scatter variants,
// scene/detail_looks.h) and the terrain's.
struct SceneMaterials {
    std::vector<SurfaceMaterial> types;
    SurfaceMaterial terrain;
};

// How much of the sky a surface mirrors in the viewport, from its roughness: 1 - roughness /
// kGlossyRoughness, clamped to [0, 1]. Water (0.1) mirrors three quarters; rough surfaces (every material
// at or above kGlossyRoughness, the default 0.9 among them) none, so they shade as they did before
// roughness was drawn. Only environmental objects are drawn glossy (their own shader variant); detail
// types and the terrain stay matte whatever their roughness. The export writes roughness as glTF's
// roughnessFactor, for any PBR viewer.
constexpr float kGlossyRoughness = 0.4f;
float materialGloss(float roughness);

// Resolves `m` for a surface whose own colour is `surface_color` (the model's base colour, or
// kTerrainColor) and bakes its texture (bakeMaterialTexture, procedural_texture.h).
SurfaceMaterial resolveMaterial(const Material& m, glm::vec3 surface_color);

// The per-instance colour multiplier for tint_variation (glTF has no per-instance colour, so exports
// carry tint_variation in the material's extras and this is for renderers). `key` is any 32-bit id of
// the instance that is stable across frames (e.g. its candidate index xor the low bits of its tile key).
// Pure integer hashing and float arithmetic, so a shader can mirror it exactly:
//   h = lowbias32(key)            (x ^= x >> 16; x *= 0x7feb352d; x ^= x >> 15; x *= 0x846ca68b; x ^= x >> 16)
//   a = float(h & 0xffff) / 65535, b = float(h >> 16) / 65535             (both in [0, 1])
//   brightness = 1 + variation * 0.5 * (2a - 1)                             ([1 - v/2, 1 + v/2])
//   warmth     = variation * 0.25 * (2b - 1)
//   tint       = brightness * (1 + warmth, 1, 1 - warmth)
// variation 0 gives exactly (1, 1, 1).
uint32_t lowbias32(uint32_t x);
glm::vec3 instanceTint(float variation, uint32_t key);

}  // namespace ug
