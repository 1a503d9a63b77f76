// The Environment window's channel view (issue 13: "a view of any channel, and the shelter, as a colour
// map on the surfaces or on a movable slice plane, with a legend"), GL-free: the environment sampled on a
// grid over the scene's extent at a height above the ground (the slice follows the terrain), each cell a
// translucent quad coloured by its value on a blue-to-red ramp between the map's lowest and highest
// values; and, with `surfaces`, on the environmental objects themselves: every vertex of their base
// geometry sampled just outside it (3 cm along its normal) and drawn 1 cm out, coloured by its value. The
// user sees where the snow will lie, what is sheltered (a bench's seat under a roof), where it is warm,
// before any effect is computed.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "editor/markers.h"
#include "scene/document.h"

namespace ug::editor {

constexpr int kChannelMapChannels = int(kEnvChannelCount) + 1;  // the channels, then the shelter
const char* channelMapName(int channel);  // "snow", ..., "temperature", "shelter"
bool channelMapFromName(const std::string& name, int* out);

struct ChannelMapSettings {
    bool on = false;
    int channel = int(EnvChannel::Snow);  // < kEnvChannelCount: EnvChannel; kEnvChannelCount: the shelter
    float height_m = 0.05f;               // the slice's height above the ground
    bool surfaces = true;                 // on the objects' surfaces too
    bool operator==(const ChannelMapSettings&) const = default;
};

// Vertices sampled on the objects' surfaces at most: beyond, the remaining objects (in tree order) are left
// bare, so a park of thousands of trees does not stall the view.
constexpr size_t kMaxSurfaceSamples = 300000;

struct ChannelMap {
    MarkerGeometry geometry;      // hull triangles: two per cell, then the surfaces' triangles
    std::vector<float> values;    // per cell, row by row from the extent's low corner
    int columns = 0, rows = 0;
    std::vector<float> surface_values;  // per sampled surface vertex (object by object, in mesh order)
    size_t surface_triangles = 0;       // in `geometry.hull` after the cells
    size_t objects_left_bare = 0;       // past kMaxSurfaceSamples
    float lo = 0.0f, hi = 0.0f;   // the ramp's ends (the legend): over the cells and the surfaces
};

// The ramp: t in [0, 1] from blue (low) through green to red (high).
glm::vec3 channelMapColor(float t);

// The map of `settings.channel` over the extent's XY in cells of about cell_m (at most 160 x 160 cells).
ChannelMap buildChannelMap(const Document& doc, const ChannelMapSettings& settings, float cell_m);

}  // namespace ug::editor
