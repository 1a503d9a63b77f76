#include "editor/editor_session.h"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "core/atomic_file.h"
#include "core/hash.h"
#include "editor/background_jobs.h"
#include "editor/navigation.h"
#include "editor/session_stats.h"
#include "editor/window_title.h"
#include "instancer/instance_query.h"
#include "instancer/tile_coord.h"

namespace ug::editor {

void EditorSession::syncTile() {
    if (!scene || scene->doc->tileGeneration() == scene_tile_generation) return;
    Document& d = *scene->doc;
    scene_tile_generation = d.tileGeneration();
    const CandidateSet& c = d.ghostTile().candidates;
    const SceneMaterials looks = d.materials();
    scene->looks = d.looks();
    scene->meshes = buildLookMeshes(scene->looks, c, &looks);
    renderer->setScene(d.compiled().extent, scene->has_terrain ? &scene->terrain : nullptr, &scene->meshes, c,
                       d.ghostTile().settings.tile_size_m, &scene->terrain_material);
    // What is on screen indexes the old tile's candidates: nothing is shown until the new result.
    instances = ResidentTiles{};
    store = std::make_shared<const InstanceStore>();
    reach_m = largestReach(d);
}

bool EditorSession::takeLiveResult() {
    if (!scene) return true;
    Document& d = *scene->doc;
    syncTile();
    LiveResult live;
    if (d.live().poll(&live) && live.generation >= d.tileLiveGeneration()) {
        if (!live.ok) messages.push_back(live.error);
        const auto t0 = Clock::now();
        std::string pack_error;
        const CandidateSet& candidates = d.ghostTile().candidates;
        const SettleSettings& settle = d.project().settling.settle;
        const bool packed =
            (live.full || !have_result)
                ? rebuildResidentTiles(*live.store, live.drops.get(), candidates,
                                       d.ghostTile().settings.tile_size_m,
                                       packedDropUnit(settle.enabled, settle.max_drop_m), &instances, &uploads,
                                       &pack_error, &scene->looks)
                : updateResidentTiles(*live.store, live.drops.get(), candidates, live.changed_tiles, &instances,
                                      &uploads, &pack_error, &scene->looks);
        if (!packed) {
            if (scripted) {
                *error = pack_error;
                return false;
            }
            messages.push_back(pack_error);
        } else {
            renderer->uploadTiles(&instances, uploads);
            if (!uploads.full) {
                result->upload_tiles.push_back(double(uploads.tiles_uploaded));
                result->tile_update_ms_max =
                    std::max(result->tile_update_ms_max,
                             std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
            }
            if (replay.started && !replay.finishing) {
                replay.uploads.push_back({{"tiles", uploads.tiles_uploaded},
                                          {"bytes", uploads.bytes_uploaded},
                                          {"full", uploads.full}});
                for (const glm::ivec3& t : uploads.tiles) replay.uploaded_tiles.insert(packTile(t));
            }
            result->repack_ms_max =
                std::max(result->repack_ms_max,
                         std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
            store = live.store;
            drops = live.drops;
            shown_generation = live.generation;
            view.instances = instances.instanceCount();
            view.instances_per_type = instances.instances_per_type;
            view.tiles_uploaded = uploads.tiles_uploaded;
            view.bytes_uploaded = uploads.bytes_uploaded;
            view.instantiate_seconds = live.stats.seconds;
            view.changed_tiles = live.changed_tiles.size();
            inst_view.have_result = true;
            inst_view.stats = live.stats;
            inst_view.changed_tiles = live.changed_tiles.size();
            inst_view.full = live.full;
            if (inst_view.update_ms.size() >= InstantiationView::kUpdateHistory)
                inst_view.update_ms.erase(inst_view.update_ms.begin());
            inst_view.update_ms.push_back(float(live.stats.seconds * 1e3));
            if (!have_result && !camera_moved) frameBounds(openingBounds(*scene, instances), &camera);
            have_result = true;
        }
    }
    return true;
}

}  // namespace ug::editor
