// The flat main loop of STYLE.md: poll -> apply finished background work (an opened document, a live
// instancing result) -> new UI frame -> navigation, tools, panels, dialogs -> replay step -> render ->
// (screenshot) -> UI on top -> swap -> stamp timings, replay bookkeeping, autosave.
//
// Live results reach the GPU per tile: the renderer's instance buffers are resident (render_data.h
// ResidentTiles: every tile owns a slot per detail type), so a result re-packs from the store only the
// tiles it changed (LiveResult::changed_tiles) and uploads only their slots; a full result (first open,
// LiveResult::full) rebuilds them all. The next frame rebuilds the indirect commands (cull + LOD per tile).
//
// Statistics of a replay, per action (ViewerResult::actions): "action", "frame" (when it started), "uploads"
// ({"tiles", "bytes"} per live result taken while the action ran), "uploaded_tiles" (every tile re-uploaded
// then, [x, y, z]), "tiles_resident", "stamps", "instances_before"/"_after", "per_type_before"/"_after",
// "instance_store_hash_before"/"_after"; for strokes "stamp_points"; for strokes and moves "box" {min, max}
// (the changed primitives' supports grown by twice the largest object reach, so collisions at the rim count
// as inside), "inside_before"/"_after" and "outside_before"/"_after" per
// type (instance origins, instance_query.h), "stamp_to_frame_ms" (per stamp, wall clock from the edit to
// the end of the first frame that shows its result). "before" is the settled state the action started
// from, "after" the settled state once the live instancer is idle and its result is on screen.
// Panels' actions add: export "ok", "error", "exported_instances", "export_seconds"; open and new "ok",
// "error", "document" (their "before" is the replaced document's); set_visible "drawn_instances_before"/
// "_after" (the renderer's instances drawn in the frame before and the frame after); move "id",
// "from_center", "to_center", "moves"; ghost_tile "ghost_tile" (replay.h); sculpt strokes "pile" (pileRecord:
// the pile's centroid, height, radius and volume around the first stamp's ground point, the cones it left)
// and "user_primitives_before"/"_after" (the sculpt type's). Mouse sculpt strokes are kept in
// ViewerResult::sculpt_strokes ("sculpt_strokes"), so a session driven by real input is judged the same way.
#include "editor/viewer.h"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <set>
#include <thread>

#include "core/atomic_file.h"
#include "core/hash.h"
#include "editor/document_loader.h"
#include "editor/background_jobs.h"
#include "editor/export_job.h"
#include "editor/gl/renderer.h"
#include "editor/gl/window.h"
#include "editor/markers.h"
#include "editor/navigation.h"
#include "editor/orbit_camera.h"
#include "editor/panels.h"
#include "editor/render_data.h"
#include "editor/session_stats.h"
#include "editor/tools.h"
#include "editor/window_title.h"
#include "instancer/instance_query.h"
#include "instancer/tile_coord.h"

namespace ug::editor {

namespace {

using Clock = std::chrono::steady_clock;

// How long a frame that made a stamp may wait for its incremental update before rendering.
constexpr double kStampWaitBudgetMs = 15.0;
// The share of the Statistics window's bar that opening a document's files takes (DocumentLoader::progress);
// its first instantiation takes the rest.
constexpr float kOpenShare = 0.25f;
using nlohmann::json;

// What "frame all" frames: the cells that hold instances once they are in (a scene's extent is often a
// conservative bound much larger than what fills), else the terrain's surface when there is one, else
// the extent.
Bounds framingBounds(const EditorScene& s, const ResidentTiles* instances) {
    if (instances && !instances->tile_coord.empty()) {
        const float size = instances->tile_size_m;
        Bounds b{glm::vec3(1e30f), glm::vec3(-1e30f)};
        for (const glm::ivec3& t : instances->tile_coord) {
            b.lo = glm::min(b.lo, glm::vec3(t) * size);
            b.hi = glm::max(b.hi, glm::vec3(t + 1) * size);
        }
        return b;
    }
    if (!s.has_terrain) return s.doc->compiled().extent;
    const Bounds3 b = meshBounds(s.terrain);
    return Bounds{b.min, b.max};
}

std::string timeText(int64_t unix_s) {
    const std::time_t t = std::time_t(unix_s);
    char buffer[64] = "";
    std::strftime(buffer, sizeof(buffer), "%Y-%m-%d %H:%M:%S", std::localtime(&t));
    return buffer;
}

// A stamp waiting for the frame that shows it.
struct PendingStamp {
    uint64_t generation = 0;
    Clock::time_point time;
    int action = -1;  // replay action index, -1 for the mouse
};

// The replay's progress (replay.h).
struct ReplayState {
    size_t index = 0;
    bool started = false;
    bool finishing = false;  // the action's edits are all made; waiting for the settled result
    std::vector<glm::vec2> path;
    size_t step = 0;
    json record;
    json uploads = json::array();           // per live result while the action ran
    std::set<uint64_t> uploaded_tiles;      // packed keys
    std::shared_ptr<const InstanceStore> before;
    std::vector<double> stamp_ms;
    Bounds moved_from;  // move: the primitive's support before
};

}  // namespace

double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t i = std::min(v.size() - 1, size_t(q * double(v.size() - 1) + 0.5));
    return v[i];
}

