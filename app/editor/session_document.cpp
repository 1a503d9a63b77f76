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
#include <ctime>

namespace ug::editor {

namespace {

std::string timeText(int64_t unix_s) {
    const std::time_t t = std::time_t(unix_s);
    char buffer[64] = "";
    std::strftime(buffer, sizeof(buffer), "%Y-%m-%d %H:%M:%S", std::localtime(&t));
    return buffer;
}

}  // namespace

// The current document stays open and editable until the new one is ready: a failed open (a corrupt
// scene or model) leaves it as it was, and the error goes to the messages (applyFinishedWork).
void EditorSession::startLoad(const std::string& path, bool recover) {
    loader = std::make_unique<DocumentLoader>(LoadRequest{path, doc_options, recover});
}

bool EditorSession::requestOpen(const std::string& path, RecoverChoice choice) {
    const bool has_recovery = findRecovery(options.config_dir, path, &recovery_info);
    if (choice == RecoverChoice::Yes && !has_recovery) {
        *error =
            path + ": --recover yes: no autosave newer than the file under '" + options.config_dir + "'";
        return false;
    }
    if (has_recovery && choice == RecoverChoice::Ask && !scripted) {
        asking_recovery = path;
        return true;
    }
    if (has_recovery && choice == RecoverChoice::No) discardRecovery(options.config_dir, path);
    startLoad(path, has_recovery && choice == RecoverChoice::Yes);
    return true;
}

void EditorSession::startNew() {
    loader = std::make_unique<DocumentLoader>(LoadRequest{new_template, doc_options, false, true});
}

bool EditorSession::applyFinishedWork() {
    // ---- apply finished background work at the frame boundary ----
    if (loader && loader->phase() == LoadPhase::Failed) {
        if (scripted && !scene) {  // the document the run was started on
            *error = loader->error();
            return false;
        }
        load_error = loader->error();
        messages.push_back(loader->error());
        loader.reset();
    }
    if (loader && loader->phase() == LoadPhase::Ready) adoptLoadedDocument();
    // A finished Ghost Tile job: applied (one undo step) or reported; the old tile stayed in use until now.
    if (ghost_job && ghost_job->finished()) {
        const bool for_replay = ghost_job_action >= 0 && size_t(ghost_job_action) == replay.index;
        Document* started_on = scene && ghost_job_doc == scene->doc.get() ? scene->doc.get() : nullptr;
        json outcome = finishGhostTileJob(std::move(ghost_job), started_on, &ghost_panel, &messages);
        if (for_replay) replay.record["ghost_tile"] = std::move(outcome);
    }
    ghost_panel.running = ghost_job != nullptr;
    ghost_panel.progress = ghost_job ? ghost_job->progress() : 0.0f;
    if (!takeLiveResult()) return false;
    syncStrands();
    syncEnvironment();
    if (export_job && export_job->finished()) {
        export_record = finishExportJob(*export_job, &export_result, &view.last_message, &messages);
        export_job.reset();
    }
    settled = scene && have_result && !scene->doc->live().pending() &&
              shown_generation == scene->doc->live().generation() && sideJobsSettled();
    return true;
}

void EditorSession::adoptLoadedDocument() {
    // Only now does the previous document go (startLoad kept it open while this one loaded).
    stroke.end();
    endViewDrags();
    renderer->clearScene();
    if (scene) scene->doc->close();
    store.reset();
    drops.reset();
    instances = ResidentTiles{};
    primitive_markers_key = PrimitiveMarkersKey{};  // a new document may come at the old one's address
    have_result = false;
    shown_generation = 0;
    inst_view = InstantiationView{};
    load_error.clear();
    scene = std::make_unique<EditorScene>(std::move(loader->scene()));
    result->recovered = loader->request().recover;
    loader.reset();
    Document& d = *scene->doc;
    renderer->setScene(d.compiled().extent, scene->has_terrain ? &scene->terrain : nullptr, &scene->meshes,
                       d.ghostTile().candidates, d.ghostTile().settings.tile_size_m, &scene->terrain_material);
    startStrands();
    startEnvironment();
    showStaticMeshes();  // environmental objects, snow, icicles, strands
    // Every document opens framed, as on startup (a camera left where the last scene was would show
    // nothing of this one); the first result frames it again by the cells that fill.
    camera_moved = false;
    frameBounds(framingBounds(*scene, nullptr), &camera);
    view.scene = d.path();
    view.type_names.clear();
    for (const DetailLodMesh& m : scene->meshes) view.type_names.push_back(m.name);
    view.instances_per_type.assign(scene->meshes.size(), 0);
    type_visible.assign(scene->meshes.size(), 1);
    if (d.path().empty()) view.scene = "untitled";
    export_settings.chunk_size_m = d.project().chunk_size_m;
    tools.brush = defaultBrush(d);
    tools.selected = 0;
    reach_m = largestReach(d);
    recent_files = loadRecentFiles(options.config_dir);
    scene_tile_generation = d.tileGeneration();
}

// Undo, redo, save, save as, delete, duplicate (from the menus and shortcuts).
void EditorSession::handleEditRequests() {
    if (doc) {
        std::string op_error;
        if (requests.undo || requests.redo) {
            stroke.end();
            endViewDrags();
        }
        if (requests.undo) doc->undo();
        if (requests.redo) doc->redo();
        if (requests.save && doc->path().empty()) {
            requests.open_save_as = true;  // an untitled document saves with Save As
        } else if (requests.save && !doc->save(&op_error)) {
            messages.push_back("Save failed: " + op_error);
        }
        if (requests.open_save_as) {
            save_as_open = true;
            save_as_path = doc->path();
        }
        // The selected primitive's whole brush stroke goes (or is copied), as one undo step.
        if (requests.delete_selected && tools.selected != 0) {
            move_drag.end();
            const std::vector<uint64_t> members = doc->strokeMembers(tools.selected);
            if (doc->removePrimitives(members, members.size() > 1 ? "Delete stroke" : "Delete primitive", &op_error))
                tools.selected = 0;
            else
                messages.push_back(op_error);
        }
        if (requests.duplicate_selected && tools.selected != 0) {
            const std::vector<uint64_t> members = doc->strokeMembers(tools.selected);
            const std::vector<uint64_t> copies = duplicateStroke(doc, tools.selected, &op_error);
            const auto at = std::find(members.begin(), members.end(), tools.selected);
            if (copies.size() == members.size() && at != members.end())
                tools.selected = copies[size_t(at - members.begin())];
            else
                messages.push_back(op_error);
        }
        if (!requests.env_drop.into.empty()) {
            // The Outliner's tree: the node moves into the group, staying where it is in the world.
            EnvironmentDesc env = doc->project().environment;
            EnvPath moved;
            if (moveEnvNodeInto(&env, requests.env_drop.node, requests.env_drop.into, &moved, &op_error) &&
                doc->setEnvironment(env, "Move into group", &op_error))
                environment_panel.selected = moved;
            else
                messages.push_back(op_error);
        }
        if (drawSaveAsDialog(&save_as_open, &save_as_path) == DialogAnswer::Yes) {
            if (!doc->saveAs(save_as_path, &op_error))
                messages.push_back("Save As failed: " + op_error);
            else
                recent_files = loadRecentFiles(options.config_dir);
        }
    }
}

// New, Open, Export, Quit, Screenshot.
void EditorSession::handleFileRequests() {
    if (requests.open_dialog) {
        open_dialog_open = true;
        if (open_dialog_path.empty() && doc) open_dialog_path = doc->path();
    }
    if (drawOpenDialog(&open_dialog_open, &open_dialog_path) == DialogAnswer::Yes)
        requests.open_path = open_dialog_path;
    if (requests.show_export) windows.export_panel = true;
    if (requests.start_export && doc && store && settled && !export_job) {
        const CandidateSet& c = doc->ghostTile().candidates;
        const json stats{{"generator", "undergrowth edit"},
                         {"scene", doc->path()},
                         {"seed", doc->project().instantiation_seed},
                         {"instances", store->instanceCount()},
                         {"instances_per_type", perTypeJson(view.type_names, perTypeCounts(*store, c))}};
        export_job = std::make_unique<ExportJob>(*doc, store, drops, export_settings, stats.dump(),
                                                 scene ? scene->static_meshes : std::vector<MeshInstances>{});
        export_result.clear();
    }
    if (requests.cancel_export && export_job) export_job->cancel();
    // The current document is closed only once the new one is ready (startLoad), so nothing is lost
    // when the new one fails to load.
    if (!requests.open_path.empty() || requests.new_document) {
        if (doc && doc->isDirty() && !scripted) {
            prompt = requests.new_document ? Prompt::New : Prompt::Open;
            prompt_open_path = requests.open_path;
        } else if (requests.new_document) {
            startNew();
        } else {
            stroke.end();
            endViewDrags();
            requestOpen(requests.open_path, RecoverChoice::Ask);
        }
    }
    if (requests.quit) window.requestClose();
    if (requests.screenshot) {
        screenshot_request_path = options.screenshot_path;
        screenshot_overlays = true;
    }
    screenshot_requested = requests.screenshot;
    requests = UiRequests{};
}

// The unsaved-changes and recovery dialogs, the messages; then the title and the Statistics panel's path.
void EditorSession::handleDialogs() {
    // Closing the window with unsaved work asks first (scripted runs never ask).
    if (window.shouldClose() && !quitting) {
        if (doc && doc->isDirty() && !scripted) {
            window.cancelClose();
            prompt = Prompt::Quit;
        } else {
            quitting = true;
        }
    }
    if (prompt != Prompt::None) {
        const DialogAnswer a =
            drawUnsavedDialog(doc && !doc->path().empty() ? doc->path() : "the document",
                              prompt == Prompt::Quit  ? "quit"
                              : prompt == Prompt::New ? "start a new document"
                                                      : "open another file");
        bool proceed = false;
        if (a == DialogAnswer::Yes && doc && doc->path().empty()) {
            save_as_open = true;  // an untitled document: Save As first, then ask again
            save_as_path.clear();
            prompt = Prompt::None;
        } else if (a == DialogAnswer::Yes) {
            std::string save_error;
            if (doc && !doc->save(&save_error))
                messages.push_back("Save failed: " + save_error);
            else
                proceed = true;
        } else if (a == DialogAnswer::No) {
            proceed = true;
        }
        if (a != DialogAnswer::Pending) {
            if (proceed) {
                stroke.end();
                endViewDrags();
                if (prompt == Prompt::Quit) {
                    if (doc) doc->close();  // removes the autosave: the user chose
                    quitting = true;
                } else if (prompt == Prompt::New) {
                    startNew();  // the document is closed once the new one is ready
                } else {
                    requestOpen(prompt_open_path, RecoverChoice::Ask);
                }
            }
            prompt = Prompt::None;
        }
    }
    if (!asking_recovery.empty()) {
        const DialogAnswer a = drawRecoveryDialog(asking_recovery, timeText(recovery_info.saved_unix_s));
        if (a == DialogAnswer::Yes || a == DialogAnswer::No) {
            const std::string path = asking_recovery;
            asking_recovery.clear();
            requestOpen(path, a == DialogAnswer::Yes ? RecoverChoice::Yes : RecoverChoice::No);
            doc = nullptr;
        }
    }
    drawMessages(&messages);
    if (doc != (scene ? scene->doc.get() : nullptr)) doc = nullptr;  // replaced this frame
    // The title and the Statistics panel follow the document's path and unsaved state every frame, so
    // an open, an edit, an undo back to the saved state, Save and Save As all show at once.
    if (scene) view.scene = scene->doc->path().empty() ? "untitled" : scene->doc->path();
    window.setTitle(windowTitle(scene ? scene->doc->path() : "", scene && scene->doc->isDirty(), scene != nullptr));
}

void EditorSession::autosave() {
    if (!scene) return;
    std::string autosave_error;
    if (scene->doc->maybeAutosave(now_s, &autosave_error)) {
        ++result->autosaves;
        last_autosave_error.clear();
    } else if (!autosave_error.empty() && autosave_error != last_autosave_error) {
        messages.push_back("Autosave failed: " + autosave_error);
        last_autosave_error = autosave_error;
    }
}

}  // namespace ug::editor
