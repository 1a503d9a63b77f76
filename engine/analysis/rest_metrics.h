// How instances rest and pack ("piles that rest"; docs/architecture.md "Plausible rest and no visible tile").
// Measured on world frames (placed_instances.h) with the models' collision spheres and meshes, so the same
// numbers come out of `undergrowth bench`, `instantiate --stats` and a test that reads an export back.
//
//  - drop: how far an instance could fall straight down before one of its collision spheres touches the
//    support (terrain, or the plane z = ground_z where there is none) or a sphere of another instance
//    whose centre is not above it. Touching or interpenetrating counts as a drop of 0. An instance
//    HOVERS when its drop exceeds the threshold (2 cm).
//  - sunk: the instance's origin lies more than the threshold below the support surface under it.
//  - volume fraction of a pile: inside the pile's core, the share of the volume that lies inside the
//    instances' meshes. With m the median instance bounding radius, the pile's envelope is the top of the
//    union of its collision spheres grown by m (so it spans the gaps between grains); the core is every
//    point of a column grid (cell `cell_m`) between the support and that envelope lowered by 2 m, i.e.
//    at least m below the grains' tops: the loose top layer and the sloped rim are left out, as one would
//    leave out the surface of a heap of gravel. Inside = ray parity against the model's mesh in model
//    space (meshes that are not closed, like leaves, hold no volume).
//  - overlap of a pile: the share of that solid volume that lies inside two or more instances' meshes at
//    once. Grains that rest touch and do not pass into one another, so this is the honest companion of the
//    volume fraction: a denser pile bought by letting collision spheres overlap (delta < 0) shows here.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "analysis/placed_instances.h"
#include "field/bounds.h"
#include "field/height_field.h"
#include "instancer/rest_support.h"
#include "mesh/detail_model.h"

namespace ug {

struct RestReport {
    uint64_t instances = 0;
    uint64_t hovering = 0;       // drop > threshold
    uint64_t hovering_5cm = 0;   // drop > 5 cm
    uint64_t sunk = 0;           // origin more than the threshold below the support
    double hovering_fraction = 0.0;
    double sunk_fraction = 0.0;
    double median_drop_m = 0.0;
    double max_drop_m = 0.0;
    double max_sunk_m = 0.0;     // deepest origin below the support (0 when none is below)
    std::vector<float> drop_m;   // per instance, in input order
    std::vector<float> sunk_m;   // per instance: how deep its lowest sphere reaches below the support (>= 0)
};

// `models` holds one model per detail type (instances' type indexes into it).
RestReport measureRest(std::span<const PlacedInstance> instances, const std::vector<const DetailModel*>& models,
                       const RestSupport& support, float threshold_m = 0.02f, int threads = 0);

// The same figures for the instances of each type (type_count reports), from `all`'s per-instance drops
// (measured with every instance present: a twig resting on a rock is supported). Per-instance vectors
// are left empty.
std::vector<RestReport> restPerType(const RestReport& all, std::span<const PlacedInstance> instances,
                                    uint32_t type_count, float threshold_m = 0.02f);

struct PackingReport {
    double volume_fraction = 0.0;  // solid samples / core samples (0 when the core is empty)
    uint64_t core_samples = 0;
    uint64_t solid_samples = 0;
    uint64_t overlap_samples = 0;  // core samples inside two or more instances' meshes
    double overlap_fraction = 0.0; // overlap samples / solid samples (0 when nothing is solid)
    double core_volume_m3 = 0.0;
    float shell_m = 0.0f;          // the top layer left out: the median instance bounding radius
};

// The pile made of the instances whose type is in `types` (all when empty). `clip` (optional) keeps only
// the core's columns inside its XY rectangle.
PackingReport measurePacking(std::span<const PlacedInstance> instances, const std::vector<const DetailModel*>& models,
                             const RestSupport& support, const std::vector<uint32_t>& types, float cell_m = 0.02f,
                             int threads = 0, const Bounds* clip = nullptr);

}  // namespace ug
