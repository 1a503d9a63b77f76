#version 430 core
// static_mesh: one static mesh (io/mesh_instances.h: an environmental object's base geometry, a snow cover,
// an icicle shape) at its instances, drawn with glDrawElementsInstanced.
// Interface: a_position (0), a_normal (1) in object space; per instance (divisor 1) a_position_scale (2:
// engine-space position, uniform scale) and a_rotation (3: unit quaternion x, y, z, w), render_data.h
// GpuStaticInstance; u_view_proj, u_color. Its texture is the box projection of the object-space position
// (lit_surface.frag mode 1), as the exporter writes TEXCOORD_0.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_position_scale;
layout(location = 3) in vec4 a_rotation;
uniform mat4 u_view_proj;
uniform vec3 u_color;
out vec3 v_world;
out vec3 v_model;
out vec3 v_tint;
out vec3 v_normal;
out vec3 v_color;

vec3 rotate(vec4 q, vec3 v) {
    vec3 t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

void main() {
    v_world = a_position_scale.xyz + rotate(a_rotation, a_position_scale.w * a_position);
    v_normal = rotate(a_rotation, a_normal);
    v_tint = vec3(1.0);
    v_color = u_color;
    v_model = a_position;
    gl_Position = u_view_proj * vec4(v_world, 1.0);
}
