#include "scene/ghost_tile_job.h"

#include <chrono>
#include <filesystem>

namespace ug {

namespace {

// Loading models is quick next to a build; this share of the bar keeps it moving while they load.
constexpr float kModelsProgressShare = 0.1f;

bool sameSpheres(const std::vector<Sphere>& a, const std::vector<Sphere>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i].center != b[i].center || a[i].radius != b[i].radius) return false;
    return true;
}

bool sameTypeSettings(const DetailTypeSettings& a, const DetailTypeSettings& b) {
    if (a.name != b.name || a.candidate_count != b.candidate_count || a.scale_min != b.scale_min ||
        a.scale_max != b.scale_max || a.position != b.position || a.orientation.mode != b.orientation.mode ||
        a.orientation.tilt_ranges.size() != b.orientation.tilt_ranges.size())
        return false;
    for (size_t r = 0; r < a.orientation.tilt_ranges.size(); ++r) {
        const TiltRange &x = a.orientation.tilt_ranges[r], &y = b.orientation.tilt_ranges[r];
        if (x.min_deg != y.min_deg || x.max_deg != y.max_deg || x.weight != y.weight) return false;
    }
    return true;
}

std::string resolve(const std::string& base_dir, const std::string& path) {
    const std::filesystem::path p(path);
    if (p.is_absolute() || base_dir.empty()) return path;
    return (std::filesystem::path(base_dir) / p).lexically_normal().string();
}

}  // namespace

ModelFileStamp modelFileStamp(const std::string& path) {
    std::error_code ec;
    ModelFileStamp stamp;
    const uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) return stamp;
    const auto time = std::filesystem::last_write_time(path, ec);
    if (ec) return stamp;
    stamp.size = int64_t(size);
    stamp.mtime_ns = int64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(time.time_since_epoch()).count());
    return stamp;
}

GhostTileSpec ghostTileSpec(const Project& project) {
    GhostTileSpec spec;
    spec.settings = project.ghost_tile;
    for (const DetailTypeDesc& t : project.detail_types) {
        spec.models.push_back(t.model);
        spec.types.push_back(t.ghost);
    }
    return spec;
}

void setGhostTileSpec(const GhostTileSpec& spec, Project* project) {
    project->ghost_tile = spec.settings;
    for (size_t t = 0; t < project->detail_types.size() && t < spec.types.size(); ++t) {
        project->detail_types[t].model = spec.models[t];
        project->detail_types[t].ghost = spec.types[t];
    }
}

bool sameModelSource(const DetailModelSource& a, const DetailModelSource& b) {
    return a.name == b.name && a.mesh_path == b.mesh_path && a.scale == b.scale && a.y_up == b.y_up &&
           sameSpheres(a.authored_spheres, b.authored_spheres) && a.fit.max_spheres == b.fit.max_spheres &&
           a.fit.tolerance_m == b.fit.tolerance_m && a.fit.tolerance_rel == b.fit.tolerance_rel &&
           a.fit.surface_samples == b.fit.surface_samples && a.fit.seed == b.fit.seed &&
           a.anchor_mode == b.anchor_mode && a.authored_anchors == b.authored_anchors &&
           a.anchor_count == b.anchor_count;
}

bool operator==(const GhostTileSpec& a, const GhostTileSpec& b) {
    if (a.settings.tile_size_m != b.settings.tile_size_m || a.settings.delta_m != b.settings.delta_m ||
        a.settings.seed != b.settings.seed || a.settings.variants != b.settings.variants || a.models.size() != b.models.size() || a.types.size() != b.types.size())
        return false;
    for (size_t t = 0; t < a.models.size(); ++t)
        if (!sameModelSource(a.models[t], b.models[t])) return false;
    for (size_t t = 0; t < a.types.size(); ++t)
        if (!sameTypeSettings(a.types[t], b.types[t])) return false;
    return true;
}

