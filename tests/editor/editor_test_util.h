// Shared by the editor's tests: a scratch copy of the small environment street (tests/engine/env_edit_scene.h)
// opened as a document, and a bit-for-bit comparison of two sets of output meshes.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "../engine/env_edit_scene.h"
#include "io/mesh_instances.h"
#include "scene/document.h"

namespace ug::editor::test {

// The street project in a fresh temporary folder, opened; the folder is removed with it.
struct OpenEnvDocument {
    std::filesystem::path dir;
    std::unique_ptr<Document> doc;
    OpenEnvDocument() {
        std::random_device rd;
        dir = std::filesystem::temp_directory_path() /
              ("ug_editor_env_test_" + std::to_string(rd()) + std::to_string(rd()));
        std::filesystem::create_directories(dir);
        std::ofstream(dir / "street.json") << ug::test::envEditProjectJson();
        std::string error;
        doc = Document::open((dir / "street.json").string(),
                             DocumentOptions{.cache_dir = (dir / "cache").string(), .threads = 2}, &error);
        EXPECT_TRUE(doc) << error;
    }
    ~OpenEnvDocument() {
        doc.reset();
        std::error_code ec;
        std::filesystem::remove_all(dir, ec);
    }
};

// Names, vertices, indices, extras and every instance's transform equal, in order.
inline void expectSameMeshes(const std::vector<MeshInstances>& a, const std::vector<MeshInstances>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].name, b[i].name);
        EXPECT_EQ(a[i].mesh->positions, b[i].mesh->positions) << a[i].name;
        EXPECT_EQ(a[i].mesh->indices, b[i].mesh->indices) << a[i].name;
        EXPECT_EQ(a[i].extras_json, b[i].extras_json) << a[i].name;
        ASSERT_EQ(a[i].instances.size(), b[i].instances.size()) << a[i].name;
        for (size_t k = 0; k < a[i].instances.size(); ++k) {
            EXPECT_EQ(a[i].instances[k].position, b[i].instances[k].position) << a[i].name;
            EXPECT_EQ(a[i].instances[k].rotation, b[i].instances[k].rotation) << a[i].name;
            EXPECT_EQ(a[i].instances[k].scale, b[i].instances[k].scale) << a[i].name;
        }
    }
}

}  // namespace ug::editor::test
