// The icicles effect's decisions (§5.2): settings checks, the length model h(θ, η), which anchors get an
// icicle and which precomputed shape instances it, and the merged mesh for exporters without instancing.
#include "env/icicles.h"

#include <bit>
#include <cmath>
#include <string>

#include "core/hash.h"

namespace ug {
namespace {

constexpr float kTwoPi = 6.28318530718f;
constexpr uint64_t kSeedSalt = 0x5eed1c1e;
constexpr uint64_t kYawSalt = 0x7a3c1c1e;
constexpr uint64_t kLengthSalt = 0x1e7c1c1e;

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// w(η) of icicles.h: continuous and increasing, w(0) = 1, always > 0.
float humidityFactor(float humidity, float gain) {
    const float g = gain * humidity;
    return humidity >= 0.0f ? 1.0f + g : 1.0f / (1.0f - g);
}

// Hash of the anchor's position bits: stable when other anchors come and go.
uint64_t anchorHash(const glm::vec3& p, uint64_t salt) {
    return hashWords(std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y), std::bit_cast<uint32_t>(p.z), salt);
}

// The length class whose shape length is nearest to h in ratio (ties to the shorter class).
size_t nearestLengthClass(float h) {
    const std::vector<IcicleShape>& shapes = icicleShapes();
    size_t best = 0;
    float best_distance = INFINITY;
    for (size_t c = 0; c < kIcicleShapeLengths; ++c) {
        const float distance = std::abs(std::log(h / shapes[c * kIcicleShapeSeeds].length_m));
        if (distance < best_distance) best = c, best_distance = distance;
    }
    return best;
}

// The length an icicle of natural length h gets below a free drop of clearance (0: none); icicles.h.
float fitToClearance(float h, float clearance) {
    const float free = std::isnan(clearance) || clearance < 0.0f ? 0.0f : kIcicleClearanceUse * clearance;
    if (free >= h) return h;
    if (free >= 0.5f * h) return free;
    return 0.0f;
}

std::string fmt(float v) { return std::to_string(v); }

}  // namespace

std::string validateIcicleSettings(const IcicleSettings& s) {
    if (!finite(s.up) || std::abs(glm::length(s.up) - 1.0f) > 1e-3f)
        return "up must be a finite unit vector, got (" + fmt(s.up.x) + ", " + fmt(s.up.y) + ", " + fmt(s.up.z) + ")";
    if (!(s.spacing_m >= 0.001f) || !std::isfinite(s.spacing_m))
        return "spacing_m must be a finite distance >= 0.001 m, got " + fmt(s.spacing_m);
    if (!(s.sharp_angle_deg >= 0.0f && s.sharp_angle_deg < 180.0f))
        return "sharp_angle_deg must be in [0, 180), got " + fmt(s.sharp_angle_deg);
    if (!(s.max_length_m > 0.0f && s.max_length_m <= 10.0f))
        return "max_length_m must be in (0, 10] m, got " + fmt(s.max_length_m);
    if (!(s.length_per_degree_m >= 0.0f) || !std::isfinite(s.length_per_degree_m))
        return "length_per_degree_m must be finite and >= 0, got " + fmt(s.length_per_degree_m);
    if (!(s.humidity_gain >= 0.0f) || !std::isfinite(s.humidity_gain))
        return "humidity_gain must be finite and >= 0, got " + fmt(s.humidity_gain);
    if (!(s.length_variation >= 0.0f && s.length_variation < 1.0f))
        return "length_variation must be in [0, 1), got " + fmt(s.length_variation);
    if (s.anchors.size() > kMaxIcicleAnchors)
        return std::to_string(s.anchors.size()) + " authored anchors exceed the limit of " +
               std::to_string(kMaxIcicleAnchors);
    for (size_t k = 0; k < s.anchors.size(); ++k)
        if (!finite(s.anchors[k])) return "anchors[" + std::to_string(k) + "] is not finite";
    return "";
}

float icicleLength(float temperature, float humidity, const IcicleSettings& s) {
    if (!(temperature < 0.0f)) return 0.0f;  // also NaN
    const float w = std::isnan(humidity) ? 1.0f : humidityFactor(humidity, s.humidity_gain);
    const float h = s.length_per_degree_m * -temperature * w;
    return std::isnan(h) ? 0.0f : std::min(h, s.max_length_m);
}

