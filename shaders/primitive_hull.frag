#version 430 core
// primitive_hull: the translucent hull around a user primitive's skeleton (markers.h), blended over the
// scene, depth-tested against it but writing no depth (hulls behind hulls still show).
// Interface: v_lit (display RGB) from skeleton_marker.vert; u_alpha (opacity, 0..1).
in vec3 v_lit;
uniform float u_alpha;
out vec4 o_color;
void main() { o_color = vec4(v_lit, u_alpha); }
