#include "analysis/tiling_metrics.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstring>
#include <limits>
#include <unordered_set>

#include "core/hash.h"
#include "core/parallel.h"

namespace ug {

namespace {

constexpr double kPositionQuantum = 1e-3;
constexpr double kFrameQuantum = 1e-5;

// The candidates of rounding one coordinate: its nearest multiple of the quantum, and the other side too
// when the value lies within 1 % of a quantum of the boundary between two.
int roundedChoices(double v, double quantum, int64_t out[2]) {
    const double r = v / quantum;
    const double base = std::floor(r + 0.5);
    out[0] = int64_t(base);
    const double frac = r - std::floor(r);
    if (std::fabs(frac - 0.5) < 0.01) {
        out[1] = frac < 0.5 ? out[0] + 1 : out[0] - 1;
        return 2;
    }
    return 1;
}

uint64_t frameHash(const PlacedInstance& p) {
    glm::quat q = p.rotation;
    if (q.w < 0.0f) q = -q;  // q and -q are the same rotation
    auto quantized = [](float v) { return uint64_t(int64_t(std::llround(double(v) / kFrameQuantum))); };
    return hashWords(hashWords(p.type, quantized(q.w), quantized(q.x), quantized(q.y)), quantized(q.z),
                     quantized(p.scale));
}

uint64_t cellKey(uint64_t frame, int64_t x, int64_t y, int64_t z) {
    return hashWords(frame, uint64_t(x), uint64_t(y), uint64_t(z));
}

}  // namespace

double twinFraction(std::span<const PlacedInstance> instances, float tile_size_m) {
    if (instances.empty()) return 0.0;
    std::unordered_set<uint64_t> present;
    present.reserve(instances.size() * 2);
    std::vector<uint64_t> frames(instances.size());
    for (size_t i = 0; i < instances.size(); ++i) {
        frames[i] = frameHash(instances[i]);
        const glm::dvec3 p(instances[i].position);
        present.insert(cellKey(frames[i], std::llround(p.x / kPositionQuantum), std::llround(p.y / kPositionQuantum),
                               std::llround(p.z / kPositionQuantum)));
    }
    uint64_t twins = 0;
    const double s = tile_size_m;
    for (size_t i = 0; i < instances.size(); ++i) {
        const glm::dvec3 p(instances[i].position);
        bool found = false;
        for (int v = 0; v < 27 && !found; ++v) {
            if (v == 13) continue;  // offset (0, 0, 0): the instance itself
            const glm::dvec3 q = p + s * glm::dvec3(v / 9 - 1, v / 3 % 3 - 1, v % 3 - 1);
            int64_t cx[2], cy[2], cz[2];
            const int nx = roundedChoices(q.x, kPositionQuantum, cx);
            const int ny = roundedChoices(q.y, kPositionQuantum, cy);
            const int nz = roundedChoices(q.z, kPositionQuantum, cz);
            for (int a = 0; a < nx && !found; ++a)
                for (int b = 0; b < ny && !found; ++b)
                    for (int c = 0; c < nz && !found; ++c)
                        found = present.count(cellKey(frames[i], cx[a], cy[b], cz[c])) != 0;
        }
        if (found) ++twins;
    }
    return double(twins) / double(instances.size());
}

SpectrumReport tilePeriodSpectrum(std::span<const PlacedInstance> instances, float tile_size_m,
                                  const std::vector<uint32_t>& types, int threads) {
    SpectrumReport report;
    std::vector<glm::dvec2> xy;
    for (const PlacedInstance& p : instances)
        if (types.empty() || std::find(types.begin(), types.end(), p.type) != types.end())
            xy.push_back(glm::dvec2(p.position));
    report.instances = xy.size();
    if (xy.size() < 2) return report;
    glm::dvec2 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const glm::dvec2& p : xy) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const glm::dvec2 size = glm::max(hi - lo, glm::dvec2(1e-9));
    constexpr double kPi = 3.14159265358979323846;
    std::vector<double> w(xy.size());
    double w2 = 0.0;
    for (size_t i = 0; i < xy.size(); ++i) {
        const glm::dvec2 u = (xy[i] - lo) / size;
        const double sx = std::sin(kPi * u.x), sy = std::sin(kPi * u.y);
        w[i] = sx * sx * sy * sy;
        w2 += w[i] * w[i];
    }
    if (!(w2 > 0.0)) return report;

    // Frequencies: 0 and 1 are the tile frequency along X and Y; the rest the background ring.
    const double k = 2.0 * kPi / double(tile_size_m);
    constexpr int kBackground = 64;
    std::vector<glm::dvec2> freqs = {{k, 0.0}, {0.0, k}};
    for (int m = 0; m < kBackground; ++m) {
        const int quadrant = m % 4;
        const double within = 15.0 + 60.0 * (double(m / 4) + 0.5) / double(kBackground / 4);
        const double angle = (90.0 * quadrant + within) * kPi / 180.0;
        freqs.push_back({k * std::cos(angle), k * std::sin(angle)});
    }
    std::vector<double> power(freqs.size());
    parallelFor(freqs.size(), threads, 1, [&](size_t b, size_t e, int) {
        for (size_t f = b; f < e; ++f) {
            double re = 0.0, im = 0.0;
            for (size_t i = 0; i < xy.size(); ++i) {
                const double phase = freqs[f].x * xy[i].x + freqs[f].y * xy[i].y;
                re += w[i] * std::cos(phase);
                im += w[i] * std::sin(phase);
            }
            power[f] = (re * re + im * im) / w2;
        }
    });
    report.peak = std::max(power[0], power[1]);
    double sum = 0.0;
    for (size_t f = 2; f < power.size(); ++f) sum += power[f];
    report.background = sum / double(kBackground);
    report.ratio = report.background > 0.0 ? report.peak / report.background : 0.0;
    return report;
}

}  // namespace ug