bool validateGhostTileSpec(const GhostTileSpec& spec, const Project& project, std::string* error) {
    const size_t n = project.detail_types.size();
    if (spec.types.size() != n || spec.models.size() != n) {
        *error = "ghost tile: the settings have " + std::to_string(spec.types.size()) + " detail types, the project " +
                 std::to_string(n);
        return false;
    }
    for (size_t t = 0; t < n; ++t) {
        const std::string& name = project.detail_types[t].model.name;
        const std::string where = "ghost tile: type '" + name + "': ";
        if (spec.types[t].name != name || spec.models[t].name != name) {
            *error = where + "the settings name it '" + spec.types[t].name + "' (types cannot be renamed here)";
            return false;
        }
        if (spec.models[t].mesh_path.empty()) {
            *error = where + "no model file";
            return false;
        }
        if (!(spec.models[t].scale > 0.0f) || !(spec.models[t].scale < 1e6f)) {
            *error = where + "model scale must be > 0 and finite, got " + std::to_string(spec.models[t].scale);
            return false;
        }
    }
    // The rest is validateGhostTileInput's, run before any model is loaded so absurd settings are refused at
    // once: a placeholder model of one tiny sphere passes the model-dependent checks, which the job repeats
    // with the real models (ghost_tile.cpp: sphere validity, the largest object fitting in the tile).
    DetailModel placeholder;
    placeholder.spheres = {Sphere{glm::vec3(0.0f), 1e-6f}};
    placeholder.bounds = placeholder.spheres[0];
    GhostTileInput input;
    input.settings = spec.settings;
    input.types = spec.types;
    input.models.assign(n, &placeholder);
    return validateGhostTileInput(input, error);
}

GhostTileJob::GhostTileJob(GhostTileSpec spec, GhostTileJobContext context) : context_(std::move(context)) {
    build_.spec = std::move(spec);
    build_.base_dir = context_.base_dir;
    thread_ = std::thread([this] { work(); });
}

GhostTileJob::~GhostTileJob() {
    cancel_.store(true);
    if (thread_.joinable()) thread_.join();
}

void GhostTileJob::wait() {
    // The thread ends right after publishing its state; joining is the wait.
    if (thread_.joinable()) thread_.join();
}

void GhostTileJob::work() {
    const auto start = std::chrono::steady_clock::now();
    auto finish = [&](GhostTileJobState state) {
        build_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        progress_.store(state == GhostTileJobState::Done ? 1.0f : progress_.load());
        state_.store(state, std::memory_order_release);
    };
    const GhostTileSpec& spec = build_.spec;
    const size_t n = spec.types.size();
    auto models = std::make_shared<std::vector<DetailModel>>(n);
    build_.model_files.assign(n, ModelFileStamp{});
    const std::vector<DetailModel>* current = context_.current_models.get();
    for (size_t t = 0; t < n; ++t) {
        if (cancel_.load()) return finish(GhostTileJobState::Cancelled);
        DetailModelSource source = spec.models[t];
        source.mesh_path = resolve(context_.base_dir, source.mesh_path);
        // Taken before loading: a file that changes while it is read is read again next time.
        build_.model_files[t] = modelFileStamp(source.mesh_path);
        const bool reuse = current && t < current->size() && t < context_.current_sources.size() &&
                           t < context_.current_files.size() &&
                           sameModelSource(spec.models[t], context_.current_sources[t]) &&
                           build_.model_files[t] == context_.current_files[t];
        if (reuse) {
            (*models)[t] = (*current)[t];
        } else {
            std::string model_error;
            if (!loadDetailModel(source, &(*models)[t], &model_error)) {
                error_ = "detail type '" + source.name + "': " + model_error;
                return finish(GhostTileJobState::Failed);
            }
            ++build_.models_loaded;
        }
        progress_.store(kModelsProgressShare * float(t + 1) / float(n));
    }
    if (cancel_.load()) return finish(GhostTileJobState::Cancelled);

    GhostTileInput input;
    input.settings = spec.settings;
    input.types = spec.types;
    for (const DetailModel& m : *models) input.models.push_back(&m);
    BuildOptions options;
    options.threads = context_.threads;
    options.cancel = &cancel_;
    options.progress = [this](float f) { progress_.store(kModelsProgressShare + (1.0f - kModelsProgressShare) * f); };
    auto tile = std::make_shared<GhostTile>();
    std::string error;
    if (!loadOrBuildGhostTile(context_.cache_dir, input, options, tile.get(), &build_.outcome, &build_.note, &error)) {
        if (cancel_.load()) return finish(GhostTileJobState::Cancelled);
        error_ = error;
        return finish(GhostTileJobState::Failed);
    }
    build_.tile = std::move(tile);
    build_.models = std::move(models);
    finish(GhostTileJobState::Done);
}

}  // namespace ug
