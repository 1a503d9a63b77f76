// Whether the Ghost Tile's period shows (issue "no visible tile"), measured on world frames so that an
// export read back gives the same figures:
//  - twin fraction: the share of instances that have an exact twin one tile away — an instance of the same
//    type, rotation and scale whose position is this one's moved by tile_size * v, v in {-1,0,1}^3 \ 0.
//    Positions are compared to 1 mm (rounding noise of tileOrigin + p is ~1e-6 m; a coordinate near a
//    rounding boundary is looked up on both sides), rotations and scales to 1e-5.
//  - spectral peak: the periodogram of the instances' XY positions, tapered by a Hann window over their
//    bounding rectangle, P(k) = |sum w e^{i k.x}|^2 / sum w^2, at the tile frequency k = 2 pi / s along X
//    and Y (the larger), divided by the background: the mean of P at the same |k| in 64 directions 15-75
//    degrees off the axes, where a tiling puts no peak. A Poisson set gives ~1; an exactly repeated tile
//    gives a ratio that grows with the number of tiles.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "analysis/placed_instances.h"

namespace ug {

double twinFraction(std::span<const PlacedInstance> instances, float tile_size_m);

struct SpectrumReport {
    double peak = 0.0;        // P at the tile frequency (the larger of X and Y)
    double background = 0.0;  // mean P at the same |k| off the axes
    double ratio = 0.0;       // peak / background (0 when there are no instances)
    uint64_t instances = 0;
};

// Instances whose type is in `types` (all when empty).
SpectrumReport tilePeriodSpectrum(std::span<const PlacedInstance> instances, float tile_size_m,
                                  const std::vector<uint32_t>& types, int threads = 0);

}  // namespace ug
