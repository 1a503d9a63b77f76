#include "scene/ghost_tile_command.h"

namespace ug {

SetGhostTileCommand::SetGhostTileCommand(GhostTileBuild build)
    : new_spec_(std::move(build.spec)),
      new_assets_{std::move(build.tile), std::move(build.models), build.outcome} {}

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
    old_assets_ = *t.assets;
    setGhostTileSpec(new_spec_, t.project);
    *t.assets = new_assets_;
    effect->full = true;
    effect->tile = true;
    return true;
}

void SetGhostTileCommand::revert(EditTarget t, EditEffect* effect) {
    setGhostTileSpec(old_spec_, t.project);
    *t.assets = old_assets_;
    effect->full = true;
    effect->tile = true;
}

}  // namespace ug
