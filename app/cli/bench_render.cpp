// bench section "render": the meadow's default view at 1280 x 720 in a window (docs/architecture.md quality
// bars: frame <= 40 ms and <= 150k triangles on llvmpipe). Runs only where a display is available
// (DISPLAY set and a window opens, e.g. under xvfb-run); elsewhere it adds no rows and says so.
// editor.stamp_to_frame_p95_ms: a replayed paint stroke of 40 stamps across the meadow (rock, 1.5 m brush,
// a stamp every 0.5 m), each timed from the edit to the end of the first frame showing its instances
// (viewer.cpp); target: docs/architecture.md "brush stamp -> frame showing it, llvmpipe"; this row: <= 50 ms.
// editor.stamp_upload_tiles_p50: tiles whose resident slots a live result of that stroke re-uploaded.
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

    editor::ReplayAction stroke;
    stroke.kind = editor::ReplayKind::PaintStroke;
    stroke.frame = 2;
    stroke.types["rock"] = 1.0f;
    stroke.radius_m = 1.5f;
    stroke.points = {glm::vec2(-10.0f, -9.0f), glm::vec2(10.0f, -9.0f)};  // 20 m / 0.5 m: 40 stamps
    options.replay = {stroke};
    options.frames = 5;
    options.config_dir.clear();  // no autosave or recent files from a benchmark
    editor::ViewerResult edit;
    if (editor::runViewer(options, &edit, error) != editor::ViewerStatus::Ok) return false;
    rows->push_back({"editor.stamp_to_frame_p95_ms", editor::percentile(edit.stamp_to_frame_ms, 0.95), "ms", "<= 50",
                     std::nullopt,
                     std::to_string(edit.stamp_to_frame_ms.size()) + " stamps, p50 " +
                         std::to_string(editor::percentile(edit.stamp_to_frame_ms, 0.5)).substr(0, 5) +
                         " ms, frame median " + std::to_string(edit.frame_ms).substr(0, 5) + " ms"});
    // Per-tile residency: an incremental live result re-uploads only the tiles it changed.
    rows->push_back({"editor.stamp_upload_tiles_p50", editor::percentile(edit.upload_tiles, 0.5), "tiles", "",
                     std::nullopt,
                     "tiles re-uploaded per incremental live result during the stroke, of " +
                         std::to_string(edit.tiles_resident) + " resident"});
    return true;
}

}  // namespace ug::cli
