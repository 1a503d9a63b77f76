#include "editor/scene_snapshot.h"

#include <chrono>
#include <thread>

#include "editor/default_view.h"

namespace ug::editor {

namespace {
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

const Bounds& SceneSnapshot::extent() const { return scene.doc->compiled().extent; }
const CandidateSet& SceneSnapshot::candidates() const { return scene.doc->ghostTile().candidates; }
float SceneSnapshot::tileSize() const { return scene.doc->ghostTile().settings.tile_size_m; }
Bounds SceneSnapshot::framing() const {
    const Bounds opening = openingBounds(extent(), terrain(), &tiles, scene.meshes);
    return scene.static_meshes.empty() ? opening : unite(opening, staticMeshesBounds(scene.static_meshes));
}

bool loadSceneSnapshot(const SceneSnapshotOptions& options, SceneSnapshot* out, std::string* error) {
    const auto t0 = Clock::now();
    LoadRequest request;
    request.scene_path = options.scene_path;
    request.options.cache_dir = options.cache_dir;
    request.options.threads = options.threads;
    // No config folder: a batch render leaves no recent-files entry and no recovery file behind.
    request.options.config_dir.clear();
    {
        // The editor's loader, waited for: the same document, terrain mesh and LODs as the editor's.
        DocumentLoader loader(request);
        while (loader.phase() == LoadPhase::Loading) std::this_thread::sleep_for(std::chrono::milliseconds(2));
        if (loader.phase() == LoadPhase::Failed) {
            *error = loader.error();
            return false;
        }
        out->scene = std::move(loader.scene());
    }
    out->load_seconds = secondsSince(t0);
    const auto t1 = Clock::now();
    Document& doc = *out->scene.doc;
    // The document started its first full instantiation (settled like `instantiate`) when it opened.
    const LiveResult live = doc.waitForResult();
    if (!live.ok || !live.store) {
        *error = options.scene_path + ": " + live.error;
        return false;
    }
    out->store = live.store;
    out->stats = live.stats;
    const SettleSettings& settle = doc.project().settling.settle;
    if (!rebuildResidentTiles(*live.store, live.drops.get(), doc.ghostTile().candidates,
                              doc.ghostTile().settings.tile_size_m, packedDropUnit(settle.enabled, settle.max_drop_m),
                              &out->tiles, &out->uploads, error, &out->scene.looks)) {
        *error = options.scene_path + ": " + *error;
        return false;
    }
    out->instantiate_seconds = secondsSince(t1);
    return true;
}

}  // namespace ug::editor
