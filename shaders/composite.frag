#version 430 core
// composite: the scene pass's colour onto the target framebuffer, darkened by the ambient occlusion
// (ambient_occlusion.frag, half resolution). The occlusion is read through four bilinear taps a
// half-resolution texel apart: a 4 x 4 texel footprint, which averages the sampling pattern away. The
// colour's alpha is the share of ambient light (lighting.glsl): sunlit faces darken less than shaded ones.
// No depth is carried: what needs the scene's depth (the hulls) is drawn before, into the scene's target.
// Interface: u_color (the scene pass's colour), u_ao (the occlusion; 1 where the sky is).
out vec4 o_color;
uniform sampler2D u_color;
uniform sampler2D u_ao;

void main() {
    vec4 c = texelFetch(u_color, ivec2(gl_FragCoord.xy), 0);
    vec2 texel = 1.0 / vec2(textureSize(u_ao, 0));
    vec2 uv = (gl_FragCoord.xy * 0.5) * texel;
    float ao = 0.25 * (texture(u_ao, uv + vec2(-1.0, -1.0) * texel).r + texture(u_ao, uv + vec2(1.0, -1.0) * texel).r +
                       texture(u_ao, uv + vec2(-1.0, 1.0) * texel).r + texture(u_ao, uv + vec2(1.0, 1.0) * texel).r);
    float share = mix(0.45, 1.0, clamp(c.a, 0.0, 1.0));
    o_color = vec4(c.rgb * mix(1.0, ao, share), 1.0);
}
