// The editor's background jobs as they end, at a frame boundary (viewer.cpp): a Ghost Tile build
// (scene/ghost_tile_job.h) is applied to its document or reported, an export (export_job.h) is reported.
// Each returns the outcome a replay action records (replay.h) and updates what the panels show.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "editor/export_job.h"
#include "editor/panels.h"
#include "scene/document.h"
#include "scene/ghost_tile_job.h"

namespace ug::editor {

// A finished Ghost Tile job: when it is Done, its tile is applied to `doc` (one undo step); `doc` null: the
// document it was started on was replaced, the build is dropped. The panel's last outcome and the messages
// say what happened. Returns {"ok", "job_seconds", "cache", "candidates", "pairs", "rho", "build_seconds",
// "graph_bytes", "bytes_per_pair"} or {"ok": false, "error" | "cancelled"}.
nlohmann::json finishGhostTileJob(std::unique_ptr<GhostTileJob> job, Document* doc, GhostTilePanelState* panel,
                                  std::vector<std::string>* messages);

// A finished export: *result is the Export window's line ("wrote N instances to PATH in S s" or the
// error), *last_message the Statistics window's (on success); a failure goes to the messages. Returns
// {"ok", "path", "exported_instances", "export_seconds", "error"?}.
nlohmann::json finishExportJob(const ExportJob& job, std::string* result, std::string* last_message,
                               std::vector<std::string>* messages);

}  // namespace ug::editor
