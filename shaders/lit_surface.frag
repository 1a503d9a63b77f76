#version 430 core
// lit_surface: terrain, details and impostors; lighting.glsl's sky + sun + haze.
// Interface: v_world, v_normal, v_color (linear RGB) from the vertex stage.
in vec3 v_world;
in vec3 v_normal;
in vec3 v_color;
out vec4 o_color;
void main() {
    vec3 n = normalize(v_normal);
    // Thin sheets (leaves, blades) are seen from both sides: light the side that faces the viewer.
    if (!gl_FrontFacing) n = -n;
    vec3 lit = shadeSurface(v_color, n, v_world);
    // Alpha carries the ambient share to the ambient occlusion pass (composite.frag).
    o_color = vec4(toDisplay(lit), g_ambient_share);
}
