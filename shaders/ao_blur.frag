#version 430 core
// ao_blur: the half-resolution occlusion averaged over 4 x 4 texels (four bilinear taps a texel apart),
// which removes ambient_occlusion.frag's 4 x 4 sampling pattern; at half resolution, so the full-resolution
// composite reads it once.
// Interface: u_ao (the raw occlusion, half resolution, bilinear); out the blurred occlusion.
out vec4 o_ao;
uniform sampler2D u_ao;
void main() {
    vec2 texel = 1.0 / vec2(textureSize(u_ao, 0));
    vec2 uv = gl_FragCoord.xy * texel;  // the corner shared by this texel and its upper-right neighbours
    o_ao = vec4(0.25 * (texture(u_ao, uv + vec2(-1.0, -1.0) * texel).r + texture(u_ao, uv + vec2(1.0, -1.0) * texel).r +
                        texture(u_ao, uv + vec2(-1.0, 1.0) * texel).r + texture(u_ao, uv + vec2(1.0, 1.0) * texel).r));
}
