#version 430 core
// detail_impostor: the far representation, one point sprite per instance (GL_POINTS, no triangles),
// centred on the instance's bounding-box centre, showing the model's silhouette from this elevation
// (impostor.frag: render_data.h silhouettes, blended between the 0, 30, 60 and 90 degree masks), so a far
// field covers the screen exactly as much as its meshes would. A sprite under two pixels is one pixel
// drawn with the probability of the silhouette's area (render_data.h coverage_m2, hashed per instance):
// the expected coverage stays the same.
// Beyond the impostor distance an object covers a few pixels, where a disc of its colour and light
// reads the same as its mesh and costs llvmpipe a fraction of a triangle.
// A far run may be thinned (render_data.h PointRun): the command's i-th point is instance
// a_run.x + i * a_run.y, and a one-pixel point is kept with a_run.y times its probability.
// Interface: a_run (3, per instance: the command's baseInstance picks its run); buffer 0 = candidate
// frames, buffer 1 = the type's packed instances (as instanced_detail.vert's a_instance); u_view_proj,
// u_tile_size_m, u_color, u_center (model space), u_coverage_m2, u_sprite_radius_m, u_layer_first,
// u_upness, u_point_scale (pixels per metre at unit depth), u_to_eye (unit, toward the camera),
// u_lod_diameter_px, u_impostor_px (the switch, as instanced_detail.vert), plus lighting.glsl's; out
// v_lit, the display colour.
// Compiled with SHADOW_CASTER, the same sprites cast the sun's shadow (renderer.cpp shadowPass): u_view_proj
// is the sun's orthographic view, u_point_scale the shadow map's texels per metre and u_to_eye the direction
// toward the sun (the silhouette from the sun's elevation); u_eye and u_lod_diameter_px stay the camera's,
// so exactly the instances the camera draws as sprites cast as sprites, those u_min_caster_px texels
// across or more. No lighting: depth only.
layout(location = 3) in uvec2 a_run;  // offset, stride

struct CandidateFrame {
    vec4 position_scale;
    vec4 rotation;
};
layout(std430, binding = 0) readonly buffer CandidateFrames { CandidateFrame u_frames[]; };
layout(std430, binding = 1) readonly buffer PackedInstances { uvec2 u_instances[]; };

uniform mat4 u_view_proj;
uniform float u_tile_size_m;
uniform float u_drop_unit_m;
uniform vec3 u_color;
uniform vec3 u_center;
uniform vec4 u_coverage_m2;
uniform float u_tint_variation;
uniform float u_sprite_radius_m;
uniform int u_layer_first;  // the type's first silhouette layer
uniform float u_upness;
uniform float u_lod_diameter_px;
uniform float u_impostor_px;
uniform float u_point_scale;
uniform vec3 u_to_eye;
#ifdef SHADOW_CASTER
uniform float u_min_caster_px;
#endif
out vec3 v_lit;
flat out int v_layer;    // the silhouette layer below this elevation (-1: a plain pixel)
out float v_layer_mix;   // toward the next layer up

vec3 rotate(vec4 q, vec3 v) {
    vec3 t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

void main() {
    uvec2 a_instance = u_instances[a_run.x + uint(gl_VertexID) * a_run.y];
    // Sign-extend the tile coordinates (16, 16 and 9 bits; arithmetic shifts of a signed int).
    ivec3 tile = ivec3(int(a_instance.x << 16) >> 16, int(a_instance.x) >> 16, int(a_instance.y << 23) >> 23);
    // The settled drop, in steps of u_drop_unit_m (render_data.h).
    float drop = float(a_instance.y >> 25) * u_drop_unit_m;
    CandidateFrame f = u_frames[(a_instance.y >> 9) & 0xffffu];
    float scale = f.position_scale.w;
    uint h = (a_instance.x * 2654435761u) ^ ((a_instance.y & 0x1ffffffu) * 2246822519u);  // not the drop: stable colours
    h ^= h >> 15;
    h *= 2246822519u;
    h ^= h >> 13;
    vec3 origin_undropped = vec3(tile) * u_tile_size_m + f.position_scale.xyz;
    float px = u_lod_diameter_px / max(distance(origin_undropped, u_eye), 1e-3);
    if (px >= u_impostor_px * (1.0 + 0.6 * float((h >> 10) & 1023u) / 1024.0)) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // drawn as a mesh (instanced_detail.vert)
        gl_PointSize = 1.0;
        return;
    }
    vec3 world = vec3(tile) * u_tile_size_m + f.position_scale.xyz + rotate(f.rotation, scale * u_center) -
                 vec3(0.0, 0.0, drop);
#ifdef SHADOW_CASTER
    // The disc faces the sun; set one radius behind the centre, it shadows what lies beyond the object,
    // not its neighbours in a flat layer (a disc through a leaf's centre would stand out of the layer).
    world -= u_to_eye * (u_sprite_radius_m * scale);
#endif
    gl_Position = u_view_proj * vec4(world, 1.0);
    float px_per_m = u_point_scale / max(gl_Position.w, 1e-4);
    float sprite_px = 2.0 * u_sprite_radius_m * scale * px_per_m;
#ifdef SHADOW_CASTER
    // Sprites under u_min_caster_px texels cast nothing; through a band above it instances stop one by one
    // (hashed), so a zoom that grows the map's texels fades a type's far shadows instead of cutting them.
    uint h_band = (h * 2654435761u) >> 22;
    if (sprite_px < u_min_caster_px * (1.0 + 0.5 * float(h_band) / 1024.0)) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        gl_PointSize = 1.0;
        return;
    }
