#version 430 core
// ambient_occlusion: screen-space ambient occlusion where surfaces meet (a rock on the ground, rocks in a
// pile, grass at its base), at half resolution (a quarter of the pixels: llvmpipe's budget); composite.frag
// blurs it back up. The occlusion of a pixel: 8 samples on a disc of u_ao_radius_m around it (projected,
// a golden-angle spiral turned per pixel by a 4 x 4 pattern that the blur's 4 x 4 footprint averages
// out); a sample occludes by how far it rises above the pixel's tangent plane (the normal comes from the
// depth of the nearer neighbours, so silhouettes do not smear), fading out beyond the radius so a far
// wall behind an edge does not darken it.
// Interface: u_depth (the scene pass's full-resolution depth), u_near_far, u_tan_half_fov (x, y),
// u_ao_radius_m; out: the ambient visibility (1 = open sky) in the red channel.
out vec4 o_ao;
uniform sampler2D u_depth;
uniform vec2 u_near_far;
uniform vec2 u_tan_half_fov;
uniform float u_ao_radius_m;
uniform float u_ao_strength;

float viewDepth(float d) {
    float n = u_near_far.x, f = u_near_far.y;
    return 2.0 * n * f / ((f + n) - (2.0 * d - 1.0) * (f - n));
}

// View-space position (camera looks down -z) of pixel `px`.
vec3 viewPos(ivec2 px, ivec2 size) {
    float z = viewDepth(texelFetch(u_depth, clamp(px, ivec2(0), size - 1), 0).r);
    vec2 ndc = (vec2(px) + 0.5) / vec2(size) * 2.0 - 1.0;
    return vec3(ndc * u_tan_half_fov * z, -z);
}

void main() {
    ivec2 size = textureSize(u_depth, 0);
    ivec2 px = ivec2(gl_FragCoord.xy) * 2;  // this half-resolution pixel's first full-resolution pixel
    float d = texelFetch(u_depth, px, 0).r;
    if (d >= 1.0) {
        o_ao = vec4(1.0);
        return;
    }
    vec3 p = viewPos(px, size);
    // Tangents from the neighbour on the nearer side in x and in y: across a silhouette the far side
    // belongs to another surface.
    vec3 l = viewPos(px - ivec2(1, 0), size), r = viewPos(px + ivec2(1, 0), size);
    vec3 b = viewPos(px - ivec2(0, 1), size), t = viewPos(px + ivec2(0, 1), size);
    vec3 dx = abs(r.z - p.z) < abs(p.z - l.z) ? r - p : p - l;
    vec3 dy = abs(t.z - p.z) < abs(p.z - b.z) ? t - p : p - b;
    vec3 n = normalize(cross(dx, dy));
    float z = -p.z;
    float radius_px = u_ao_radius_m * 0.5 * float(size.y) / (u_tan_half_fov.y * z);
    if (radius_px < 2.0) {  // the disc is inside a pixel or two: nothing to resolve
        o_ao = vec4(1.0);
        return;
    }
    radius_px = min(radius_px, 96.0);
    // A 4 x 4 ordered pattern (Bayer): every 4 x 4 block turns the spiral through 16 even steps.
    ivec2 q = ivec2(gl_FragCoord.xy) & 3;
    const int kBayer[16] = int[16](0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5);
    float turn = (float(kBayer[q.y * 4 + q.x]) + 0.5) / 16.0;
    float occlusion = 0.0;
    const int kSamples = 8;
    float r2 = u_ao_radius_m * u_ao_radius_m;
    for (int i = 0; i < kSamples; ++i) {
        float s = (float(i) + 0.5) / float(kSamples);
        float a = 2.39996323 * float(i) + 6.2831853 * turn;
        vec2 o = vec2(cos(a), sin(a)) * radius_px * sqrt(s);
        vec3 sp = viewPos(px + ivec2(round(o)), size);
        vec3 v = sp - p;
        float vv = dot(v, v);
        float rise = dot(v, n) * inversesqrt(vv + 1e-8);
        occlusion += clamp(rise - 0.05, 0.0, 1.0) * max(0.0, 1.0 - vv / r2);
    }
    o_ao = vec4(max(0.0, 1.0 - 2.0 * occlusion / float(kSamples)));
}
