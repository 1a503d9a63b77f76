#version 430 core
// composite: the scene pass's colour onto the target framebuffer, darkened by the ambient occlusion
// (ambient_occlusion.frag, half resolution), and its depth carried over (gl_FragDepth) so the hulls and
// overlays drawn afterwards are still depth-tested. The occlusion is read through four bilinear taps a
// half-resolution texel apart: a 4 x 4 texel footprint, which averages the sampling pattern away. The
// colour's alpha is the share of ambient light (lighting.glsl): sunlit faces darken less than shaded ones.
// Interface: u_color, u_depth (the scene pass's textures), u_ao (the occlusion), u_ao_strength (0: copy).
out vec4 o_color;
uniform sampler2D u_color;
uniform sampler2D u_depth;
uniform sampler2D u_ao;
uniform float u_ao_strength;

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 c = texelFetch(u_color, px, 0);
    float d = texelFetch(u_depth, px, 0).r;
    gl_FragDepth = d;
    if (u_ao_strength <= 0.0 || d >= 1.0) {
        o_color = vec4(c.rgb, 1.0);
        return;
    }
    vec2 texel = 1.0 / vec2(textureSize(u_ao, 0));
    vec2 uv = (gl_FragCoord.xy * 0.5) * texel;
    float ao = 0.25 * (texture(u_ao, uv + vec2(-1.0, -1.0) * texel).r + texture(u_ao, uv + vec2(1.0, -1.0) * texel).r +
                       texture(u_ao, uv + vec2(-1.0, 1.0) * texel).r + texture(u_ao, uv + vec2(1.0, 1.0) * texel).r);
    ao = 1.0 - u_ao_strength * (1.0 - ao);
    float share = mix(0.45, 1.0, clamp(c.a, 0.0, 1.0));
    o_color = vec4(c.rgb * mix(1.0, ao, share), 1.0);
}
