// File > Export glTF: the engine's exporter (io/instance_export.h) run on a background thread over a
// snapshot of the document, so the UI keeps drawing and editing while it writes. GL-free.
//
//   ExportJob job(doc, store_on_screen, settings, stats_json);   // starts at once
//   every frame:  draw job.progress() and job.stage(); a Cancel button calls job.cancel();
//                 if (job.finished()) { job.ok() ? "wrote N instances" : messages.push_back(job.error()); }
//
// The job copies what it reads (the candidates, the models, the terrain's shared pointer, the extent, the
// surfaces' materials, the looks) and holds the instance store snapshot and its settled drops (so the file holds the
// instances where the viewport shows them, resting, as `instantiate` writes them), so the document may be edited, closed or replaced while it runs.
// Cancel works until the final write starts; the write itself is one atomic step (nothing half-written is
// ever left at the path), and a Cancel that comes during it is too late: the file is written.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>

#include "ghosttile/ghost_tile.h"
#include "instancer/instance_store.h"
#include "instancer/settling.h"
#include "io/mesh_instances.h"
#include "material/material.h"
#include "mesh/detail_model.h"
#include "scene/document.h"

namespace ug::editor {

struct ExportSettings {
    std::string path = "export.glb";  // .glb (binary) or .gltf (JSON, buffer embedded)
    bool plain_nodes = false;         // one node per instance instead of EXT_mesh_gpu_instancing
    float chunk_size_m = 8.0f;        // XY chunk edge the instances are grouped by, > 0
};

enum class ExportStage : int { Gathering, Writing, Done, Failed, Cancelled };
const char* exportStageName(ExportStage stage);  // "gathering instances", "writing the file", ...

class ExportJob {
  public:
    // `store` must not be null. `stats_json` (a JSON object) goes into the scene's extras.
    // `drops`: the store's settled drops (null: the scene does not settle). `static_meshes`: the
    // environmental objects and their effects as shown (EditorScene::static_meshes), written after the
    // details and the terrain like `instantiate` writes them (copied: the entries share their meshes).
    ExportJob(const Document& doc, std::shared_ptr<const InstanceStore> store,
              std::shared_ptr<const SettledDrops> drops, ExportSettings settings, std::string stats_json,
              std::vector<MeshInstances> static_meshes = {});
    ~ExportJob();  // cancels (when still possible) and waits for the thread
    ExportJob(const ExportJob&) = delete;
    ExportJob& operator=(const ExportJob&) = delete;

    void cancel() { cancel_.store(true, std::memory_order_relaxed); }
    bool cancelRequested() const { return cancel_.load(std::memory_order_relaxed); }
    ExportStage stage() const { return stage_.load(std::memory_order_acquire); }
    bool finished() const { return stage() >= ExportStage::Done; }
    float progress() const { return progress_.load(std::memory_order_relaxed); }  // [0, 1]

    // Valid once finished().
    const std::string& error() const { return error_; }  // Failed: "<path>: <reason>"
    double seconds() const { return seconds_; }
    const ExportSettings& settings() const { return settings_; }
    uint64_t instances() const { return store_->instanceCount(); }

  private:
    void work();

    ExportSettings settings_;
    std::string stats_json_;
    GhostTile tile_;  // settings and candidates only (the collision graph is not needed to export)
    std::vector<DetailModel> models_;
    std::shared_ptr<const HeightField> terrain_;
    Bounds extent_;
    std::shared_ptr<const InstanceStore> store_;
    std::shared_ptr<const SettledDrops> drops_;
    SceneMaterials materials_;
    // The looks (scattered types' variants) as `instantiate` writes them: over models_ and the document's
    // variant models, which this job keeps alive.
    std::shared_ptr<const std::vector<std::vector<DetailModel>>> variant_models_;
    DetailLooks looks_;
    std::vector<MeshInstances> static_meshes_;

    std::atomic<bool> cancel_{false};
    std::atomic<float> progress_{0.0f};
    std::atomic<ExportStage> stage_{ExportStage::Gathering};
    std::string error_;
    double seconds_ = 0.0;
    std::thread thread_;  // last: starts after everything above is set
};

}  // namespace ug::editor
