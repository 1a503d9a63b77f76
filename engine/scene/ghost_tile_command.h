// Applying a new Ghost Tile to the document as one undo step (issue 4, "Ghost Tile panel").
//
// The tile and its models are immutable and shared: the command keeps the old and the new ones, so undo
// and redo swap pointers and never rebuild, and undo gives back exactly the previous instance set (the
// instantiator is deterministic in its inputs, and every input is restored: the project's tile settings,
// the model sources, the tile, the models).
#pragma once

#include <memory>
#include <cstdint>
#include <string>
#include <vector>

#include "ghosttile/ghost_tile.h"
#include "ghosttile/ghost_tile_cache.h"
#include "mesh/detail_model.h"
#include "scene/edit_commands.h"
#include "scene/ghost_tile_job.h"

namespace ug {

// The document's Ghost Tile and the models it was built from (one per detail type, project order), with
// how the tile was obtained (for the panel's statistics).
struct TileAssets {
    std::shared_ptr<const GhostTile> tile;
    std::shared_ptr<const std::vector<DetailModel>> models;
    CacheOutcome outcome = CacheOutcome::BuiltMissing;
    std::vector<ModelFileStamp> model_files;  // per type: the model files as they were loaded
};

// Swaps the project's Ghost Tile spec (ghost_tile_job.h) and the target's assets for `build`'s. Refused
// (nothing changes) when the build's types are not the project's. Effect: full and tile.
class SetGhostTileCommand : public Command {
public:
    explicit SetGhostTileCommand(GhostTileBuild build);
    std::string name() const override { return "Ghost Tile"; }
    bool apply(EditTarget target, EditEffect* effect, std::string* error) override;
    void revert(EditTarget target, EditEffect* effect) override;

private:
    // Model paths are kept absolute here and written back relative to the project's folder of the moment
    // (those that were relative; absolute ones stay absolute): a Save As to another folder between an apply
    // and its undo must not leave paths meant for the old folder.
    GhostTileSpec new_spec_, old_spec_;
    std::vector<uint8_t> new_relative_, old_relative_;  // per type: the path was relative
    TileAssets new_assets_, old_assets_;
};

}  // namespace ug
