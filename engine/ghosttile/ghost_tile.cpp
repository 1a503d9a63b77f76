// Ghost Tile creation (Guérin et al. 2016, §4.2 candidates, §4.3 collision graph).
//
// Where we differ from the paper:
// - Random numbers are a hash of (seed, type, candidate, draw), not a generator's state, so a candidate's
//   frame does not depend on the other types' counts or on the build order.
// - The grid accelerates sphere-vs-sphere tests, not object-vs-object ones: every sphere of every
//   candidate copy near the tile goes into the cells its box overlaps, and each home candidate's spheres
//   query those cells. Leaves and branches carry tens of spheres, so this turns the paper's 93 s build
//   (1.12k candidates, 990k pairs) into well under a second (see `undergrowth bench`).
// - Rows are computed independently in parallel (each pair is found from both sides), then sorted, so
//   the graph is bit-identical for any thread count and every edge has its mirror by construction of
//   the symmetric predicate spheresCollide().
#include "ghosttile/ghost_tile.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/hash.h"
#include "core/parallel.h"

namespace ug {

namespace {

constexpr uint32_t kBuilderVersion = 1;  // bump when candidate generation or the graph changes

bool finite(float v) { return std::isfinite(v); }

std::string typeLabel(const GhostTileInput& input, size_t t) {
    std::string label = "detail type " + std::to_string(t);
    if (t < input.types.size() && !input.types[t].name.empty()) label += " '" + input.types[t].name + "'";
    return label;
}

// Uniform random rotation (Shoemake 1992) from three uniforms.
glm::quat uniformRotation(double u1, double u2, double u3) {
    const double two_pi = 6.283185307179586;
    double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
    return glm::normalize(glm::quat(float(b * std::cos(two_pi * u3)), float(a * std::sin(two_pi * u2)),
                                    float(a * std::cos(two_pi * u2)), float(b * std::sin(two_pi * u3))));
}

glm::quat tiltRotation(const OrientationDistribution& o, uint64_t h) {
    double total = 0.0;
    for (const TiltRange& r : o.tilt_ranges) total += r.weight;
    double pick = unitDouble(hashWords(h, 1)) * total;
    const TiltRange* range = &o.tilt_ranges.back();
    for (const TiltRange& r : o.tilt_ranges) {
        if (pick < r.weight) {
            range = &r;
            break;
        }
        pick -= r.weight;
    }
    // Uniform by solid angle inside the band [min, max]: cos(tilt) is uniform between the two cosines.
    const double deg = 0.017453292519943295;
    double c0 = std::cos(range->min_deg * deg), c1 = std::cos(range->max_deg * deg);
    double cos_tilt = c0 + (c1 - c0) * unitDouble(hashWords(h, 2));
    double tilt = std::acos(std::clamp(cos_tilt, -1.0, 1.0));
    double azimuth = 6.283185307179586 * unitDouble(hashWords(h, 3));  // direction the object leans to
    double spin = 6.283185307179586 * unitDouble(hashWords(h, 4));     // yaw about its own axis
    glm::quat rz_azimuth = glm::angleAxis(float(azimuth), glm::vec3(0, 0, 1));
    glm::quat ry_tilt = glm::angleAxis(float(tilt), glm::vec3(0, 1, 0));
    glm::quat rz_spin = glm::angleAxis(float(spin), glm::vec3(0, 0, 1));
    return glm::normalize(rz_azimuth * ry_tilt * rz_spin);
}

}  // namespace

bool validateGhostTileInput(const GhostTileInput& input, std::string* error) {
    const GhostTileSettings& s = input.settings;
    if (!finite(s.tile_size_m) || s.tile_size_m <= 0.0f || s.tile_size_m > 1000.0f) {
        *error = "ghost tile: tile_size_m must be in (0, 1000] metres, got " + std::to_string(s.tile_size_m);
        return false;
    }
    if (!finite(s.delta_m) || std::abs(s.delta_m) > s.tile_size_m) {
        *error = "ghost tile: delta_m must be finite and no larger than the tile, got " + std::to_string(s.delta_m);
        return false;
    }
    if (input.types.empty()) {
        *error = "ghost tile: no detail types";
        return false;
    }
    if (input.types.size() > 65535) {
        *error = "ghost tile: " + std::to_string(input.types.size()) + " detail types (at most 65535)";
        return false;
    }
    if (input.models.size() != input.types.size()) {
        *error = "ghost tile: " + std::to_string(input.types.size()) + " detail types but " +
                 std::to_string(input.models.size()) + " models";
        return false;
    }
    uint64_t total = 0;
    float largest_radius = 0.0f;
    for (size_t t = 0; t < input.types.size(); ++t) {
        const DetailTypeSettings& d = input.types[t];
        const std::string where = "ghost tile: " + typeLabel(input, t);
        if (d.candidate_count == 0) {
            *error = where + ": candidate_count is 0 (at least 1)";
            return false;
        }
        if (d.candidate_count > kMaxCandidatesPerTile) {
            *error = where + ": candidate_count " + std::to_string(d.candidate_count) + " exceeds the limit of " +
                     std::to_string(kMaxCandidatesPerTile) + " per tile";
            return false;
        }
        total += d.candidate_count;
        if (!finite(d.scale_min) || !finite(d.scale_max) || d.scale_min <= 0.0f || d.scale_max < d.scale_min ||
            d.scale_max > 100.0f) {
            *error = where + ": scale range [" + std::to_string(d.scale_min) + ", " + std::to_string(d.scale_max) +
                     "] must satisfy 0 < scale_min <= scale_max <= 100";
            return false;
        }
        if (d.orientation.mode == OrientationMode::Tilt) {
            if (d.orientation.tilt_ranges.empty()) {
                *error = where + ": orientation 'tilt' needs at least one tilt range";
                return false;
            }
            for (size_t r = 0; r < d.orientation.tilt_ranges.size(); ++r) {
                const TiltRange& tr = d.orientation.tilt_ranges[r];
                if (!finite(tr.min_deg) || !finite(tr.max_deg) || !finite(tr.weight) || tr.min_deg < 0.0f ||
                    tr.max_deg > 180.0f || tr.min_deg > tr.max_deg || tr.weight <= 0.0f) {
                    *error = where + ": tilt range " + std::to_string(r) +
                             " must have 0 <= min_deg <= max_deg <= 180 and weight > 0";
                    return false;
                }
            }
        }
        const DetailModel* m = input.models[t];
        if (m == nullptr || m->spheres.empty()) {
            *error = where + ": its model has no collision spheres";
            return false;
        }
        for (size_t k = 0; k < m->spheres.size(); ++k) {
            const Sphere& sp = m->spheres[k];
            if (!finite(sp.center.x) || !finite(sp.center.y) || !finite(sp.center.z) || !finite(sp.radius) ||
                sp.radius <= 0.0f) {
                *error = where + ": collision sphere " + std::to_string(k) + " is not finite or has radius <= 0";
                return false;
            }
        }
        largest_radius = std::max(largest_radius, m->bounds.radius * d.scale_max);
    }
    if (total > kMaxCandidatesPerTile) {
        *error = "ghost tile: " + std::to_string(total) + " candidates in all exceeds the limit of " +
                 std::to_string(kMaxCandidatesPerTile) + " per tile";
        return false;
    }
    // A candidate may only reach the 26 neighbour tiles: objects larger than the tile would need more.
    if (2.0f * largest_radius + std::max(0.0f, s.delta_m) > s.tile_size_m) {
        *error = "ghost tile: the largest object (diameter " + std::to_string(2.0f * largest_radius) +
                 " m at its largest scale) does not fit in the tile (" + std::to_string(s.tile_size_m) +
                 " m); the paper uses a tile 1-3x the largest object";
        return false;
    }
    return true;
}

uint64_t ghostTileKey(const GhostTileInput& input) {
    Hasher h;
    h.add(kBuilderVersion);
    h.add(input.settings.tile_size_m);
    h.add(input.settings.delta_m);
    h.add(input.settings.seed);
    h.add(uint64_t(input.types.size()));
    for (size_t t = 0; t < input.types.size(); ++t) {
        const DetailTypeSettings& d = input.types[t];
        h.add(d.candidate_count);
        h.add(d.orientation.mode);
        h.add(uint64_t(d.orientation.tilt_ranges.size()));
        for (const TiltRange& r : d.orientation.tilt_ranges) {
            h.add(r.min_deg);
            h.add(r.max_deg);
            h.add(r.weight);
        }
        h.add(d.scale_min);
        h.add(d.scale_max);
        h.add(d.position);
        const DetailModel* m = t < input.models.size() ? input.models[t] : nullptr;
        uint64_t sphere_count = m ? m->spheres.size() : 0;
        h.add(sphere_count);
        if (m) {
            for (const Sphere& s : m->spheres) {
                h.add(s.center);
                h.add(s.radius);
            }
            h.add(m->bounds.center);
            h.add(m->bounds.radius);
        }
    }
    return h.value();
}

bool generateCandidates(const GhostTileInput& input, CandidateSet* out, std::string* error) {
    if (!validateGhostTileInput(input, error)) return false;
    const float s = input.settings.tile_size_m;
    CandidateSet c;
    c.type_begin.push_back(0);
    for (const DetailTypeSettings& d : input.types) c.type_begin.push_back(c.type_begin.back() + d.candidate_count);
    const uint32_t n = c.type_begin.back();
    c.type.resize(n);
    c.position.resize(n);
    c.rotation.resize(n);
    c.scale.resize(n);
    for (uint32_t t = 0; t < input.types.size(); ++t) {
        const DetailTypeSettings& d = input.types[t];
        // Jittered: the smallest g with g^3 >= count; candidate j takes cell floor(j g^3 / count), so cells
        // are spread evenly when the count is not a cube.
        uint32_t g = 1;
        while (uint64_t(g) * g * g < d.candidate_count) ++g;
        const uint64_t cells = uint64_t(g) * g * g;
        for (uint32_t j = 0; j < d.candidate_count; ++j) {
            const uint32_t idx = c.type_begin[t] + j;
            const uint64_t h = hashWords(input.settings.seed, t, j, 0x67686f7374ull);  // "ghost"
            glm::vec3 u(unitFloat(hashWords(h, 10)), unitFloat(hashWords(h, 11)), unitFloat(hashWords(h, 12)));
            glm::vec3 p;
            if (d.position == PositionMode::Jittered) {
                uint64_t cell = uint64_t(j) * cells / d.candidate_count;
                glm::vec3 cell_xyz(float(cell % g), float(cell / g % g), float(cell / (uint64_t(g) * g)));
                p = (cell_xyz + u) * (s / float(g));
            } else {
                p = u * s;
            }
            // Keep positions in [0, s): float rounding of (cell + u) * s / g may reach s.
            p = glm::min(p, glm::vec3(std::nextafter(s, 0.0f)));
            c.position[idx] = p;
            c.rotation[idx] = d.orientation.mode == OrientationMode::Tilt
                                  ? tiltRotation(d.orientation, hashWords(h, 20))
                                  : uniformRotation(unitDouble(hashWords(h, 21)), unitDouble(hashWords(h, 22)),
                                                    unitDouble(hashWords(h, 23)));
            c.scale[idx] = d.scale_min + (d.scale_max - d.scale_min) * unitFloat(hashWords(h, 30));
            c.type[idx] = uint16_t(t);
        }
    }
    *out = std::move(c);
    return true;
}

void candidateSpheres(const CandidateSet& candidates, uint32_t index, const DetailModel& model,
                      std::vector<Sphere>* out) {
    out->clear();
    const glm::quat& q = candidates.rotation[index];
    const float sc = candidates.scale[index];
    const glm::vec3& p = candidates.position[index];
    for (const Sphere& s : model.spheres) out->push_back({p + q * (sc * s.center), sc * s.radius});
}

namespace {

// One sphere of one candidate copy, as stored in the grid.
struct GridSphere {
    glm::vec3 center;  // tile space of the copy's own tile (the offset is applied in the predicate)
    float radius;
    uint32_t key;      // j * 27 + offset index
};

struct SphereGrid {
    glm::vec3 origin{0.0f};
    float cell_m = 1.0f;
    glm::ivec3 dims{1};
    std::vector<uint32_t> cell_begin;  // CSR over cells
    std::vector<GridSphere> entries;

