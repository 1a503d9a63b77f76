// Opening a document off the UI thread. The worker opens the Document (project, models, the verified Ghost
// Tile cache or a build, terrain, compile; its live instancer then starts the first full instantiation in
// the background), or recovers its autosave, builds the terrain mesh and the detail LODs and publishes
// them (phase Ready). The UI thread polls phase() every frame and never waits, except in the destructor
// (which waits for the open to finish: Document::open cannot be cancelled half-way).
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "env/env_effects.h"
#include "io/mesh_instances.h"
#include "editor/render_data.h"
#include "mesh/triangle_mesh.h"
#include "scene/document.h"

namespace ug::editor {

enum class LoadPhase : int { Loading, Ready, Failed };

// What the worker produced; complete once the phase is Ready, then owned by the UI thread.
struct EditorScene {
    std::unique_ptr<Document> doc;
    bool has_terrain = false;
    TriangleMesh terrain;               // world space; empty without terrain
    std::vector<DetailLodMesh> meshes;  // one per look (doc->looks()): the types', then their variants'
    DetailLooks looks;                  // which mesh each instance takes; points into doc's models
    SurfaceMaterial terrain_material;
    // The environmental objects' base geometry and effects (snow, icicles) as the renderer draws them
    // (env/env_outputs.h); empty without an environment.
    std::shared_ptr<const EnvEffects> env_effects;
    std::shared_ptr<const EnvScene> env_scene;  // what env_effects were computed for
    std::vector<MeshInstances> static_meshes;   // every one, as the export writes them
};

struct LoadRequest {
    std::string scene_path;
    DocumentOptions options;
    bool recover = false;  // open the autosave (Document::recover) instead of the file
    // File > New: scene_path is a template project (its terrain, extent and detail types); the document is
    // untitled (saved with Save As) and every type starts with no density.
    bool new_from_template = false;
};

class DocumentLoader {
  public:
    explicit DocumentLoader(LoadRequest request);
    ~DocumentLoader();
    DocumentLoader(const DocumentLoader&) = delete;
    DocumentLoader& operator=(const DocumentLoader&) = delete;

    LoadPhase phase() const { return phase_.load(std::memory_order_acquire); }
    // The worker's stages so far, in [0, 1]: the document opened (project, terrain, models, the Ghost Tile
    // verified or built, compiled), its terrain mesh, its detail LODs. The first instantiation comes after
    // (LiveInstancer::fullRunProgress).
    float progress() const { return progress_.load(std::memory_order_relaxed); }
    const LoadRequest& request() const { return request_; }
    // Valid when phase() is Ready; the worker has finished with it.
    EditorScene& scene() { return *scene_; }
    // Valid when phase() is Failed.
    const std::string& error() const { return error_; }

  private:
    void work();

    LoadRequest request_;
    std::unique_ptr<EditorScene> scene_;
    std::string error_;
    std::atomic<LoadPhase> phase_{LoadPhase::Loading};
    std::atomic<float> progress_{0.0f};
    std::thread thread_;
};

}  // namespace ug::editor
