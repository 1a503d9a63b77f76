// The editor's session: a window on a Document (document.h), opened in the background, edited with the
// tools (tools.h), instantiated live, saved and autosaved. `undergrowth edit` runs it interactively or
// scripted (a replay script of tool actions, a number of frames, a screenshot and the statistics), and
// `undergrowth bench` runs it scripted to time the renderer and the live loop.
//
//   ViewerOptions options{.scene_path = "assets/scenes/meadow.json", .frames = 30};
//   ViewerResult result;
//   switch (runViewer(options, &result, &error)) { ... }
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "editor/render_data.h"
#include "editor/replay.h"

namespace ug::editor {

enum class RecoverChoice { Ask, Yes, No };

struct ViewerOptions {
    std::string scene_path;
    std::string cache_dir = "out/cache";
    std::string config_dir;  // recent files and recovery ("" = neither; the CLI passes defaultConfigDir())
    int threads = 0;
    int width = 1280;
    int height = 720;
    // 0: interactive until the window closes. N > 0: scripted; runs the replay (if any), waits until the
    // live instancer is idle and its result on screen, renders N more frames, writes the screenshot (when
    // a path is given) and returns. Scripted runs never show a modal dialog.
    int frames = 0;
    std::string screenshot_path;  // scripted: written after the last frame; interactive: File > Screenshot
    bool finish_each_frame = false;  // glFinish every frame (frame times then include the GPU's work)
    bool quiet = false;
    LodSettings lod;
    ViewportLook look;                 // shadows and ambient occlusion (the Render panel's toggles)
    std::vector<ReplayAction> replay;  // run in order (replay.h)
    // An autosave newer than the file: Ask shows a dialog (interactive; a scripted run opens the file and
    // leaves the autosave alone), Yes recovers it, No opens the file and removes the autosave.
    RecoverChoice recover = RecoverChoice::Ask;
    double autosave_interval_s = 60.0;
    // Interactive runs with a replay write their statistics here when the script is done (and at exit);
    // scripted runs leave writing them to the caller.
    std::string stats_path;
};

struct ViewerResult {
    std::string scene;
    uint64_t instances = 0;
    std::vector<std::string> type_names;
    std::vector<uint64_t> instances_per_type;
    uint64_t instance_store_hash = 0;
    double instantiate_seconds = 0.0;
    int frames_measured = 0;    // frames rendered with the instances on screen
    double frame_ms = 0.0;      // median over those frames (whole loop: events, UI, render, swap)
    double frame_ms_p95 = 0.0;
    uint64_t triangles = 0;     // the last frame's (terrain + detail meshes; not sky, grid or UI)
    uint64_t points = 0;        // the last frame's impostor point sprites
    uint64_t draw_calls = 0;
    std::array<uint64_t, kLodCount> lod_instances{};
    uint64_t tiles_visible = 0;
    uint64_t tiles_culled = 0;
    uint64_t indirect_commands = 0;  // the last frame's commands in its multi-draws (draw_calls counts those)
    uint64_t tiles_resident = 0;
    uint64_t tiles_uploaded = 0;     // the latest live result's upload (tiles re-packed, bytes sent)
    uint64_t bytes_uploaded = 0;
    std::vector<double> upload_tiles;  // tiles uploaded by every incremental (not full) live result
    std::string gl_version;
    std::string renderer;
    int window_width = 0, window_height = 0;
    int framebuffer_width = 0, framebuffer_height = 0;
    std::string screenshot;     // the path written, if any
    // The document and the live loop.
    std::string document_path;
    bool recovered = false;
    bool dirty = false;
    std::string undo_name;  // what Ctrl+Z would undo now ("" for nothing)
    uint64_t user_primitives = 0;
    int autosaves = 0;
    std::vector<double> stamp_to_frame_ms;  // every stamp: from the edit to the end of the frame showing it
    // Every environment edit (a drag step, a weather stamp): from the edit to the end of the first frame
    // showing its effects, by what made it ("env_move", "footprints", "weather_stroke", "mouse").
    std::map<std::string, std::vector<double>> env_stamp_to_frame_ms;
    // Every swap of the static meshes (an environment result shown, objects hidden or shown): the entries
    // uploaded and those whose buffers were kept.
    std::vector<std::array<uint64_t, 2>> static_swaps;
    double repack_ms_max = 0.0;             // the slowest CPU re-pack of a live result's tiles for the GPU
    double tile_update_ms_max = 0.0;  // the slowest incremental one (changed tiles re-packed and uploaded)
    nlohmann::json actions = nlohmann::json::array();  // per replay action (viewer.cpp, "Statistics")
    // Mouse sculpt strokes, in order: each one's pile (viewer.cpp pileRecord) measured as it was released.
    nlohmann::json sculpt_strokes = nlohmann::json::array();
    std::vector<std::string> messages;      // errors shown in the UI
    // The viewport as the user sees it (viewer.cpp viewportJson): the camera, the eye's ground height, the
    // cursor, the ground point under it, the brush ring's screen centre, the active tool, the Statistics
    // panel's document name, whether ImGui has the keyboard. Interactive runs with --stats rewrite the
    // statistics on F12 too, so a driven session can read it after each step.
    nlohmann::json viewport = nlohmann::json::object();
    // The particle systems as the document holds them ({"systems": [{"name", "attractors", "generators",
    // "cutters": [[x, y, z]] centres, "charge_keys": per attractor [[step, charge]]}], "selected_attractor",
    // "selected_handle": {"part", "index"}, "handles_px": the open window's dots on screen [{"part", "index",
    // "px"}], "strands_settled", "last": the last growth's statistics}); {}
    // without any.
    nlohmann::json particles = nlohmann::json::object();
    nlohmann::json environment = nlohmann::json::object();  // the environmental objects (none: empty)
    std::string window_title;
};

enum class ViewerStatus { Ok, NoDisplay, Failed };

// NoDisplay: no window could be opened (no X server / DISPLAY); Failed: the scene failed to load in a
// scripted run, a shader failed, or a scripted screenshot could not be written — *error says which.
ViewerStatus runViewer(const ViewerOptions& options, ViewerResult* result, std::string* error);

// The --stats file of `undergrowth edit`.
nlohmann::json viewerStatsJson(const ViewerResult& result, const LodSettings& lod);

double percentile(std::vector<double> values, double q);  // nearest rank; 0 for none

}  // namespace ug::editor