    glm::ivec3 cellOf(const glm::vec3& p) const {
        glm::ivec3 c = glm::ivec3(glm::floor((p - origin) / cell_m));
        return glm::clamp(c, glm::ivec3(0), dims - 1);
    }
    size_t flat(int x, int y, int z) const { return (size_t(z) * dims.y + y) * dims.x + x; }
};

}  // namespace

bool buildGhostTile(const GhostTileInput& input, const BuildOptions& options, GhostTile* out, std::string* error) {
    const auto t0 = std::chrono::steady_clock::now();
    CandidateSet cand;
    if (!generateCandidates(input, &cand, error)) return false;
    const uint32_t n = cand.size();
    const float s = input.settings.tile_size_m;
    const float delta = input.settings.delta_m;
    const float delta_pos = std::max(0.0f, delta);
    const int threads = resolveThreadCount(options.threads);
    auto cancelled = [&] { return options.cancel && options.cancel->load(std::memory_order_relaxed); };
    auto progress = [&](float f) {
        if (options.progress) options.progress(f);
    };

    // Home spheres (offset 0), flattened: candidate i owns [sphere_begin[i], sphere_begin[i+1]).
    std::vector<uint32_t> sphere_begin(size_t(n) + 1, 0);
    for (uint32_t i = 0; i < n; ++i)
        sphere_begin[i + 1] = sphere_begin[i] + uint32_t(input.models[cand.type[i]]->spheres.size());
    std::vector<Sphere> home(sphere_begin[n]);
    std::vector<Sphere> bound(n);  // per-candidate bounding sphere
    float max_sphere_r = 0.0f;
    std::vector<float> radii;
    radii.reserve(home.size());
    {
        std::vector<Sphere> tmp;
        for (uint32_t i = 0; i < n; ++i) {
            const DetailModel& m = *input.models[cand.type[i]];
            candidateSpheres(cand, i, m, &tmp);
            std::copy(tmp.begin(), tmp.end(), home.begin() + sphere_begin[i]);
            bound[i] = {cand.position[i] + cand.rotation[i] * (cand.scale[i] * m.bounds.center),
                        cand.scale[i] * m.bounds.radius};
            for (const Sphere& sp : tmp) {
                max_sphere_r = std::max(max_sphere_r, sp.radius);
                radii.push_back(sp.radius);
            }
        }
    }
    progress(0.05f);

    // Region the home spheres' query boxes reach; copies are inserted only where they overlap it.
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const Sphere& sp : home) {
        lo = glm::min(lo, sp.center - (sp.radius + delta_pos));
        hi = glm::max(hi, sp.center + (sp.radius + delta_pos));
    }
    // Cell size: about two median sphere diameters. Spheres go into every cell their box overlaps, so
    // the large rocks' spheres cost a few extra entries rather than a coarse grid for everyone.
    std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
    const float median_r = radii[radii.size() / 2];
    SphereGrid grid;
    grid.origin = lo;
    const glm::vec3 extent = hi - lo;
    grid.cell_m = std::max(4.0f * median_r + delta_pos, std::max({extent.x, extent.y, extent.z}) / 128.0f);
    grid.dims = glm::max(glm::ivec3(1), glm::ivec3(glm::ceil(extent / grid.cell_m)));

