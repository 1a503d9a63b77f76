#version 430 core
// sky: lighting.glsl's skyColor along each pixel's view ray.
// Interface: v_dir; lighting.glsl's u_sun_dir.
in vec3 v_dir;
out vec4 o_color;
void main() { o_color = vec4(toDisplay(skyColor(normalize(v_dir))), 1.0); }
