#version 430 core
// skeleton_marker: the user primitives' skeletons and the brush outline, as lines and points, unlit.
// Interface: a_position (0), a_color (1); u_view_proj, u_point_size.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_color;
uniform mat4 u_view_proj;
uniform float u_point_size;
out vec3 v_lit;
void main() {
    v_lit = a_color;
    gl_PointSize = u_point_size;
    gl_Position = u_view_proj * vec4(a_position, 1.0);
}
