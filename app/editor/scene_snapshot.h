// A scene instantiated, settled and packed for the renderer, GL-free: what `undergrowth render` and the
// bench's offscreen rows draw. It is made the way the editor makes what it shows on open (the document
// loader: Document::open, the terrain mesh, the detail LODs; then the live instancer's first full,
// settled result packed into resident tiles), so a rendered picture shows the instances the editor shows
// (the GUI tests check those match `undergrowth instantiate`).
//
//   SceneSnapshot snap;
//   if (!loadSceneSnapshot({.scene_path = "assets/scenes/meadow.json"}, &snap, &error)) ...;
//   renderer.setScene(snap.extent(), snap.terrain(), &snap.scene.meshes, snap.candidates(), snap.tileSize());
//   renderer.setStaticMeshes(&snap.scene.static_meshes);  // environmental objects, snow, icicles
//   renderer.uploadTiles(&snap.tiles, snap.uploads);
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "editor/document_loader.h"
#include "editor/render_data.h"
#include "io/mesh_instances.h"

namespace ug::editor {

struct SceneSnapshotOptions {
    std::string scene_path;
    std::string cache_dir = "out/cache";  // the Ghost Tile cache (loaded when verified, else built there)
    int threads = 0;                      // 0 = all hardware threads
};

struct SceneSnapshot {
    EditorScene scene;  // the document (project, models, Ghost Tile, compiled fields), terrain mesh, LODs
    std::shared_ptr<const InstanceStore> store;  // the settled instance set
    ResidentTiles tiles;  // `store` packed for the GPU; the renderer keeps a pointer: keep the snapshot alive
    TileUploads uploads;  // a full upload of `tiles`
    InstanceStats stats;
    double load_seconds = 0.0;  // opening the document (models, Ghost Tile, terrain mesh, LODs)
    double instantiate_seconds = 0.0;  // from the end of the open to the settled result, packed

    const Bounds& extent() const;
    const TriangleMesh* terrain() const { return scene.has_terrain ? &scene.terrain : nullptr; }
    const CandidateSet& candidates() const;
    float tileSize() const;
    Bounds framing() const;  // default_view.h openingBounds, grown to hold the static meshes when there are any
};

// Fails with the document's error (naming the scene file, the place and the reason) or the instancer's.
bool loadSceneSnapshot(const SceneSnapshotOptions& options, SceneSnapshot* out, std::string* error);

}  // namespace ug::editor