#endif
    // A one-pixel point is kept when keep < its area (times the run's stride: it stands for that many).
    float keep = float((h >> 20) & 1023u) / 1024.0 / float(a_run.y);
    float most_m2 = max(max(u_coverage_m2[0], u_coverage_m2[1]), max(u_coverage_m2[2], u_coverage_m2[3]));
    if (sprite_px < 2.0 && keep >= most_m2 * scale * scale * px_per_m * px_per_m) {
        // Dropped whatever its elevation (below): most of a far field ends here, before the arcsine.
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        gl_PointSize = 1.0;
        return;
    }
    // The silhouette area from this elevation, in pixels.
#ifdef SHADOW_CASTER
    vec3 to_eye = u_to_eye;
#else
    vec3 to_eye = u_eye - world;
#endif
    float e = clamp(asin(clamp(abs(to_eye.z) / max(length(to_eye), 1e-6), 0.0, 1.0)) / 0.5235988, 0.0, 2.999);
    int k = int(e);
    float cover_m2 = mix(u_coverage_m2[k], u_coverage_m2[k + 1], e - float(k)) * scale * scale;
    float area_px = cover_m2 * px_per_m * px_per_m;
    if (sprite_px < 2.0) {
        // One pixel, kept with the probability of the silhouette's area in pixels. Decided before the
        // lighting below: in a far field most points are dropped, and the lighting is most of the cost.
        if (keep >= area_px) {
            gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
            gl_PointSize = 1.0;
            return;
        }
        v_layer = -1;
        gl_PointSize = 1.0;
    } else {
        v_layer = u_layer_first + k;
        v_layer_mix = e - float(k);
        gl_PointSize = min(sprite_px, 255.0);
    }
#ifdef SHADOW_CASTER
    v_lit = vec3(0.0);
#else
    // Lit like its faces on average, not like a flat lawn: the model's +Z (a leaf's face, a tuft's up)
    // weighted by how flat its faces are (u_upness, render_data.h), and four upright faces around it
    // (a tuft's blades, a rock's sides) for the rest; every normal turned toward the eye, as the mesh's
    // two-sided sheets are (lit_surface.frag). The haze is linear in the colour: applied once, to the blend.
    // The material's average colour (its texture's mean is u_color) with the mesh's per-instance tint.
    vec3 albedo = u_color * (0.9 + 0.2 * float(h & 1023u) / 1023.0) * instanceTint(u_tint_variation, h);
    vec3 up = rotate(f.rotation, vec3(0.0, 0.0, 1.0));
    vec3 across = rotate(f.rotation, vec3(1.0, 0.0, 0.0));
    vec3 along = cross(up, across);
    float visibility = sunVisibility(world, up);
    vec3 flat_lit = lightSurface(albedo, dot(up, u_to_eye) < 0.0 ? -up : up, visibility);
    // Of the four upright faces, each opposite pair turned toward the eye is one normal: two to light.
    vec3 upright_lit = 0.5 * (lightSurface(albedo, dot(across, u_to_eye) < 0.0 ? -across : across, visibility) +
                              lightSurface(albedo, dot(along, u_to_eye) < 0.0 ? -along : along, visibility));
    v_lit = toDisplay(hazed(mix(upright_lit, flat_lit, u_upness), world));
#endif
}
