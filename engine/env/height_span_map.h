// Where a mesh lies above and below a point along the vertical: docs/architecture.md "Beyond the paper:
// shelter". For a grid of cells over the mesh's XY bounds, every height at which the mesh crosses the
// vertical line through the cell's centre, sorted. Built once per environmental-object type in its own
// space; objects turn only about the vertical, so a world point is looked up by mapping it into an
// object's space.
//
// Vertical faces (walls) cross no vertical line and so shelter nothing from snow falling straight down,
// which is what a wall does. Geometry thinner than a cell may fall between the centres: it is too thin to
// keep snow off anyway.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "mesh/triangle_mesh.h"

namespace ug {

constexpr float kShelterCellM = 0.025f;        // grid cell at scale 1 (coarsened for very large meshes)
constexpr size_t kMaxSpanMapCells = 1u << 22;  // per type: beyond this the cell grows

class HeightSpanMap {
public:
    HeightSpanMap() = default;
    // The mesh must pass validateMesh.
    // `skip_blocks` false leaves out the blocks' bounds (below): coveredAlong then tests every step's
    // cell, the reference its skipping must agree with (tests).
    explicit HeightSpanMap(const TriangleMesh& mesh, bool skip_blocks = true);

    // The highest crossing above z + eps at the cell of (x, y); false when there is none (or (x, y) is
    // outside the grid).
    bool coveredAbove(glm::vec3 p, float eps) const;
    // Whether the ray from p going up with horizontal drift `slope` (metres per metre of rise) meets the
    // mesh more than eps above p, between the heights z_bottom and z_top (the mesh's): the ray is followed
    // through the part of the grid it crosses at half a cell per step, and a step is blocked by a crossing
    // of its cell between the step's heights or by being inside a part (walls, which the vertical lines
    // see only as their tops and bottoms). slope (0, 0) is coveredAbove.
    bool coveredAlong(glm::vec3 p, glm::vec2 slope, float eps, float z_bottom, float z_top) const;
    // What a point rests on: the highest crossing at or below z at the cell of (x, y), or -infinity when
    // there is none (or (x, y) is outside the grid); *inside tells whether z lies inside one of the mesh's
    // parts (then nothing rests there). For a point outside every part the crossing is an up-facing
    // surface: a seat's top, not its underside.
    float supportBelow(glm::vec3 p, bool* inside) const;
    // The highest crossing below z - eps at the cell of (x, y), or -infinity when there is none.
    float highestBelow(glm::vec3 p, float eps) const;
    // Over the 3 x 3 cells around (x, y), the highest of each cell's first crossing above z + eps, or
    // -infinity when there is none: the surface just over a point on the mesh's edge, whichever side of
    // the edge the cell centres fall (an icicle's water comes from there).
    float surfaceAboveNear(glm::vec3 p, float eps) const;

    float cellSize() const { return cell_; }
    glm::vec2 origin() const { return origin_; }
    int width() const { return nx_; }
    int height() const { return ny_; }
    size_t crossingCount() const { return z_.size(); }

private:
    static constexpr int kSpanBlockCells = 8;
    // Per block of kSpanBlockCells x kSpanBlockCells cells: the lowest and highest crossing in it (+inf
    // and -inf when it has none); the top is +inf when a line of the block is inside a part above its
    // last crossing (an open mesh), where a step above every crossing could still be inside.
    struct SpanBlock {
        float bottom, top;
    };
    // coveredAlong's walk: the last step from step k on (k's midpoint in block (bi, bj)) whose midpoint
    // is still in the block and whose top is below z_limit, a step short of both to absorb rounding.
    long lastStepInBlock(long k, int bi, int bj, glm::vec3 p, glm::vec2 slope, float lo_z, float dz,
                         float z_limit) const;
    // The cell holding (x, y), or -1 outside the grid.
    long cellOf(float x, float y) const {
        int i = 0, j = 0;
        return cellAt(x, y, &i, &j);
    }
    // cellOf, with the cell's column and row (coveredAlong's walk needs its block).
    long cellAt(float x, float y, int* i, int* j) const;
    // Whether height z of the cell's line lies inside the mesh's closed, outward-wound parts: more faces
    // entered (down-facing) than left (up-facing) below it. Overlapping parts count once each.
    bool insideSolid(long cell, float z) const;

    glm::vec2 origin_{0.0f};  // XY of cell (0, 0)'s lower corner
    float cell_ = kShelterCellM;
    int nx_ = 0, ny_ = 0;
    std::vector<uint32_t> first_;  // nx*ny + 1 offsets into z_
    std::vector<float> z_;         // per cell, ascending
    std::vector<int16_t> depth_;   // per crossing: how many parts the line is inside just above it
    int block_nx_ = 0;             // blocks along x; no blocks when skipping is off
    std::vector<SpanBlock> blocks_;
};

}  // namespace ug
