// Scripted editor runs (`undergrowth edit SCENE --replay SCRIPT.json`): a JSON list of tool actions, run
// in order through the same code as the mouse (tools.h: BrushStroke on rays straight down onto world XY).
//
//   [{"frame": 5, "action": "paint_stroke", "type": "rock", "points": [[x, y], ...], "radius": 1.5,
//     "strength": 1.0, "falloff": 0.5, "subtract": false},
//    {"action": "paint_stroke", "types": {"rock": 1.0, "pebble": 0.5}, "points": [...]},   a mix
//    {"action": "sculpt_stroke", "type": "rock", "points": [[x, y], ...], "radius": 0.6, "steps": 10,
//     "strength": 1.0},
//    {"action": "sculpt_stroke", ..., "from_camera": true}   the brush's rays come from the camera's eye
//     through the ground under each point (what the mouse does over that point), not straight down
//    {"action": "erase_stroke", "type": "rock", "points": [...], "radius": 1.0, "strength": 1.0},
//    {"action": "paint_stroke", "type": "leaf_oak", "surface": "rock", ...}   paint onto the rock pile
//    {"action": "undo"}, {"action": "redo"}, {"action": "save"}, {"action": "save_as", "path": "out.json"},
//    {"action": "screenshot", "path": "shot.png", "overlays": false, "ui": false},   ui: with the panels
//    {"action": "view", "target": [x, y, z], "distance": 8, "yaw_deg": -90, "pitch_deg": 35},
//    {"action": "move", "from": [x, y], "to": [x, y], "steps": 10},   Select-drag the user primitive whose
//                                                                     centre is nearest `from` (in XY) by to - from
//    {"action": "ghost_tile", "type": "rock", "count": 400, "delta": -0.001, "scale": [0.8, 1.2],
//     "model": "../models/rock.glb", "model_scale": 1.0, "tile_size": 0.5, "seed": 7},   every key but
//     "action" optional; "type" is needed for the per-type ones. Builds the edited Ghost Tile in the
//     background (as the panel's Build) and applies it as one undo step; the action ends when the job has
//     ended and the new tile's result is on screen. Its statistics add "ghost_tile": {"ok", "error" or the
//     tile's "candidates", "pairs", "rho", "build_seconds", "graph_bytes", "bytes_per_pair", "cache",
//     "job_seconds"}. A refused or failed build is reported there and in the messages; the run goes on.
//    {"action": "set_seed", "seed": 42},                                    one undo step
//    {"action": "set_instancing", "type": "rock", "strategy": "elevation", "layer": 0.05,
//     "orientation": {"direction": [0, 0, 1] | "gradient", "max_angle_deg": 30} | false,
//     "size": {"target": 1.0, "tolerance": 0.2} | false},                   only the keys given change
//    {"action": "export", "path": "out.glb", "plain_nodes": false, "chunk": 8},   waits for the file
//    {"action": "open", "path": "other.json"},    waits for the load; a failed one keeps the document
//    {"action": "new"},                           an untitled document from assets/scenes/default.json
//    {"action": "set_visible", "type": "rock", "visible": false},   the outliner's eye (view state only); or
//     "node": 11 (or a path [11, 0]): an environmental node's eye; its statistics add "static_triangles_before"
//     and "static_triangles_after" (the static meshes drawn)
//    {"action": "set_attractor", "system": 0, "attractor": 1, "a_m": [x, y, z], "influence": 0.3,
//     "charge": 1.5},   the Particles window's edit of one attractor (keys but the indices optional; a
//     charge replaces the keys by one), one undo step; ends when the strands re-grown for it are on
//     screen; its statistics add "particles": {"ok", "error"?, "strands", "incremental", "recomputed",
//     "reused", "grow_seconds"}
//    {"action": "env_add", "type": "bench", "at": [x, y], "yaw_deg": 90, "scale": 1},   the Environment
//     window's Add: the type on the ground at (x, y) (or at [x, y, z]: on a pavement; or with "on_surface":
//     true on whatever an object dropped at (x, y) would stand on, as a click in the view places it), one
//     undo step
//    {"action": "env_move", "node": 3, "to": [x, y], "steps": 10},   Select-drag the top-level node (or the
//     node at a path, "node": [1, 0]) over the ground (its height above the ground kept), one step a frame,
//     one undo step
//    {"action": "env_handle", "node": 3, "handle": "turn" | "scale", "to": [x, y], "steps": 10, "snap": false},
//     the selected node's handle in the view (env_handles.h) dragged from where it is to (x, y), one step a
//     frame ("snap": as with Ctrl held), one undo step; its statistics add "yaw_deg" and "scale" (world)
//    {"action": "env_remove", "node": 3},                         Delete, one undo step
//    {"action": "env_global", "channel": "snow", "value": 0.2},   a global field's value (added when the
//     channel has none), one undo step
//    {"action": "weather_stroke", "brush": "warm", "points": [[x, y], ...], "radius": 0.6, "strength": 1},
//     a weather brush (env_tools.h: footprints, warm, cold, wet, leaves, trash, grass, erase) dragged along
//     the polyline, a short step a frame, one undo step; {"action": "footprints", "points": [...]} is the
//     footprint brush's
//     The env_ actions and weather strokes end when the effects computed for them are on screen; their
//     statistics add "environment" (the tree, the fields, the last computation's time and region).
//    {"action": "env_tree", "op": "group" | "ungroup" | "into" | "reusable" | "instance", "node": [1, 0],
//     "group": [2], "name": "stop", "at": [x, y]},   the window's tree edits (env/env_tree_edits.h): a node
//     by its path; "into" moves it into "group"; "reusable" names a top-level group; "instance" places the
//     named group again at (x, y) on the ground. One undo step.
//    {"action": "env_view", "channel": "shelter", "height": 0.3, "surfaces": true},   the Environment window's
//     channel view on the slice at that height and (unless "surfaces" is false) on the objects' surfaces
//     ("off" hides it); view state only; its statistics add "channel_map" {"channel", "lo", "hi", "cells",
//     "surface_triangles"}
//    {"action": "show_window", "window": "environment", "open": true},   a panel opened or closed as by the
//     Window menu (statistics, tools, inspector, ghost_tile, render, outliner, instantiation, export,
//     particles, environment); view state only
//    {"action": "wait_idle"}]
//
// "frame" (optional) is the earliest frame, counted from the first frame that shows the document's
// instances, at which the action may start. Every action also waits until the previous one is finished and
// the live instancer's result for it is on screen (so per-action statistics compare settled states).
// Strokes run one step per frame: a paint or erase stroke moves the brush along the polyline by a little
// more than radius / 3 per frame (one stamp each), a sculpt stroke takes `steps` frames spread evenly along
// the polyline (one point at the same place is a pile growing while the brush is held).
#pragma once

