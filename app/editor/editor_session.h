// The editor's session (viewer.h runViewer): one window on a Document, its panels, tools, live instancing,
// replay and statistics. The state lives here; the frame's steps are methods, grouped by subsystem in
// their own files:
//   editor_session.cpp    the main loop (STYLE.md's flat loop), start-up, the statistics
//   session_document.cpp  the document's lifecycle: open / recover / new, menus and shortcuts' requests,
//                         save, save as, the unsaved-changes and recovery dialogs, autosave
//   session_live.cpp      live instancing: finished results re-packed for the GPU (resident tiles)
//   session_input.cpp     the UI frame: navigation (zoom to the cursor, the eye above the ground), the
//                         keyboard given back to the viewport, panels, the mouse tools and brush ring
//   session_replay.cpp    replay scripts (replay.h): actions started, advanced and recorded
//   session_strands.cpp   the particle systems' strands re-grown after their edits (live_strands.h)
//   session_environment.cpp  the environmental effects computed again after their edits (live_environment.h)
//   session_render.cpp    the frame's render, overlays and screenshots; the after-frame bookkeeping
//   session_stats.h, background_jobs.h   free helpers: action statistics, finished jobs' outcomes
// Internal to app/editor: nothing outside viewer.cpp constructs one.
#pragma once

#include <chrono>
#include <cstdint>
#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "analysis/placed_instances.h"
#include "editor/document_loader.h"
#include "editor/export_job.h"
#include "editor/gl/renderer.h"
#include "editor/gl/window.h"
#include "editor/channel_map.h"
#include "editor/env_handles.h"
#include "editor/env_tools.h"
#include "editor/live_environment.h"
#include "editor/live_strands.h"
#include "editor/markers.h"
#include "editor/orbit_camera.h"
#include "editor/panels.h"
#include "editor/particle_tools.h"
#include "editor/render_data.h"
#include "editor/tools.h"
#include "editor/viewer.h"
#include "scene/document.h"
#include "scene/ghost_tile_job.h"

namespace ug::editor {

// What "frame all" (Home) frames, and the view a scene opens on, for the session's scene (viewer.cpp,
// over default_view.h).
Bounds framingBounds(const EditorScene& s, const ResidentTiles* instances);
Bounds openingBounds(const EditorScene& s, const ResidentTiles& instances);

class EditorSession {
public:
    EditorSession(const ViewerOptions& options, ViewerResult* result, std::string* error);
    ViewerStatus run();

private:
    using Clock = std::chrono::steady_clock;
    using json = nlohmann::json;

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
        json uploads = json::array();       // per live result while the action ran
        std::set<uint64_t> uploaded_tiles;  // packed keys
        std::shared_ptr<const InstanceStore> before;
        std::vector<double> stamp_ms;
        Bounds moved_from;  // move: the support of the primitive's stroke before
    };
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
    struct BrushProbe {
        bool drawn = false;
        bool on_pile = false;
        glm::vec3 center{0.0f};
        glm::vec2 ring_center_px{0.0f};  // the ring's centre (its vertices' mean) on screen
    };
    enum class Prompt { None, Quit, Open, New };

