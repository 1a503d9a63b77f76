// The editor's Dear ImGui panels. Panels are functions over plain state (STYLE.md "Panels are functions"):
// they read numbers the renderer and the loader expose and set request flags; they never call GL.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "editor/render_data.h"

namespace ug::editor {

// Requests the panels raise; the main loop acts on them at the right point of the frame.
struct UiRequests {
    bool screenshot = false;  // File > Screenshot: the next frame's viewport is saved
    bool quit = false;        // File > Quit
};

// What the Statistics window shows.
struct StatisticsView {
    std::string scene;
    std::string status;            // "loading scene…", "instantiating… 42 %", "ready", or the error
    bool pending = false;          // background work running
    float progress = 0.0f;
    std::vector<std::string> type_names;
    std::vector<uint64_t> instances_per_type;
    uint64_t instances = 0;
    double instantiate_seconds = 0.0;
    double frame_ms = 0.0;          // the last frame
    double frame_ms_avg = 0.0;      // over the last second or so
    uint64_t triangles = 0;
    uint64_t points = 0;
    uint64_t draw_calls = 0;
    std::array<uint64_t, kLodCount> lod_instances{};
    uint64_t tiles_visible = 0;
    uint64_t tiles_culled = 0;
    std::string gl_version;
    std::string renderer;
    std::string last_message;       // e.g. "saved screenshot.png"
};

void drawMainMenu(UiRequests* requests, bool* show_statistics);
void drawStatisticsPanel(const StatisticsView& view, bool* open);

}  // namespace ug::editor
