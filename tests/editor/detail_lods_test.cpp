// The mesh levels of every starter model are honest (render_data.h buildDetailLods): each level's
// silhouette is within kLodCoverageTolerance of the model's from every elevation, levels never gain
// triangles, the rocks do get cheaper, and the impostor switch moves out only for a model that stays heavy.
#include <cmath>

#include <gtest/gtest.h>

#include "editor/coverage.h"
#include "editor/render_data.h"
#include "mesh/procedural_models.h"

namespace ug::editor {
namespace {

DetailModel starter(const std::string& name) {
    DetailModel m;
    m.name = name;
    EXPECT_TRUE(makeStarterAsset(name, kStarterAssetSeed, &m.mesh));
    return m;
}

TEST(DetailLods, EveryLevelOfEveryStarterModelKeepsTheSilhouette) {
    for (const std::string& name : starterAssetNames()) {
        const DetailLodMesh lods = buildDetailLods(starter(name), 1.0f);
        const CoverageProfile model = measureCoverage(lods.positions, lods.indices.data() + lods.index_first[0],
                                                      lods.index_count[0]);
        for (int level = 1; level < kMeshLodCount; ++level) {
            EXPECT_LE(lods.index_count[size_t(level)], lods.index_count[size_t(level - 1)]) << name;
            const CoverageProfile c = measureCoverage(
                lods.positions, lods.indices.data() + lods.index_first[size_t(level)], lods.index_count[size_t(level)]);
            for (int e = 0; e < kCoverageElevations; ++e)
                EXPECT_NEAR(c.area_m2[size_t(e)], model.area_m2[size_t(e)], kLodCoverageTolerance * model.area_m2[size_t(e)])
                    << name << " LOD " << level << " elevation " << 30 * e;
        }
        // The impostor covers what the model covers (the same measure, at the same elevations).
        for (int e = 0; e < kCoverageElevations; ++e)
            EXPECT_NEAR(lods.coverage_m2[size_t(e)], model.area_m2[size_t(e)], 1e-9f) << name;
        EXPECT_GE(lods.impostor_scale, 1.0f) << name;
        EXPECT_LE(lods.impostor_scale, 4.0f) << name;
    }
}

TEST(DetailLods, RocksGetCheaperAndTheGrassTuftHandsOverToItsSpriteSooner) {
    const DetailLodMesh rock = buildDetailLods(starter("rock"), 1.0f);
    EXPECT_LT(rock.index_count[2] * 8, rock.index_count[0]);
    EXPECT_EQ(rock.impostor_scale, 1.0f);
    // The tuft's blades are thinner than any simplification that saves triangles keeps: its coarsest
    // level stays over the budget, so its switch to the sprite comes at a larger size.
    const DetailLodMesh grass = buildDetailLods(starter("grass_tuft"), 1.0f);
    EXPECT_GT(grass.index_count[2] / 3, kImpostorBudgetTriangles);
    EXPECT_GT(grass.impostor_scale, 1.0f);
}

TEST(DetailLods, TheSilhouetteMasksCoverWhatTheProfileSaysFromAbove) {
    // From straight above the view has no azimuth: the mask's area is the profile's area exactly.
    const DetailLodMesh leaf = buildDetailLods(starter("leaf_oak"), 1.0f);
    const SilhouetteMasks& s = leaf.silhouettes;
    ASSERT_GT(s.resolution, 0);
    size_t covered = 0;
    for (uint8_t m : s.mask[kCoverageElevations - 1]) covered += m ? 1 : 0;
    const float cell = 2.0f * s.radius / float(s.resolution);
    // The profile is rastered at 128, the mask at 64: the same area to about a texel along the outline.
    EXPECT_NEAR(float(covered) * cell * cell, leaf.coverage_m2[kCoverageElevations - 1],
                0.15f * leaf.coverage_m2[kCoverageElevations - 1]);
}

TEST(DetailLods, TheSpriteShowsEveryCoveredTexelAndTheTuftsSpriteIsCropped) {
    for (const std::string& name : starterAssetNames()) {
        const SilhouetteMasks s = buildDetailLods(starter(name), 1.0f).silhouettes;
        ASSERT_GT(s.resolution, 0) << name;
        ASSERT_GT(s.extent, 0.0f) << name;
        ASSERT_LE(s.extent, 1.0f) << name;
        // Every covered texel's centre lies inside the centred square of side `extent`.
        const float half = 0.5f * s.extent * float(s.resolution);
        for (const std::vector<uint8_t>& m : s.mask)
            for (int y = 0; y < s.resolution; ++y)
                for (int x = 0; x < s.resolution; ++x)
                    if (m[size_t(y) * size_t(s.resolution) + size_t(x)]) {
                        EXPECT_LE(std::abs(float(x) + 0.5f - 0.5f * float(s.resolution)), half) << name;
                        EXPECT_LE(std::abs(float(y) + 0.5f - 0.5f * float(s.resolution)), half) << name;
                    }
    }
    // A tuft is taller than wide, but its bounding sphere's square is wider still than its height.
    EXPECT_LT(buildDetailLods(starter("grass_tuft"), 1.0f).silhouettes.extent, 0.9f);
}

}  // namespace
}  // namespace ug::editor