    // ---- editor_session.cpp ----
    ViewerStatus start();            // the window, the renderer, the first document's open
    json viewportJson();             // ViewerResult::viewport
    void fillDocumentResult();
    void writeInteractiveStats();
    void updateStatus();             // the Statistics window's status line and progress bar
    // After this frame's edits, before it renders: a stamp's instances, an environment or particle edit's
    // effects or strands are waited for and shown in this very frame when they make it in time. Rendering
    // the frame without them would show nothing new, take as long as a frame takes, and on a software
    // renderer take the cores the worker needs; so the wait lasts up to the previous frame's render time (a
    // fast GPU waits a few ms at most, llvmpipe the 30-40 ms of a meadow stamp or the ~50 ms of a
    // footprint), at most kFreshWaitMaxMs, all waits together. (Stamps were waited for at most 15 ms
    // while their settling took 60-110 ms; with it at ~30 ms a stroke's stamp shows in its own frame.)
    void showFreshResults();
    // A stamp made this frame: waits up to `budget` for the live instancer (renderFrame takes its result).
    void waitForStampUpdate(std::chrono::milliseconds budget);
    static constexpr double kFreshWaitMaxMs = 250.0;
    // ---- session_document.cpp ----
    void startLoad(const std::string& path, bool recover);
    // Opens `path`, asking first (interactive) when an autosave of it is newer than the file.
    bool requestOpen(const std::string& path, RecoverChoice choice);
    void startNew();
    bool applyFinishedWork();        // a loaded document, a finished Ghost Tile build or export, a live result
    void adoptLoadedDocument();      // the loader's document replaces the current one
    // Menus' and shortcuts' requests, then the dialogs (in this order, once a frame).
    void handleEditRequests();
    void handleFileRequests();
    void handleDialogs();
    void autosave();
    // ---- session_live.cpp ----
    void syncTile();
    // Takes a finished live result, if any, and re-packs it for the GPU (viewer.cpp's header).
    bool takeLiveResult();
    // ---- session_strands.cpp ----
    // The document's particle systems submitted after an edit; finished strands swapped into the static
    // meshes (at the frame boundary).
    void startStrands();
    void syncStrands();
    bool strandsSettled() const;  // the strands on screen are the document's systems'
    // An edit made this frame: its strands shown in this frame if they are grown within `budget`.
    void showFreshStrands(std::chrono::milliseconds budget);
    // The document's systems submitted when an edit moved their generation (the worker made with the
    // first system, a cancel request taken); whether they were.
    bool submitStrands();
    // The Particles window's Cancel: the growth in progress stops and the edit it grows is undone, so
    // the strands on screen are the document's again (only when Ctrl+Z would undo exactly that edit;
    // false when it did nothing).
    bool cancelStrands();
    json strandsJson() const;     // the last growth, for the replay's record
    // ---- session_environment.cpp ----
    // The same for the environment: the compiled scene submitted after an edit, the finished snow and
    // icicles swapped into the static meshes.
    void startEnvironment();
    void syncEnvironment();
    // The environment submitted when an edit moved its generation; whether it did.
    bool submitEnvironment();
    // An edit made this frame: its effects shown in this frame if they are done within `budget`.
    void showFreshEnvironment(std::chrono::milliseconds budget);
    void placeFromPalette(const Ray& ray, bool mouse_free);  // the palette armed: a click places its type
    void placeParticlePart(const Ray& ray, bool mouse_free);  // the Particles window's click to place
    // The scene's static meshes to the renderer, less the objects the Outliner hides (drawn_static_meshes).
    void showStaticMeshes();
    bool environmentSettled() const;  // the effects on screen are the document's environment's
    json environmentJson() const;     // the tree, fields and last computation, for the statistics
    // The strands and the effects are the document's (part of "settled").
    bool sideJobsSettled() const { return strandsSettled() && environmentSettled(); }
    // An environment edit made now (if `generation_before` moved) waits for the frame that shows it.
    void noteEnvStamp(uint64_t generation_before, int action);
    void timeEnvStamps(Clock::time_point frame_end);  // after the frame: the shown ones timed
    // The channel view's map built again (and uploaded) when the environment or the view's settings changed.
    void updateChannelMap();
    // Ends every drag in the view (the document is about to change under it: undo, open, delete).
    void endViewDrags() {
        move_drag.end();
        particle_drag.end();
        env_drag.end();
        env_handle_drag.end();
        weather_stroke.end();
    }
    // ---- session_input.cpp ----
    void drawUi();                   // navigation, panels
    void mouseTools();
    // The ground's height under a world XY on the current document (the camera stays above it).
    float groundZ(glm::vec2 xy) const;
    // ---- session_replay.cpp ----
    bool stepReplay();               // start or advance the current action; false: the script is wrong
    bool startReplayStroke(const ReplayAction& action);
    bool runReplayAction(const ReplayAction& action);
    void recordChangeBox(Bounds box);
    void recordPile(const BrushStroke& stroke);
    static Bounds strokeBounds(const Document& doc, uint64_t id, nlohmann::json* centres);
    // A type named by the script, or kNoType with *error set (the run fails: the script is wrong).
    static constexpr size_t kNoType = SIZE_MAX;
    size_t replayType(const std::string& name);
    Ray strokeRay(const ReplayAction& action, glm::vec2 xy) const;
    void finishReplayAction();       // the action's record, once its result is settled and on screen
    // ---- session_env_replay.cpp ----
    bool startEnvReplayAction(const ReplayAction& action);  // env_add, env_move, env_remove, env_global, footprints, weather_stroke
    void stepEnvReplay();            // the next frame of an env_move drag or a weather stroke
    // ---- session_render.cpp ----
    bool renderFrame();              // false: a scripted screenshot failed, or a live result
    bool afterFrame();               // false: the run is over

    const ViewerOptions& options;
    ViewerResult* result;
    std::string* error;
    const bool scripted;
    std::vector<std::string>& messages;
    gl::Window window;
    std::unique_ptr<gl::Renderer> renderer;  // made once the window (its context) is open
    DocumentOptions doc_options;

    // ---- the document: opened (or recovered) in the background ----
    std::unique_ptr<DocumentLoader> loader;
    std::unique_ptr<EditorScene> scene;
    ResidentTiles instances;  // the tiles as the GPU holds them
    TileUploads uploads;      // what the latest live result changed in them
    std::shared_ptr<const InstanceStore> store;  // the result on screen
    std::shared_ptr<const SettledDrops> drops;   // and its settled drops (null: the scene does not settle)
    // Click to place: the result on screen as world frames (surface_pick.h), and which result they are.
    std::vector<PlacedInstance> pick_instances;
    std::shared_ptr<const InstanceStore> pick_store;
    std::shared_ptr<const SettledDrops> pick_drops;
    uint64_t shown_generation = 0;
    bool have_result = false;
    std::string asking_recovery;  // a path whose recovery dialog is open
    RecoveryInfo recovery_info;

