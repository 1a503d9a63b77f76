// The environment in the project file (format version 3): the "environment" key of scene/project.h.
//
//   "environment": {
//     "types": [{"name": "bench", "mesh": "../env_models/bench.glb", "scale": 1, "y_up": true,
//                "fields": [<field>, ...],                                   (object space)
//                "snow": {"mode": "geometry" | "box" | "cylinder" | "sphere" | "none",
//                         "max_face_angle_deg": 60, "d0_m": 0.05, "target_edge_m": 0.05},
//                "icicles": {"enabled": true, "automatic_anchors": true, "anchors": [[x, y, z], ...],
//                            "spacing_m": 0.06, "max_length_m": 0.35, "length_per_degree_m": 0.03},
//                "material": <material>,
//                "receives": ["leaves", "grass", "trash"],     (scattered effects resting on it; default none)
//                "shelters": true}, ...],                       (false: keeps nothing off what is below)
//     "groups": {"<name>": <group or lod node>, ...},     (instanced by "ref" nodes only)
//     "tree": [<node>, ...],
//     "global_fields": [<field>, ...],                     (world space)
//     "terrain": {"snow": true, "snow_cell_m": 0.1, "receives": [...]},   (receives: default all three)
//     "use_lod_nodes": true,
//     "snow_direction": [0, 0, -1],                       (unit after reading; at most 45 degrees from down)
//     "snow_spread_deg": 0,                               (the shelter rays' cone around it, at most 20)
//     "sharing_threshold": 0.0001                          (negative: never share effects)
//   }
//   <node>  = {"object": "<type name>", <placement>, "fields": [...], "snow": {...}, "icicles": {...}}
//           | {"group": {<placement>, "children": [<node>, ...], "fields": [...], "snow": .., "icicles": ..}}
//           | {"lod":   {<placement>, "children": [<node>, ...], "fields": [...]}}
//           | {"ref": "<group name>", <placement>, "snow": .., "icicles": ..}
//   <placement> = "at": [x, y, z], "yaw_deg": 0, "scale": 1      (each optional)
//   <field> = {"channel": "snow" | "icicles" | "leaves" | "grass" | "trash" | "occlusion" | "humidity" |
//                         "temperature",
//              "value": v,
//              "shape": {"point": {...}} | {"segment": {...}} | {"disc": {...}} | {"box": {...}}}
//             shapes as in field_json.h without "weight" (the value is the weight); no "shape": the value
//             everywhere. Occlusion values are in [0, 1].
//   A node's "snow" / "icicles" override the type's settings for its subtree (every key optional).
//
// Errors name the file, the JSON Pointer and the reason; the tree's depth is checked before it is walked
// (kMaxEnvTreeDepth), references are resolved at compile time (env_scene.h).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "env/env_desc.h"
#include "scene/json_reader.h"

namespace ug {

bool readEnvironment(JsonReader& r, const nlohmann::json& j, const std::string& pointer, EnvironmentDesc* out);
// Every setting explicitly; readEnvironment(envToJson(e)) gives e back bit for bit.
nlohmann::json environmentToJson(const EnvironmentDesc& env);

}  // namespace ug