    // Count, then fill, the entries of every candidate copy (j, v) whose spheres reach the region.
    auto forEachCopySphere = [&](auto&& visit) {
        for (uint32_t v = 0; v < kOffsetCount; ++v) {
            const glm::vec3 shift = glm::vec3(offsetVector(v)) * s;
            for (uint32_t j = 0; j < n; ++j) {
                const Sphere& b = bound[j];
                glm::vec3 bc = b.center + shift;
                if (glm::any(glm::lessThan(bc + b.radius, lo)) || glm::any(glm::greaterThan(bc - b.radius, hi)))
                    continue;
                for (uint32_t k = sphere_begin[j]; k < sphere_begin[j + 1]; ++k) {
                    const Sphere& sp = home[k];
                    glm::vec3 c = sp.center + shift;
                    if (glm::any(glm::lessThan(c + sp.radius, lo)) || glm::any(glm::greaterThan(c - sp.radius, hi)))
                        continue;
                    glm::ivec3 a = grid.cellOf(c - sp.radius), z = grid.cellOf(c + sp.radius);
                    for (int cz = a.z; cz <= z.z; ++cz)
                        for (int cy = a.y; cy <= z.y; ++cy)
                            for (int cx = a.x; cx <= z.x; ++cx)
                                visit(grid.flat(cx, cy, cz), GridSphere{sp.center, sp.radius, j * kOffsetCount + v});
                }
            }
        }
    };
    const size_t cell_count = size_t(grid.dims.x) * grid.dims.y * grid.dims.z;
    grid.cell_begin.assign(cell_count + 1, 0);
    forEachCopySphere([&](size_t cell, const GridSphere&) { grid.cell_begin[cell + 1]++; });
    for (size_t c = 0; c < cell_count; ++c) grid.cell_begin[c + 1] += grid.cell_begin[c];
    grid.entries.resize(grid.cell_begin[cell_count]);
    {
        std::vector<uint32_t> cursor(grid.cell_begin.begin(), grid.cell_begin.end() - 1);
        forEachCopySphere([&](size_t cell, const GridSphere& e) { grid.entries[cursor[cell]++] = e; });
    }
    progress(0.15f);
    if (cancelled()) {
        *error = "ghost tile build cancelled";
        return false;
    }

