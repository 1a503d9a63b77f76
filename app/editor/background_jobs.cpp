#include "editor/background_jobs.h"

#include <cstdio>

namespace ug::editor {

using nlohmann::json;

json finishGhostTileJob(std::unique_ptr<GhostTileJob> job, Document* doc, GhostTilePanelState* panel,
                        std::vector<std::string>* messages) {
    json outcome = {{"job_seconds", 0.0}};
    std::string apply_error;
    if (!doc) {
        panel->last_outcome = "the document changed: build dropped";
    } else if (job->state() == GhostTileJobState::Done) {
        GhostTileBuild build = job->take();
        const double seconds = build.seconds;
        const CacheOutcome cache = build.outcome;
        if (doc->applyGhostTile(std::move(build), &apply_error)) {
            char text[160];
            std::snprintf(text, sizeof(text), "applied: %s in %.2f s", cacheOutcomeName(cache), seconds);
            panel->last_outcome = text;
            const GhostTileStats& st = doc->ghostTile().stats;
            outcome = {{"ok", true},
                       {"job_seconds", seconds},
                       {"cache", cacheOutcomeName(cache)},
                       {"candidates", st.candidate_count},
                       {"pairs", st.pair_count},
                       {"rho", st.rho},
                       {"build_seconds", st.build_seconds},
                       {"graph_bytes", st.graph_bytes},
                       {"bytes_per_pair", st.bytes_per_pair}};
        } else {
            messages->push_back("Ghost Tile: " + apply_error);
            panel->last_outcome = "failed: " + apply_error;
            outcome = {{"ok", false}, {"error", apply_error}};
        }
    } else if (job->state() == GhostTileJobState::Failed) {
        messages->push_back("Ghost Tile build failed: " + job->error());
        panel->last_outcome = "failed: " + job->error();
        outcome = {{"ok", false}, {"error", job->error()}};
    } else {
        panel->last_outcome = "cancelled";
        outcome = {{"ok", false}, {"cancelled", true}};
    }
    return outcome;
}

json finishExportJob(const ExportJob& j, std::string* result, std::string* last_message,
                     std::vector<std::string>* messages) {
    json record{{"ok", j.stage() == ExportStage::Done},
                {"path", j.settings().path},
                {"exported_instances", j.instances()},
                {"export_seconds", j.seconds()}};
    if (j.stage() == ExportStage::Done) {
        char text[64];
        std::snprintf(text, sizeof(text), " in %.2f s", j.seconds());
        *result = "wrote " + std::to_string(j.instances()) + " instances to " + j.settings().path + text;
        *last_message = *result;
    } else {
        *result = j.error();
        record["error"] = j.error();
        if (j.stage() == ExportStage::Failed) messages->push_back(j.error());
    }
    return record;
}

}  // namespace ug::editor
