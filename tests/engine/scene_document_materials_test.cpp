// The document exposes the project's materials (Document::materials) for the renderer, keeps them
// through save and reopen, and materials never change what is instantiated.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "material/procedural_texture.h"
#include "mesh/terrain_mesh.h"
#include "scene/document.h"
#include "scene_test_util.h"

namespace ug {
namespace {

namespace fs = std::filesystem;

std::string sceneJson(bool materials) {
    const std::string models = (fs::path(UG_SOURCE_DIR) / "assets" / "models").string();
    const std::string rock_material =
        materials ? R"(, "material": {"base_color": [0.4, 0.35, 0.3], "texture": "rock", "tint_variation": 0.3})" : "";
    const std::string ground_material =
        materials ? R"(, "material": {"texture": "ground", "texture_scale_m": 0.5})" : "";
    return R"({"format": "undergrowth-project", "format_version": 2, "name": "looks",
 "ghost_tile": {"tile_size_m": 0.5, "delta_m": -0.002, "seed": 7},
 "terrain": {"procedural": {"origin": [-2, -2], "cell_size_m": 0.25, "width": 17, "height": 17, "seed": 3,
                            "octaves": 2, "amplitude_m": 0.15, "feature_size_m": 2})" +
           ground_material + R"(},
 "extent": {"min": [-2, -2, -0.5], "max": [2, 2, 0.8]},
 "detail_types": [
  {"name": "rock", "model": {"mesh": ")" + models + R"(/rock.glb"}, "candidates": {"count": 100})" + rock_material + R"(,
   "density": {"blend": [{"point": {"center": [0.5, 0.5, 0], "radius": 0.8, "weight": 0.8}}]}},
  {"name": "pebble", "model": {"mesh": ")" + models + R"(/pebble.glb"}, "candidates": {"count": 160},
   "density": {"terrain_layer": {"thickness": 0.05, "radius": 0.1, "weight": 0.7}}}]})";
}

std::unique_ptr<Document> open(const fs::path& path, const std::string& text, const test::TempDir& dir) {
    std::ofstream(path) << text;
    std::string error;
    DocumentOptions options{.cache_dir = (dir.path() / "cache").string(), .config_dir = "", .threads = 2};
    std::unique_ptr<Document> doc = Document::open(path.string(), options, &error);
    EXPECT_TRUE(doc) << error;
    return doc;
}

TEST(Document, MaterialsAreExposedKeptOnSaveAndChangeNoInstance) {
    test::TempDir dir("ug_document_materials_");
    auto with = open(dir.path() / "with.json", sceneJson(true), dir);
    auto without = open(dir.path() / "without.json", sceneJson(false), dir);
    ASSERT_TRUE(with && without);

    const SceneMaterials looks = with->materials();
    ASSERT_EQ(looks.types.size(), 2u);
    EXPECT_EQ(looks.types[0].base_color, glm::vec3(0.4f, 0.35f, 0.3f));
    EXPECT_EQ(looks.types[0].tint_variation, 0.3f);
    ASSERT_NE(looks.types[0].texture, nullptr);
    EXPECT_EQ(looks.types[0].texture->rgba, bakeMaterialTexture(TextureKind::Rock, false, looks.types[0].base_color).rgba);
    EXPECT_EQ(looks.types[1].texture, nullptr);  // no material: the model's own colour
    EXPECT_EQ(looks.types[1].base_color, with->models()[1].mesh.base_color);
    ASSERT_NE(looks.terrain.texture, nullptr);
    EXPECT_EQ(looks.terrain.base_color, kTerrainColor);
    EXPECT_EQ(looks.terrain.texture_scale_m, 0.5f);

    // The same instances with and without materials, and the same Ghost Tile.
    const LiveResult a = with->waitForResult(), b = without->waitForResult();
    ASSERT_TRUE(a.ok && b.ok) << a.error << b.error;
    EXPECT_GT(a.store->instanceCount(), 0u);
    EXPECT_TRUE(*a.store == *b.store);

    // Saved and reopened: the same materials.
    std::string error;
    const fs::path copy = dir.path() / "copy.json";
    ASSERT_TRUE(with->saveAs(copy.string(), &error)) << error;
    DocumentOptions options{.cache_dir = (dir.path() / "cache").string(), .config_dir = "", .threads = 2};
    auto reopened = Document::open(copy.string(), options, &error);
    ASSERT_TRUE(reopened) << error;
    EXPECT_EQ(reopened->project().detail_types[0].material, with->project().detail_types[0].material);
    EXPECT_EQ(reopened->project().terrain.material, with->project().terrain.material);
    EXPECT_EQ(reopened->materials().types[0].texture->rgba, looks.types[0].texture->rgba);
}

}  // namespace
}  // namespace ug
