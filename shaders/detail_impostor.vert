#version 430 core
// detail_impostor: the far representation, one point sprite per instance (GL_POINTS, no triangles),
// centred on the instance's bounding-box centre, as wide on screen as the model's mean projected size.
// Beyond the impostor distance an object covers a few pixels, where a square of its colour and light
// reads the same as its mesh and costs llvmpipe a fraction of a triangle.
// Interface: a_instance (2, per vertex here: one vertex per instance), as instanced_detail.vert;
// buffer 0 = candidate frames; u_view_proj, u_tile_size_m, u_color, u_center (model space),
// u_half_size_m, u_point_scale (pixels per metre at unit depth), u_to_eye (unit, toward the camera),
// plus lighting.glsl's; out v_lit, the display colour.
layout(location = 2) in uvec2 a_instance;

struct CandidateFrame {
    vec4 position_scale;
    vec4 rotation;
};
layout(std430, binding = 0) readonly buffer CandidateFrames { CandidateFrame u_frames[]; };

uniform mat4 u_view_proj;
uniform float u_tile_size_m;
uniform float u_drop_unit_m;
uniform vec3 u_color;
uniform vec3 u_center;
uniform float u_half_size_m;
uniform float u_point_scale;
uniform vec3 u_to_eye;
out vec3 v_lit;

vec3 rotate(vec4 q, vec3 v) {
    vec3 t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

void main() {
    // Sign-extend the tile coordinates (16, 16 and 9 bits; arithmetic shifts of a signed int).
    ivec3 tile = ivec3(int(a_instance.x << 16) >> 16, int(a_instance.x) >> 16, int(a_instance.y << 23) >> 23);
    // The settled drop, in steps of u_drop_unit_m (render_data.h).
    float drop = float(a_instance.y >> 25) * u_drop_unit_m;
    CandidateFrame f = u_frames[(a_instance.y >> 9) & 0xffffu];
    float scale = f.position_scale.w;
    vec3 world = vec3(tile) * u_tile_size_m + f.position_scale.xyz + rotate(f.rotation, scale * u_center) -
                 vec3(0.0, 0.0, drop);
    // The model's +Z as the normal (a leaf's face, a tuft's up), turned toward the eye: the sprite is lit
    // like the object's dominant facet.
    vec3 n = rotate(f.rotation, vec3(0.0, 0.0, 1.0));
    n = dot(n, u_to_eye) < 0.0 ? -n : n;
    uint h = (a_instance.x * 2654435761u) ^ ((a_instance.y & 0x1ffffffu) * 2246822519u);  // not the drop: stable colours
    h ^= h >> 15;
    h *= 2246822519u;
    h ^= h >> 13;
    vec3 albedo = u_color * (0.9 + 0.2 * float(h & 1023u) / 1023.0);
    // Lit once per point (lighting.glsl), not per pixel: a sprite is one colour anyway.
    v_lit = toDisplay(shadeSurface(albedo, n, world));
    gl_Position = u_view_proj * vec4(world, 1.0);
    gl_PointSize = max(1.0, 2.0 * scale * u_half_size_m * u_point_scale / max(gl_Position.w, 1e-4));
}
