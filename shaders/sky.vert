#version 430 core
// sky: one triangle covering the screen at the far plane, drawn after the scene with depth test LEQUAL so
// that only the pixels nothing covers pay for the sky shader (llvmpipe tests depth before shading).
// Interface: no attributes; u_view_to_world (camera rotation), u_tan_half_fov (x, y); out v_dir, the
// unnormalised world direction of the pixel's view ray (linear across the screen in view space).
uniform mat3 u_view_to_world;
uniform vec2 u_tan_half_fov;
out vec3 v_dir;
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
    v_dir = u_view_to_world * vec3(p * u_tan_half_fov, -1.0);
    gl_Position = vec4(p, 1.0, 1.0);
}
