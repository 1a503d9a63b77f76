#version 430 core
// ground_grid: a lit neutral ground with anti-aliased lines every u_cell_m (minor) and 10 u_cell_m (major).
// The ground fades into the sky between u_fade_m.x and u_fade_m.y metres from the eye, like Blender's
// floor: a pile on an endless grid would otherwise leave no horizon.
// Interface: v_world; u_cell_m, u_fade_m, plus lighting.glsl's.
uniform float u_cell_m;
uniform vec2 u_fade_m;
in vec3 v_world;
out vec4 o_color;

float gridLine(vec2 p, float cell) {
    vec2 q = p / cell;
    vec2 w = fwidth(q);
    vec2 d = abs(fract(q - 0.5) - 0.5) / max(w, vec2(1e-6));
    return 1.0 - min(min(d.x, d.y), 1.0);
}

void main() {
    vec3 ground = vec3(0.13, 0.13, 0.12);
    float minor = gridLine(v_world.xy, u_cell_m);
    float major = gridLine(v_world.xy, 10.0 * u_cell_m);
    // Lines fade out where they get denser than the pixels (grazing angles, far away).
    float density = clamp(length(fwidth(v_world.xy / u_cell_m)) * 2.0, 0.0, 1.0);
    vec3 albedo = mix(ground, vec3(0.24, 0.24, 0.22), minor * (1.0 - density) * 0.6);
    albedo = mix(albedo, vec3(0.36, 0.35, 0.32), major * 0.8);
    vec3 lit = shadeSurface(albedo, vec3(0.0, 0.0, 1.0), v_world);
    vec3 to_point = v_world - u_eye;
    float fade = smoothstep(u_fade_m.x, u_fade_m.y, length(to_point));
    o_color = vec4(toDisplay(mix(lit, skyColor(normalize(to_point)), fade)), g_ambient_share);
}
