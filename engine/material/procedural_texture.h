// Procedural, tileable textures for materials (material.h): one pattern per TextureKind, made from
// integer hashing and basic float arithmetic only (no std:: random distributions, no libm
// transcendental functions), so the same kind, seed and size give the same bytes on every machine.
// The source file is compiled with -ffp-contract=off so that no compiler fuses the arithmetic.
//
// Two images:
//   detail map  RGB = the pattern as a multiplier of the base colour, stored as round(detail * 128)
//               (so 128 = 1.0 and the largest is 255/128 ~ 2.0), linear; its mean over the covered
//               pixels is 1.0 per channel (within rounding), so base_color stays the surface's average
//               colour. A = coverage: 255, or 0 where an alpha cut-out removes the surface.
//   baked       RGB = sRGB(clamp(base_color * detail, 0, 1)), A copied: what the renderer samples and
//               the exporter writes (glTF baseColorTexture is sRGB).
// Patterns, in texture space (u right, v down the rows, one repeat per texture_scale_m):
//   rock    grain, dark and light speckle, a few thin dark cracks;
//   leaf    a midrib along u through the tile's corner (u = v = 0: a leaf model centred on its origin,
//           long along X, with texture_scale_m = its length, gets the midrib on its own), with lateral
//           veins; as a cut-out, the alpha is one leaf outline per repeat, centred on that corner;
//   bark    fibres along u (so along X on the Y- and Z-facing sides of a box-projected branch modelled
//           along X, like the starter twig), darker furrows between plates;
//   grass   blade streaks along v with per-blade shade; as a cut-out, thin gaps between blades;
//   ground  soil with small pebbles and grit;
//   hay     crossing straw streaks (steep diagonals) with dark gaps.
// Every image wraps: column width-1 continues into column 0 and row height-1 into row 0.
#pragma once

#include <cstdint>

#include "material/material.h"

namespace ug {

constexpr int kTextureSize = 256;           // pixels per side of the materials' textures
constexpr uint64_t kTextureSeed = 2016;     // the seed materials use (the starter assets' seed)
constexpr int kMinTextureSize = 16;
constexpr int kMaxTextureSize = 2048;
constexpr int kDetailOne = 128;             // the detail map's byte for a multiplier of 1.0

// The detail map of `kind` (see above). `size` is clamped to [kMinTextureSize, kMaxTextureSize] and
// must be a power of two for the patterns to wrap exactly (asserted). TextureKind::None gives a flat
// map (every pixel 128, 128, 128, 255).
TextureImage makeDetailMap(TextureKind kind, bool alpha_cutout, uint64_t seed = kTextureSeed,
                           int size = kTextureSize);

// The final colour texture from a detail map (see above).
TextureImage bakeTexture(const TextureImage& detail_map, glm::vec3 base_color);

// makeDetailMap then bakeTexture.
TextureImage bakeMaterialTexture(TextureKind kind, bool alpha_cutout, glm::vec3 base_color,
                                 uint64_t seed = kTextureSeed, int size = kTextureSize);

// The sRGB transfer function (IEC 61966-2-1) to and from 8 bits, computed with basic arithmetic only
// (deterministic). Values outside [0, 1] are clamped.
uint8_t linearToSrgb8(float linear);
float srgb8ToLinear(uint8_t code);

}  // namespace ug
