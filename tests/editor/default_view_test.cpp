// The view a scene opens on (app/editor/default_view.h): what it frames, and that the frame holds it,
// tightly, from the documented direction. The editor and `undergrowth render` both start from it.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/constants.hpp>

#include "editor/default_view.h"
#include "instancer/tile_coord.h"

namespace ug::editor {
namespace {

// The largest |NDC x| or |NDC y| over the box's eight corners; +inf when a corner is behind the eye.
float cornerReach(const OrbitCamera& camera, const Bounds& box) {
    const glm::mat4 m = camera.viewProjection();
    float reach = 0.0f;
    for (int k = 0; k < 8; ++k) {
        const glm::vec3 p((k & 1) ? box.hi.x : box.lo.x, (k & 2) ? box.hi.y : box.lo.y, (k & 4) ? box.hi.z : box.lo.z);
        const glm::vec4 q = m * glm::vec4(p, 1.0f);
        if (q.w <= 0.0f) return INFINITY;
        reach = std::max({reach, std::abs(q.x / q.w), std::abs(q.y / q.w)});
    }
    return reach;
}

TEST(DefaultView, FramingPrefersInstancesThenTerrainThenExtent) {
    const Bounds extent{glm::vec3(-50.0f, -50.0f, -5.0f), glm::vec3(50.0f, 50.0f, 5.0f)};
    TriangleMesh terrain;
    terrain.positions = {glm::vec3(-10.0f, -8.0f, 0.0f), glm::vec3(12.0f, -8.0f, 1.5f), glm::vec3(0.0f, 9.0f, -0.5f)};
    terrain.indices = {0, 1, 2};
    ResidentTiles tiles;
    tiles.tile_size_m = 0.5f;
    tiles.tile_coord = {glm::ivec3(-2, 3, 0), glm::ivec3(4, -1, -1)};

    // Instances: the union of their cells, [t, t + 1) * size per axis.
    const Bounds cells = framingBounds(extent, &terrain, &tiles);
    EXPECT_EQ(cells.lo, glm::vec3(-1.0f, -0.5f, -0.5f));
    EXPECT_EQ(cells.hi, glm::vec3(2.5f, 2.0f, 0.5f));
    // No instances (none yet, or an empty set): the terrain's surface.
    const ResidentTiles none;
    for (const ResidentTiles* t : {static_cast<const ResidentTiles*>(nullptr), &none}) {
        const Bounds ground = framingBounds(extent, &terrain, t);
        EXPECT_EQ(ground.lo, glm::vec3(-10.0f, -8.0f, -0.5f));
        EXPECT_EQ(ground.hi, glm::vec3(12.0f, 9.0f, 1.5f));
    }
    // No terrain (or an empty mesh): the extent.
    const TriangleMesh empty;
    for (const TriangleMesh* m : {static_cast<const TriangleMesh*>(nullptr), &empty}) {
        const Bounds b = framingBounds(extent, m, nullptr);
        EXPECT_EQ(b.lo, extent.lo);
        EXPECT_EQ(b.hi, extent.hi);
    }
}

TEST(DefaultView, LooksAtTheCentreFromThirtyFiveDegreesOnTheMinusYSide) {
    const Bounds box{glm::vec3(-3.0f, 1.0f, 0.0f), glm::vec3(5.0f, 4.0f, 2.0f)};
    const OrbitCamera c = defaultView(box, 16.0f / 9.0f);
    EXPECT_EQ(c.target, glm::vec3(1.0f, 2.5f, 1.0f));
    EXPECT_FLOAT_EQ(c.pitch_rad, glm::radians(35.0f));
    EXPECT_FLOAT_EQ(c.yaw_rad, glm::radians(-105.0f));
    EXPECT_FLOAT_EQ(c.aspect, 16.0f / 9.0f);
    // The eye is above the target and on its -Y side, a little towards -X (yaw -105: 15 degrees past -Y).
    const glm::vec3 to_eye = c.eye() - c.target;
    EXPECT_GT(to_eye.z, 0.0f);
    EXPECT_LT(to_eye.y, 0.0f);
    EXPECT_LT(to_eye.x, 0.0f);
    EXPECT_NEAR(std::atan2(to_eye.z, glm::length(glm::vec2(to_eye))), glm::radians(35.0f), 1e-5f);
}

TEST(DefaultView, TheFrameHoldsTheWholeBoxAndNoMore) {
    const Bounds boxes[] = {
        {glm::vec3(-40.0f, -40.0f, -1.0f), glm::vec3(40.0f, 40.0f, 3.0f)},  // a flat field
        {glm::vec3(-1.0f, -1.0f, 0.0f), glm::vec3(1.0f, 1.0f, 1.2f)},       // a pile
        {glm::vec3(0.0f, 0.0f, 0.0f), glm::vec3(0.5f, 0.5f, 6.0f)},         // a tall thin column
    };
    for (const Bounds& box : boxes) {
        for (const float aspect : {16.0f / 9.0f, 1.0f, 9.0f / 16.0f}) {
            const OrbitCamera c = defaultView(box, aspect);
            // Every corner inside 90 % of the view...
            EXPECT_LE(cornerReach(c, box), 0.9f + 1e-4f) << "aspect " << aspect;
            // ...and the nearest such distance: 3 % closer, a corner leaves it.
            OrbitCamera closer = c;
            closer.distance_m *= 0.97f;
            EXPECT_GT(cornerReach(closer, box), 0.9f) << "aspect " << aspect;
        }
    }
}

TEST(DefaultView, ANarrowerViewportStandsFurtherBack) {
    const Bounds field{glm::vec3(-40.0f, -40.0f, -1.0f), glm::vec3(40.0f, 40.0f, 3.0f)};
    const float wide = defaultView(field, 16.0f / 9.0f).distance_m;
    const float square = defaultView(field, 1.0f).distance_m;
    const float tall = defaultView(field, 9.0f / 16.0f).distance_m;
    EXPECT_LT(wide, square);
    EXPECT_LT(square, tall);
}

// Resident tiles with `n` instances of type 0 in each listed cell (only the fields openingBounds reads).
ResidentTiles tilesWith(const std::vector<std::pair<glm::ivec3, uint32_t>>& cells) {
    ResidentTiles r;
    r.type_count = 1;
    r.tile_size_m = 0.5f;
    r.instances_per_type = {0};
    for (const auto& [c, n] : cells) {
        r.tile_key.push_back(packTile(c));
        r.tile_coord.push_back(c);
        r.count.push_back(n);
        r.instances_per_type[0] += n;
    }
    return r;
}

TEST(DefaultView, ALargeSceneOpensOnItsDensestPatchAtDetailSize) {
    const Bounds extent{glm::vec3(-40.0f, -40.0f, -1.0f), glm::vec3(40.0f, 40.0f, 3.0f)};
    std::vector<std::pair<glm::ivec3, uint32_t>> cells;
    for (int x = -80; x < 80; x += 4)
        for (int y = -80; y < 80; y += 4) cells.push_back({glm::ivec3(x, y, 0), 1});  // a sparse field
    for (int x = 40; x < 44; ++x)
        for (int y = -20; y < -16; ++y) cells.push_back({glm::ivec3(x, y, 4), 50});  // a dense heap at (21, -9), 2 m up
    const ResidentTiles tiles = tilesWith(cells);
    std::vector<DetailLodMesh> meshes(1);
    meshes[0].radius_m = 0.1f;
    meshes[0].scale_max = 1.0f;
    const Bounds open = openingBounds(extent, nullptr, &tiles, meshes);
    const glm::vec2 centre = 0.5f * (glm::vec2(open.lo) + glm::vec2(open.hi));
    EXPECT_NEAR(centre.x, 21.0f, 1.5f);
    EXPECT_NEAR(centre.y, -9.0f, 1.5f);
    // The patch's floor and ceiling (the field's cells in it and the heap's), not the extent's.
    EXPECT_EQ(open.lo.z, 0.0f);
    EXPECT_EQ(open.hi.z, 2.5f);
    // Framed, a 0.2 m object at the target fills about 1/30 of the view's height.
    const OrbitCamera cam = defaultView(open, 16.0f / 9.0f);
    const float fraction = 0.2f / (2.0f * cam.distance_m * std::tan(0.5f * cam.fov_y_rad));
    EXPECT_GT(fraction, 0.5f * kOpeningDetailFraction);
    EXPECT_LT(fraction, 2.0f * kOpeningDetailFraction);
}

TEST(DefaultView, ASmallPileOpensWhole) {
    const Bounds extent{glm::vec3(-2.0f), glm::vec3(2.0f)};
    const ResidentTiles tiles = tilesWith({{glm::ivec3(-1, -1, 0), 40}, {glm::ivec3(0, 0, 0), 40}, {glm::ivec3(1, 0, 0), 3}});
    std::vector<DetailLodMesh> meshes(1);
    meshes[0].radius_m = 0.1f;
    const Bounds open = openingBounds(extent, nullptr, &tiles, meshes);
    const Bounds all = framingBounds(extent, nullptr, &tiles);
    EXPECT_EQ(glm::vec2(open.lo), glm::vec2(all.lo));
    EXPECT_EQ(glm::vec2(open.hi), glm::vec2(all.hi));
}

}  // namespace
}  // namespace ug::editor
