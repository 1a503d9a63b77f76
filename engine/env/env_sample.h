// The environment e(p) of the environmental-objects paper (Grosbellet et al. 2016, §4) at one point:
// the eight channels, plus the shelter term of docs/architecture.md ("Beyond the paper: shelter").
//
// Channels blend by sum, except occlusion, which multiplies (α = Π α_i, each α_i = 1 - w·K(d), so α stays
// in [0, 1] when every w is in [0, 1]). Where no field reaches, a point has no snow, icicles, leaves,
// grass or trash, α = 1 (open), η = 0 and θ = 0 (the freezing point: θ < 0 freezes).
//
// shelter is the fraction of the sky, seen along the snow direction, that the scene's base geometry
// leaves open above the point: 1 in the open, 0 under a roof. Effects multiply α by it for snow, leaves
// and trash, and icicles need the open air below their edge.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

#include <glm/glm.hpp>

namespace ug {

enum class EnvChannel : uint8_t { Snow, Icicles, Leaves, Grass, Trash, Occlusion, Humidity, Temperature };
constexpr size_t kEnvChannelCount = 8;

struct EnvSample {
    float snow = 0.0f;         // s: metres of fallen snow
    float icicles = 0.0f;      // i: > 0 lets icicles form
    float leaves = 0.0f;       // l: metres of leaf layer
    float grass = 0.0f;        // g
    float trash = 0.0f;        // t
    float occlusion = 1.0f;    // α in [0, 1]: 1 open, 0 fully occluded
    float humidity = 0.0f;     // η: < 0 dry
    float temperature = 0.0f;  // θ: degrees above freezing; below 0 icicles form, above it snow melts
                               // (snow.h kSnowMeltPerDegreeM)
    float shelter = 1.0f;      // fraction of the sky left open above the point (1 = open)

    // The occlusion the snow, leaf and trash effects use: α times the shelter.
    float openness() const { return occlusion * shelter; }
};

// The environment at n points given in one object's space (the caller maps them to the world): effects
// compute in object space so that objects sharing an environment can share one result (§6.2).
using EnvQuery = std::function<void(const glm::vec3* points, size_t n, EnvSample* out)>;

}  // namespace ug