#include <cmath>
#include <glm/glm.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scene/ghost_tile_job.h"
namespace ug {
struct InstancingDesc;
}

namespace ug::editor {

enum class ReplayKind {
    PaintStroke,
    SculptStroke,
    EraseStroke,
    Undo,
    Redo,
    Save,
    SaveAs,
    Screenshot,
    View,
    Move,
    WaitIdle,
    GhostTile,
    SetSeed,
    SetInstancing,
    Export,
    Open,
    New,
    SetVisible,
    SetAttractor,
    EnvAdd,
    EnvMove,
    EnvRemove,
    EnvGlobal,
    Footprints,
    WeatherStroke,
    ShowWindow,
    EnvView,
    EnvTree,
    EnvHandle,
    ParticleEntry
};
constexpr int kReplayKindCount = int(ReplayKind::ParticleEntry) + 1;
const char* replayKindName(ReplayKind kind);  // the "action" string
// The actions that edit the environment (env_add, env_move, env_handle, env_remove, env_global, env_tree,
// footprints, weather_stroke): they end when the effects computed for them are on screen.
bool editsEnvironment(ReplayKind kind);

struct ReplayAction {
    ReplayKind kind = ReplayKind::WaitIdle;
    int frame = -1;                      // earliest frame; -1: as soon as the previous action is done
    std::map<std::string, float> types;  // strokes: type name -> mix weight ("type": name gives weight 1)
    std::vector<glm::vec2> points;       // strokes: world XY, at least one; move: from, to
    float radius_m = 1.0f;
    float strength = 1.0f;
    float falloff_m = 0.5f;
    bool subtract = false;
    int steps = 10;        // sculpt, move: frames
    std::string surface;   // strokes: the type whose pile the brush works on ("": the stroke's last type)
    bool from_camera = false;  // strokes: rays from the camera's eye onto the ground under each point
    std::string path;      // save_as, screenshot
    bool overlays = true;  // screenshot: draw the skeleton overlays
    bool ui = false;       // screenshot: include the panels (read after the UI is drawn)
    // view
    bool has_target = false;
    glm::vec3 target{0.0f};
    float distance_m = -1.0f;  // < 0: keep
    float yaw_deg = NAN, pitch_deg = NAN;
    // ghost_tile: the settings to change (absent ones keep the document's); the type is `types`' key
    struct GhostTileEdit {
        int64_t count = -1;  // < 0: keep
        float delta_m = NAN, tile_size_m = NAN, scale_min = NAN, scale_max = NAN, model_scale = NAN;
        std::string model_path;  // "": keep
        bool has_seed = false;
        uint64_t seed = 0;
    } ghost;
    uint64_t seed = 0;            // set_seed
    std::string type;             // set_instancing, set_visible
    bool visible = true;          // set_visible
    std::string instancing_json;  // set_instancing: the action's object (applyInstancingChanges reads it)
    bool plain_nodes = false;     // export
    float chunk_m = -1.0f;        // export: <= 0 keeps the project's chunk size
    // set_attractor
    size_t system = 0, attractor = 0;
    bool has_a = false;
    glm::vec3 a_m{0.0f};
    float influence_m = NAN, charge = NAN;  // NaN: keep
    bool cancel = false;  // set_attractor: the Particles window's Cancel pressed at once (the edit undone)
    // particle_entry ("system" as above): the entry's name ("name", absent: kept) and offset ("offset_m")
    std::optional<std::string> entry_name;
    std::optional<glm::vec3> entry_offset;
    // env_add (type: `type`, turn: yaw_deg), env_move, env_remove, env_global
    size_t node = 0;        // env_remove
    glm::vec2 at_xy{0.0f};  // env_add: "at"; env_move, env_handle: "to"
    std::string handle;     // env_handle
    bool snap = false;      // env_handle
    float at_z = NAN;       // env_add: "at"'s third value (NaN: on the ground)
    float env_scale = 1.0f; // env_add
    bool on_surface = false;  // env_add: on what an object dropped at (x, y) stands on (a slab, a table);
                              // env_view: the map on the objects' surfaces too
    std::string channel;    // env_global
    std::string brush = "footprints";  // weather_stroke
    std::string window;                // show_window (and `visible`: open or close)
    std::string op, name;              // env_tree (and `at_xy`)
    std::vector<uint32_t> node_path, group_path;  // env_tree; node_path: env_move, env_handle too
    float value = 0.0f;
};

// set_instancing: applies the keys the action gives ("strategy", "layer", "orientation", "size") to *desc;
// the others keep their values. Errors name the key and the reason.
bool applyInstancingChanges(const std::string& action_json, InstancingDesc* desc, std::string* error);

// Reads a script; errors name the file, the action's index and the reason.
bool loadReplayScript(const std::string& path, std::vector<ReplayAction>* out, std::string* error);
// The same from the script's text (`path` names it in errors): the benchmark's scripted runs.
bool parseReplayScript(const std::string& text, const std::string& path, std::vector<ReplayAction>* out,
                       std::string* error);

// A ghost_tile action's edits written into `spec` (ghost_tile_job.h); false when its type is unknown.
bool applyReplayGhostTile(const ReplayAction& action, GhostTileSpec* spec, std::string* error);

// The brush positions (world XY) a stroke visits, one per frame: paint and erase every 1.001 * radius / 3
// along the polyline (and its last point); sculpt `steps` positions evenly spaced along it; move `steps`
// positions from just after `from` to `to`.
std::vector<glm::vec2> strokePath(const ReplayAction& action);

}  // namespace ug::editor
