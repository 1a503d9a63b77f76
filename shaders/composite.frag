#version 430 core
// composite: the scene pass's colour onto the target framebuffer, darkened by the ambient occlusion
// (ambient_occlusion.frag at half resolution, ao_blur.frag), read once, bilinearly. The colour's alpha is the share of ambient light (lighting.glsl): sunlit faces darken less than shaded ones.
// No depth is carried: what needs the scene's depth (the hulls) is drawn before, into the scene's target.
// Interface: u_color (the scene pass's colour), u_ao (the occlusion; 1 where the sky is).
out vec4 o_color;
uniform sampler2D u_color;
uniform sampler2D u_ao;

void main() {
    vec4 c = texelFetch(u_color, ivec2(gl_FragCoord.xy), 0);
    float ao = texture(u_ao, gl_FragCoord.xy * 0.5 / vec2(textureSize(u_ao, 0))).r;
    float share = mix(0.45, 1.0, clamp(c.a, 0.0, 1.0));
    o_color = vec4(c.rgb * mix(1.0, ao, share), 1.0);
}