glm::mat4 icicleTransform(const IcicleInstance& icicle) {
    const glm::vec3 up = glm::normalize(icicle.up);
    const glm::vec3 ref = std::abs(up.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    const glm::vec3 e1 = glm::normalize(ref - glm::dot(ref, up) * up);
    const glm::vec3 e2 = glm::cross(up, e1);
    const float c = std::cos(icicle.yaw_rad), sn = std::sin(icicle.yaw_rad);
    glm::mat4 m(1.0f);
    m[0] = glm::vec4(icicle.scale * (c * e1 + sn * e2), 0.0f);
    m[1] = glm::vec4(icicle.scale * (-sn * e1 + c * e2), 0.0f);
    m[2] = glm::vec4(icicle.scale * up, 0.0f);
    m[3] = glm::vec4(icicle.anchor, 1.0f);
    return m;
}

std::vector<IcicleInstance> placeIcicles(const std::vector<IcicleAnchor>& anchors, const std::vector<EnvSample>& env,
                                         const std::vector<float>& clearance_m, const IcicleSettings& s,
                                         std::string* error) {
    std::string why = validateIcicleSettings(s);
    if (why.empty() && (env.size() != anchors.size() || clearance_m.size() != anchors.size()))
        why = "placeIcicles needs one environment sample and one clearance per anchor: " +
              std::to_string(anchors.size()) + " anchors, " + std::to_string(env.size()) + " samples, " +
              std::to_string(clearance_m.size()) + " clearances";
    if (!why.empty()) {
        if (error) *error = why;
        return {};
    }
    const std::vector<IcicleShape>& shapes = icicleShapes();
    std::vector<IcicleInstance> out;
    for (size_t j = 0; j < anchors.size(); ++j) {
        const EnvSample& e = env[j];
        if (!(e.temperature < 0.0f && e.icicles > 0.0f)) continue;  // §5.2's presence test (NaN fails)
        const glm::vec3 p = anchors[j].position;
        const float natural = icicleLength(e.temperature, e.humidity, s) *
                              (1.0f - s.length_variation * unitFloat(anchorHash(p, kLengthSalt)));
        const float h = fitToClearance(natural, clearance_m[j]);
        if (!(h >= kMinIcicleLength_m)) continue;
        const size_t shape = nearestLengthClass(h) * kIcicleShapeSeeds + anchorHash(p, kSeedSalt) % kIcicleShapeSeeds;
        IcicleInstance icicle;
        icicle.shape = uint32_t(shape);
        icicle.anchor = p;
        icicle.yaw_rad = kTwoPi * unitFloat(anchorHash(p, kYawSalt));
        icicle.scale = h / shapes[shape].length_m;
        icicle.length_m = h;
        icicle.up = s.up;
        out.push_back(icicle);
    }
    return out;
}

TriangleMesh icicleMesh(const std::vector<IcicleInstance>& icicles, std::string* error) {
    const std::vector<IcicleShape>& shapes = icicleShapes();
    size_t triangles = 0;
    for (size_t k = 0; k < icicles.size(); ++k) {
        if (icicles[k].shape >= shapes.size()) {
            if (error)
                *error = "icicle " + std::to_string(k) + " names shape " + std::to_string(icicles[k].shape) + " of " +
                         std::to_string(shapes.size());
            return {};
        }
        if (!(icicles[k].scale > 0.0f) || !std::isfinite(icicles[k].scale)) {
            if (error) *error = "icicle " + std::to_string(k) + " has scale " + fmt(icicles[k].scale);
            return {};
        }
        triangles += shapes[icicles[k].shape].mesh.triangleCount();
        if (triangles > kMaxIcicleMeshTriangles) {
            if (error)
                *error = std::to_string(icicles.size()) + " icicles make more than " +
                         std::to_string(kMaxIcicleMeshTriangles) + " triangles";
            return {};
        }
    }
    TriangleMesh out;
    out.base_color = shapes.front().mesh.base_color;
    out.positions.reserve(triangles * 3 / 2 + icicles.size());
    out.normals.reserve(out.positions.capacity());
    out.indices.reserve(triangles * 3);
    for (const IcicleInstance& icicle : icicles) {
        const TriangleMesh& shape = shapes[icicle.shape].mesh;
        const glm::mat4 m = icicleTransform(icicle);
        const glm::mat3 rotation = glm::mat3(m) / icicle.scale;
        const uint32_t base = uint32_t(out.positions.size());
        for (const glm::vec3& p : shape.positions) out.positions.push_back(glm::vec3(m * glm::vec4(p, 1.0f)));
        for (const glm::vec3& n : shape.normals) out.normals.push_back(rotation * n);
        for (uint32_t i : shape.indices) out.indices.push_back(base + i);
    }
    return out;
}

}  // namespace ug
