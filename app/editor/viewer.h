// The editor's viewport session: a window showing a scene, loaded and instantiated in the background.
// `undergrowth edit` runs it interactively or scripted (a fixed number of frames, a screenshot and the
// statistics), and `undergrowth bench` runs it scripted to time the renderer.
//
//   ViewerOptions options{.scene_path = "assets/scenes/meadow.json", .frames = 30};
//   ViewerResult result;
//   switch (runViewer(options, &result, &error)) { ... }
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "editor/render_data.h"

namespace ug::editor {

struct ViewerOptions {
    std::string scene_path;
    std::string cache_dir = "out/cache";
    int threads = 0;
    int width = 1280;
    int height = 720;
    // 0: interactive until the window closes. N > 0: scripted; waits for the instances, renders N frames
    // of the default view with them, writes the screenshot (when a path is given) and returns.
    int frames = 0;
    std::string screenshot_path;  // scripted: written after the last frame; interactive: File > Screenshot
    bool finish_each_frame = false;  // glFinish every frame (frame times then include the GPU's work)
    bool quiet = false;
    LodSettings lod;
};

struct ViewerResult {
    std::string scene;
    uint64_t instances = 0;
    std::vector<std::string> type_names;
    std::vector<uint64_t> instances_per_type;
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
    std::string gl_version;
    std::string renderer;
    int window_width = 0, window_height = 0;
    int framebuffer_width = 0, framebuffer_height = 0;
    std::string screenshot;     // the path written, if any
};

enum class ViewerStatus { Ok, NoDisplay, Failed };

// NoDisplay: no window could be opened (no X server / DISPLAY); Failed: the scene failed to load, a
// shader failed, or the screenshot could not be written — *error says which.
ViewerStatus runViewer(const ViewerOptions& options, ViewerResult* result, std::string* error);

// The --stats file of `undergrowth edit`.
nlohmann::json viewerStatsJson(const ViewerResult& result, const LodSettings& lod);

}  // namespace ug::editor
