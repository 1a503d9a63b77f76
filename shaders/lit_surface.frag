#version 430 core
// lit_surface: terrain, details and impostors; lighting.glsl's sky + sun + haze.
// A textured material (material.h: the image is the final colour, sRGB, sampled as linear) replaces the
// flat colour: texture x the instance's tint. Its coordinates are material/uv_projection.h's box
// projection of the model-space position, by the face's dominant axis (ties to Z, then X), divided by the
// texture's scale, as the exporter writes TEXCOORD_0; or, for the terrain, world X and Y over the scale;
// then turned by the material's texture_rotation_deg (u_texture_turn = its cos and sin).
// GLOSSY (the program for smooth environmental objects, renderer.cpp): the surface also mirrors the sky by
// u_gloss (material.h materialGloss), weighted by Schlick's Fresnel term for water (F0 = 0.02): dark
// looking down, the sky's colour at grazing angles, the sun's glint where the sky holds it. A variant of
// its own rather than a branch on u_gloss: llvmpipe ran the branch's body for every fragment of every
// surface (the meadow's close view 10 % slower with gloss 0 everywhere).
// Interface: v_world, v_normal, v_color (linear RGB), v_model, v_tint from the vertex stage; u_albedo,
// u_texture_mode (0: none, 1: box projection of v_model, 2: world XY), u_texture_scale_m, u_texture_turn,
// u_alpha_cutout.
in vec3 v_world;
in vec3 v_normal;
in vec3 v_color;
in vec3 v_model;
in vec3 v_tint;
uniform sampler2D u_albedo;
uniform int u_texture_mode;
uniform float u_texture_scale_m;
uniform vec2 u_texture_turn;
uniform int u_alpha_cutout;
#ifdef GLOSSY
uniform float u_gloss;
#endif
out vec4 o_color;

vec2 textureCoordinates() {
    vec2 uv;
    if (u_texture_mode == 2) {
        uv = v_model.xy;
    } else {
        vec3 a = abs(cross(dFdx(v_model), dFdy(v_model)));
        uv = (a.z >= a.x && a.z >= a.y) ? v_model.xy : (a.x >= a.y ? v_model.yz : v_model.xz);
    }
    uv /= u_texture_scale_m;
    return vec2(u_texture_turn.x * uv.x - u_texture_turn.y * uv.y, u_texture_turn.y * uv.x + u_texture_turn.x * uv.y);
}

void main() {
    vec3 albedo = v_color;
    if (u_texture_mode == 2) {
        // Ground seen over tens of metres would show the repeat as a grid of blotches: a second, turned
        // and stretched lookup of the same image averages it away (the mean colour is unchanged).
        vec2 uv = textureCoordinates();
        vec2 turned = mat2(0.8, 0.6, -0.6, 0.8) * uv * 0.37 + vec2(0.31, 0.17);
        albedo = 0.5 * (texture(u_albedo, uv).rgb + texture(u_albedo, turned).rgb) * v_tint;
    } else if (u_texture_mode != 0) {
        vec4 t = texture(u_albedo, textureCoordinates());
        if (u_alpha_cutout != 0 && t.a < 0.5) discard;
        albedo = t.rgb * v_tint;
    }
    vec3 n = normalize(v_normal);
    // Thin sheets (leaves, blades) are seen from both sides: light the side that faces the viewer.
    if (!gl_FrontFacing) n = -n;
#ifdef GLOSSY
    float visibility = dot(n, u_sun_dir) > 0.0 ? sunVisibility(v_world, n) : 0.0;
    vec3 view = normalize(v_world - u_eye);
    float c = 1.0 - clamp(-dot(view, n), 0.0, 1.0);
    float c2 = c * c;
    float fresnel = 0.02 + 0.98 * c2 * c2 * c;
    // The glint is the sky's sun disc: dimmed where the surface is in shadow.
    vec3 mirrored = skyColor(reflect(view, n)) * mix(0.6, 1.0, visibility);
    vec3 lit = hazed(mix(lightSurface(albedo, n, visibility), mirrored, fresnel * u_gloss), v_world);
#else
    vec3 lit = shadeSurface(albedo, n, v_world);
#endif
    // Alpha carries the ambient share to the ambient occlusion pass (composite.frag).
    o_color = vec4(toDisplay(lit), g_ambient_share);
}
