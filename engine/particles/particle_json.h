// A particle system as JSON (docs/particles.md "File format"): the scene of particle_scene.h, how its
// strands are meshed, and their material. The keys are the struct fields' names, lengths in metres:
//
//   {"format": "undergrowth-particles", "format_version": 1, "name": "fur_ball",
//    "generators": [{"kind": "sphere", "center_m": [0, 0, 0], "radius_m": 0.05, "count": 20000,
//                    "heading_cone_deg": 15}],            rectangle: axis_u_m, axis_v_m; box: half_extents_m;
//                                                          objects: "object_type", "max_height_m",
//                                                          "sides_only" (the project's objects' surfaces)
//                                                          details: "detail_type", center_m,
//                                                          half_extents_m (the box the instances' origins
//                                                          lie in), "min_normal_z" (the project's
//                                                          instances of that type, as instantiated)
//    "attractors": [{"kind": "point", "a_m": [0, 0, 0], "charge": [[0, -1.0]], "influence_m": 0}],
//                                                          segment: a_m, b_m; sphere: a_m, radius_m;
//                                                          mesh: "mesh" (relative to the file), "scale",
//                                                          "points" (1..1024), placed at a_m;
//                                                          objects: "object_type" (the project's
//                                                          environmental-object type), "points" per object;
//                                                          charge: [[step, a], ...] keys or one number
//    "cutters": [{"kind": "plane", "center_m": [0, 0, 0.3], "normal": [0, 0, 1], "threshold_m": 0,
//                 "side": "above", "action": {"kind": "split", "split_count": 3, "split_angle_deg": 40}}],
//    "walk": {"seed": 1, "steps": 32, "trials": 8, "cone_deg": 30, "step_length_m": 0.01,
//             "strand_radius_m": 0.001, "collisions": true, "on_collision": {"kind": "stop"},
//             "max_age_steps": 0, "on_age": {"kind": "stop"}, "max_split_depth": 4, "max_points": 50000000,
//             "solids": true, "keep_distance_m": 0, "on_distance": {"kind": "stop"}, "retry_refused": false},
//    "mesh": {"shape": "tube", "sides": 6, "max_triangles": 20000000},
//                                                          blade: "blade_width_m": 0.004, "blade_tip": 0.2
//    "material": MATERIAL}                                 scene/material_json.h
//
// Strict like the project file: unknown keys, wrong types, NaN and values out of range are errors naming
// the file and the JSON Pointer; then validateParticleScene checks what depends on several fields.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "material/material.h"
#include "particles/particle_scene.h"

namespace ug {

// How strands are meshed (strand_mesh.h).
enum class StrandShape : uint8_t {
    Tube,   // a closed tube at the strand's radius: fur, roots, vines
    Blade,  // a flat ribbon seen from both sides, tapering to its tip: grass, leaves of moss
};

struct StrandMeshSettings {
    StrandShape shape = StrandShape::Tube;
    uint32_t sides = 6;                   // a tube's cross-section, in [3, 32]
    float blade_width_m = 0.0f;           // a blade's width at its root; 0: four strand radii
    float blade_tip = 0.2f;               // a blade's width at its tip, as a share of the root's, in [0, 1]
    uint64_t max_triangles = 20'000'000;  // refuse (before meshing) strands that would need more
};

struct ParticleSystemFile {
    std::string name;
    // The name the file itself gives (its stem when it gives none): a project's entry may rename the
    // system (scene/scene_particles.h), and the editor writes the file back under its own name.
    std::string file_name;
    ParticleScene scene;
    StrandMeshSettings mesh;
    Material material;
};

// Reads a particle system from the file at `path` (errors name it); a system without a name takes the
// file's stem. Sizes are refused before anything is allocated for them.
bool loadParticleSystem(const std::string& path, ParticleSystemFile* out, std::string* error);
// Reads from parsed JSON; `source` names it in errors.
bool parseParticleSystem(const nlohmann::json& j, const std::string& source, ParticleSystemFile* out,
                         std::string* error);
// Every field explicitly: parseParticleSystem(particleSystemToJson(s)) gives s back.
nlohmann::json particleSystemToJson(const ParticleSystemFile& system);

}  // namespace ug
