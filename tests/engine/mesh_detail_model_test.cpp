#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "mesh_test_util.h"
#include "io/gltf_mesh_io.h"
#include "mesh/detail_model.h"
#include "mesh/procedural_models.h"

namespace ug {
namespace {

void expectBoundsEncloseSpheres(const DetailModel& model) {
    for (const Sphere& s : model.spheres)
        EXPECT_LE(glm::length(s.center - model.bounds.center) + s.radius, model.bounds.radius);
}

}  // namespace

TEST(DetailModel, LoadsGlbConvertsYUpAndScales) {
    const TriangleMesh mushroom = makeMushroom(3);
    const std::string path = test::tempPath("mushroom.glb");
    std::string error;
    ASSERT_TRUE(writeGltfMeshes(path, {{"mushroom", &mushroom}}, &error)) << error;
    DetailModelSource source;
    source.name = "mushroom";
    source.mesh_path = path;
    source.scale = 2.0f;
    DetailModel model;
    ASSERT_TRUE(loadDetailModel(source, &model, &error)) << error;
    const Bounds3 a = meshBounds(mushroom), b = meshBounds(model.mesh);
    EXPECT_NEAR(b.max.z, 2.0f * a.max.z, 1e-5f);  // still Z up, twice the size
    EXPECT_NEAR(b.min.y, 2.0f * a.min.y, 1e-5f);
    EXPECT_FALSE(model.spheres.empty());
    // Default: SphereCenters, thinned to at most 8 centres, the first the one nearest the origin.
    EXPECT_EQ(model.anchors.size(), std::min<size_t>(8, model.spheres.size()));
    for (const glm::vec3& anchor : model.anchors)
        EXPECT_TRUE(std::any_of(model.spheres.begin(), model.spheres.end(),
                                [&](const Sphere& s) { return s.center == anchor; }));
    for (const Sphere& s : model.spheres) EXPECT_GE(glm::length(s.center), glm::length(model.anchors[0]));
    EXPECT_EQ(model.fit_report.sphere_count, model.spheres.size());
    expectBoundsEncloseSpheres(model);
}

TEST(DetailModel, AuthoredSpheresAndAnchorModes) {
    DetailModelSource source;
    source.name = "cube";
    source.authored_spheres = {{{0, 0, 0}, 0.8f}};
    DetailModel model;
    std::string error;
    source.anchor_mode = AnchorMode::Center;
    ASSERT_TRUE(makeDetailModel(source, test::unitCube(), &model, &error)) << error;
    ASSERT_EQ(model.spheres.size(), 1u);
    EXPECT_EQ(model.fit_report.sphere_count, 0u);
    EXPECT_EQ(model.anchors, std::vector<glm::vec3>{glm::vec3(0.0f)});
    expectBoundsEncloseSpheres(model);

    source.anchor_mode = AnchorMode::Surface;
    source.anchor_count = 8;
    ASSERT_TRUE(makeDetailModel(source, test::unitCube(), &model, &error)) << error;
    EXPECT_EQ(model.anchors.size(), 9u);  // 8 on the surface + the origin

    source.anchor_mode = AnchorMode::Authored;
    source.authored_anchors = {{0.1f, 0.2f, 0.3f}};
    ASSERT_TRUE(makeDetailModel(source, test::unitCube(), &model, &error)) << error;
    EXPECT_EQ(model.anchors, source.authored_anchors);
}

TEST(DetailModel, BadParametersNameTheField) {
    struct Case {
        const char* field;
        void (*edit)(DetailModelSource*);
    };
    const Case cases[] = {
        {"scale", [](DetailModelSource* s) { s->scale = 0.0f; }},
        {"scale", [](DetailModelSource* s) { s->scale = std::numeric_limits<float>::quiet_NaN(); }},
        {"max_spheres", [](DetailModelSource* s) { s->fit.max_spheres = 0; }},
        {"max_spheres", [](DetailModelSource* s) { s->fit.max_spheres = 5000; }},
        {"tolerance_m", [](DetailModelSource* s) { s->fit.tolerance_m = -0.01f; }},
        {"tolerance_m", [](DetailModelSource* s) { s->fit.tolerance_m = std::numeric_limits<float>::quiet_NaN(); }},
        {"surface_samples", [](DetailModelSource* s) { s->fit.surface_samples = 2000000; }},
        {"authored_spheres[1]", [](DetailModelSource* s) { s->authored_spheres = {{{0, 0, 0}, 1.0f}, {{0, 0, 0}, 0.0f}}; }},
        {"authored_spheres[0]",
         [](DetailModelSource* s) { s->authored_spheres = {{{0, 0, 0}, std::numeric_limits<float>::quiet_NaN()}}; }},
        {"anchor_count", [](DetailModelSource* s) { s->anchor_mode = AnchorMode::Surface; s->anchor_count = 0; }},
        {"authored_anchors", [](DetailModelSource* s) { s->anchor_mode = AnchorMode::Authored; }},
    };
    for (const Case& c : cases) {
        DetailModelSource source;
        source.name = "cube";
        c.edit(&source);
        DetailModel model;
        std::string error;
        EXPECT_FALSE(makeDetailModel(source, test::unitCube(), &model, &error)) << c.field;
        EXPECT_NE(error.find(c.field), std::string::npos) << error;
        EXPECT_NE(error.find("cube"), std::string::npos) << error;
    }
}

TEST(DetailModel, FileErrorsNameThePath) {
    DetailModelSource source;
    source.name = "ghost";
    source.mesh_path = test::tempPath("nowhere.obj");
    DetailModel model;
    std::string error;
    EXPECT_FALSE(loadDetailModel(source, &model, &error));
    EXPECT_NE(error.find(source.mesh_path), std::string::npos) << error;

    TriangleMesh nan_mesh = test::unitCube();
    nan_mesh.positions[0].z = std::numeric_limits<float>::infinity();
    source.mesh_path.clear();
    EXPECT_FALSE(makeDetailModel(source, nan_mesh, &model, &error));
    EXPECT_NE(error.find("non-finite"), std::string::npos) << error;

    EXPECT_FALSE(makeDetailModel(source, TriangleMesh{}, &model, &error));
    EXPECT_NE(error.find("no triangles"), std::string::npos) << error;
}

}  // namespace ug