    // Rows in parallel. Each chunk of rows encodes into its own byte buffer; buffers are concatenated in
    // chunk order, so the stream does not depend on the thread count.
    const size_t chunk = 16;
    const size_t chunk_count = (size_t(n) + chunk - 1) / chunk;
    std::vector<std::vector<uint8_t>> chunk_bytes(chunk_count);
    std::vector<uint32_t> row_size(n, 0);
    std::vector<std::vector<uint32_t>> stamp(static_cast<size_t>(threads));
    std::vector<std::vector<uint32_t>> row_keys(static_cast<size_t>(threads));
    std::atomic<uint64_t> total_bytes{0};
    std::atomic<bool> too_big{false};
    std::atomic<size_t> rows_done{0};
    parallelFor(n, threads, chunk, [&](size_t begin, size_t end, int worker) {
        if (cancelled() || too_big.load(std::memory_order_relaxed)) return;
        std::vector<uint32_t>& seen = stamp[size_t(worker)];
        if (seen.empty()) seen.assign(size_t(n) * kOffsetCount, ~0u);
        std::vector<uint32_t>& keys = row_keys[size_t(worker)];
        std::vector<uint8_t>& bytes = chunk_bytes[begin / chunk];
        for (size_t i = begin; i < end; ++i) {
            keys.clear();
            const uint32_t self_key = uint32_t(i) * kOffsetCount + kCenterOffset;
            seen[self_key] = uint32_t(i);  // a candidate never collides with itself
            for (uint32_t k = sphere_begin[i]; k < sphere_begin[i + 1]; ++k) {
                const Sphere& a = home[k];
                glm::ivec3 c0 = grid.cellOf(a.center - (a.radius + delta_pos));
                glm::ivec3 c1 = grid.cellOf(a.center + (a.radius + delta_pos));
                for (int cz = c0.z; cz <= c1.z; ++cz)
                    for (int cy = c0.y; cy <= c1.y; ++cy)
                        for (int cx = c0.x; cx <= c1.x; ++cx) {
                            size_t cell = grid.flat(cx, cy, cz);
                            for (uint32_t e = grid.cell_begin[cell]; e < grid.cell_begin[cell + 1]; ++e) {
                                const GridSphere& b = grid.entries[e];
                                if (seen[b.key] == uint32_t(i)) continue;
                                glm::vec3 shift = glm::vec3(offsetVector(b.key % kOffsetCount)) * s;
                                if (spheresCollide(a.center, a.radius, b.center, b.radius, shift, delta)) {
                                    seen[b.key] = uint32_t(i);
                                    keys.push_back(b.key);
                                }
                            }
                        }
            }
            std::sort(keys.begin(), keys.end());
            const size_t before = bytes.size();
            CollisionGraph::encodeRow(keys.data(), keys.size(), &bytes);
            row_size[i] = uint32_t(bytes.size() - before);
            if (total_bytes.fetch_add(bytes.size() - before) > kMaxGraphBytes) too_big = true;
        }
        size_t done = rows_done.fetch_add(end - begin) + (end - begin);
        if (worker == 0) progress(0.15f + 0.8f * float(done) / float(n));
    });
    if (cancelled()) {
        *error = "ghost tile build cancelled";
        return false;
    }
    if (too_big) {
        *error = "ghost tile: the collision graph exceeds " + std::to_string(kMaxGraphBytes >> 20) +
                 " MiB; use fewer candidates, smaller objects or a larger tile";
        return false;
    }

