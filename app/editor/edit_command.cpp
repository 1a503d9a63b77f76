// `undergrowth edit SCENE.json`: the editor's window on a scene; with --frames N a scripted run for tests
// and users (N frames once the instances are in, then the screenshot and the statistics).
#include <cstdio>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "scene/document.h"
#include "editor/viewer.h"

namespace ug::cli {

namespace {

int fail(const std::string& message, int code = 1) {
    std::fprintf(stderr, "undergrowth edit: %s\n", message.c_str());
    return code;
}

// "1280x720": two whole numbers in [64, 8192].
bool parseSize(const std::string& text, int* width, int* height, std::string* error) {
    const size_t x = text.find('x');
    long w = 0, h = 0;
    if (x == std::string::npos || !parseInt("--size", text.substr(0, x), 64, 8192, &w, error) ||
        !parseInt("--size", text.substr(x + 1), 64, 8192, &h, error)) {
        *error = "--size: expected WIDTHxHEIGHT, each in [64, 8192], got '" + text + "'";
        return false;
    }
    *width = int(w);
    *height = int(h);
    return true;
}

}  // namespace

int runEditCommand(int argc, char** argv) {
    const char* usage =
        "usage: undergrowth edit SCENE.json [--frames N] [--screenshot OUT.png] [--stats STATS.json] [--size WxH]\n"
        "       [--threads N] [--cache DIR] [--config DIR] [--replay SCRIPT.json] [--recover yes|no]\n"
        "       [--autosave-interval SECONDS] [--no-shadows] [--no-ao]";
    Args args;
    std::string error;
    if (!parseArgs(argc, argv, 2, {"--frames", "--screenshot", "--stats", "--size", "--threads", "--cache", "--config", "--replay",
                    "--recover", "--autosave-interval"}, {"--no-shadows", "--no-ao"}, &args,
                   &error) ||
        args.positional.size() != 1)
        return fail(error.empty() ? usage : error + "\n" + usage, 2);
    editor::ViewerOptions options;
    options.scene_path = args.positional[0];
    options.cache_dir = args.get("--cache", options.cache_dir);
    options.screenshot_path = args.get("--screenshot");
    options.look.shadows = !args.has("--no-shadows");
    options.look.ambient_occlusion = !args.has("--no-ao");
    long value = 0;
    if (args.has("--frames")) {
        if (!parseInt("--frames", args.get("--frames"), 1, 1000000, &value, &error)) return fail(error, 2);
        options.frames = int(value);
        // Scripted runs time their frames: include the GPU's work in each.
        options.finish_each_frame = true;
    }
    if (args.has("--threads")) {
        if (!parseInt("--threads", args.get("--threads"), 0, 256, &value, &error)) return fail(error, 2);
        options.threads = int(value);
    }
    if (args.has("--size") && !parseSize(args.get("--size"), &options.width, &options.height, &error))
        return fail(error, 2);
    options.config_dir = args.has("--config") ? args.get("--config") : defaultConfigDir();
    if (args.has("--recover")) {
        const std::string r = args.get("--recover");
        if (r != "yes" && r != "no") return fail("--recover: expected yes or no, got '" + r + "'", 2);
        options.recover = r == "yes" ? editor::RecoverChoice::Yes : editor::RecoverChoice::No;
    }
    if (args.has("--autosave-interval")) {
        if (!parseInt("--autosave-interval", args.get("--autosave-interval"), 1, 86400, &value, &error))
            return fail(error, 2);
        options.autosave_interval_s = double(value);
    }
    if (args.has("--replay") && !editor::loadReplayScript(args.get("--replay"), &options.replay, &error))
        return fail(error);
    if (args.has("--stats") && options.frames == 0 && !args.has("--replay"))
        return fail("--stats needs --frames N or --replay SCRIPT (the statistics of a scripted run)", 2);
    // Interactive runs with a replay write the statistics themselves when the script is done.
    if (args.has("--stats") && options.frames == 0) options.stats_path = args.get("--stats");

    editor::ViewerResult result;
    switch (editor::runViewer(options, &result, &error)) {
        case editor::ViewerStatus::Ok: break;
        case editor::ViewerStatus::NoDisplay: return fail(error);
        case editor::ViewerStatus::Failed: return fail(error);
    }
    if (options.frames > 0)
        std::fprintf(stderr, "edit: %llu instances, %d frames, median %.1f ms, %llu triangles, %llu draws (%s)\n",
                     (unsigned long long)result.instances, result.frames_measured, result.frame_ms,
                     (unsigned long long)result.triangles, (unsigned long long)result.draw_calls, result.renderer.c_str());
    if (!result.screenshot.empty()) std::fprintf(stderr, "edit: wrote %s\n", result.screenshot.c_str());
    for (const std::string& m : result.messages) std::fprintf(stderr, "edit: message: %s\n", m.c_str());
    if (args.has("--stats") && options.frames > 0) {
        const std::string path = args.get("--stats");
        if (!writeTextFileAtomically(path, editor::viewerStatsJson(result, options.lod).dump(2) + "\n", &error)) return fail(error);
        std::fprintf(stderr, "edit: wrote %s\n", path.c_str());
    }
    return 0;
}

}  // namespace ug::cli
