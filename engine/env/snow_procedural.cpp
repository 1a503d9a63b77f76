// Procedural snow (§5.1 "black box" effects): the snow of a box top, a cylinder top and a sphere cap,
// generated directly at the target edge length with the exact distance to the rim, no extraction.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "env/snow.h"
#include "env/snow_detail.h"

namespace ug {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr double kPi = 3.14159265358979323846;

// The longest edge of the ring disc below is at most this many ring spacings (sqrt(1 + (π/3)²) ≈ 1.448
// is the limit of the spoke-and-arc diagonal; measured maxima stay below it for every ring count).
constexpr double kRingDiscEdgeRatio = 1.46;

bool fail(std::string* error, const std::string& why) {
    if (error) *error = why;
    return false;
}

bool finite3(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool tooMany(double triangles, const char* what, std::string* error) {
    if (triangles <= double(kMaxSnowTriangles)) return false;
    fail(error, std::string("snow: the ") + what + " would take about " +
                    std::to_string(uint64_t(std::min(triangles, 1e18))) + " triangles (more than " +
                    std::to_string(kMaxSnowTriangles) + "); raise target_edge_m");
    return true;
}

// An empty cover (no snow can lie there), as a success.
bool emptyCover(SnowCover* out) {
    SnowCover c;
    c.mesh.base_color = glm::vec3(0.9f, 0.92f, 0.95f);
    *out = std::move(c);
    return true;
}

// Whether the +Z top of a box or cylinder faces `up` closely enough to take snow.
bool topTakesSnow(const SnowSettings& s) {
    const glm::vec3 up = snow_detail::unitUp(s);
    return up.z >= std::cos(glm::radians(s.max_face_angle_deg));
}

// Ring count so that the disc's longest edge (kRingDiscEdgeRatio ring spacings) stays <= target.
double ringCount(double extent_m, float target_m) {
    return std::max(1.0, std::ceil(kRingDiscEdgeRatio * extent_m / double(target_m)));
}

// A disc of K rings around a centre vertex, ring k (1..K) holding 6k vertices at angles 2πj / 6k, and
// the triangles joining consecutive rings (counter-clockwise in the (k, angle) plane): 6K² in all.
// `point(k, j)` gives the vertex and its border distance; ring K is the rim.
template <class Point>
snow_detail::SnowLayout ringDisc(uint32_t K, Point point) {
    snow_detail::SnowLayout out;
    const size_t verts = 1 + size_t(3) * K * (K + 1);
    out.surface.reserve(verts);
    out.border_distance.reserve(verts);
    out.indices.reserve(size_t(18) * K * K);
    for (uint32_t k = 0; k <= K; ++k)
        for (uint32_t j = 0; j < (k == 0 ? 1u : 6 * k); ++j) {
            float d = 0.0f;
            out.surface.push_back(point(k, j, &d));
            out.border_distance.push_back(d);
        }
    auto start = [](uint32_t k) { return k == 0 ? 0u : 1 + 3 * k * (k - 1); };
    for (uint32_t j = 0; j < 6; ++j)
        out.indices.insert(out.indices.end(), {0u, start(1) + j, start(1) + (j + 1) % 6});
    for (uint32_t k = 2; k <= K; ++k) {
        const uint32_t m1 = 6 * (k - 1), m2 = 6 * k, s1 = start(k - 1), s2 = start(k);
        uint32_t a = 0, b = 0;
        // Zip the two rings by angle: advance the ring whose next edge midpoint comes first (exact in
        // integers), which keeps the diagonals short and every triangle counter-clockwise.
        while (a < m1 || b < m2) {
            if (b < m2 && (a >= m1 || uint64_t(2 * b + 1) * m1 < uint64_t(2 * a + 1) * m2)) {
                out.indices.insert(out.indices.end(), {s1 + a % m1, s2 + b, s2 + (b + 1) % m2});
                ++b;
            } else {
                out.indices.insert(out.indices.end(), {s1 + a, s2 + b % m2, s1 + (a + 1) % m1});
                ++a;
            }
        }
    }
    return out;
}

}  // namespace

std::vector<SnowBorderSide> snowBoxSides(glm::vec3 center, glm::vec3 half_extents, const SnowSettings& s) {
    if (!validateSnowSettings(s, nullptr) || !finite3(center) || !finite3(half_extents) || !topTakesSnow(s))
        return {};
    const float x0 = center.x - half_extents.x, x1 = center.x + half_extents.x;
    const float y0 = center.y - half_extents.y, y1 = center.y + half_extents.y;
    const float z = center.z + half_extents.z;
    const glm::vec3 top(center.x, center.y, z);
    return {SnowBorderSide{{x0, y0, z}, {x1, y0, z}, {0, 1, 0}, top}, SnowBorderSide{{x1, y0, z}, {x1, y1, z}, {-1, 0, 0}, top},
            SnowBorderSide{{x0, y1, z}, {x1, y1, z}, {0, -1, 0}, top}, SnowBorderSide{{x0, y0, z}, {x0, y1, z}, {1, 0, 0}, top}};
}

bool buildBoxSnow(glm::vec3 center, glm::vec3 half_extents, const SnowSettings& s, const EnvQuery& env,
                  SnowCover* out, std::string* error) {
    if (!validateSnowSettings(s, error)) return false;
    if (!finite3(center) || !finite3(half_extents) ||
        !(half_extents.x > 0 && half_extents.y > 0 && half_extents.z > 0))
        return fail(error, "snow box: center must be finite and half_extents finite and > 0");
    if (!env) return fail(error, "snow: no environment query");
    if (!topTakesSnow(s)) return emptyCover(out);

    // The sides another object's snow continues beyond (-y, +x, +y, -x: snowBoxSides' order) are no rim:
    // the cover reaches half way across their joint.
    const std::vector<SnowBorderSide> sides = snowBoxSides(center, half_extents, s);
    float gap[4] = {-1.0f, -1.0f, -1.0f, -1.0f};  // < 0: a rim
    for (const SnowSegment& g : s.bridged_borders)
        for (int k = 0; k < 4; ++k)
            if ((g.a == sides[size_t(k)].a && g.b == sides[size_t(k)].b) || (g.a == sides[size_t(k)].b && g.b == sides[size_t(k)].a))
                gap[k] = std::max(gap[k], std::max(0.0f, g.gap_m));
    const float x0 = center.x - half_extents.x - 0.5f * std::max(0.0f, gap[3]);
    const float x1 = center.x + half_extents.x + 0.5f * std::max(0.0f, gap[1]);
    const float y0 = center.y - half_extents.y - 0.5f * std::max(0.0f, gap[0]);
    const float y1 = center.y + half_extents.y + 0.5f * std::max(0.0f, gap[2]);
    const float z = center.z + half_extents.z;

    // Square-ish cells whose diagonal is <= target.
    const double cell = double(s.target_edge_m) / std::sqrt(2.0);
    const double wx = 2.0 * double(half_extents.x) + 0.5 * double(std::max(0.0f, gap[1]) + std::max(0.0f, gap[3]));
    const double wy = 2.0 * double(half_extents.y) + 0.5 * double(std::max(0.0f, gap[0]) + std::max(0.0f, gap[2]));
    const double nxd = std::max(1.0, std::ceil(wx / cell));
    const double nyd = std::max(1.0, std::ceil(wy / cell));
    if (tooMany(2.0 * nxd * nyd, "box top", error)) return false;
    const uint32_t nx = uint32_t(nxd), ny = uint32_t(nyd);

    snow_detail::SnowLayout layout;
    layout.surface.reserve(size_t(nx + 1) * (ny + 1));
    layout.border_distance.reserve(size_t(nx + 1) * (ny + 1));
    for (uint32_t j = 0; j <= ny; ++j) {
        // The rim lands exactly on the box's sides.
        const float y = j == ny ? y1 : y0 + (y1 - y0) * (float(j) / float(ny));
        for (uint32_t i = 0; i <= nx; ++i) {
            const float x = i == nx ? x1 : x0 + (x1 - x0) * (float(i) / float(nx));
            // The distance to the nearest rim side (bridged sides are none).
            float d = kInf;
            if (gap[3] < 0.0f) d = std::min(d, x - x0);
            if (gap[1] < 0.0f) d = std::min(d, x1 - x);
            if (gap[0] < 0.0f) d = std::min(d, y - y0);
            if (gap[2] < 0.0f) d = std::min(d, y1 - y);
            const bool rim = (i == 0 && gap[3] < 0.0f) || (i == nx && gap[1] < 0.0f) || (j == 0 && gap[0] < 0.0f) ||
                             (j == ny && gap[2] < 0.0f);
            if (rim) d = 0.0f;
            layout.surface.emplace_back(x, y, z);
            layout.border_distance.push_back(d < s.d0_m ? d : kInf);
        }
    }
    snow_detail::appendGridTriangles(nx, ny, &layout.indices);
    return snow_detail::finishSnowCover(std::move(layout), s, env, /*zero_below_min_open=*/true, 1, 1, out,
                                        error);
}

bool buildCylinderSnow(glm::vec3 base_center, float radius, float height, const SnowSettings& s,
                       const EnvQuery& env, SnowCover* out, std::string* error) {
    if (!validateSnowSettings(s, error)) return false;
    if (!finite3(base_center) || !(radius > 0 && std::isfinite(radius)) ||
        !(height > 0 && std::isfinite(height)))
        return fail(error, "snow cylinder: base_center must be finite, radius and height finite and > 0");
    if (!env) return fail(error, "snow: no environment query");
    if (!topTakesSnow(s)) return emptyCover(out);

    const double Kd = ringCount(radius, s.target_edge_m);
    if (tooMany(6.0 * Kd * Kd, "cylinder top", error)) return false;
    const uint32_t K = uint32_t(Kd);
    const float z = base_center.z + height;
    snow_detail::SnowLayout layout = ringDisc(K, [&](uint32_t k, uint32_t j, float* d) {
        if (k == 0) {
            *d = radius < s.d0_m ? radius : kInf;
            return glm::vec3(base_center.x, base_center.y, z);
        }
        const float r = k == K ? radius : radius * (float(k) / float(K));
        const double a = 2.0 * kPi * double(j) / double(6 * k);
        const float dist = radius - r;
        *d = k == K ? 0.0f : (dist < s.d0_m ? dist : kInf);
        return glm::vec3(base_center.x + r * float(std::cos(a)), base_center.y + r * float(std::sin(a)), z);
    });
    return snow_detail::finishSnowCover(std::move(layout), s, env, /*zero_below_min_open=*/true, 1, 1, out,
                                        error);
}

bool buildSphereSnow(glm::vec3 center, float radius, const SnowSettings& s, const EnvQuery& env,
                     SnowCover* out, std::string* error) {
    if (!validateSnowSettings(s, error)) return false;
    if (!finite3(center) || !(radius > 0 && std::isfinite(radius)))
        return fail(error, "snow sphere: center must be finite and radius finite and > 0");
    if (!env) return fail(error, "snow: no environment query");
    const double phi_max = glm::radians(double(s.max_face_angle_deg));
    if (!(phi_max > 0.0)) return emptyCover(out);

    // A sphere looks the same from every side: its cap is centred on `up` itself.
    const glm::vec3 up = snow_detail::unitUp(s);
    const glm::vec3 helper = std::fabs(up.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    const glm::vec3 ex = glm::normalize(glm::cross(helper, up)), ey = glm::cross(up, ex);

    const double Kd = ringCount(double(radius) * phi_max, s.target_edge_m);
    if (tooMany(6.0 * Kd * Kd, "sphere cap", error)) return false;
    const uint32_t K = uint32_t(Kd);
    snow_detail::SnowLayout layout = ringDisc(K, [&](uint32_t k, uint32_t j, float* d) {
        const double phi = phi_max * double(k) / double(K);
        const double a = k == 0 ? 0.0 : 2.0 * kPi * double(j) / double(6 * k);
        const float geodesic = float(double(radius) * (phi_max - phi));  // along the sphere to the rim
        *d = k == K ? 0.0f : (geodesic < s.d0_m ? geodesic : kInf);
        const float sp = float(std::sin(phi)), cp = float(std::cos(phi));
        const glm::vec3 dir = up * cp + (ex * float(std::cos(a)) + ey * float(std::sin(a))) * sp;
        return center + dir * radius;
    });
    return snow_detail::finishSnowCover(std::move(layout), s, env, /*zero_below_min_open=*/true, 1, 1, out,
                                        error);
}

}  // namespace ug
