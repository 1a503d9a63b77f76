// A material (material/material.h) in the project file, on a detail type or on the terrain:
//   "material": {"base_color": [r, g, b],   linear, each in [0, 1]; absent: the model's own colour
//                                            (the terrain: kTerrainColor)
//                "roughness": 0.9,           [0, 1]
//                "texture": "rock",          none | rock | leaf | bark | grass | ground | hay
//                "texture_scale_m": 0.2,     metres per texture repeat, [0.001, 1000]
//                "texture_rotation_deg": 0,  the texture turned in its uv plane, [-360, 360]
//                "tint_variation": 0.3,      [0, 1], per-instance spread of brightness and hue
//                "alpha_cutout": false}      the texture's alpha cuts the surface
// Every key is optional (the defaults of Material); unknown keys, wrong types, NaN and values out of
// range are errors naming the JSON Pointer.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "material/material.h"
#include "scene/json_reader.h"

namespace ug {

// Reads the object at `pointer` into *out (absent keys keep *out's values).
bool readMaterial(JsonReader& r, const nlohmann::json& j, const std::string& pointer, Material* out);

// Every setting explicitly, except base_color when it is not set and texture_rotation_deg when it is 0
// (files written before it existed stay byte for byte). parseMaterial(materialToJson(m)) == m.
nlohmann::json materialToJson(const Material& m);

}  // namespace ug
