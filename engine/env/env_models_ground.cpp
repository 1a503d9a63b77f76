// Ground pieces: pavement slab with a kerb, road segment, steps.
#include "env/env_model_makers.h"

namespace ug::envmodels {
using envparts::addBox;
using envparts::MeshBuilder;

TriangleMesh makePavementSlab(uint64_t) {
    MeshBuilder b;
    // 4 x 4 separate paving slabs over y in [-1, 0.85] with 8 mm joints between them (the outer edges
    // flush with the footprint), and the kerb stone along the +Y edge. The slab tops are 4 x 4 grids so
    // snow has vertices to sit on.
    const float joint = 0.008f, kerb_y = 0.85f;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            const float x0 = -1.0f + 0.5f * float(i), x1 = x0 + 0.5f;
            const float y0 = -1.0f + (kerb_y + 1.0f) * 0.25f * float(j),
                        y1 = -1.0f + (kerb_y + 1.0f) * 0.25f * float(j + 1);
            const glm::vec3 lo(i == 0 ? x0 : x0 + 0.5f * joint, j == 0 ? y0 : y0 + 0.5f * joint, 0.0f);
            const glm::vec3 hi(i == 3 ? x1 : x1 - 0.5f * joint, y1 - 0.5f * joint, 0.12f);
            addBox(&b, lo, hi, {4, 4, 1});
        }
    addBox(&b, {-1.0f, kerb_y, 0.0f}, {1.0f, 1.0f, 0.15f}, {16, 1, 1});
    return b.finish({0.55f, 0.54f, 0.52f});
}

TriangleMesh makeRoadSegment(uint64_t) {
    MeshBuilder b;
    addBox(&b, {-2.0f, -2.0f, 0.0f}, {2.0f, 2.0f, 0.1f}, {32, 32, 1});
    return b.finish({0.12f, 0.12f, 0.13f});
}

TriangleMesh makeSteps(uint64_t) {
    MeshBuilder b;
    // One block per step, each from the ground to its tread and one tread deep: the blocks abut, so
    // every tread is an exposed up-facing face (no tread hidden inside the step above).
    const int steps = 4;
    const float tread = 0.3f, riser = 0.16f, half_width = 0.75f, front = 0.5f * tread * float(steps);
    for (int k = 0; k < steps; ++k) {
        const float y1 = front - tread * float(k), y0 = y1 - tread;
        addBox(&b, {-half_width, y0, 0.0f}, {half_width, y1, riser * float(k + 1)}, {6, 2, 1});
    }
    return b.finish({0.58f, 0.56f, 0.53f});
}

}  // namespace ug::envmodels
