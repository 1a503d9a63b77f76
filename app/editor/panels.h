// The editor's Dear ImGui panels. Panels are functions over plain state (STYLE.md "Panels are functions"):
// they read numbers the renderer and the document expose, edit plain settings, and raise requests the
// main loop acts on at the right point of the frame; they never call GL.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "editor/channel_map.h"
#include "editor/env_tools.h"
#include "editor/env_tree_view.h"
#include "editor/export_job.h"
#include "editor/particle_tools.h"
#include "editor/render_data.h"
#include "editor/tools.h"
#include "instancer/instantiator.h"
#include "scene/document.h"

namespace ug::editor {

// Requests the panels and shortcuts raise; the main loop acts on them.
struct UiRequests {
    bool screenshot = false;    // File > Screenshot: the next frame's viewport is saved
    bool quit = false;          // File > Quit (asks first when there are unsaved changes)
    bool save = false;          // File > Save
    bool open_save_as = false;  // File > Save As: show the path dialog
    std::string save_as_path;   // the dialog confirmed this path
    std::string open_path;  // File > Open Recent: open this file (asks first when there are unsaved changes)
    bool undo = false;
    bool redo = false;
    bool delete_selected = false;
    bool duplicate_selected = false;
    // ---- New / Open / Export (outliner, instantiation and export panels) ----
    bool new_document = false;  // File > New (asks first when there are unsaved changes)
    bool open_dialog = false;   // File > Open...: show the path dialog (its answer goes to open_path)
    bool show_export = false;   // File > Export glTF...: show the Export window
    bool start_export = false;  // the Export window's Export button
    bool cancel_export = false;
    EnvTreeDrop env_drop;  // the Outliner's tree: a node dropped onto a group (moves into it)
};

struct EnvironmentPanelState;

// What the Statistics window shows.
struct StatisticsView {
    std::string scene;
    std::string status;    // "loading scene…", "pending…", "ready", or the error
    bool pending = false;  // background work running
    float progress = 0.0f;
    std::vector<std::string> type_names;
    std::vector<uint64_t> instances_per_type;
    uint64_t instances = 0;
    double instantiate_seconds = 0.0;  // the latest live run
    double frame_ms = 0.0;             // the last frame
    double frame_ms_avg = 0.0;         // over the last second or so
    uint64_t triangles = 0;
    uint64_t points = 0;
    uint64_t draw_calls = 0;
    std::array<uint64_t, kLodCount> lod_instances{};
    uint64_t tiles_visible = 0;
    uint64_t tiles_culled = 0;
    uint64_t changed_tiles = 0;      // in the latest live result
    // Render residency (renderer.h RenderStats): the latest live result's upload, the frame's commands.
    uint64_t tiles_uploaded = 0;
    uint64_t bytes_uploaded = 0;
    uint64_t tiles_resident = 0;
    uint64_t indirect_commands = 0;
    double stamp_to_frame_ms = 0.0;  // the latest stamp's
    std::string gl_version;
    std::string renderer;
    std::string last_message;  // e.g. "saved screenshot.png"
};

// The tool bar's state: the active tool, the brush, overlays.
struct ToolState {
    ToolKind tool = ToolKind::Select;
    BrushSettings brush;
    bool show_markers = true;
    uint64_t selected = 0;  // a user primitive's id, 0 = none
};

// What the File and Edit menus show.
struct MenuView {
    bool has_document = false;
    bool dirty = false;
    std::string undo_name, redo_name;  // "" = nothing to undo / redo
    std::vector<std::string> recent_files;
};

struct WindowToggles {
    bool statistics = true;
    bool tools = true;
    bool inspector = true;
    bool ghost_tile = false;
    bool render = false;
    bool outliner = true;
    bool instantiation = true;
    bool export_panel = false;  // opened by File > Export glTF...
    bool particles = false;     // opened by Window > Particles
    bool environment = false;   // opened by Window > Environment
};
// The toggle of a window by its replay name ("statistics", ..., "export", "particles", "environment");
// null for an unknown name.
bool* windowToggle(WindowToggles* windows, const std::string& name);

// The Render panel's settings: LOD switch distances and what is drawn over the scene.
struct RenderSettings {
    LodSettings lod;
    ViewportLook look;            // shadows and ambient occlusion
    bool hulls = true;            // translucent hulls of the user primitives
    bool tile_grid = false;       // outlines of the non-empty tiles near the view target
    bool anchors = false;         // Ghost Tile candidates' anchors in the tiles near the target
    bool sphere_sets = false;     // collision spheres of the instances near the target
    float overlay_radius_m = 3.0f;  // "near the target"
};

// ---- outliner, instantiation and export panels ----

// One row per detail type (a layer), in type order.
struct OutlinerView {
    std::vector<std::string> type_names;
    std::vector<glm::vec3> colors;  // linear RGB, the viewport's
    std::vector<uint64_t> instances_per_type;
};

// The live instancer's latest run and the recent ones (viewer.cpp keeps them).
struct InstantiationView {
    bool have_result = false;
    bool pending = false;
    InstanceStats stats;           // of the latest run
    uint64_t changed_tiles = 0;    // tiles whose selected set changed since the previous result
    bool full = false;             // the latest result came from a full run
    std::vector<float> update_ms;  // the last runs, oldest first (at most kUpdateHistory)
    static constexpr size_t kUpdateHistory = 100;
};

// What the Export window shows about the running (or last) export.
struct ExportView {
    bool has_document = false;
    bool running = false;
    bool can_cancel = false;  // false once the final write started
    float progress = 0.0f;
    std::string stage;        // exportStageName
    std::string last_result;  // "wrote N instances to PATH in S s", or the error
};

// Layers (detail types: swatch, instance count, visibility, "paint with this type"), each with its user
// primitives (click selects; Delete / Duplicate raise the requests) and a summary of the file's own
// density tree. `visible` is view state (one byte per type), not a document edit. Below them, the
// environmental objects' tree (env_tree_view.h): an eye per node, selection shared with the Environment
// window (`environment`), drag onto a group to regroup (requests->env_drop).
void drawOutliner(const Document* doc, const OutlinerView& view, std::vector<uint8_t>* visible,
                  ToolState* tools, EnvironmentPanelState* environment, UiRequests* requests, bool* open);
// Per type strategy, layer, orientation and size constraints, and the seed: each finished edit is one
// Document::setInstancing / setSeed (one undo step); errors go to *message. Then the statistics.
void drawInstantiationPanel(Document* doc, const std::vector<std::string>& type_names,
                            const InstantiationView& view, std::string* message, bool* open);
// Path, format (by extension), plain nodes, chunk size; Export / Cancel raise the requests.
void drawExportPanel(const ExportView& view, ExportSettings* settings, UiRequests* requests, bool* open);

// Begins a panel that works on the document: false (the window already ended) when it is collapsed, or
// when there is no document (it then says so); true: draw its content, then ImGui::End().
bool beginDocumentPanel(const char* title, bool* open, bool has_document);

// The main menu bar and the global shortcuts (Ctrl+N, Ctrl+O, Ctrl+S, Ctrl+Z, Ctrl+Shift+Z, Ctrl+Q, F12,
// Delete, Ctrl+D, and the tool keys Q / B / S / E), ignored while ImGui has the keyboard.
void drawMainMenu(const MenuView& view, UiRequests* requests, ToolState* tools, WindowToggles* windows);
void drawStatisticsPanel(const StatisticsView& view, bool* open);
// Tool bar and brush settings; type names index the brush's per-type mix. With the Sculpt tool, the pile
// type's angle of repose is the document's (one undo step a drag); refusals go to *message.
void drawToolsPanel(Document* doc, const std::vector<std::string>& type_names, ToolState* state,
                    std::string* message, bool* open);
// The selected primitive's centre, radius and weight; every finished edit is one SetPrimitive (one undo
// step). Errors go to *message.
void drawInspector(Document* doc, const std::vector<std::string>& type_names, ToolState* state,
                   UiRequests* requests, std::string* message, bool* open);

// ---- Ghost Tile panel (ghost_tile_panel.cpp) ----
// The panel edits a pending copy of the project's Ghost Tile settings; the document keeps its tile until
// a build started from the panel finishes and the main loop applies it (one undo step).
struct GhostTilePanelState {
    GhostTileSpec pending;        // the edited copy
    GhostTileSpec synced;         // the document's settings when `pending` was last taken from it
    const Document* synced_doc = nullptr;
    uint64_t synced_generation = 0;  // the document's tileGeneration() then
    int selected_type = 0;
    // Set by the main loop: the job in flight.
    bool running = false;
    float progress = 0.0f;
    std::string last_outcome;     // "built in 0.42 s", "cancelled", "failed: ..."
    // Raised by the panel, cleared by the main loop.
    bool build = false;           // start a job on `pending`
    bool cancel = false;
};
// Fields per detail type (model file, model scale and axes, anchors, candidate count, orientation
// distribution, scale range, positions) and the tile (size, δ, seed); Build / Cancel with a progress bar,
// Revert; statistics of the document's tile; the selected type's collision spheres in three orthographic
// views (ImGui draw list).
void drawGhostTilePanel(const Document* doc, GhostTilePanelState* state, bool* open);

// ---- particles panel (particles_panel.cpp) ----
struct ParticlesPanelState {
    size_t selected = 0;     // the system shown
    ParticleHandle selected_handle;  // picked in the viewport (an attractor, generator or cutter), or none
    glm::vec3 place_at{0.0f};        // where Add puts a new part: the ground under the view's centre
    ParticlePart placing = ParticlePart::None;  // armed: the next left click in the view places one there
    // Clicks also meet the detail instances (rocks, not the ground under the grass): a generator placed
    // on one grows on its type's instances there (addDetailsGenerator).
    bool place_on_details = false;
    bool growing = false;    // its strands are growing in the background
    float progress = 0.0f;   // of that growth, [0, 1]
    bool can_cancel = false;        // the growth is for an edit that Cancel would undo
    bool cancel_requested = false;  // Cancel pressed: the session stops the growth and undoes the edit
    std::string status;      // the last growth: strands, time, share re-grown
    std::string last_error;  // the last refused edit
    // The copy the widgets edit: taken from the document whenever no widget is active, so a field being
    // typed keeps its text and a drag its value between frames.
    ParticleSystemFile editing;
    ParticleSystemRef editing_entry;  // its entry in the project's list: name and offset
    const Document* editing_doc = nullptr;
    size_t editing_index = SIZE_MAX;
};
// The project's particle systems: generators, attractors (with a(t)), cutters and the walk of the selected
// one, edited through Document::setParticleSystem (a drag is one undo step); refusals go to *message.
void drawParticlesPanel(Document* doc, ParticlesPanelState* state, std::string* message, bool* open);

// ---- environment panel (environment_panel.cpp) ----
constexpr int kPaletteThumbnailPx = 96;  // the palette's pictures (drawn at half size)

struct EnvironmentPanelState {
    EnvPath selected;            // a node of the tree (empty: none); the Outliner's too
    std::vector<EnvPath> hidden; // nodes hidden in the view by the Outliner's eyes (view only)
    bool brush_on = false;       // a weather brush: a left drag on the ground stamps it (env_tools.h)
    WeatherSettings weather;
    ChannelMapSettings view;     // the channel view (channel_map.h); its legend's ends from the last map
    float view_lo = 0.0f, view_hi = 0.0f;
    bool computing = false;      // the effects are being computed in the background
    std::string status;          // the last computation: snow, icicles, time
    std::string last_error;      // the last refused edit
    int add_type = 0;            // the palette's choice
    std::vector<uint64_t> thumbnails;  // per type: its picture (a texture for ImGui::Image; 0: none)
    bool placing = false;        // the next left click in the view places the palette's type there
    glm::vec3 place_at{0.0f};    // where Add places an object: the ground under the view's centre
    // The copy the widgets edit (as for the Particles window).
    EnvironmentDesc editing;
    const Document* editing_doc = nullptr;
};
// The environmental objects: the global fields (snow depth, temperature, humidity, ...) live, the tree's
// top level with the selected node's transform, add from the type palette, duplicate, delete, and the
// footprint brush's switch; every edit through Document::setEnvironment (a drag is one undo step).
void drawEnvironmentPanel(Document* doc, EnvironmentPanelState* state, std::string* message, bool* open);

// LOD thresholds (pixels), overlay toggles and the renderer's numbers (from the Statistics view).
void drawRenderPanel(const StatisticsView& stats, RenderSettings* settings, bool* open);

// Modal dialogs. Each returns its answer once (then closes), else Pending.
enum class DialogAnswer { Pending, Yes, No, Cancel };
// "An autosave of PATH is newer than the file. Recover it?" Yes: recover; No: open the file, drop it.
DialogAnswer drawRecoveryDialog(const std::string& path, const std::string& saved_when);
// "Save changes to PATH?" Yes: save; No: discard; Cancel: keep editing.
DialogAnswer drawUnsavedDialog(const std::string& path, const std::string& what);
// The Save As path field; *open turns false when closed; Yes puts the path in *path.
DialogAnswer drawSaveAsDialog(bool* open, std::string* path);
// The Open path field (no native file dialog): like Save As; Yes puts the path in *path.
DialogAnswer drawOpenDialog(bool* open, std::string* path);
// Errors: a window listing them with a Dismiss button (clears the list).
void drawMessages(std::vector<std::string>* messages);

}  // namespace ug::editor
