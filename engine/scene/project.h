// The project (scene) document: what the user edits and saves. It stores the terrain's recipe, models by
// path, seeds, density primitives and instantiation settings, never instances, so a project stays a few
// kilobytes however many objects it makes (docs/architecture.md "what users of the peers complain about").
// scene_compile.h turns it into what the instantiator runs on.
//
// File: JSON. Relative paths inside a project are relative to the project file's folder. Reading is
// strict: unknown keys are errors, and so are keys of a newer format version in an older file.
//
//   {"format": "undergrowth-project", "format_version": 2,          (1 is still read: no terrain, no
//    "name": "meadow",                                               density, default instancing)
//    "ghost_tile": {"tile_size_m": 0.5, "delta_m": -0.002, "seed": 7, "variants": 4},
//                                                  (variants: optional, 1..64, default 1; see ghost_tile.h)
//    "terrain": {"procedural": {"origin": [x, y], "cell_size_m", "width", "height", "seed", "octaves",
//                               "base_height_m", "amplitude_m", "feature_size_m", "lacunarity", "gain"}}
//            or {"image": {"path": "ground.png", "origin": [x, y], "cell_size_m", "min_height_m",
//                          "max_height_m"}},                     (optional; see height_field.h for meanings)
//               either may add "material": <material>          (the ground's look; default kTerrainColor,
//                                                                untextured; uv = world XY / texture_scale_m)
//    "extent": {"min": [x, y, z], "max": [x, y, z]},             (optional: derived when absent, see
//                                                                 computeSceneExtent)
//    "instantiation": {"seed": 1, "chunk_size_m": 8},            (optional; chunk: export chunking, > 0)
//    "settling": {"enabled": true, "passes": 8, "max_drop_m": 0.5,  (optional; instancer/settling.h;
//                 "ground_z": 0},                                    ground_z: the plane without a terrain)
//    "detail_types": [{
//        "name": "grass_tuft",
//        "model": {"mesh": "../models/grass_tuft.glb", "scale", "y_up", "spheres", "anchors"},
//        "candidates": {"count", "orientation", "scale", "position"},       (the Ghost Tile's candidates)
//        "density": <field node>,        (optional, default: 0 everywhere; grammar in field_json.h)
//        "subtract_terrain": true,       (optional: remove the ground solid so details never sink; only
//        "terrain_falloff_m": 0.05,       acts when the project has a terrain; falloff > 0)
//        "angle_of_repose_deg": 35,      (optional: the steepest slope a sculpted pile of this type keeps,
//                                         in (0, 89]; the sculpt brush grows cones this steep, tools.h)
//        "material": <material>,         (optional: the look; never changes what is instantiated)
//        "scatter": {                    (optional, format 3: an environmental effect that scatters,
//            "channel": "leaves" | "grass" | "trash",      env/env_scatter.h: density (α·c·h − d) / s)
//            "thickness_m": 0.05,                          (h, in (0, 100])
//            "ramp_m": 0.01,                               (s, in (0, 100])
//            "sheltered": true,                            (default: true for leaves and trash, false for grass)
//            "variants": [{"name": "leaf_oak_wet", "model": {...}, "material": <material>,
//                          "when": {"channel": "humidity", "min": 0, "max": 1e30}}, ...]},
//                                        (when: any channel; min / max optional; the first that holds wins)
//        "instancing": {                 (optional)
//            "strategy": "random" | "elevation" | "distance_to_boundary",   (default random)
//            "layer_m": 0.02,                                                (> 0)
//            "orientation": {"direction": [x, y, z] (non-zero) | "gradient" (default [0, 0, 1]),
//                            "max_angle_deg": 30 (0..180)},
//            "size": {"target": 1.2 (> 0) | {"field": <field node>, "value_lo": 0, "value_hi": 1,
//                                              "scale_lo": 1, "scale_hi": 1},
//                     "tolerance": 0.25 (>= 0)}}}, ...]}
//
// <material> is {"base_color": [r, g, b] (linear, each in [0, 1]; absent: the model's own colour),
//   "roughness": 0..1 (0.9), "texture": "none" | "rock" | "leaf" | "bark" | "grass" | "ground" | "hay"
//   ("none"), "texture_scale_m": metres per repeat in [0.001, 1000] (0.2), "texture_rotation_deg":
//   -360..360 (0), "tint_variation": 0..1 (0), "alpha_cutout": false}, every key optional
//   (scene/material_json.h, material/material.h).
//
// An orientation or size object switches that constraint on. "gradient" means the gradient of the
// type's own compiled density (Ghost Tile Fig. 17 right); a size ramp maps its field's values
// [value_lo, value_hi] (value_lo < value_hi) to scales [scale_lo, scale_hi] (both > 0, Fig. 22).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "field/bounds.h"
#include "field/density_field.h"
#include "field/direction_field.h"
#include "field/height_field.h"
#include "env/env_desc.h"
#include "env/env_scatter.h"
#include "ghosttile/ghost_tile.h"
#include "instancer/instancing_settings.h"
#include "instancer/settling.h"
#include "material/material.h"
#include "mesh/detail_model.h"

