// The parts of the snow effect every builder shares: settings validation, the paper's elevation profile
// and displacement, and the final environment pass (engine/env/snow_detail.h).
#include "env/snow.h"

#include <cmath>
#include <cstdio>

#include "env/snow_detail.h"

namespace ug {

namespace {

bool fail(std::string* error, const std::string& why) {
    if (error) *error = why;
    return false;
}

std::string num(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", double(v));
    return buf;
}

}  // namespace

bool validateSnowSettings(const SnowSettings& s, std::string* error) {
    if (!std::isfinite(s.up.x) || !std::isfinite(s.up.y) || !std::isfinite(s.up.z))
        return fail(error, "snow settings: up must be finite");
    const float len = glm::length(s.up);
    if (!(std::fabs(len - 1.0f) <= 1e-3f))
        return fail(error, "snow settings: up must be a unit vector (length " + num(len) + ")");
    if (!(s.max_face_angle_deg >= 0.0f && s.max_face_angle_deg <= 90.0f))
        return fail(error, "snow settings: max_face_angle_deg must be in [0, 90] (got " +
                               num(s.max_face_angle_deg) + ")");
    if (!(s.d0_m > 0.0f) || !std::isfinite(s.d0_m))
        return fail(error, "snow settings: d0_m must be finite and > 0 (got " + num(s.d0_m) + ")");
    if (!(s.target_edge_m > 0.0f) || !std::isfinite(s.target_edge_m))
        return fail(error,
                    "snow settings: target_edge_m must be finite and > 0 (got " + num(s.target_edge_m) + ")");
    if (!(s.min_open >= 0.0f && s.min_open <= 1.0f))
        return fail(error, "snow settings: min_open must be in [0, 1] (got " + num(s.min_open) + ")");
    return true;
}

float snowEdgeProfile(float d_m, float d0_m) {
    if (!(d_m > 0.0f)) return 0.0f;  // the border itself (and d < 0, which the profile does not define)
    if (d_m >= d0_m) return 1.0f;
    const float u = 1.0f - d_m / d0_m;
    const float v = 1.0f - u * u;
    const float v2 = v * v;
    return v2 * v2;
}

float snowDisplacement(const EnvSample& e, float d_m, float d0_m) {
    // Only warmth melts: a temperature below freezing adds no snow (the paper's θ is a melting term).
    const float melt = e.temperature > 0.0f ? e.temperature * kSnowMeltPerDegreeM : 0.0f;
    const float v = e.openness() * e.snow * snowEdgeProfile(d_m, d0_m) - melt;
    // Clamp to zero (no negative snow) but let a NaN through, so callers can report a broken environment.
    return v <= 0.0f ? 0.0f : v;
}

namespace snow_detail {

void appendGridTriangles(uint32_t nx, uint32_t ny, std::vector<uint32_t>* indices) {
    indices->reserve(indices->size() + size_t(6) * nx * ny);
    for (uint32_t j = 0; j < ny; ++j)
        for (uint32_t i = 0; i < nx; ++i) {
            const uint32_t a = j * (nx + 1) + i, b = a + 1, c = a + (nx + 1) + 1, d = a + (nx + 1);
            indices->insert(indices->end(), {a, b, c, a, c, d});
        }
}

namespace {

// The triangles that keep some snow, and the vertices they use renumbered in their original order.
// Also counts the distinct faces of `tri_face` (nondecreasing, or empty) that keep a triangle.
void dropBare(const std::vector<uint32_t>& indices, const std::vector<uint32_t>& tri_face,
              const std::vector<float>& disp, std::vector<uint32_t>* kept, std::vector<uint32_t>* remap,
              uint32_t* used_count, size_t* faces_kept) {
    *faces_kept = 0;
    uint32_t last_face = UINT32_MAX;
    kept->clear();
    kept->reserve(indices.size());
    std::vector<uint8_t> used(disp.size(), 0);
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
        if (disp[a] == 0.0f && disp[b] == 0.0f && disp[c] == 0.0f) continue;
        if (!tri_face.empty() && tri_face[t / 3] != last_face) {
            last_face = tri_face[t / 3];
            ++*faces_kept;
        }
        kept->push_back(a);
        kept->push_back(b);
        kept->push_back(c);
        used[a] = used[b] = used[c] = 1;
    }
    remap->assign(disp.size(), UINT32_MAX);
    uint32_t next = 0;
    for (size_t v = 0; v < disp.size(); ++v)
        if (used[v]) (*remap)[v] = next++;
    *used_count = next;
}

}  // namespace

bool finishSnowCover(SnowLayout&& layout, const SnowSettings& s, const EnvQuery& env,
                     bool zero_below_min_open, size_t base_faces_used_if_any, size_t patch_count,
                     SnowCover* out, std::string* error) {
    const size_t n = layout.surface.size();
    std::vector<EnvSample> samples(n);
    if (n > 0) env(layout.surface.data(), n, samples.data());

    std::vector<float> disp(n);
    for (size_t i = 0; i < n; ++i) {
        const EnvSample& e = samples[i];
        float d = snowDisplacement(e, layout.border_distance[i], s.d0_m);
        if (zero_below_min_open && !(e.shelter >= s.min_open)) d = 0.0f;
        // The border stays on the base (g(0) = 0): pinned, so no rounding lifts it off and opens a crack.
        if (layout.border_distance[i] == 0.0f) d = 0.0f;
        if (!std::isfinite(d))
            return fail(error, "snow: the environment gives a non-finite displacement at vertex " +
                                   std::to_string(i) + " (snow " + num(e.snow) + ", occlusion " +
                                   num(e.occlusion) + ", shelter " + num(e.shelter) + ", temperature " +
                                   num(e.temperature) + ")");
        disp[i] = d;
    }

    std::vector<uint32_t> kept, remap;
    uint32_t used_count = 0;
    size_t faces_kept = 0;
    dropBare(layout.indices, layout.tri_face, disp, &kept, &remap, &used_count, &faces_kept);

    SnowCover cover;
    cover.triangles_before_drop = layout.indices.size() / 3;
    cover.mesh.base_color = glm::vec3(0.9f, 0.92f, 0.95f);
    cover.mesh.positions.resize(used_count);
    cover.surface_positions.resize(used_count);
    cover.displacement_m.resize(used_count);
    cover.border_distance_m.resize(used_count);
    const glm::vec3 up = unitUp(s);
    for (size_t v = 0; v < n; ++v) {
        const uint32_t r = remap[v];
        if (r == UINT32_MAX) continue;
        cover.surface_positions[r] = layout.surface[v];
        cover.displacement_m[r] = disp[v];
        cover.border_distance_m[r] = layout.border_distance[v];
        cover.mesh.positions[r] = layout.surface[v] + up * disp[v];
    }
    for (uint32_t& i : kept) i = remap[i];
    cover.mesh.indices = std::move(kept);
    computeNormals(&cover.mesh);
    const bool any = !cover.mesh.indices.empty();
    cover.base_faces_used = !layout.tri_face.empty() ? faces_kept : (any ? base_faces_used_if_any : 0);
    cover.patch_count = any ? patch_count : 0;
    *out = std::move(cover);
    return true;
}

}  // namespace snow_detail

}  // namespace ug
