#include "scene/ghost_tile_command.h"

#include <filesystem>

namespace ug {

namespace {

namespace fs = std::filesystem;

fs::path absoluteDir(const std::string& base_dir) {
    return fs::absolute(base_dir.empty() ? fs::path(".") : fs::path(base_dir)).lexically_normal();
}

// Makes the spec's relative model paths absolute (against base_dir) and says which were relative.
void absolutizeModelPaths(GhostTileSpec* spec, const std::string& base_dir, std::vector<uint8_t>* relative) {
    relative->assign(spec->models.size(), 0);
    for (size_t t = 0; t < spec->models.size(); ++t) {
        std::string& path = spec->models[t].mesh_path;
        if (path.empty() || fs::path(path).is_absolute()) continue;
        path = (absoluteDir(base_dir) / path).lexically_normal().string();
        (*relative)[t] = 1;
    }
}

// The spec as the project in base_dir writes it: the paths that were relative, relative to base_dir.
GhostTileSpec modelPathsRelativeTo(GhostTileSpec spec, const std::string& base_dir,
                                   const std::vector<uint8_t>& relative) {
    for (size_t t = 0; t < spec.models.size() && t < relative.size(); ++t) {
        if (!relative[t]) continue;
        std::string& path = spec.models[t].mesh_path;
        const fs::path rel = fs::path(path).lexically_relative(absoluteDir(base_dir));
        if (!rel.empty()) path = rel.string();
    }
    return spec;
}

}  // namespace

SetGhostTileCommand::SetGhostTileCommand(GhostTileBuild build)
    : new_spec_(std::move(build.spec)),
      new_assets_{std::move(build.tile), std::move(build.models), build.outcome, std::move(build.model_files)} {
    absolutizeModelPaths(&new_spec_, build.base_dir, &new_relative_);
}

bool SetGhostTileCommand::apply(EditTarget t, EditEffect* effect, std::string* error) {
    if (!t.assets) {
        *error = "ghost tile: the document has no tile to replace";
        return false;
    }
    const size_t n = t.project->detail_types.size();
    if (!new_assets_.tile || !new_assets_.models || new_assets_.models->size() != n ||
        new_assets_.tile->candidates.typeCount() != n || new_spec_.types.size() != n) {
        *error = "ghost tile: the new tile was built for other detail types than the project's " + std::to_string(n);
        return false;
    }
    for (size_t k = 0; k < n; ++k)
        if (new_spec_.types[k].name != t.project->detail_types[k].model.name) {
            *error = "ghost tile: the new tile's type " + std::to_string(k) + " is '" + new_spec_.types[k].name +
                     "', the project's '" + t.project->detail_types[k].model.name + "'";
            return false;
        }
    old_spec_ = ghostTileSpec(*t.project);
    absolutizeModelPaths(&old_spec_, t.project->base_dir, &old_relative_);
    old_assets_ = *t.assets;
    setGhostTileSpec(modelPathsRelativeTo(new_spec_, t.project->base_dir, new_relative_), t.project);
    *t.assets = new_assets_;
    effect->full = true;
    effect->tile = true;
    return true;
}

void SetGhostTileCommand::revert(EditTarget t, EditEffect* effect) {
    setGhostTileSpec(modelPathsRelativeTo(old_spec_, t.project->base_dir, old_relative_), t.project);
    *t.assets = old_assets_;
    effect->full = true;
    effect->tile = true;
}

}  // namespace ug
