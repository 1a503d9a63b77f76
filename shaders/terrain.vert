#version 430 core
// terrain: the height field mesh, world space already.
// Interface: a_position (0), a_normal (1); u_view_proj, u_color.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_view_proj;
uniform vec3 u_color;
out vec3 v_world;
out vec3 v_normal;
out vec3 v_color;
out vec3 v_model;  // the texture's coordinates come from world X and Y (lit_surface.frag mode 2)
out vec3 v_tint;
void main() {
    v_world = a_position;
    v_normal = a_normal;
    // Steeper ground shows more bare earth, flatter ground a little more moss: a cue to the relief that
    // needs no texture.
    float flatness = smoothstep(0.85, 1.0, a_normal.z);
    v_tint = mix(vec3(1.1, 0.95, 0.85), vec3(0.9, 1.1, 0.8), flatness);
    v_color = u_color * v_tint;
    v_model = a_position;
    gl_Position = u_view_proj * vec4(a_position, 1.0);
}
