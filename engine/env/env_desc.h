// The environmental-object scene as the project stores it (Grosbellet et al. 2016 §3; docs/architecture.md
// "Environmental objects"): the type library, the construction tree and the global fields. env_json.h reads
// and writes it; env_scene.h compiles it into what effects query.
//
// Transforms are a translation, a turn about the vertical (yaw) and a uniform scale: the snow falls
// along -Z, so in every object's own space "up" stays +Z, and objects of one type that share an
// environment can share one computed effect (§6.2).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "env/env_sample.h"
#include "field/primitive.h"
#include "material/material.h"

namespace ug {

// Nesting limit of the tree (groups, LOD nodes, references followed): a deeper one comes from a generator
// gone wrong, and is refused before it is walked.
constexpr int kMaxEnvTreeDepth = 64;
// Objects after references are expanded (the Montmartre scene has ~10,000); refused before allocating.
constexpr size_t kMaxEnvObjects = 2000000;
constexpr size_t kMaxEnvTypes = 4096;
constexpr size_t kMaxEnvFields = 1000000;

const char* envChannelName(EnvChannel c);                  // "snow", "icicles", ..., "temperature"
bool envChannelFromName(const std::string& name, EnvChannel* out);

// One emitted field (§4): a skeletal primitive of engine/field (point, segment, disc, box) carrying a
// channel and a value, or a field everywhere (a global field: the value at every point). The primitive's
// weight is the value: the field is value·K(d). For occlusion the field contributes the factor
// α_i = 1 - value·K(d) (value in [0, 1]).
struct EnvFieldDesc {
    EnvChannel channel = EnvChannel::Snow;
    bool everywhere = false;  // true: `value` at every point, no shape
    float value = 0.0f;       // == shape.weight when !everywhere
    Primitive shape;          // object space (the owner's), kinds Point, Segment, Disc, Box
};

enum class SnowMode : uint8_t { None, Geometry, Box, Cylinder, Sphere };
const char* snowModeName(SnowMode m);

// Snow settings of a type (§5.1); procedural modes cover the base mesh's bounding box / upright cylinder
// / sphere.
struct SnowEffectDesc {
    SnowMode mode = SnowMode::Geometry;
    float max_face_angle_deg = 60.0f;  // (0, 90)
    float d0_m = 0.05f;                // > 0
    float target_edge_m = 0.05f;       // > 0
};

// Icicle settings of a type (§5.2).
struct IcicleEffectDesc {
    bool enabled = true;
    bool automatic_anchors = true;
    std::vector<glm::vec3> anchors;     // authored, object space
    float spacing_m = 0.06f;            // > 0
    float max_length_m = 0.35f;         // > 0
    float length_per_degree_m = 0.03f;  // > 0
};

// Per-object or per-group changes to a type's effect settings; a subtree inherits them, and the nearest
// node that sets a value wins.
struct EffectOverrides {
    std::optional<SnowMode> snow_mode;
    std::optional<float> snow_max_face_angle_deg, snow_d0_m, snow_target_edge_m;
    std::optional<bool> icicles_enabled;
    std::optional<float> icicle_spacing_m, icicle_max_length_m;
    bool empty() const;
};

// Which scattered channels (leaves, grass, trash: env/env_scatter.h) come to rest on a surface, as a set
// of bits 1 << EnvChannel.
constexpr uint32_t envChannelBit(EnvChannel c) { return 1u << uint32_t(c); }
constexpr uint32_t kAllEnvChannels = ~0u;
constexpr uint32_t kScatterChannels =
    envChannelBit(EnvChannel::Leaves) | envChannelBit(EnvChannel::Grass) | envChannelBit(EnvChannel::Trash);

struct EnvTypeDesc {
    std::string name;
    std::string mesh_path;   // as written (relative to the project file): glTF, OBJ, PLY, STL, OFF
    float scale = 1.0f;      // applied to the mesh on load, > 0
    bool y_up = true;        // the file is Y up (glTF is, by its spec); false for Z-up OBJ, PLY, STL, OFF
    std::vector<EnvFieldDesc> fields;  // object space
    SnowEffectDesc snow;
    IcicleEffectDesc icicles;
    Material material;
    // Scattered effects (§5.3-5.4) that rest on the type's up-facing, unsheltered surfaces: a bench seat
    // takes leaves and trash, a lawn grass; none by default (a lamppost's top collects nothing).
    uint32_t receives = 0;  // bits of kScatterChannels
    // false: the base geometry keeps nothing off what is below it (a tree's crown lets snow and leaves
    // through); it still supports what lands on it when it receives.
    bool shelters = true;
};

struct EnvTransform {
    glm::vec3 translation{0.0f};
    float yaw_deg = 0.0f;
    float scale = 1.0f;  // > 0
};

enum class EnvNodeKind : uint8_t { Object, Group, Lod, Reference };

// A node of the construction tree (§3.1, §6.1). Objects are leaves; groups combine their children
// (fields summed, occlusion multiplied) and may carry fields and overrides of their own; an LOD node's own
// fields replace its subtree's for field queries (its subtree's objects keep their geometry and effects);
// a reference instances a named group (§3.2) under its own transform.
struct EnvNode {
    EnvNodeKind kind = EnvNodeKind::Object;
    EnvTransform transform;
    uint32_t type = 0;                 // Object: index into EnvironmentDesc::types
    std::string target;                // Reference: the group's name (EnvironmentDesc::groups)
    std::vector<EnvFieldDesc> fields;  // in this node's space
    EffectOverrides overrides;
    std::vector<EnvNode> children;     // Group, Lod
};

struct NamedEnvGroup {
    std::string name;
    EnvNode group;  // kind Group or Lod
};

// The terrain as an environmental object: its snow is the height field displaced.
struct TerrainEffectsDesc {
    bool snow = true;
    float snow_cell_m = 0.1f;  // > 0
    uint32_t receives = kScatterChannels;  // the scattered effects that rest on the ground
};

// The steepest snowfall the shelter term follows: beyond it the marching through the height-span maps
// gets long and wind-driven snow is better modelled by other means.
constexpr float kMaxSnowTiltDeg = 45.0f;
// The widest spread of snowfall directions around snow_direction (flakes swirl: a lee fades out over
// metres behind a tall building instead of ending at one line).
constexpr float kMaxSnowSpreadDeg = 20.0f;

struct EnvironmentDesc {
    // The direction snow falls in, world space, unit, at most kMaxSnowTiltDeg from straight down: faces
    // take snow when they face against it, and shelter looks back along it (wind-driven snow reaches
    // the windward sills under a cornice).
    glm::vec3 snow_direction{0.0f, 0.0f, -1.0f};
    // Half-angle in degrees, in [0, kMaxSnowSpreadDeg], of the cone of directions the shelter's rays take
    // around snow_direction; 0: every ray follows it (the paper's single direction).
    float snow_spread_deg = 0.0f;
    std::vector<EnvTypeDesc> types;
    std::vector<NamedEnvGroup> groups;  // instanced by references; not part of the scene by themselves
    std::vector<EnvNode> roots;         // the tree's top level
    std::vector<EnvFieldDesc> global_fields;  // world space
    TerrainEffectsDesc terrain;
    bool use_lod_nodes = true;         // false: LOD nodes act as groups (their subtree's fields count)
    float sharing_threshold = 1e-4f;   // §6.2: L² distance of sampled environments (0 = identical only),
                                       // negative: no sharing
    bool empty() const { return types.empty() && roots.empty() && global_fields.empty() && groups.empty(); }
};

}  // namespace ug
