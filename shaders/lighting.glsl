// The light model every surface shares (inserted after each fragment shader's #version line):
//   hemisphere ambient (sky from above, warm ground bounce from below), one directional sun, and a haze
//   that thickens with distance toward the sky's horizon colour. Linear RGB in, display (gamma 2) out.
// Interface: u_sun_dir (unit, toward the sun), u_eye (world), u_fog_density (1/m).
uniform vec3 u_sun_dir;
uniform vec3 u_eye;
uniform float u_fog_density;

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

vec3 shadeSurface(vec3 albedo, vec3 n, vec3 world) {
    float ndl = max(dot(n, u_sun_dir), 0.0);
    vec3 ambient = mix(kGroundBounce, kSkyLight, 0.5 + 0.5 * n.z);
    vec3 c = albedo * (ambient + 1.1 * kSunColor * ndl);
    vec3 to_point = world - u_eye;
    float d = length(to_point);
    float fog = 1.0 - exp(-d * u_fog_density);
    return mix(c, skyColor(to_point / max(d, 1e-6)), clamp(fog, 0.0, 1.0));
}

// Gamma 2 (sqrt) rather than 2.2: within a few levels of sRGB in the mid-tones, and much cheaper per pixel.
vec3 toDisplay(vec3 linear_rgb) { return sqrt(clamp(linear_rgb, 0.0, 1.0)); }
