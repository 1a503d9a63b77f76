// bench section "render": the meadow's default view at 1280 x 720 in a real window (DESIGN.md quality
// bars: frame <= 40 ms and <= 150k triangles on llvmpipe). Runs only where a display is available
// (DISPLAY set and a window opens, e.g. under xvfb-run); elsewhere it adds no rows and says so.
#include <cstdio>
#include <cstdlib>

#include "cli/bench.h"
#include "editor/viewer.h"

namespace ug::cli {

bool benchRender(const BenchContext& ctx, std::vector<BenchRow>* rows, std::string* error) {
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display) {
        std::fprintf(stderr, "bench: render: skipped, no display (DISPLAY unset; run under xvfb-run)\n");
        return true;
    }
    editor::ViewerOptions options;
    options.scene_path = ctx.assets_dir + "/scenes/meadow.json";
    options.cache_dir = ctx.cache_dir;
    options.threads = ctx.threads;
    options.width = 1280;
    options.height = 720;
    options.frames = ctx.quick ? 20 : 60;
    options.finish_each_frame = true;  // time what the GPU (llvmpipe) does, not only the submission
    options.quiet = true;
    editor::ViewerResult result;
    switch (editor::runViewer(options, &result, error)) {
        case editor::ViewerStatus::Ok: break;
        case editor::ViewerStatus::NoDisplay:
            std::fprintf(stderr, "bench: render: skipped, %s\n", error->c_str());
            error->clear();
            return true;
        case editor::ViewerStatus::Failed: return false;
    }
    const std::string note = std::to_string(result.frames_measured) + " frames, " + std::to_string(result.instances) +
                             " instances, " + result.renderer;
    rows->push_back({"render.meadow.frame_ms", result.frame_ms, "ms", "<= 40", std::nullopt, "median; " + note});
    rows->push_back({"render.meadow.triangles", double(result.triangles), "triangles", "<= 150000", std::nullopt,
                     "per frame, LOD 0/1/2/impostor instances " + std::to_string(result.lod_instances[0]) + "/" +
                         std::to_string(result.lod_instances[1]) + "/" + std::to_string(result.lod_instances[2]) + "/" +
                         std::to_string(result.lod_instances[3])});
    rows->push_back({"render.meadow.draw_calls", double(result.draw_calls), "draws", "", std::nullopt, "scene draws per frame"});
    return true;
}

}  // namespace ug::cli
