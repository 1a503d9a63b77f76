// Ghost Tile creation (Guérin et al. 2016, §4.2 candidates, §4.3 collision graph).
//
// Where we differ from the paper:
// - Random numbers are a hash of (seed, type, candidate, draw), not a generator's state, so a candidate's
//   frame does not depend on the other types' counts or on the build order.
// - Collision detection is two-level. A uniform grid over the candidates' bounding spheres (with the 26
//   neighbour copies) finds the pairs that may touch; the narrow phase first drops the spheres of each side
//   that cannot reach the other's bounding sphere, then tests the survivors with an early exit. Leaves
//   and branches carry tens of spheres, so this is what turns the paper's 93 s build (1.12k candidates,
//   990k pairs) into well under two seconds on two cores (see `undergrowth bench`).
// - Each unordered pair is tested once and both directed edges are recorded; rows are then gathered and
//   sorted, so the graph is bit-identical for any thread count, and the predicate spheresCollide() is
//   symmetric in floating point, so the brute-force definition and the graph agree exactly.
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
    if (s.variants < 1 || s.variants > kMaxTileVariants) {
        *error = "ghost tile: variants must be in [1, " + std::to_string(kMaxTileVariants) + "], got " +
                 std::to_string(s.variants);
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
    // The tile stores every variant: the limit (and the memory it bounds) is on the product.
    if (total * s.variants > kMaxCandidatesPerTile) {
        *error = "ghost tile: " + std::to_string(s.variants) + " variants x " + std::to_string(total) +
                 " candidates = " + std::to_string(total * s.variants) + " candidates exceeds the limit of " +
                 std::to_string(kMaxCandidatesPerTile) + " per tile; use fewer variants or fewer candidates";
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
    // Only when it matters, so a single-variant tile keeps the key (and cache file name) it always had.
    if (input.settings.variants != 1) h.add(input.settings.variants);
    return h.value();
}

bool generateCandidates(const GhostTileInput& input, CandidateSet* out, std::string* error) {
    if (!validateGhostTileInput(input, error)) return false;
    const float s = input.settings.tile_size_m;
    const uint32_t variants = input.settings.variants;
    CandidateSet c;
    c.variants = variants;
    c.type_begin.push_back(0);
    for (const DetailTypeSettings& d : input.types)
        c.type_begin.push_back(c.type_begin.back() + variants * d.candidate_count);
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
        for (uint32_t k = 0; k < variants * d.candidate_count; ++k) {
            const uint32_t v = k / d.candidate_count, j = k % d.candidate_count;
            const uint32_t idx = c.type_begin[t] + k;
            // Variant 0 keeps the single-variant hash (the same tile as before variants); the others
            // re-hash it with their number, an independent draw of the same distribution.
            uint64_t h = hashWords(input.settings.seed, t, j, 0x67686f7374ull);  // "ghost"
            if (v > 0) h = hashWords(h, v, 0x76617269616e74ull);                  // "variant"
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

// A candidate copy (j, v) in the broad-phase grid: its bounding sphere, shifted into the home tile's frame.
struct CopyEntry {
    glm::vec3 center;
    float radius;
    uint32_t key;  // j * 27 + offset index
};

// Uniform grid over the copies' bounding-sphere centres (one cell per copy).
struct CopyGrid {
    glm::vec3 origin{0.0f};
    float cell_m = 1.0f;
    glm::ivec3 dims{1};
    std::vector<uint32_t> cell_begin;  // CSR over cells
    std::vector<CopyEntry> entries;

    glm::ivec3 cellOf(const glm::vec3& p) const {
        return glm::clamp(glm::ivec3(glm::floor((p - origin) / cell_m)), glm::ivec3(0), dims - 1);
    }
    size_t flat(int x, int y, int z) const { return (size_t(z) * dims.y + y) * dims.x + x; }
};

// Narrow phase between candidate A (offset 0) and candidate B at `shift`: do any two spheres satisfy
// spheresCollide()? Spheres of one side that cannot reach the other's bounding sphere are dropped first
// (a conservative filter with a small margin; the decision itself is always spheresCollide), then the
// survivors are tested with an early exit. Scratch vectors are per worker.
bool sphereSetsCollide(const Sphere* a, uint32_t na, const Sphere& bound_a, const Sphere* b, uint32_t nb,
                       const Sphere& bound_b, const glm::vec3& shift, float delta, float margin,
                       std::vector<uint32_t>* near_a, std::vector<uint32_t>* near_b) {
    const float reach = std::max(0.0f, delta) + margin;
    const glm::vec3 cb = bound_b.center + shift;
    near_a->clear();
    near_b->clear();
    for (uint32_t k = 0; k < na; ++k) {
        float r = a[k].radius + bound_b.radius + reach;
        glm::vec3 d = a[k].center - cb;
        if (glm::dot(d, d) <= r * r) near_a->push_back(k);
    }
    if (near_a->empty()) return false;
    for (uint32_t k = 0; k < nb; ++k) {
        float r = b[k].radius + bound_a.radius + reach;
        glm::vec3 d = (b[k].center + shift) - bound_a.center;
        if (glm::dot(d, d) <= r * r) near_b->push_back(k);
    }
    for (uint32_t ka : *near_a)
        for (uint32_t kb : *near_b)
            if (spheresCollide(a[ka].center, a[ka].radius, b[kb].center, b[kb].radius, shift, delta)) return true;
    return false;
}

}  // namespace

bool buildGhostTile(const GhostTileInput& input, const BuildOptions& options, GhostTile* out, std::string* error) {
    const auto t0 = std::chrono::steady_clock::now();
    CandidateSet cand;
    if (!generateCandidates(input, &cand, error)) return false;
    const uint32_t n = cand.size();
    const float s = input.settings.tile_size_m;
    const float delta = input.settings.delta_m;
    const float delta_pos = std::max(0.0f, delta);
    const float margin = 1e-5f * s;  // float slack for the conservative filters only
    const int threads = resolveThreadCount(options.threads);
    auto cancelled = [&] { return options.cancel && options.cancel->load(std::memory_order_relaxed); };
    auto progress = [&](float f) {
        if (options.progress) options.progress(f);
    };

    // Variant of each candidate, for the offset-0 rule; empty (never read) with a single variant.
    std::vector<uint8_t> variant_of;
    const bool several_variants = cand.variants > 1;
    if (several_variants) {
        variant_of.resize(n);
        for (uint32_t i = 0; i < n; ++i) variant_of[i] = uint8_t(cand.variantOf(i));
    }

    // Spheres in tile space (offset 0), flattened: candidate i owns [sphere_begin[i], sphere_begin[i+1]).
    std::vector<uint32_t> sphere_begin(size_t(n) + 1, 0);
    for (uint32_t i = 0; i < n; ++i)
        sphere_begin[i + 1] = sphere_begin[i] + uint32_t(input.models[cand.type[i]]->spheres.size());
    std::vector<Sphere> spheres(sphere_begin[n]);
    std::vector<Sphere> bound(n);
    float max_bound_r = 0.0f;
    {
        std::vector<Sphere> tmp;
        for (uint32_t i = 0; i < n; ++i) {
            const DetailModel& m = *input.models[cand.type[i]];
            candidateSpheres(cand, i, m, &tmp);
            std::copy(tmp.begin(), tmp.end(), spheres.begin() + sphere_begin[i]);
            // The model's bounds enclose its spheres; recompute the radius in tile space so that float
            // rounding of the transform can never leave a sphere poking out.
            glm::vec3 c = cand.position[i] + cand.rotation[i] * (cand.scale[i] * m.bounds.center);
            float r = 0.0f;
            for (const Sphere& sp : tmp) r = std::max(r, glm::length(sp.center - c) + sp.radius);
            bound[i] = {c, r * (1.0f + 1e-6f) + margin};
            max_bound_r = std::max(max_bound_r, bound[i].radius);
        }
    }
    progress(0.05f);

    // Broad phase: copies (j, v) whose bounding sphere can reach a home candidate's, binned by centre.
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const Sphere& b : bound) {
        lo = glm::min(lo, b.center - b.radius);
        hi = glm::max(hi, b.center + b.radius);
    }
    const float reach = max_bound_r + delta_pos;  // how far outside a home bound a copy's centre can matter
    lo -= glm::vec3(reach);
    hi += glm::vec3(reach);
    CopyGrid grid;
    grid.origin = lo;
    grid.cell_m = std::max(max_bound_r, 1e-6f);
    grid.dims = glm::max(glm::ivec3(1), glm::min(glm::ivec3(glm::ceil((hi - lo) / grid.cell_m)), glm::ivec3(256)));
    grid.cell_m = std::max({(hi - lo).x / float(grid.dims.x), (hi - lo).y / float(grid.dims.y),
                            (hi - lo).z / float(grid.dims.z)});
    {
        const size_t cell_count = size_t(grid.dims.x) * grid.dims.y * grid.dims.z;
        std::vector<CopyEntry> copies;
        std::vector<uint32_t> copy_cell;
        for (uint32_t v = 0; v < kOffsetCount; ++v) {
            const glm::vec3 shift = glm::vec3(offsetVector(v)) * s;
            for (uint32_t j = 0; j < n; ++j) {
                glm::vec3 c = bound[j].center + shift;
                if (glm::any(glm::lessThan(c, lo)) || glm::any(glm::greaterThan(c, hi))) continue;
                copies.push_back({c, bound[j].radius, j * kOffsetCount + v});
                glm::ivec3 cell = grid.cellOf(c);
                copy_cell.push_back(uint32_t(grid.flat(cell.x, cell.y, cell.z)));
            }
        }
        grid.cell_begin.assign(cell_count + 1, 0);
        for (uint32_t c : copy_cell) grid.cell_begin[c + 1]++;
        for (size_t c = 0; c < cell_count; ++c) grid.cell_begin[c + 1] += grid.cell_begin[c];
        grid.entries.resize(copies.size());
        std::vector<uint32_t> cursor(grid.cell_begin.begin(), grid.cell_begin.end() - 1);
        for (size_t k = 0; k < copies.size(); ++k) grid.entries[cursor[copy_cell[k]]++] = copies[k];
    }
    progress(0.1f);
    if (cancelled()) {
        *error = "ghost tile build cancelled";
        return false;
    }

    // Narrow phase, each unordered pair once: {(i,0), (j,v)} is tested from row i when i < j, or when
    // i == j and v is on the positive side of the centre. Both directed edges are recorded; rows are
    // then gathered and sorted, so the result does not depend on the thread count or the chunking.
    struct HalfEdge {
        uint32_t row;
        uint32_t key;
    };
    // Per worker, each on cache lines of its own: a vector's end moves at every push, and with two
    // workers' vectors side by side every push waited for the line to come back from the other core.
    struct alignas(64) WorkerEdges {
        std::vector<HalfEdge> edges;
        std::vector<uint32_t> near_a, near_b;  // sphereSetsCollide's scratch
    };
    std::vector<WorkerEdges> found(static_cast<size_t>(threads));
    std::atomic<uint64_t> edge_total{0};
    std::atomic<bool> too_big{false};
    std::atomic<size_t> rows_done{0};
    const uint64_t max_edges = kMaxGraphBytes / 2;  // at least one byte per edge, plus the gathering
    parallelFor(n, threads, 8, [&](size_t begin, size_t end, int worker) {
        if (cancelled() || too_big.load(std::memory_order_relaxed)) return;
        WorkerEdges& mine = found[size_t(worker)];
        std::vector<HalfEdge>& edges = mine.edges;
        const size_t before = edges.size();
        for (size_t ii = begin; ii < end; ++ii) {
            const uint32_t i = uint32_t(ii);
            const Sphere& bi = bound[i];
            const float query = bi.radius + max_bound_r + delta_pos;
            glm::ivec3 c0 = grid.cellOf(bi.center - query), c1 = grid.cellOf(bi.center + query);
            for (int cz = c0.z; cz <= c1.z; ++cz)
                for (int cy = c0.y; cy <= c1.y; ++cy)
                    for (int cx = c0.x; cx <= c1.x; ++cx) {
                        const size_t cell = grid.flat(cx, cy, cz);
                        for (uint32_t e = grid.cell_begin[cell]; e < grid.cell_begin[cell + 1]; ++e) {
                            const CopyEntry& ce = grid.entries[e];
                            const uint32_t j = ce.key / kOffsetCount, v = ce.key % kOffsetCount;
                            if (j < i || (j == i && v <= kCenterOffset)) continue;
                            const float r = bi.radius + ce.radius + delta_pos;
                            const glm::vec3 d = ce.center - bi.center;
                            if (glm::dot(d, d) > r * r) continue;
                            // One tile holds one variant: two variants never meet at offset 0. Tested after
                            // the bounds, on the few pairs that pass them, so one variant pays nothing.
                            if (several_variants && v == kCenterOffset && variant_of[i] != variant_of[j]) continue;
                            const glm::vec3 shift = glm::vec3(offsetVector(v)) * s;
                            if (sphereSetsCollide(&spheres[sphere_begin[i]], sphere_begin[i + 1] - sphere_begin[i], bi,
                                                  &spheres[sphere_begin[j]], sphere_begin[j + 1] - sphere_begin[j],
                                                  bound[j], shift, delta, margin, &mine.near_a, &mine.near_b)) {
                                edges.push_back({i, ce.key});
                                edges.push_back({j, i * kOffsetCount + mirrorOffset(v)});
                            }
                        }
                    }
        }
        if (edge_total.fetch_add(edges.size() - before) > max_edges) too_big = true;
        size_t done = rows_done.fetch_add(end - begin) + (end - begin);
        if (worker == 0) progress(0.1f + 0.75f * float(done) / float(n));
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

    // Gather rows (counting sort by row), sort each row, encode. Rows are independent: parallel again.
    std::vector<uint32_t> row_begin(size_t(n) + 1, 0);
    for (const WorkerEdges& w : found)
        for (const HalfEdge& h : w.edges) row_begin[h.row + 1]++;
    for (uint32_t i = 0; i < n; ++i) row_begin[i + 1] += row_begin[i];
    std::vector<uint32_t> keys(row_begin[n]);
    {
        std::vector<uint32_t> cursor(row_begin.begin(), row_begin.end() - 1);
        for (WorkerEdges& w : found) {
            for (const HalfEdge& h : w.edges) keys[cursor[h.row]++] = h.key;
            std::vector<HalfEdge>().swap(w.edges);
        }
    }
    const size_t chunk = 64;
    std::vector<std::vector<uint8_t>> chunk_bytes((size_t(n) + chunk - 1) / chunk);
    std::vector<uint32_t> row_size(n, 0);
    parallelFor(n, threads, chunk, [&](size_t begin, size_t end, int) {
        // Encoded into a local vector and moved once: neighbouring chunks' vectors share cache lines.
        std::vector<uint8_t> bytes;
        for (size_t i = begin; i < end; ++i) {
            std::sort(keys.begin() + row_begin[i], keys.begin() + row_begin[i + 1]);
            const size_t before = bytes.size();
            CollisionGraph::encodeRow(keys.data() + row_begin[i], row_begin[i + 1] - row_begin[i], &bytes);
            row_size[i] = uint32_t(bytes.size() - before);
        }
        chunk_bytes[begin / chunk] = std::move(bytes);
    });
    progress(0.95f);
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