namespace ug {

// 2: terrain, extent, instantiation, and per type density, subtract_terrain, terrain_falloff_m, instancing.
// 3: environment (the environmental-object tree, env/env_json.h).
// 4: particles (particle systems grown into the scene, scene/scene_particles.h).
constexpr int kProjectFormatVersion = 4;
// Particle systems a project may name (each grows and meshes its own strands).
constexpr size_t kMaxParticleSystems = 64;
// Refused when the project is read, before any model is loaded (each type costs a model load and a fit).
constexpr size_t kMaxDetailTypes = 1024;
// Larger project files are refused before they are read (named in the message).
constexpr size_t kMaxProjectFileBytes = size_t(64) << 20;

// The orientation constraint as the user sets it (compiled to OrientationConstraint).
struct OrientationDesc {
    bool enabled = false;
    DirectionFieldKind kind = DirectionFieldKind::Constant;  // Gradient: of the type's compiled density
    glm::vec3 direction{0.0f, 0.0f, 1.0f};                   // Constant: unit length
    float max_angle_deg = 30.0f;                             // in [0, 180]
};

// The size constraint as the user sets it (compiled to SizeConstraint).
struct SizeDesc {
    bool enabled = false;
    SizeFieldKind kind = SizeFieldKind::Constant;
    float target = 1.0f;    // Constant: the prescribed scale, > 0
    DensityField field;     // Ramp: like DetailTypeDesc::density (terrain = height field 0, none attached)
    float value_lo = 0.0f;  // Ramp: field values mapped to scale_lo / scale_hi, value_lo < value_hi
    float value_hi = 1.0f;
    float scale_lo = 1.0f;  // Ramp: > 0
    float scale_hi = 1.0f;
    float tolerance = 0.25f;  // relative, >= 0
};

struct InstancingDesc {
    PriorityStrategy strategy = PriorityStrategy::Random;
    float layer_m = 0.02f;  // > 0
    OrientationDesc orientation;
    SizeDesc size;
};

// A look of a scattered type chosen per instance from the environment at its origin (Fig. 12: wet, flat
// leaves where η >= 0; Fig. 14: dried grass where θ is high); the selection never sees it.
struct ScatterVariantDesc {
    DetailModelSource model;  // model.name: the variant's name, unique among types and variants
    Material material;
    ScatterCondition when;
};

// The type is an environmental effect that scatters (env/env_scatter.h): its density is the effect's
// term (α·c·h − d)/s, blended with the type's own brushes.
struct ScatterDesc {
    bool enabled = false;
    ScatterSettings settings;
    std::vector<ScatterVariantDesc> variants;  // the first whose condition holds wins; none: the type's own
};

struct DetailTypeDesc {
    DetailModelSource model;    // model.name is the type's name
    DetailTypeSettings ghost;   // ghost.name == model.name
    // f_i before the solids are subtracted. Terrain primitives refer to height field 0, the project's
    // terrain; height_fields stays empty here (compileDetailType attaches the loaded terrain).
    // root == kNoNode: 0 everywhere (the default).
    DensityField density;
    bool subtract_terrain = true;     // only acts when the project has a terrain
    float terrain_falloff_m = 0.05f;  // depth over which the ground solid reaches full weight, > 0
    // The sculpt brush's piles of this type keep this slope (loose gravel ~35 deg), in (0, 89]: a vertical
    // pile (90) has no cone, and the tangent grows without bound.
    float angle_of_repose_deg = 35.0f;
    InstancingDesc instancing;
    Material material;  // the look only: instantiation never reads it
    ScatterDesc scatter;  // format 3
};

enum class TerrainKind : uint8_t { None, Procedural, Image };

struct TerrainDesc {
    TerrainKind kind = TerrainKind::None;
    ProceduralTerrainDesc procedural;  // kind == Procedural
    HeightFieldImageDesc image;        // kind == Image
    std::string image_path;            // kind == Image: a PNG, as written (relative to the project file)
    Material material;                 // the ground's look (kind != None); base colour absent: kTerrainColor
};

// Settling (instancer/settling.h) as the project sets it; the support is the terrain, or without one the
// plane z = ground_z when given.
struct SettlingDesc {
    SettleSettings settle;                 // enabled false: instances stay where their candidates are
    std::optional<float> ground_z;         // only without a terrain; absent: no ground plane
};

// One particle system of the project: a particle file (particles/particle_json.h), relative to the
// project's folder, moved by offset_m; `name` (when set) replaces the file's own, so one file can be used
// twice. The system itself is read by loadSceneParticles (scene/scene_particles.h).
struct ParticleSystemRef {
    std::string file;
    std::string name;                 // "" : the file's name
    glm::vec3 offset_m{0.0f};         // added to every generator, attractor and cutter position
    bool operator==(const ParticleSystemRef&) const = default;
};

struct Project {
    std::string name;
    GhostTileSettings ghost_tile;
    SettlingDesc settling;
    TerrainDesc terrain;
    std::optional<Bounds> extent;  // finite, lo < hi on every axis; absent: derived (computeSceneExtent)
    uint64_t instantiation_seed = 1;
    float chunk_size_m = 8.0f;  // export: edge of the square XY chunks instances are grouped by, > 0
    std::vector<DetailTypeDesc> detail_types;
    EnvironmentDesc environment;  // format 3: environmental objects, fields and effects (empty: none)
    std::vector<ParticleSystemRef> particles;  // format 4: particle systems (empty: none)
    std::string base_dir;  // folder of the file it was loaded from (not saved)
    std::string source;    // the file (or source name) it was parsed from, for messages (not saved)
};

// Errors: "<path>: <JSON pointer>: <reason>", e.g.
// "meadow.json: /detail_types/1/candidates/scale: expected [min, max] with 0 < min <= max".
bool loadProject(const std::string& path, Project* out, std::string* error);
bool parseProject(const std::string& text, const std::string& source_name, Project* out, std::string* error);
// Always writes the current format version, every setting explicitly. Density fields are written as
// trees from their roots (field_json.h: unreachable nodes are dropped, a polyline comes back as the Union
// of its segments); parseProject(projectToJson(p)) gives back p's settings and fields with the same
// primitives, nodes and values, bit for bit. Disabled orientation / size constraints are left out (their
// settings come back as defaults), and so are materials equal to the default Material (a project
// without materials saves exactly as before).
std::string projectToJson(const Project& project);
bool saveProject(const std::string& path, const Project& project, std::string* error);  // atomic

// Loads every detail type's model (fitting sphere sets) and assembles the Ghost Tile input.
// `models` receives the loaded models; input.models points into it (keep it alive). An error names the
// scene file (project.source, when set), the JSON Pointer of the type's model and the model's own message
// ("meadow.json: /detail_types/2/model: detail model 'rock' (rock.ply): rock.ply: line 7: ...").
bool loadProjectModels(const Project& project, std::vector<DetailModel>* models, std::string* error);
GhostTileInput ghostTileInput(const Project& project, const std::vector<DetailModel>& models);
// The scattered types' variant models: (*out)[t][k] is type t's variant k (empty for other types). Errors
// as loadProjectModels', naming /detail_types/<t>/scatter/variants/<k>/model.
bool loadScatterVariantModels(const Project& project, std::vector<std::vector<DetailModel>>* out, std::string* error);

// Resolves a project-relative path.
std::string resolveProjectPath(const Project& project, const std::string& path);

}  // namespace ug
