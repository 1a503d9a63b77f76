#include "editor/export_job.h"

#include <chrono>

#include "io/instance_export.h"

namespace ug::editor {

const char* exportStageName(ExportStage stage) {
    switch (stage) {
        case ExportStage::Gathering:
            return "gathering instances";
        case ExportStage::Writing:
            return "writing the file";
        case ExportStage::Done:
            return "done";
        case ExportStage::Failed:
            return "failed";
        case ExportStage::Cancelled:
            return "cancelled";
    }
    return "?";
}

ExportJob::ExportJob(const Document& doc, std::shared_ptr<const InstanceStore> store,
                     std::shared_ptr<const SettledDrops> drops, ExportSettings settings, std::string stats_json,
                     std::vector<MeshInstances> static_meshes)
    : settings_(std::move(settings)),
      stats_json_(std::move(stats_json)),
      models_(doc.models()),
      terrain_(doc.terrain()),
      extent_(doc.compiled().extent),
      store_(std::move(store)),
      drops_(std::move(drops)),
      materials_(doc.materials()),
      variant_models_(doc.variantModels()),
      looks_(detailLooks(doc.project(), models_, *variant_models_, doc.environment())),
      static_meshes_(std::move(static_meshes)) {
    tile_.settings = doc.ghostTile().settings;
    tile_.candidates = doc.ghostTile().candidates;
    thread_ = std::thread([this] { work(); });
}

ExportJob::~ExportJob() {
    cancel();
    if (thread_.joinable()) thread_.join();
}

void ExportJob::work() {
    const auto t0 = std::chrono::steady_clock::now();
    InstanceExportOptions options;
    options.chunk_size_m = settings_.chunk_size_m;
    options.use_instancing_extension = !settings_.plain_nodes;
    options.drops = drops_.get();
    options.materials = &materials_;
    options.static_meshes = &static_meshes_;
    // Each instance's look, as `instantiate` writes it: wet leaves in the puddle are their own mesh.
    const std::vector<uint32_t> instance_looks =
        instanceLooks(looks_, tile_.candidates, tile_.settings.tile_size_m, *store_, 0);
    if (!instance_looks.empty()) {
        options.look_models = looks_.models;
        options.instance_looks = &instance_looks;
    }
    options.progress = [this](float fraction) {
        progress_.store(fraction, std::memory_order_relaxed);
        if (cancelRequested()) return false;
        // The last callback comes just before the write: from here on Cancel is too late.
        if (fraction >= 0.9f) stage_.store(ExportStage::Writing, std::memory_order_release);
        return true;
    };
    std::string error;
    const bool ok = exportInstancedScene(settings_.path, tile_, models_, *store_, terrain_.get(), extent_,
                                         options, stats_json_, &error);
    seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    progress_.store(1.0f, std::memory_order_relaxed);
    if (ok) {
        stage_.store(ExportStage::Done, std::memory_order_release);
    } else if (cancelRequested() && stage_.load(std::memory_order_relaxed) == ExportStage::Gathering) {
        error_ = settings_.path + ": export cancelled";
        stage_.store(ExportStage::Cancelled, std::memory_order_release);
    } else {
        error_ = "Export failed: " + error;
        stage_.store(ExportStage::Failed, std::memory_order_release);
    }
}

}  // namespace ug::editor