    std::vector<uint32_t> row_offsets(size_t(n) + 1, 0);
    for (uint32_t i = 0; i < n; ++i) row_offsets[i + 1] = row_offsets[i] + row_size[i];
    std::vector<uint8_t> stream;
    stream.reserve(row_offsets[n]);
    for (auto& b : chunk_bytes) stream.insert(stream.end(), b.begin(), b.end());

    GhostTile tile;
    tile.key = ghostTileKey(input);
    tile.settings = input.settings;
    if (!CollisionGraph::fromEncoded(n, std::move(row_offsets), std::move(stream), &tile.graph, error)) return false;
    tile.candidates = std::move(cand);
    const auto t1 = std::chrono::steady_clock::now();
    GhostTileStats& st = tile.stats;
    st.candidate_count = n;
    st.pair_count = tile.graph.edgeCount() / 2;
    st.rho = n ? double(st.pair_count) / double(n) : 0.0;
    st.build_seconds = std::chrono::duration<double>(t1 - t0).count();
    st.graph_bytes = tile.graph.byteSize();
    st.total_bytes = st.graph_bytes + uint64_t(n) * (sizeof(uint16_t) + sizeof(glm::vec3) + sizeof(glm::quat) +
                                                     sizeof(float));
    st.bytes_per_pair = st.pair_count ? double(st.graph_bytes) / double(st.pair_count) : 0.0;
    progress(1.0f);
    *out = std::move(tile);
    return true;
}

}  // namespace ug
