#version 430 core
// instanced_detail: one detail type at one mesh LOD, one instance per (tile, candidate).
// Interface: a_position (0), a_normal (1) in model space; a_instance (2, per instance) = the packed
// instance of app/editor/render_data.h: x = uint16(t.x) | uint16(t.y) << 16, y = uint9(t.z) | j << 9 |
// drop code << 25; buffer 0 = the Ghost Tile's candidate frames (uploaded once); u_view_proj,
// u_tile_size_m, u_drop_unit_m, u_color, u_tint_variation (material.h); u_eye (lighting.glsl), u_lod_diameter_px (the type's bounding
// diameter on screen at 1 m), u_impostor_px: the per-instance mesh-or-impostor rule of render_data.h
// (drawnAsMesh), whose impostor half detail_impostor.vert draws.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in uvec2 a_instance;

struct CandidateFrame {
    vec4 position_scale;  // xyz: position in the tile (m), w: uniform scale
    vec4 rotation;        // unit quaternion (x, y, z, w)
};
layout(std430, binding = 0) readonly buffer CandidateFrames { CandidateFrame u_frames[]; };

uniform mat4 u_view_proj;
uniform float u_tile_size_m;
uniform float u_drop_unit_m;
uniform vec3 u_color;
uniform float u_lod_diameter_px;
uniform float u_impostor_px;
uniform float u_tint_variation;
out vec3 v_world;
out vec3 v_model;  // model-space position (the texture's box projection, lit_surface.frag)
out vec3 v_tint;   // the instance's colour multiplier (a textured surface's albedo is texture x tint)
out vec3 v_normal;
out vec3 v_color;

vec3 rotate(vec4 q, vec3 v) {
    vec3 t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

void main() {
    // Sign-extend the tile coordinates (16, 16 and 9 bits; arithmetic shifts of a signed int).
    ivec3 tile = ivec3(int(a_instance.x << 16) >> 16, int(a_instance.x) >> 16, int(a_instance.y << 23) >> 23);
    // The settled drop, in steps of u_drop_unit_m (render_data.h).
    float drop = float(a_instance.y >> 25) * u_drop_unit_m;
    uint j = (a_instance.y >> 9) & 0xffffu;
    CandidateFrame f = u_frames[j];
    // render_data.h's instanceHash, bit for bit; the low 10 bits vary the colour, the next 10 the LOD.
    uint h = (a_instance.x * 2654435761u) ^ ((a_instance.y & 0x1ffffffu) * 2246822519u);  // not the drop
    h ^= h >> 15;
    h *= 2246822519u;
    h ^= h >> 13;
    vec3 origin_undropped = vec3(tile) * u_tile_size_m + f.position_scale.xyz;
    float px = u_lod_diameter_px / max(distance(origin_undropped, u_eye), 1e-3);
    if (px < u_impostor_px * (1.0 + 0.6 * float((h >> 10) & 1023u) / 1024.0)) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // an impostor (outside the clip volume: nothing drawn)
        return;
    }
    // tileOrigin(t, s) + p_j + R_j (scale_j v): the engine's expression, so instances sit where the
    // exporter puts them.
    vec3 origin = vec3(tile) * u_tile_size_m;
    v_world = origin + f.position_scale.xyz + rotate(f.rotation, f.position_scale.w * a_position) - vec3(0.0, 0.0, drop);
    v_normal = rotate(f.rotation, a_normal);
    // +-10 % brightness per instance, hashed from (tile, candidate): neighbours of one type do not look cloned.
    v_tint = (0.9 + 0.2 * float(h & 1023u) / 1023.0) * instanceTint(u_tint_variation, h);
    v_color = u_color * v_tint;
    v_model = a_position;
    gl_Position = u_view_proj * vec4(v_world, 1.0);
}
