#version 430 core
// ground_grid: a large square at height u_ground_z around u_grid_center, drawn when there is no terrain.
// Interface: no attributes (a 4-vertex strip); u_view_proj, u_grid_center, u_grid_half_m, u_ground_z.
uniform mat4 u_view_proj;
uniform vec2 u_grid_center;
uniform float u_grid_half_m;
uniform float u_ground_z;
out vec3 v_world;
void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
    v_world = vec3(u_grid_center + corner * u_grid_half_m, u_ground_z);
    gl_Position = u_view_proj * vec4(v_world, 1.0);
}
