#include "editor/channel_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "editor/tools.h"

namespace ug::editor {

namespace {

constexpr int kMaxCellsPerSide = 160;

float channelValue(const EnvSample& e, int channel) {
    switch (channel) {
        case int(EnvChannel::Snow): return e.snow;
        case int(EnvChannel::Icicles): return e.icicles;
        case int(EnvChannel::Leaves): return e.leaves;
        case int(EnvChannel::Grass): return e.grass;
        case int(EnvChannel::Trash): return e.trash;
        case int(EnvChannel::Occlusion): return e.occlusion;
        case int(EnvChannel::Humidity): return e.humidity;
        case int(EnvChannel::Temperature): return e.temperature;
        default: return e.shelter;
    }
}

// The channel (or the shelter) at every point: only the asked channel is summed, and the shelter's rays
// are cast only for the shelter.
std::vector<float> sampleChannel(const EnvScene& env, int channel, const std::vector<glm::vec3>& points) {
    std::vector<EnvSample> samples(points.size());
    if (channel < int(kEnvChannelCount))
        env.channelsBatch(points.data(), points.size(), samples.data(), envChannelBit(EnvChannel(channel)));
    else
        env.sampleBatch(points.data(), points.size(), samples.data());
    std::vector<float> values(samples.size());
    for (size_t k = 0; k < samples.size(); ++k) values[k] = channelValue(samples[k], channel);
    return values;
}

}  // namespace

const char* channelMapName(int channel) {
    return channel >= 0 && channel < int(kEnvChannelCount) ? envChannelName(EnvChannel(channel)) : "shelter";
}

bool channelMapFromName(const std::string& name, int* out) {
    for (int c = 0; c < kChannelMapChannels; ++c)
        if (name == channelMapName(c)) {
            *out = c;
            return true;
        }
    return false;
}

glm::vec3 channelMapColor(float t) {
    t = std::clamp(std::isfinite(t) ? t : 0.0f, 0.0f, 1.0f);
    const glm::vec3 stops[] = {{0.15f, 0.25f, 0.85f}, {0.1f, 0.75f, 0.85f}, {0.2f, 0.8f, 0.25f},
                               {0.95f, 0.85f, 0.15f}, {0.9f, 0.2f, 0.1f}};
    const float x = t * 4.0f;
    const int i = std::min(3, int(x));
    return glm::mix(stops[i], stops[i + 1], x - float(i));
}

ChannelMap buildChannelMap(const Document& doc, const ChannelMapSettings& settings, float cell_m) {
    ChannelMap map;
    const Bounds& extent = doc.compiled().extent;
    if (extent.empty() || !(cell_m > 0.0f)) return map;
    const glm::vec2 lo(extent.lo), size = glm::vec2(extent.hi) - lo;
    map.columns = std::clamp(int(std::ceil(size.x / cell_m)), 1, kMaxCellsPerSide);
    map.rows = std::clamp(int(std::ceil(size.y / cell_m)), 1, kMaxCellsPerSide);
    const glm::vec2 cell = size / glm::vec2(float(map.columns), float(map.rows));
    // Corners (shared by the cells around them) carry the slice's height; cells carry the value at their centre.
    auto corner = [&](int i, int j) {
        const glm::vec2 xy = lo + cell * glm::vec2(float(i), float(j));
        return glm::vec3(xy, groundHeightAt(doc, xy) + settings.height_m);
    };
    std::vector<glm::vec3> centres;
    centres.reserve(size_t(map.columns) * size_t(map.rows));
    for (int j = 0; j < map.rows; ++j)
        for (int i = 0; i < map.columns; ++i) {
            const glm::vec2 xy = lo + cell * glm::vec2(float(i) + 0.5f, float(j) + 0.5f);
            centres.push_back(glm::vec3(xy, groundHeightAt(doc, xy) + settings.height_m));
        }
    map.values = sampleChannel(*doc.environment(), settings.channel, centres);
    // The objects' surfaces: each vertex drawn 1 cm out along its normal, sampled 3 cm out (just outside:
    // the top of a roof is open, its underside sheltered).
    struct Placed {
        const TriangleMesh* mesh;
        size_t first;  // its first vertex in `drawn` / the samples
    };
    std::vector<Placed> placed;
    std::vector<glm::vec3> drawn, probes;
    if (settings.surfaces) {
        for (const EnvObject& o : doc.environment()->objects()) {
            const TriangleMesh& mesh = *doc.environment()->types()[o.type].mesh;
            if (mesh.normals.size() != mesh.positions.size()) continue;
            if (drawn.size() + mesh.positions.size() > kMaxSurfaceSamples) {
                ++map.objects_left_bare;
                continue;
            }
            placed.push_back({&mesh, drawn.size()});
            const EnvPlacement& p = o.placement;
            for (size_t v = 0; v < mesh.positions.size(); ++v) {
                const glm::vec3 n = mesh.normals[v];
                const glm::vec3 world_n(p.c * n.x - p.s * n.y, p.s * n.x + p.c * n.y, n.z);
                const glm::vec3 at = p.toWorld(mesh.positions[v]);
                drawn.push_back(at + 0.01f * world_n);
                probes.push_back(at + 0.03f * world_n);
            }
        }
        map.surface_values = sampleChannel(*doc.environment(), settings.channel, probes);
    }
    map.lo = std::numeric_limits<float>::infinity();
    map.hi = -std::numeric_limits<float>::infinity();
    for (const std::vector<float>* list : {&map.values, &map.surface_values})
        for (float v : *list) {
            map.lo = std::min(map.lo, v);
            map.hi = std::max(map.hi, v);
        }
    const float range = map.hi > map.lo ? map.hi - map.lo : 1.0f;
    map.geometry.hull.reserve(map.values.size() * 6);
    for (int j = 0; j < map.rows; ++j)
        for (int i = 0; i < map.columns; ++i) {
            const glm::vec3 c = channelMapColor((map.values[size_t(j) * size_t(map.columns) + size_t(i)] - map.lo) / range);
            const glm::vec3 a = corner(i, j), b = corner(i + 1, j), d = corner(i, j + 1), e = corner(i + 1, j + 1);
            for (const glm::vec3& p : {a, b, e, a, e, d}) map.geometry.hull.push_back({p, c});
        }
    for (const Placed& p : placed) {
        for (uint32_t index : p.mesh->indices) {
            const size_t v = p.first + index;
            map.geometry.hull.push_back({drawn[v], channelMapColor((map.surface_values[v] - map.lo) / range)});
        }
        map.surface_triangles += p.mesh->indices.size() / 3;
    }
    return map;
}

}  // namespace ug::editor