ViewerStatus runViewer(const ViewerOptions& options, ViewerResult* result, std::string* error) {
    const bool scripted = options.frames > 0;
    gl::Window window;
    gl::WindowOptions window_options;
    window_options.width = options.width;
    window_options.height = options.height;
    window_options.vsync = !scripted;
    switch (window.open(window_options, error)) {
        case gl::OpenStatus::Ok:
            break;
        case gl::OpenStatus::NoDisplay:
            return ViewerStatus::NoDisplay;
        case gl::OpenStatus::Failed:
            return ViewerStatus::Failed;
    }
    gl::Renderer renderer;
    if (!renderer.init(gl::shadersDir(), error)) return ViewerStatus::Failed;

    *result = ViewerResult{};
    result->scene = options.scene_path;
    result->gl_version = window.glVersion();
    result->renderer = window.rendererName();
    result->window_width = options.width;
    result->window_height = options.height;

    DocumentOptions doc_options;
    doc_options.cache_dir = options.cache_dir;
    doc_options.config_dir = options.config_dir;
    doc_options.threads = options.threads;
    doc_options.autosave_interval_s = options.autosave_interval_s;

    // ---- the document: opened (or recovered) in the background ----
    std::unique_ptr<DocumentLoader> loader;
    std::unique_ptr<EditorScene> scene;
    ResidentTiles instances;  // the tiles as the GPU holds them
    TileUploads uploads;      // what the latest live result changed in them
    std::shared_ptr<const InstanceStore> store;  // the result on screen
    uint64_t shown_generation = 0;
    bool have_result = false;
    std::string asking_recovery;  // a path whose recovery dialog is open
    RecoveryInfo recovery_info;
    // The current document stays open and editable until the new one is ready: a failed open (a corrupt
    // scene or model) leaves it as it was, and the error goes to the messages (see "apply finished work").
    auto startLoad = [&](const std::string& path, bool recover) {
        loader = std::make_unique<DocumentLoader>(LoadRequest{path, doc_options, recover});
    };
    // Opens `path`, asking first (interactive) when an autosave of it is newer than the file.
    auto requestOpen = [&](const std::string& path, RecoverChoice choice) -> bool {
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
    };
    if (!requestOpen(options.scene_path, options.recover)) return ViewerStatus::Failed;

    OrbitCamera camera;
    camera.aspect = float(options.width) / float(options.height);
    bool camera_moved = false;
    UiRequests requests;
    WindowToggles windows;
    ToolState tools;
    BrushStroke stroke;
    MoveDrag move_drag;
    MarkerGeometry markers;
    // The user primitives' skeletons and hulls change only with an edit, the selection or the hull toggle,
    // so they are kept between frames: a stroke leaves dozens of hulls of hundreds of triangles each.
    struct PrimitiveMarkersKey {
        const Document* doc = nullptr;
        uint64_t edits = 0;  // the live instancer's generation: every edit, undo and redo moves it
        uint64_t tile = 0;   // type colours come from the meshes, rebuilt with the tile
        uint64_t selected = 0;
        bool hulls = false;
        bool operator==(const PrimitiveMarkersKey&) const = default;
    };
    MarkerGeometry primitive_markers;
    PrimitiveMarkersKey primitive_markers_key;
    RenderSettings render_settings;
    render_settings.lod = options.lod;
    StatisticsView view;
    view.scene = options.scene_path;
    view.gl_version = window.glVersion();
    view.renderer = window.rendererName();
    std::vector<std::string> recent_files = loadRecentFiles(options.config_dir);
    std::vector<std::string>& messages = result->messages;
    std::string last_autosave_error;
    bool save_as_open = false;
    std::string save_as_path;
    enum class Prompt { None, Quit, Open, New } prompt = Prompt::None;
    std::string prompt_open_path;
    bool quitting = false;
    // ---- outliner, instantiation and export panels, New / Open ----
    std::vector<uint8_t> type_visible;  // view state, not a document edit: never undone, never saved
    InstantiationView inst_view;
    ExportSettings export_settings;
    std::unique_ptr<ExportJob> export_job;
    std::string export_result;
    json export_record;  // the finished export's outcome, for the replay
    bool open_dialog_open = false;
    std::string open_dialog_path;
    std::string load_error;  // the last failed open or new (for the replay's record)
    // File > New: the template's terrain, extent and types, no density.
    const std::string new_template = std::string(UG_SOURCE_DIR) + "/assets/scenes/default.json";
    auto startNew = [&] {
        loader = std::make_unique<DocumentLoader>(LoadRequest{new_template, doc_options, false, true});
    };

    std::vector<double> frame_ms;
    std::vector<uint8_t> pixels;
    int screenshot_count = 0;
    std::string screenshot_request_path;
    std::string ui_screenshot_path;  // replay "screenshot" with "ui": true: read after the panels are drawn
    bool screenshot_overlays = true;
    std::vector<PendingStamp> pending_stamps;
    ReplayState replay;
    float reach_m = 0.0f;
    int frame_index = 0;        // frames since the first result was on screen
    int frames_after_done = 0;  // scripted: frames since the script finished and the result settled
    bool stats_written = false;
    const auto start_time = Clock::now();
    auto last_frame_end = start_time;

    // ---- what the viewport shows, for the statistics (ViewerResult::viewport) ----
    int last_fb_w = options.width, last_fb_h = options.height;
    glm::vec2 cursor_px(NAN);  // framebuffer pixels; NaN until the pointer is in the window
    struct BrushProbe {
        bool drawn = false;
        bool on_pile = false;
        glm::vec3 center{0.0f};
        glm::vec2 ring_center_px{0.0f};  // the ring's centre (its vertices' mean) on screen
    } brush_probe;
    // The ground's height under a world XY on the current document (the camera stays above it).
    auto groundZ = [&](glm::vec2 xy) { return scene ? groundHeightAt(*scene->doc, xy) : -1.0e30f; };
    auto viewportJson = [&] {
        json v;
        const glm::vec3 eye = camera.eye();
        v["camera"] = {{"target", vec3Json(camera.target)},
                       {"eye", vec3Json(eye)},
                       {"distance", camera.distance_m},
                       {"yaw_deg", glm::degrees(camera.yaw_rad)},
                       {"pitch_deg", glm::degrees(camera.pitch_rad)}};
        if (scene) v["eye_ground_z"] = groundZ(glm::vec2(eye));
        v["framebuffer"] = {last_fb_w, last_fb_h};
        if (std::isfinite(cursor_px.x)) {
            v["cursor_px"] = {cursor_px.x, cursor_px.y};
            if (scene) {
                const Ray ray = rayThroughPixel(camera.viewProjection(), float(last_fb_w), float(last_fb_h), cursor_px);
                const SurfaceHit g = pickGround(*scene->doc, ray);
                if (g.hit) v["ground_under_cursor"] = vec3Json(g.point_m);
            }
        }
        v["brush"] = {{"drawn", brush_probe.drawn}};
        if (brush_probe.drawn) {
            v["brush"]["center"] = vec3Json(brush_probe.center);
            v["brush"]["on_pile"] = brush_probe.on_pile;
            v["brush"]["ring_center_px"] = {brush_probe.ring_center_px.x, brush_probe.ring_center_px.y};
        }
        v["tool"] = toolName(tools.tool);
        v["brush_radius"] = tools.brush.radius_m;
        v["statistics_scene"] = view.scene;
        v["statistics_status"] = view.status;
        v["statistics_progress"] = view.progress;
        v["imgui_wants_keyboard"] = ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard;
        return v;
    };

    auto fillDocumentResult = [&] {
        result->viewport = viewportJson();
        result->window_title = window.title();
        if (!scene) return;
        Document& doc = *scene->doc;
        result->document_path = doc.path();
        result->dirty = doc.isDirty();
        result->user_primitives = 0;
        for (size_t t = 0; t < doc.project().detail_types.size(); ++t)
            result->user_primitives += doc.primitiveIds(t).size();
        result->type_names.clear();
        for (const DetailLodMesh& m : scene->meshes) result->type_names.push_back(m.name);
        if (store) {
            result->instances = store->instanceCount();
            result->instances_per_type = perTypeCounts(*store, doc.ghostTile().candidates);
            result->instance_store_hash = instanceStoreHash(*store);
        }
    };
    auto writeInteractiveStats = [&] {
        if (options.stats_path.empty()) return;
        fillDocumentResult();
        std::string write_error;
        if (!writeTextFileAtomically(options.stats_path, viewerStatsJson(*result, options.lod).dump(2) + "\n",
                                     &write_error))
            messages.push_back(write_error);
    };

    // ---- Ghost Tile panel: one background build at a time (ghost_tile_job.h), applied at the frame boundary;
    // the renderer's scene (LOD meshes, candidate frames) follows the document's tile generation ----
    GhostTilePanelState ghost_panel;
    std::unique_ptr<GhostTileJob> ghost_job;
    const Document* ghost_job_doc = nullptr;  // the document it was started on
    int ghost_job_action = -1;                // the replay action that started it, -1: the panel
    uint64_t scene_tile_generation = 0;       // the tile generation the renderer's scene was set for
    auto syncTile = [&] {
        if (!scene || scene->doc->tileGeneration() == scene_tile_generation) return;
        Document& doc = *scene->doc;
        scene_tile_generation = doc.tileGeneration();
        const CandidateSet& c = doc.ghostTile().candidates;
        scene->meshes = buildTypeMeshes(doc.models(), c);
        renderer.setScene(doc.compiled().extent, scene->has_terrain ? &scene->terrain : nullptr, &scene->meshes, c,
                          doc.ghostTile().settings.tile_size_m);
        // What is on screen indexes the old tile's candidates: nothing is shown until the new result.
        instances = ResidentTiles{};
        store = std::make_shared<const InstanceStore>();
        reach_m = largestReach(doc);
    };

    // Takes a finished live result, if any, and re-packs it for the GPU (see the top of this file).
    auto takeLiveResult = [&]() -> bool {
        if (!scene) return true;
        Document& doc = *scene->doc;
        syncTile();
        LiveResult live;
        if (doc.live().poll(&live) && live.generation >= doc.tileLiveGeneration()) {
            if (!live.ok) messages.push_back(live.error);
            const auto t0 = Clock::now();
            std::string pack_error;
            const CandidateSet& candidates = doc.ghostTile().candidates;
            const SettleSettings& settle = doc.project().settling.settle;
            const bool packed =
                (live.full || !have_result)
                    ? rebuildResidentTiles(*live.store, live.drops.get(), candidates,
                                           doc.ghostTile().settings.tile_size_m,
                                           packedDropUnit(settle.enabled, settle.max_drop_m), &instances, &uploads,
                                           &pack_error)
                    : updateResidentTiles(*live.store, live.drops.get(), candidates, live.changed_tiles, &instances,
                                          &uploads, &pack_error);
            if (!packed) {
                if (scripted) {
                    *error = pack_error;
                    return false;
                }
                messages.push_back(pack_error);
            } else {
                renderer.uploadTiles(&instances, uploads);
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
                if (!have_result && !camera_moved) frameBounds(framingBounds(*scene, &instances), &camera);
                have_result = true;
            }
        }
        return true;
    };

    while (true) {
        const auto frame_start = Clock::now();
        window.pollEvents();
        int fb_w = 0, fb_h = 0;
        window.framebufferSize(&fb_w, &fb_h);
        if (fb_w <= 0 || fb_h <= 0) continue;  // minimised
        camera.aspect = float(fb_w) / float(fb_h);
        const double now_s = std::chrono::duration<double>(frame_start - start_time).count();

        // ---- apply finished background work at the frame boundary ----
        if (loader && loader->phase() == LoadPhase::Failed) {
            if (scripted && !scene) {  // the document the run was started on
                *error = loader->error();
                return ViewerStatus::Failed;
            }
            load_error = loader->error();
            messages.push_back(loader->error());
            loader.reset();
        }
        if (loader && loader->phase() == LoadPhase::Ready) {
            // Only now does the previous document go (startLoad kept it open while this one loaded).
            stroke.end();
            move_drag.end();
            renderer.clearScene();
            if (scene) scene->doc->close();
            store.reset();
            instances = ResidentTiles{};
            primitive_markers_key = PrimitiveMarkersKey{};  // a new document may come at the old one's address
            have_result = false;
            shown_generation = 0;
            inst_view = InstantiationView{};
            load_error.clear();
            scene = std::make_unique<EditorScene>(std::move(loader->scene()));
            result->recovered = loader->request().recover;
            loader.reset();
            Document& doc = *scene->doc;
            renderer.setScene(doc.compiled().extent, scene->has_terrain ? &scene->terrain : nullptr,
                              &scene->meshes, doc.ghostTile().candidates,
                              doc.ghostTile().settings.tile_size_m);
            // Every document opens framed, as on startup (a camera left where the last scene was would show
            // nothing of this one); the first result frames it again by the cells that fill.
            camera_moved = false;
            frameBounds(framingBounds(*scene, nullptr), &camera);
            view.scene = doc.path();
            view.type_names.clear();
            for (const DetailLodMesh& m : scene->meshes) view.type_names.push_back(m.name);
            view.instances_per_type.assign(scene->meshes.size(), 0);
            type_visible.assign(scene->meshes.size(), 1);
            if (doc.path().empty()) view.scene = "untitled";
            export_settings.chunk_size_m = doc.project().chunk_size_m;
            tools.brush = defaultBrush(doc);
            tools.selected = 0;
            reach_m = largestReach(doc);
            recent_files = loadRecentFiles(options.config_dir);
            scene_tile_generation = doc.tileGeneration();
        }
        // A finished Ghost Tile job: applied (one undo step) or reported; the old tile stayed in use until now.
        if (ghost_job && ghost_job->finished()) {
            const bool for_replay = ghost_job_action >= 0 && size_t(ghost_job_action) == replay.index;
            Document* started_on = scene && ghost_job_doc == scene->doc.get() ? scene->doc.get() : nullptr;
            json outcome = finishGhostTileJob(std::move(ghost_job), started_on, &ghost_panel, &messages);
            if (for_replay) replay.record["ghost_tile"] = std::move(outcome);
        }
        ghost_panel.running = ghost_job != nullptr;
        ghost_panel.progress = ghost_job ? ghost_job->progress() : 0.0f;
        if (!takeLiveResult()) return ViewerStatus::Failed;
        if (export_job && export_job->finished()) {
            export_record = finishExportJob(*export_job, &export_result, &view.last_message, &messages);
            export_job.reset();
        }
        const bool settled = scene && have_result && !scene->doc->live().pending() &&
                             shown_generation == scene->doc->live().generation();
        // Long background jobs show in the Statistics window too, whichever panel started them.
        view.pending = loader != nullptr || ghost_job != nullptr || export_job != nullptr ||
                       (scene && (!settled || !have_result));
        // Opening a document: the loader's stages are the first quarter of the bar, its first full
        // instantiation (seconds on a big field) the rest; later, a full run's own progress (a seed or a
        // strategy change; an incremental update is short and shows as done).
        const bool first_result = scene && !have_result;
        const float open_progress =
            loader ? kOpenShare * loader->progress()
                   : kOpenShare + (1.0f - kOpenShare) * (scene ? scene->doc->live().fullRunProgress() : 0.0f);
        view.progress = ghost_job    ? ghost_job->progress()
                        : export_job ? export_job->progress()
                        : settled    ? 1.0f
                        : loader || first_result ? open_progress
                        : scene                  ? scene->doc->live().fullRunProgress()
                                                 : 0.0f;
        view.status = loader         ? "loading scene\xE2\x80\xA6"
                      : !scene       ? "no document"
                      : first_result ? "instantiating\xE2\x80\xA6"
                      : ghost_job    ? "building the Ghost Tile\xE2\x80\xA6"
                      : export_job   ? "exporting glTF\xE2\x80\xA6"
                      : view.pending ? "pending\xE2\x80\xA6"
                                     : "ready";

        // ---- UI: navigation, tools, panels, dialogs ----
        const size_t stamps_before_frame = pending_stamps.size();
        window.beginUiFrame();
        // While another document loads, the current one is shown but not edited: it is replaced (and its
        // edits dropped) when the new one is ready, and is editable again if that load fails.
        Document* doc = scene && !loader ? scene->doc.get() : nullptr;
        const ImGuiIO& io = ImGui::GetIO();
        last_fb_w = fb_w;
        last_fb_h = fb_h;
        cursor_px = ImGui::IsMousePosValid() ? glm::vec2(io.MousePos.x * io.DisplayFramebufferScale.x,
                                                         io.MousePos.y * io.DisplayFramebufferScale.y)
                                             : glm::vec2(NAN);
        // The mouse moving or clicking in the viewport takes the keyboard back from a panel's field.
        if (!scripted) giveKeyboardBackToViewport();
        if (scene && !scripted) {
            Bounds selection;
            Primitive selected_prim;
            if (tools.selected != 0 && doc && doc->findPrimitive(tools.selected, nullptr, &selected_prim))
                selection = editBounds(selected_prim);
            // Terrain kinds reach everywhere in XY: nothing sensible to frame.
            for (int a = 0; a < 3; ++a)
                if (!std::isfinite(selection.lo[a]) || !std::isfinite(selection.hi[a])) selection = Bounds{};
            // The wheel zooms toward the ground under the cursor.
            glm::vec3 pivot(0.0f);
            bool has_pivot = false;
            if (io.MouseWheel != 0.0f && std::isfinite(cursor_px.x)) {
                const SurfaceHit g = pickGround(
                    *scene->doc, rayThroughPixel(camera.viewProjection(), float(fb_w), float(fb_h), cursor_px));
                has_pivot = g.hit;
                pivot = g.point_m;
            }
            camera_moved |= navigate(&camera, framingBounds(*scene, have_result ? &instances : nullptr),
                                     float(fb_h), &selection, has_pivot ? &pivot : nullptr);
            keepEyeAboveGround(&camera, groundZ);
        }
        // After navigation: the brush ring and picking use this frame's camera, not the last one's.
        const glm::mat4 view_proj = camera.viewProjection();
        MenuView menu;
        menu.has_document = doc != nullptr;
        menu.dirty = doc && doc->isDirty();
        menu.undo_name = doc && doc->canUndo() ? doc->undoName() : "";
        menu.redo_name = doc && doc->canRedo() ? doc->redoName() : "";
        menu.recent_files = recent_files;
        drawMainMenu(menu, &requests, &tools, &windows);
        drawStatisticsPanel(view, &windows.statistics);
        drawRenderPanel(view, &render_settings, &windows.render);
        drawToolsPanel(view.type_names, &tools, &windows.tools);
        std::string inspector_message;
        drawInspector(doc, view.type_names, &tools, &requests, &inspector_message, &windows.inspector);
        if (!inspector_message.empty()) messages.push_back(inspector_message);
        drawGhostTilePanel(doc, &ghost_panel, &windows.ghost_tile);
        if (doc && ghost_panel.build && !ghost_job) {
            std::string job_error;
            ghost_job = doc->startGhostTileJob(ghost_panel.pending, &job_error);
            ghost_job_doc = doc;
            ghost_job_action = -1;
            if (!ghost_job) {
                messages.push_back(job_error);
                ghost_panel.last_outcome = "refused: " + job_error;
            }
        }
        if (ghost_job && ghost_panel.cancel) ghost_job->cancel();
        ghost_panel.build = ghost_panel.cancel = false;
        {
            OutlinerView outliner;
            outliner.type_names = view.type_names;
            outliner.instances_per_type = view.instances_per_type;
            if (scene)
                for (const DetailLodMesh& m : scene->meshes) outliner.colors.push_back(m.color);
            drawOutliner(doc, outliner, &type_visible, &tools, &requests, &windows.outliner);
            for (size_t t = 0; t < type_visible.size(); ++t) renderer.setTypeVisible(t, type_visible[t] != 0);
            inst_view.pending = scene && !settled;
            std::string panel_message;
            drawInstantiationPanel(doc, view.type_names, inst_view, &panel_message, &windows.instantiation);
            if (!panel_message.empty()) messages.push_back(panel_message);
            ExportView export_view;
            export_view.has_document = doc != nullptr && store != nullptr && settled;  // the settled set
            export_view.running = export_job != nullptr;
            export_view.can_cancel = export_job && export_job->stage() == ExportStage::Gathering;
            export_view.progress = export_job ? export_job->progress() : 0.0f;
            export_view.stage = export_job ? exportStageName(export_job->stage()) : "";
            export_view.last_result = export_result;
            drawExportPanel(export_view, &export_settings, &requests, &windows.export_panel);
        }

        markers.clear();
        brush_probe.drawn = false;
        // Mouse tools: not while a panel has the mouse, Alt is held (Alt + left drag orbits) or a replay
        // stroke is running.
        const bool replay_stroke = replay.started && !replay.finishing;
        if (doc && have_result && !scripted && !replay_stroke && asking_recovery.empty() &&
            prompt == Prompt::None) {
            const glm::vec2 cursor(io.MousePos.x * io.DisplayFramebufferScale.x,
                                   io.MousePos.y * io.DisplayFramebufferScale.y);
            const Ray ray = rayThroughPixel(view_proj, float(fb_w), float(fb_h), cursor);
            const bool mouse_free = !io.WantCaptureMouse && !io.KeyAlt;
            if (tools.tool == ToolKind::Select) {
                // Click picks; dragging the picked primitive moves it (Shift: up and down).
                if (mouse_free && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
                    tools.selected = pickPrimitive(*doc, view_proj, float(fb_w), float(fb_h), cursor, 20.0f);
                    if (tools.selected != 0) move_drag.begin(doc, tools.selected, ray);
                } else if (move_drag.active() && ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
                    const uint64_t generation = doc->live().generation();
                    std::string move_error;
                    if (!move_drag.drag(ray, io.KeyShift, &move_error)) messages.push_back(move_error);
                    if (doc->live().generation() != generation)
                        pending_stamps.push_back({doc->live().generation(), Clock::now(), -1});
                }
            } else {
                // The marker shows where the brush works: for Sculpt, where the material lands.
                const SurfaceHit hit = tools.tool == ToolKind::Sculpt
                                           ? sculptLanding(*doc, tools.brush.sculpt_type, ray)
                                           : pickBrushSurface(*doc, tools.brush, ray);
                if (hit.hit && mouse_free) {
                    const size_t first = markers.lines.size();
                    addBrushMarker(*doc, hit.point_m, tools.brush.radius_m, !hit.on_pile, &markers);
                    glm::vec3 sum(0.0f);
                    for (size_t i = first; i < markers.lines.size(); ++i) sum += markers.lines[i].position;
                    const glm::vec3 ring_centre = sum / float(std::max<size_t>(1, markers.lines.size() - first));
                    brush_probe = {true, hit.on_pile, hit.point_m,
                                   projectToPixel(view_proj, float(fb_w), float(fb_h), ring_centre)};
                }
                const int before = stroke.stamps();
                std::string stroke_error;
                bool ok = true;
                if (mouse_free && ImGui::IsMouseClicked(ImGuiMouseButton_Left))
                    ok = stroke.begin(doc, tools.tool, tools.brush, ray, now_s, &stroke_error);
                else if (stroke.active() && ImGui::IsMouseDown(ImGuiMouseButton_Left))
                    ok = stroke.drag(ray, now_s, &stroke_error);
                if (!ok) messages.push_back(stroke_error);
                if (stroke.stamps() > before)
                    pending_stamps.push_back({doc->live().generation(), Clock::now(), -1});
            }
            if (stroke.active() && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
                // The statistics keep each mouse sculpt stroke's pile (tests drive the mouse with xdotool).
                if (stroke.tool() == ToolKind::Sculpt && !stroke.stampPoints().empty() && !options.stats_path.empty())
                    result->sculpt_strokes.push_back(pileRecord(*doc, stroke));
                stroke.end();
            }
            if (move_drag.active() && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) move_drag.end();
        }

        // Requests from menus and shortcuts.
        if (doc) {
            std::string op_error;
            if (requests.undo || requests.redo) {
                stroke.end();
                move_drag.end();
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
            if (requests.delete_selected && tools.selected != 0) {
                move_drag.end();
                if (doc->removePrimitive(tools.selected, &op_error))
                    tools.selected = 0;
                else
                    messages.push_back(op_error);
            }
            if (requests.duplicate_selected && tools.selected != 0) {
                Primitive p;
                if (doc->findPrimitive(tools.selected, nullptr, &p)) {
                    const float offset = std::max(p.radius_m, p.disc_radius_m);
                    const uint64_t id =
                        doc->duplicatePrimitive(tools.selected, glm::vec3(offset, 0.0f, 0.0f), &op_error);
                    if (id)
                        tools.selected = id;
                    else
                        messages.push_back(op_error);
                }
            }
            if (drawSaveAsDialog(&save_as_open, &save_as_path) == DialogAnswer::Yes) {
                if (!doc->saveAs(save_as_path, &op_error))
                    messages.push_back("Save As failed: " + op_error);
                else
                    recent_files = loadRecentFiles(options.config_dir);
            }
        }
        // ---- New, Open, Export ----
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
            export_job = std::make_unique<ExportJob>(*doc, store, export_settings, stats.dump());
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
                move_drag.end();
                requestOpen(requests.open_path, RecoverChoice::Ask);
            }
        }
        if (requests.quit) window.requestClose();
        if (requests.screenshot) {
            screenshot_request_path = options.screenshot_path;
            screenshot_overlays = true;
        }
        const bool screenshot_requested = requests.screenshot;
        requests = UiRequests{};
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
                    move_drag.end();
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

        // ---- replay: start or advance the current action ----
        // Where an action's edits changed the fields, grown by twice the largest object reach (collisions at
        // the rim count as inside): its statistics count instances inside and outside it.
        auto recordChangeBox = [&](Bounds box) {
            const float grow = 2.0f * reach_m + std::max(0.0f, scene->doc->ghostTile().settings.delta_m);
            box.lo -= grow;
            box.hi += grow;
            replay.record["box"] = {{"min", {box.lo.x, box.lo.y, box.lo.z}}, {"max", {box.hi.x, box.hi.y, box.hi.z}}};
        };
        auto recordPile = [&](const BrushStroke& st) {
            replay.record["pile"] = pileRecord(*doc, st);
            replay.record["user_primitives_after"] = doc->primitiveIds(st.sculptType()).size();
        };
        // A type named by the script, or kNoType with *error set (the run fails: the script is wrong).
        constexpr size_t kNoType = SIZE_MAX;
        auto replayType = [&](const std::string& name) -> size_t {
            const auto it = std::find(view.type_names.begin(), view.type_names.end(), name);
            if (it != view.type_names.end()) return size_t(it - view.type_names.begin());
            *error = "replay: action " + std::to_string(replay.index) + ": no detail type '" + name + "'";
            return kNoType;
        };
        // A replayed brush's ray: straight down onto the point, or ("from_camera") the ray the mouse over
        // that point's ground would cast from the current view.
        auto strokeRay = [&](const ReplayAction& a, glm::vec2 xy) {
            const Ray down = rayDownOnto(*doc, xy);
            if (!a.from_camera) return down;
            const SurfaceHit ground = pickGround(*doc, down);
            const glm::vec3 eye = camera.eye();
            const glm::vec3 to = ground.hit ? ground.point_m : glm::vec3(xy, 0.0f);
            return Ray{eye, glm::normalize(to - eye)};
        };
        if (doc && have_result && replay.index < options.replay.size() && !replay.finishing) {
            const ReplayAction& a = options.replay[replay.index];
            std::string op_error;
            bool continue_move = false;  // a move runs over the next frames
            if (!replay.started && frame_index >= a.frame && settled) {
                replay.started = true;
                replay.record = json{{"action", replayKindName(a.kind)}, {"frame", frame_index}};
                replay.before = store;
                replay.stamp_ms.clear();
                // Counted now, with the candidates `store` indexes: a Ghost Tile action or its undo swaps them.
                const InstanceStore none;
                const InstanceStore& now = store ? *store : none;
                replay.record["instances_before"] = now.instanceCount();
                replay.record["per_type_before"] =
                    perTypeJson(view.type_names, perTypeCounts(now, doc->ghostTile().candidates));
                replay.record["instance_store_hash_before"] = hex64(instanceStoreHash(now));
                const bool is_stroke = a.kind == ReplayKind::PaintStroke ||
                                       a.kind == ReplayKind::SculptStroke ||
                                       a.kind == ReplayKind::EraseStroke;
                if (is_stroke) {
                    BrushSettings brush = tools.brush;
                    brush.radius_m = a.radius_m;
                    brush.strength = a.strength;
                    brush.falloff_m = a.falloff_m;
                    brush.subtract = a.subtract;
                    brush.type_mix.assign(view.type_names.size(), 0.0f);
                    json types = json::object();
                    for (const auto& [name, weight] : a.types) {
                        const size_t t = replayType(name);
                        if (t == kNoType) return ViewerStatus::Failed;
                        brush.type_mix[t] = weight;
                        brush.sculpt_type = t;
                        types[name] = weight;
                    }
                    // Paint and erase work on the ground unless the script names a pile ("surface").
                    if (a.kind != ReplayKind::SculptStroke) brush.sculpt_type = SIZE_MAX;
                    if (!a.surface.empty()) {
                        brush.sculpt_type = replayType(a.surface);
                        if (brush.sculpt_type == kNoType) return ViewerStatus::Failed;
                    }
                    replay.record["types"] = types;
                    replay.record["radius"] = a.radius_m;
                    const ToolKind tool = a.kind == ReplayKind::PaintStroke    ? ToolKind::Paint
                                          : a.kind == ReplayKind::SculptStroke ? ToolKind::Sculpt
                                                                               : ToolKind::Erase;
                    if (tool == ToolKind::Sculpt && brush.sculpt_type < view.type_names.size())
                        replay.record["user_primitives_before"] = doc->primitiveIds(brush.sculpt_type).size();
                    replay.path = strokePath(a);
                    replay.step = 0;
                    if (!stroke.begin(doc, tool, brush, strokeRay(a, replay.path[0]), 0.0, &op_error))
                        messages.push_back(op_error);
                    if (stroke.stamps() > 0)
                        pending_stamps.push_back({doc->live().generation(), Clock::now(), int(replay.index)});
                    replay.step = 1;
                } else {
                    switch (a.kind) {
                        case ReplayKind::Undo:
                            replay.record["ok"] = doc->undo();
                            break;
                        case ReplayKind::Redo:
                            replay.record["ok"] = doc->redo();
                            break;
                        case ReplayKind::Save:
                        case ReplayKind::SaveAs: {
                            const bool ok = a.kind == ReplayKind::Save ? doc->save(&op_error)
                                                                       : doc->saveAs(a.path, &op_error);
                            replay.record["ok"] = ok;
                            if (!ok) {
                                replay.record["error"] = op_error;
                                messages.push_back("Save failed: " + op_error);
                            }
                            replay.record["path"] = a.kind == ReplayKind::Save ? doc->path() : a.path;
                            break;
                        }
                        case ReplayKind::Screenshot:
                            (a.ui ? ui_screenshot_path : screenshot_request_path) = a.path;
                            screenshot_overlays = a.overlays;
                            replay.record["path"] = a.path;
                            break;
                        case ReplayKind::Move: {
                            // The user primitive whose centre is nearest `from` in XY, dragged by the
                            // Select tool's MoveDrag on rays straight down (one position per frame).
                            uint64_t nearest = 0;
                            float nearest_d = 1e30f;
                            for (size_t t = 0; t < view.type_names.size(); ++t)
                                for (uint64_t id : doc->primitiveIds(t)) {
                                    Primitive p;
                                    if (!doc->findPrimitive(id, nullptr, &p)) continue;
                                    const float d = glm::length(glm::vec2(p.center_m) - a.points.front());
                                    if (d < nearest_d) {
                                        nearest_d = d;
                                        nearest = id;
                                    }
                                }
                            Primitive p;
                            if (nearest != 0 && doc->findPrimitive(nearest, nullptr, &p) &&
                                move_drag.begin(doc, nearest, rayDownOnto(*doc, a.points.front()))) {
                                tools.selected = nearest;
                                replay.record["id"] = nearest;
                                replay.record["from_center"] = {p.center_m.x, p.center_m.y, p.center_m.z};
                                replay.moved_from = editBounds(p);
                                replay.path = strokePath(a);
                                replay.step = 0;
                                continue_move = true;
                            } else {
                                replay.record["ok"] = false;
                                messages.push_back("replay: move: no movable user primitive");
                            }
                            break;
                        }
                        case ReplayKind::GhostTile: {
                            // Builds in the background like the panel's Build; the action ends when the job has
                            // ended and (if it was applied) the new tile's result is on screen.
                            GhostTileSpec spec = ghostTileSpec(doc->project());
                            if (!applyReplayGhostTile(a, &spec, &op_error) ||
                                !(ghost_job = doc->startGhostTileJob(std::move(spec), &op_error))) {
                                replay.record["ghost_tile"] = {{"ok", false}, {"error", op_error}};
                                messages.push_back(op_error);
                            } else {
                                ghost_job_doc = doc;
                                ghost_job_action = int(replay.index);
                            }
                            break;
                        }
                        case ReplayKind::SetSeed:
                            replay.record["seed"] = a.seed;
                            replay.record["ok"] = doc->setSeed(a.seed, &op_error);
                            break;
                        case ReplayKind::SetInstancing: {
                            const size_t t = replayType(a.type);
                            if (t == kNoType) return ViewerStatus::Failed;
                            InstancingDesc desc = doc->project().detail_types[t].instancing;
                            replay.record["type"] = a.type;
                            replay.record["ok"] =
                                applyInstancingChanges(a.instancing_json, &desc, &op_error) &&
                                doc->setInstancing(t, desc, &op_error);
                            replay.record["strategy"] =
                                priorityStrategyName(doc->project().detail_types[t].instancing.strategy);
                            break;
                        }
                        case ReplayKind::Export: {
                            export_settings.path = a.path;
                            export_settings.plain_nodes = a.plain_nodes;
                            export_settings.chunk_size_m =
                                a.chunk_m > 0.0f ? a.chunk_m : doc->project().chunk_size_m;
                            requests.start_export = true;  // started below, the way the Export button does
                            export_record = json();
                            windows.export_panel = true;  // its progress shows there, as for the menu
                            replay.record["path"] = a.path;
                            break;
                        }
                        case ReplayKind::SetVisible: {
                            const size_t t = replayType(a.type);
                            if (t == kNoType) return ViewerStatus::Failed;
                            replay.record["type"] = a.type;
                            replay.record["visible"] = a.visible;
                            replay.record["drawn_instances_before"] = renderer.stats().instances_drawn;
                            type_visible.resize(view.type_names.size(), 1);
                            type_visible[t] = a.visible ? 1 : 0;
                            renderer.setTypeVisible(t, a.visible);  // this frame already draws it so
                            break;
                        }
                        case ReplayKind::Open:
                        case ReplayKind::New:
                            load_error.clear();
                            if (a.kind == ReplayKind::New)
                                startNew();
                            else
                                requestOpen(a.path, RecoverChoice::Ask);
                            replay.record["path"] = a.path;
                            break;
                        case ReplayKind::View:
                            if (a.has_target) camera.target = a.target;
                            if (a.distance_m > 0.0f) camera.distance_m = a.distance_m;
                            if (!std::isnan(a.yaw_deg)) camera.yaw_rad = glm::radians(a.yaw_deg);
                            if (!std::isnan(a.pitch_deg)) camera.pitch_rad = glm::radians(a.pitch_deg);
                            camera_moved = true;
                            break;
                        default:
                            break;
                    }
                    if (!continue_move) replay.finishing = a.kind != ReplayKind::GhostTile || !ghost_job;
                }
            } else if (replay.started && move_drag.active()) {
                const uint64_t generation = doc->live().generation();
                if (replay.step < replay.path.size() &&
                    !move_drag.drag(rayDownOnto(*doc, replay.path[replay.step]), false, &op_error))
                    messages.push_back(op_error);
                if (doc->live().generation() != generation)
                    pending_stamps.push_back({doc->live().generation(), Clock::now(), int(replay.index)});
                if (++replay.step >= replay.path.size()) {
                    Primitive p;
                    doc->findPrimitive(move_drag.id(), nullptr, &p);
                    replay.record["moves"] = move_drag.moves();
                    replay.record["to_center"] = {p.center_m.x, p.center_m.y, p.center_m.z};
                    // Old and new supports: where the move can change instances.
                    recordChangeBox(unite(replay.moved_from, editBounds(p)));
                    move_drag.end();
                    replay.finishing = true;
                }
            } else if (replay.started && a.kind == ReplayKind::GhostTile) {
                replay.finishing = !ghost_job;  // the job was applied or reported at this frame's start
            } else if (replay.started && stroke.active()) {
                // One brush position per frame; the virtual clock advances one hold interval per step so a
                // sculpt stroke stamps at every step, whatever the frame rate.
                const int before = stroke.stamps();
                if (replay.step < replay.path.size() &&
                    !stroke.drag(strokeRay(a, replay.path[replay.step]),
                                 double(replay.step) * kSculptHoldInterval_s, &op_error))
                    messages.push_back(op_error);
                if (stroke.stamps() > before)
                    pending_stamps.push_back({doc->live().generation(), Clock::now(), int(replay.index)});
                if (++replay.step >= replay.path.size()) {
                    replay.record["stamps"] = stroke.stamps();
                    json points = json::array();
                    for (const glm::vec3& p : stroke.stampPoints()) points.push_back({p.x, p.y, p.z});
                    replay.record["stamp_points"] = points;
                    if (stroke.tool() == ToolKind::Sculpt && !stroke.stampPoints().empty())
                        recordPile(stroke);
                    recordChangeBox(stroke.changedBounds());
                    stroke.end();
                    replay.finishing = true;
                }
            }
        }

        // ---- render ----
        // A stamp made this frame: wait a little for its update (an incremental update takes a few ms) so
        // this frame already shows it, instead of the next one a whole frame later (on llvmpipe a frame is
        // 30-40 ms; the stamp-to-frame target is 50 ms). Bounded, so a slow update never stalls the UI.
        if (scene && pending_stamps.size() > stamps_before_frame) {
            const auto wait_start = Clock::now();
            while (scene->doc->live().pending() &&
                   std::chrono::duration<double, std::milli>(Clock::now() - wait_start).count() <
                       kStampWaitBudgetMs)
                std::this_thread::sleep_for(std::chrono::microseconds(250));
        }
        if (!takeLiveResult()) return ViewerStatus::Failed;
        // The camera never goes below the ground, whatever moved it (navigation, a replayed view, framing).
        if (scene) keepEyeAboveGround(&camera, groundZ);
        // The skeleton overlays (Window > Skeleton overlays) and the Render panel's overlays (tile grid,
        // anchors, sphere sets) are separate toggles: one does not hide the others.
        if (doc && have_result && (screenshot_request_path.empty() || screenshot_overlays)) {
            if (tools.show_markers) {
                const PrimitiveMarkersKey key{doc, doc->live().generation(), doc->tileGeneration(), tools.selected,
                                              render_settings.hulls};
                if (!(key == primitive_markers_key)) {
                    primitive_markers.clear();
                    addPrimitiveMarkers(*doc, scene->meshes, tools.selected, &primitive_markers);
                    if (render_settings.hulls)
                        addPrimitiveHulls(*doc, scene->meshes, tools.selected, &primitive_markers);
                    primitive_markers_key = key;
                }
                markers.append(primitive_markers);
            }
            const float r = render_settings.overlay_radius_m;
            const CandidateSet& c = doc->ghostTile().candidates;
            if (render_settings.tile_grid) addTileOverlay(instances, camera.target, r, &markers);
            if (render_settings.anchors) addAnchorOverlay(instances, c, scene->meshes, camera.target, r, &markers);
            if (render_settings.sphere_sets) addSphereOverlay(instances, c, doc->models(), camera.target, r, &markers);
        }
        if (!screenshot_request_path.empty() && !screenshot_overlays) markers.clear();
        renderer.setMarkers(markers);
        renderer.render(camera, fb_w, fb_h, render_settings.lod);
        const gl::RenderStats& rs = renderer.stats();
        view.triangles = rs.triangles;
        view.points = rs.points;
        view.draw_calls = rs.draw_calls;
        view.lod_instances = rs.lod_instances;
        view.tiles_visible = rs.tiles_visible;
        view.tiles_culled = rs.tiles_culled;
        view.tiles_resident = rs.tiles_resident;
        view.indirect_commands = rs.indirect_commands;

        // The screenshot is the viewport alone, read before the UI is drawn over it.
        const bool last_scripted_frame = scripted && replay.index >= options.replay.size() && settled &&
                                         frames_after_done + 1 >= options.frames;
        if (screenshot_requested || !screenshot_request_path.empty() ||
            (last_scripted_frame && !options.screenshot_path.empty())) {
            std::string path =
                screenshot_request_path.empty() ? options.screenshot_path : screenshot_request_path;
            if (path.empty() || (screenshot_requested && !scripted && screenshot_count > 0))
                path = std::filesystem::path(options.scene_path).stem().string() + "-screenshot-" +
                       std::to_string(++screenshot_count) + ".png";
            else
                ++screenshot_count;
            renderer.readPixels(fb_w, fb_h, &pixels);
            std::string write_error;
            if (writeScreenshot(path, fb_w, fb_h, pixels, &write_error)) {
                view.last_message = "saved " + path;
                result->screenshot = path;
            } else {
                messages.push_back(write_error);
                if (scripted) {
                    *error = write_error;
                    return ViewerStatus::Failed;
                }
            }
            screenshot_request_path.clear();
            // F12 in an interactive run with --stats also rewrites the statistics (a driven session reads
            // the viewport's state after each step).
            if (screenshot_requested && !scripted) writeInteractiveStats();
        }
        window.renderUi();
        if (!ui_screenshot_path.empty()) {
            renderer.readPixels(fb_w, fb_h, &pixels);
            std::string write_error;
            if (!writeScreenshot(ui_screenshot_path, fb_w, fb_h, pixels, &write_error))
                messages.push_back(write_error);
            ui_screenshot_path.clear();
        }
        if (options.finish_each_frame) window.finish();
        window.swapBuffers();

        // ---- after the frame: stamp timings, replay bookkeeping, autosave ----
        const auto frame_end = Clock::now();
        for (size_t i = 0; i < pending_stamps.size();) {
            if (have_result && pending_stamps[i].generation <= shown_generation) {
                const double ms =
                    std::chrono::duration<double, std::milli>(frame_end - pending_stamps[i].time).count();
                result->stamp_to_frame_ms.push_back(ms);
                view.stamp_to_frame_ms = ms;
                if (pending_stamps[i].action == int(replay.index)) replay.stamp_ms.push_back(ms);
                pending_stamps.erase(pending_stamps.begin() + long(i));
            } else {
                ++i;
            }
        }
        const bool settled_now = scene && have_result && !scene->doc->live().pending() &&
                                 shown_generation == scene->doc->live().generation();
        // An open, a new document or an export finishes when its background work did (and, for a document
        // that loaded, once its first result is on screen).
        const bool export_waiting = replay.finishing && replay.index < options.replay.size() &&
                                    options.replay[replay.index].kind == ReplayKind::Export &&
                                    (export_job || export_record.is_null());
        if (replay.finishing && settled_now && scene && !loader && !export_waiting) {
            Document& d = *scene->doc;
            const CandidateSet& c = d.ghostTile().candidates;
            const std::vector<std::string>& names = view.type_names;
            json& r = replay.record;
            const InstanceStore empty;
            const InstanceStore& before = replay.before ? *replay.before : empty;
            r["instances_after"] = store->instanceCount();
            r["per_type_after"] = perTypeJson(names, perTypeCounts(*store, c));
            r["instance_store_hash_after"] = hex64(instanceStoreHash(*store));
            const ReplayKind kind = options.replay[replay.index].kind;
            if (kind == ReplayKind::Export) r.update(export_record);
            if (kind == ReplayKind::SetVisible) r["drawn_instances_after"] = renderer.stats().instances_drawn;
            if (kind == ReplayKind::View) {
                r["eye"] = vec3Json(camera.eye());
                r["target"] = vec3Json(camera.target);
                r["eye_ground_z"] = groundZ(glm::vec2(camera.eye()));
            }
            if (kind == ReplayKind::Open || kind == ReplayKind::New) {
                r["camera_target"] = vec3Json(camera.target);
                r["camera_eye"] = vec3Json(camera.eye());
                r["ok"] = load_error.empty();
                if (!load_error.empty()) r["error"] = load_error;
                r["document"] = d.path();
            }
            if (r.contains("pile")) {
                r["pile"]["instances"] = pileInstancesJson(d, *store, r["pile"]);
                r["pile"]["instances_before"] = pileInstancesJson(d, before, r["pile"]);
            }
            if (r.contains("box")) {
                auto corner = [&](const char* key) {
                    const json& v = r["box"][key];
                    return glm::vec3(v[0].get<float>(), v[1].get<float>(), v[2].get<float>());
                };
                const Bounds box{corner("min"), corner("max")};
                const float s = d.ghostTile().settings.tile_size_m;
                const BoxCounts b = countInstancesInBox(before, c, s, box),
                                a = countInstancesInBox(*store, c, s, box);
                r["inside_before"] = perTypeJson(names, b.inside);
                r["inside_after"] = perTypeJson(names, a.inside);
                r["outside_before"] = perTypeJson(names, b.outside);
                r["outside_after"] = perTypeJson(names, a.outside);
                r["stamp_to_frame_ms"] = replay.stamp_ms;
            }
            r["dirty"] = d.isDirty();
            r["uploads"] = replay.uploads;
            json tiles = json::array();
            for (uint64_t key : replay.uploaded_tiles) {
                const glm::ivec3 t = unpackTile(key);
                tiles.push_back({t.x, t.y, t.z});
            }
            r["uploaded_tiles"] = tiles;
            r["tiles_resident"] = instances.tileCount();
            r["tile_size_m"] = instances.tile_size_m;
            result->actions.push_back(r);
            replay = ReplayState{replay.index + 1};
            if (replay.index >= options.replay.size() && !scripted && !stats_written) {
                writeInteractiveStats();
                stats_written = true;
            }
        }
        if (scene) {
            std::string autosave_error;
            if (scene->doc->maybeAutosave(now_s, &autosave_error)) {
                ++result->autosaves;
                last_autosave_error.clear();
            } else if (!autosave_error.empty() && autosave_error != last_autosave_error) {
                messages.push_back("Autosave failed: " + autosave_error);
                last_autosave_error = autosave_error;
            }
        }

        const double ms = std::chrono::duration<double, std::milli>(frame_end - frame_start).count();
        view.frame_ms = std::chrono::duration<double, std::milli>(frame_end - last_frame_end).count();
        view.frame_ms_avg =
            view.frame_ms_avg == 0.0 ? view.frame_ms : 0.95 * view.frame_ms_avg + 0.05 * view.frame_ms;
        last_frame_end = frame_end;
        if (have_result) {
            ++frame_index;
            frame_ms.push_back(ms);
            result->triangles = rs.triangles;
            result->points = rs.points;
            result->draw_calls = rs.draw_calls;
            result->lod_instances = rs.lod_instances;
            result->tiles_visible = rs.tiles_visible;
            result->tiles_culled = rs.tiles_culled;
            result->indirect_commands = rs.indirect_commands;
            result->tiles_uploaded = rs.tiles_uploaded;
            result->bytes_uploaded = rs.bytes_uploaded;
            result->tiles_resident = rs.tiles_resident;
            result->framebuffer_width = fb_w;
            result->framebuffer_height = fb_h;
            result->instantiate_seconds = view.instantiate_seconds;
            if (scripted && replay.index >= options.replay.size() && settled_now &&
                ++frames_after_done >= options.frames)
                break;
        }
        if (quitting) break;
    }
    result->frames_measured = int(frame_ms.size());
    result->frame_ms = percentile(frame_ms, 0.5);
    result->frame_ms_p95 = percentile(frame_ms, 0.95);
    // The statistics describe the document as it was left: its final instance set, not a stale one.
    if (scene && !scripted && !options.stats_path.empty()) {
        scene->doc->live().waitIdle();
        LiveResult last;
        if (scene->doc->live().poll(&last) && last.generation >= scene->doc->tileLiveGeneration()) store = last.store;
    }
    fillDocumentResult();
    if (!scripted) writeInteractiveStats();
    return ViewerStatus::Ok;
}