    OrbitCamera camera;
    bool camera_moved = false;
    UiRequests requests;
    WindowToggles windows;
    ToolState tools;
    BrushStroke stroke;
    MoveDrag move_drag;
    MarkerGeometry markers;
    MarkerGeometry primitive_markers;
    PrimitiveMarkersKey primitive_markers_key;
    RenderSettings render_settings;
    StatisticsView view;
    std::vector<std::string> recent_files;
    std::string last_autosave_error;
    bool save_as_open = false;
    std::string save_as_path;
    Prompt prompt = Prompt::None;
    std::string prompt_open_path;
    bool quitting = false;
    // ---- particle systems: strands re-grown off the UI thread ----
    std::unique_ptr<LiveStrands> live_strands;  // null: the document has no particle system
    uint64_t strands_submitted = 0;             // the particlesGeneration() last submitted
    uint64_t strands_shown = 0;                 // and the one on screen
    LiveStrandsResult last_strands;             // its statistics (meshes moved out)
    ParticleHandleDrag particle_drag;           // the Select tool on a particle handle (the Particles window open)
    ParticlesPanelState particles_panel;
    // ---- environmental objects: effects computed again off the UI thread ----
    std::unique_ptr<LiveEnvironment> live_environment;  // null: the project has no environmental-object types
    uint64_t environment_submitted = 0;                 // the environmentGeneration() last submitted
    uint64_t environment_shown = 0;                     // and the one on screen
    LiveEnvironmentResult last_environment;             // its statistics (meshes moved out)
    EnvObjectDrag env_drag;                             // the Select tool on an object (the window open)
    EnvHandleDrag env_handle_drag;                      // ... on the selected node's turn or scale handle
    WeatherStroke weather_stroke;                       // a weather brush's stroke (footprints, warm, ...)
    EnvironmentPanelState environment_panel;
    std::vector<float> palette_coverage;             // per type: the part of its thumbnail the mesh covers
    std::vector<uint8_t> env_hidden_drawn;           // the objects hidden in the view (envObjectMask)
    std::vector<MeshInstances> drawn_static_meshes;  // the statics drawn while some are hidden
    ChannelMap channel_map;
    struct ChannelMapKey {
        const Document* doc = nullptr;
        uint64_t environment = 0;
        ChannelMapSettings settings;
        bool operator==(const ChannelMapKey&) const = default;
    } channel_map_key;
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

    std::vector<double> frame_ms;
    double last_render_ms = 0.0;  // the last renderFrame() (showFreshResults' budget)
    std::vector<uint8_t> pixels;
    int screenshot_count = 0;
    std::string screenshot_request_path;
    std::string ui_screenshot_path;  // replay "screenshot" with "ui": true: read after the panels are drawn
    bool screenshot_overlays = true;
    std::vector<PendingStamp> pending_stamps;
    std::vector<PendingStamp> pending_env_stamps;  // generation: the environmentGeneration() to be shown
    ReplayState replay;
    float reach_m = 0.0f;
    int frame_index = 0;        // frames since the first result was on screen
    int frames_after_done = 0;  // scripted: frames since the script finished and the result settled
    bool stats_written = false;
    const Clock::time_point start_time = Clock::now();
    Clock::time_point last_frame_end = start_time;

    // ---- what the viewport shows, for the statistics (ViewerResult::viewport) ----
    int last_fb_w = 0, last_fb_h = 0;
    glm::vec2 cursor_px{NAN};  // framebuffer pixels; NaN until the pointer is in the window
    BrushProbe brush_probe;

    // ---- Ghost Tile panel: one background build at a time (ghost_tile_job.h), applied at the frame
    // boundary; the renderer's scene (LOD meshes, candidate frames) follows the document's tile generation
    GhostTilePanelState ghost_panel;
    std::unique_ptr<GhostTileJob> ghost_job;
    const Document* ghost_job_doc = nullptr;  // the document it was started on
    int ghost_job_action = -1;                // the replay action that started it, -1: the panel
    uint64_t scene_tile_generation = 0;       // the tile generation the renderer's scene was set for

    // ---- the current frame (set by run() and the steps, read by the later steps) ----
    Clock::time_point frame_start;
    int fb_w = 0, fb_h = 0;
    double now_s = 0.0;
    bool settled = false;             // the live result is on screen and nothing is pending
    size_t stamps_before_frame = 0;
    // While another document loads, the current one is shown but not edited: it is replaced (and its
    // edits dropped) when the new one is ready, and is editable again if that load fails.
    Document* doc = nullptr;
    glm::mat4 view_proj{1.0f};        // after navigation
    bool screenshot_requested = false;
};

}  // namespace ug::editor
