#version 430 core
// flat_color: the colour the vertex stage gave (overlay lines and points).
// Interface: v_lit (display RGB).
in vec3 v_lit;
out vec4 o_color;
void main() { o_color = vec4(v_lit, 1.0); }
