#version 430 core
// impostor: the model's silhouette in the point sprite's square (detail_impostor.vert sizes and picks it),
// two elevation layers dithered together. The mask's value is a coverage (its mipmaps average it), so it is cut
// against a per-pixel dither rather than 0.5: a thin blade a third of a texel wide still covers a third of
// the pixels it crosses, where a fixed threshold would drop it.
// Interface: v_lit (display RGB), v_layer (-1: a plain pixel), v_layer_mix; u_silhouettes (R8 array),
// u_sprite_extent.
in vec3 v_lit;
flat in int v_layer;
in float v_layer_mix;
uniform sampler2DArray u_silhouettes;
uniform float u_sprite_extent;  // the share of the mask's square the sprite shows (coverage.h extent)
out vec4 o_color;
void main() {
    if (v_layer >= 0) {
        // Masks are stored bottom-up; the sprite shows their centred u_sprite_extent.
        vec2 uv = 0.5 + (vec2(gl_PointCoord.x, 1.0 - gl_PointCoord.y) - 0.5) * u_sprite_extent;
        float dither = fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
        // Between two elevations, pixels pick one layer or the other (one fetch, not two).
        int layer = v_layer + (fract(dither * 7.0) < v_layer_mix ? 1 : 0);
        if (texture(u_silhouettes, vec3(uv, float(layer))).r <= dither) discard;
    }
    o_color = vec4(v_lit, 1.0);
}
