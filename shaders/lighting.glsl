// The light model every surface shares (inserted after each fragment shader's #version line):
//   hemisphere ambient (sky from above, warm ground bounce from below), one directional sun, and a haze
//   that thickens with distance toward the sky's horizon colour. Linear RGB in, display (gamma 2) out.
// The sun is shadowed through a shadow map (renderer.cpp's shadow pass, shadow_frame.h's view), filtered
// by percentage-closer filtering (one hardware-compared bilinear tap: edges soft over a texel, which the
// map's fit to the view keeps a few millimetres wide close up).
// Interface: u_sun_dir (unit, toward the sun), u_eye (world), u_fog_density (1/m); u_shadow_map (a depth
// texture with compare mode), u_shadow_texture (world -> shadow texture coordinates and depth),
// u_shadow_strength (0: no shadow map; 1: full), u_shadow_offset_m (the lookup moves this far along the
// normal: no self-shadowing acne on surfaces that face the sun at a grazing angle).
// shadeSurface also leaves in g_ambient_share the share of the light it returned that is sky and bounce
// light, which the ambient occlusion pass darkens most (composite.frag).
uniform vec3 u_sun_dir;
uniform vec3 u_eye;
uniform float u_fog_density;
uniform sampler2DShadow u_shadow_map;
uniform mat4 u_shadow_texture;
uniform float u_shadow_strength;
uniform float u_shadow_offset_m;

float g_ambient_share = 1.0;

// material.h instanceTint: the per-instance colour multiplier for a material's tint_variation (brightness
// and warmth from lowbias32 of a stable instance key).
uint lowbias32(uint x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}
vec3 instanceTint(float variation, uint key) {
    uint h = lowbias32(key);
    float a = float(h & 0xffffu) / 65535.0, b = float(h >> 16) / 65535.0;
    float brightness = 1.0 + variation * 0.5 * (2.0 * a - 1.0);
    float warmth = variation * 0.25 * (2.0 * b - 1.0);
    return brightness * vec3(1.0 + warmth, 1.0, 1.0 - warmth);
}

const vec3 kZenith = vec3(0.16, 0.33, 0.72);
const vec3 kHorizon = vec3(0.60, 0.72, 0.86);
const vec3 kBelowHorizon = vec3(0.52, 0.60, 0.68);
const vec3 kSkyLight = vec3(0.30, 0.36, 0.48);
const vec3 kGroundBounce = vec3(0.12, 0.10, 0.07);
const vec3 kSunColor = vec3(1.00, 0.92, 0.80);

// Cheap on purpose (sqrt and multiplications, no pow): on llvmpipe the sky and the haze are shaded for
// most of the screen's pixels.
vec3 skyColor(vec3 dir) {
    float h = dir.z;
    vec3 c = h >= 0.0 ? mix(kHorizon, kZenith, sqrt(h)) : mix(kHorizon, kBelowHorizon, clamp(-h * 3.0, 0.0, 1.0));
    float s = max(dot(dir, u_sun_dir), 0.0);
    float s2 = s * s, s4 = s2 * s2, s8 = s4 * s4;
    float s64 = s8 * s8; s64 *= s64; s64 *= s64;
    return c + kSunColor * (0.25 * s8 + 1.5 * s64 * s64 * s64 * s64);
}

// 1 where the sun reaches `world`, 0 in full shadow.
float sunVisibility(vec3 world, vec3 n) {
    if (u_shadow_strength <= 0.0) return 1.0;
    vec4 s = u_shadow_texture * vec4(world + n * u_shadow_offset_m, 1.0);
    vec3 t = s.xyz / s.w;
    if (any(lessThan(t, vec3(0.0))) || any(greaterThan(t, vec3(1.0)))) return 1.0;  // outside the map: lit
    // One hardware-compared bilinear tap (a 2 x 2 percentage-closer filter on Mesa): a four-tap filter
    // looked softer but cost llvmpipe a third of the frame.
    return 1.0 - u_shadow_strength * (1.0 - texture(u_shadow_map, t));
}

// The sky, bounce and sun light on a surface of normal n, before the haze; the sun's visibility given.
vec3 lightSurface(vec3 albedo, vec3 n, float visibility) {
    float ndl = max(dot(n, u_sun_dir), 0.0) * visibility;
    vec3 ambient = mix(kGroundBounce, kSkyLight, 0.5 + 0.5 * n.z);
    vec3 direct = 1.1 * kSunColor * ndl;
    g_ambient_share = dot(ambient, vec3(1.0)) / max(dot(ambient + direct, vec3(1.0)), 1e-6);
    return albedo * (ambient + direct);
}

// The haze between the eye and `world` over a lit colour. Linear in the colour, so a blend of several
// lit normals at one point (the impostors) takes it once.
vec3 hazed(vec3 lit, vec3 world) {
    vec3 to_point = world - u_eye;
    float d = length(to_point);
    float fog = 1.0 - exp(-d * u_fog_density);
    return mix(lit, skyColor(to_point / max(d, 1e-6)), clamp(fog, 0.0, 1.0));
}

vec3 shadeSurface(vec3 albedo, vec3 n, vec3 world) {
    return hazed(lightSurface(albedo, n, dot(n, u_sun_dir) > 0.0 ? sunVisibility(world, n) : 0.0), world);
}

// Gamma 2 (sqrt) rather than 2.2: within a few levels of sRGB in the mid-tones, and much cheaper per pixel.
vec3 toDisplay(vec3 linear_rgb) { return sqrt(clamp(linear_rgb, 0.0, 1.0)); }
