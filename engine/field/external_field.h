// A density term computed outside engine/field: the environmental effects that scatter (leaves, trash,
// grass; engine/env/env_scatter.h) give their detail types the density (α·c·h − d)/s, which depends on the
// environment and the scene's base geometry, not on skeletal primitives. An External primitive of a
// DensityField refers to one of these by index (DensityField::externals) and evaluates to
// weight · value(p), so the term composes with brushes and solids like any primitive, and the
// instantiator's tile lists, culling and exact incremental path apply unchanged.
//
// Contract, what the instantiator's exactness rests on (docs/architecture.md "Instantiation as a pure
// function"): value() is a pure function of the point, the same bits whichever thread or batch asks;
// it is exactly +0 outside bounds(); positiveBoundsIn() encloses every point of the box where it is > 0.
// The gradient of an External primitive is taken as 0 (orientation "gradient" constraints do not see it).
#pragma once

#include <cstddef>

#include <glm/glm.hpp>

#include "field/bounds.h"

namespace ug {

class ExternalField {
public:
    virtual ~ExternalField() = default;
    virtual float value(glm::vec3 p) const = 0;
    // out[k] = value(points[k]), bit for bit; a field may share work between the points (a tile's anchors
    // ask the environment together).
    virtual void valueBatch(const glm::vec3* points, size_t n, float* out) const {
        for (size_t k = 0; k < n; ++k) out[k] = value(points[k]);
    }
    // Every point where value() != 0 lies inside.
    virtual Bounds bounds() const = 0;
    // A conservative AABB of {p in box : value(p) > 0} (empty when there is none).
    virtual Bounds positiveBoundsIn(const Bounds& box) const = 0;
};

}  // namespace ug