json viewerStatsJson(const ViewerResult& r, const LodSettings& lod) {
    json per_type = json::object();
    for (size_t i = 0; i < r.type_names.size(); ++i)
        per_type[r.type_names[i]] = i < r.instances_per_type.size() ? r.instances_per_type[i] : 0;
    return {
        {"scene", r.scene},
        {"instances", r.instances},
        {"instances_per_type", per_type},
        {"instance_store_hash", hex64(r.instance_store_hash)},
        {"instantiate_seconds", r.instantiate_seconds},
        {"frames_measured", r.frames_measured},
        {"frame_ms", r.frame_ms},
        {"frame_ms_p95", r.frame_ms_p95},
        {"triangles", r.triangles},
        {"impostor_points", r.points},
        {"draw_calls", r.draw_calls},
        {"lod_instances",
         {{"lod0", r.lod_instances[0]},
          {"lod1", r.lod_instances[1]},
          {"lod2", r.lod_instances[2]},
          {"impostor", r.lod_instances[3]}}},
        {"lod_settings_px", {{"lod1", lod.lod1_px}, {"lod2", lod.lod2_px}, {"impostor", lod.impostor_px}}},
        {"tiles_visible", r.tiles_visible},
        {"tiles_culled", r.tiles_culled},
        {"indirect_commands", r.indirect_commands},
        {"tiles_resident", r.tiles_resident},
        {"tiles_uploaded", r.tiles_uploaded},
        {"bytes_uploaded", r.bytes_uploaded},
        {"upload_tiles_p50", percentile(r.upload_tiles, 0.5)},
        {"tile_update_ms_max", r.tile_update_ms_max},
        {"gl_version", r.gl_version},
        {"renderer", r.renderer},
        {"window", {r.window_width, r.window_height}},
        {"framebuffer", {r.framebuffer_width, r.framebuffer_height}},
        {"screenshot", r.screenshot},
        {"document",
         {{"path", r.document_path},
          {"recovered", r.recovered},
          {"dirty", r.dirty},
          {"user_primitives", r.user_primitives},
          {"autosaves", r.autosaves}}},
        {"stamps", r.stamp_to_frame_ms.size()},
        {"stamp_to_frame_ms_p50", percentile(r.stamp_to_frame_ms, 0.5)},
        {"stamp_to_frame_ms_p95", percentile(r.stamp_to_frame_ms, 0.95)},
        {"repack_ms_max", r.repack_ms_max},
        {"actions", r.actions},
        {"sculpt_strokes", r.sculpt_strokes},
        {"messages", r.messages},
        {"viewport", r.viewport},
        {"window_title", r.window_title}};
}

}  // namespace ug::editor
