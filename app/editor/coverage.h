// How much of the screen a model covers when it is small (GL-free, unit-tested): its silhouette's area
// (the union of its triangles' projections, not their sum: a tuft's blades overlap) seen from elevations
// of 0, 30, 60 and 90 degrees above its horizon, each averaged over azimuths. The far representation
// (impostor sprites) is sized from it, so a meadow seen from afar is exactly as dense as its meshes would
// be, and the mesh LODs are checked against it, so a simplification that loses blades is not used.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace ug::editor {

constexpr int kCoverageElevations = 4;  // 0, 30, 60, 90 degrees

struct CoverageProfile {
    std::array<float, kCoverageElevations> area_m2{};  // silhouette area per elevation, model units squared
    float mean_m2 = 0.0f;                                // the four elevations' mean (for comparing LODs)
};

// The silhouettes themselves, for the impostors (detail_impostor.vert draws one as a camera-facing
// sprite): per elevation a `resolution` x `resolution` mask (255 covered, 0 not; rows bottom-up, row
// direction = the view's up, the projection of the model's +Z; columns = the view's right), seen from
// azimuth 0 (from +X), across the square of side 2 radius around `centre` (the bounding box's centre and
// half-diagonal). Both are what measureCoverage uses, so the masks' areas are its areas at azimuth 0.
struct SilhouetteMasks {
    int resolution = 0;
    glm::vec3 centre{0.0f};
    float radius = 0.0f;
    std::array<std::vector<uint8_t>, kCoverageElevations> mask;
    // The centred square, as a fraction of the whole (0, 1], outside which no mask covers a texel: the
    // sprite is drawn that much smaller (a tuft fills little of its bounding sphere's square, and every
    // empty pixel of a sprite still costs llvmpipe a texture lookup).
    float extent = 1.0f;
};
SilhouetteMasks silhouetteMasks(const std::vector<glm::vec3>& positions, const uint32_t* indices, size_t index_count,
                                int resolution = 64);

// `indices` (count a multiple of 3) index `positions`. The raster is `resolution` pixels across the
// model's bounding sphere, so areas are exact to about 1/resolution of the radius along the silhouette.
CoverageProfile measureCoverage(const std::vector<glm::vec3>& positions, const uint32_t* indices, size_t index_count,
                                int resolution = 128);

}  // namespace ug::editor
