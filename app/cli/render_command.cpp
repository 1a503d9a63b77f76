// `undergrowth render SCENE -o PICTURE.png`: a picture of the scene without any display (EGL, no X server),
// for batch jobs and documentation. The scene is opened, instantiated and settled as the editor does it and
// drawn by the editor's renderer from the editor's default view (or --camera); the PNG is the viewport the
// editor would show, without its UI.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <vector>

#include <glm/glm.hpp>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "editor/offscreen_render.h"
#include "editor/screenshot.h"

namespace ug::cli {

namespace fs = std::filesystem;

namespace {

constexpr const char* kUsage =
    "usage: undergrowth render SCENE.json -o PICTURE.png [--camera tx,ty,tz,distance,yaw_deg,pitch_deg]\n"
    "       [--size WxH] [--threads N] [--cache DIR]\n"
    "  --size: each side in [16, 16384], at most 67,108,864 pixels (8192 x 8192); default 1280x720\n"
    "  --camera: orbit target (metres), distance (metres, > 0), yaw (degrees; -90 looks from -Y) and\n"
    "            pitch (degrees above the horizon, in [-89, 89]); default: the editor's opening view";
constexpr long kMaxSide = 16384;
constexpr long kMaxPixels = 8192L * 8192L;  // 256 MiB of RGBA: beyond this a picture is a mistake

int fail(const std::string& message, int code = 1) {
    std::fprintf(stderr, "undergrowth render: %s\n", message.c_str());
    return code;
}
int usageError(const std::string& message) { return fail(message + "\n" + kUsage, 2); }

std::string numberText(double v) {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", v);
    return text;
}

// Six finite numbers: target x, y, z, distance (> 0), yaw and pitch in degrees (pitch within the orbit
// camera's +-89).
bool parseCamera(const std::string& text, editor::OrbitCamera* camera, std::string* error) {
    std::vector<double> v;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        size_t used = 0;
        double d = 0.0;
        try {
            d = std::stod(item, &used);
        } catch (...) {
            used = 0;
        }
        if (used == 0 || used != item.size() || !std::isfinite(d)) {
            *error = "--camera: '" + item + "' is not a finite number";
            return false;
        }
        v.push_back(d);
    }
    if (v.size() != 6 || text.empty() || text.back() == ',') {
        *error = "--camera: expected tx,ty,tz,distance,yaw_deg,pitch_deg (6 numbers), got '" + text + "'";
        return false;
    }
    if (!(v[3] > 0.0 && v[3] <= 1.0e5)) {
        *error = "--camera: the distance must be in (0, 100000] metres, got " + numberText(v[3]);
        return false;
    }
    if (std::abs(v[5]) > 89.0) {
        *error = "--camera: the pitch must be in [-89, 89] degrees, got " + numberText(v[5]);
        return false;
    }
    camera->target = glm::vec3(float(v[0]), float(v[1]), float(v[2]));
    camera->distance_m = float(v[3]);
    camera->yaw_rad = glm::radians(float(v[4]));
    camera->pitch_rad = glm::radians(float(v[5]));
    return true;
}

}  // namespace

int runRenderCommand(int argc, char** argv) {
    Args args;
    std::string error;
    if (!parseArgs(argc, argv, 2, {"-o", "--out", "--camera", "--size", "--threads", "--cache"}, {}, &args, &error))
        return usageError(error);
    if (args.positional.size() != 1)
        return usageError(args.positional.empty() ? "missing SCENE" : "one SCENE only, got " +
                                                                           std::to_string(args.positional.size()));
    const std::string out = args.has("-o") ? args.get("-o") : args.get("--out");
    if (out.empty()) return usageError("missing -o PICTURE.png");
    std::string ext = fs::path(out).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext != ".png") return usageError(out + ": the picture must end in .png");
    editor::OffscreenRenderOptions options;
    options.scene_path = args.positional[0];
    options.cache_dir = args.get("--cache", "out/cache");
    if (args.has("--size")) {
        if (!parseSize("--size", args.get("--size"), 16, kMaxSide, &options.width, &options.height, &error))
            return usageError(error);
        if (long(options.width) * long(options.height) > kMaxPixels)
            return usageError("--size: " + args.get("--size") + " is more than 67,108,864 pixels (8192 x 8192)");
    }
    if (args.has("--threads")) {
        long t = 0;
        if (!parseInt("--threads", args.get("--threads"), 0, 256, &t, &error)) return usageError(error);
        options.threads = int(t);
    }
    if (args.has("--camera")) {
        editor::OrbitCamera camera;
        if (!parseCamera(args.get("--camera"), &camera, &error)) return usageError(error);
        options.camera = camera;
    }

    editor::OffscreenRenderResult result;
    switch (editor::renderSceneOffscreen(options, &result, &error)) {
        case editor::OffscreenRenderStatus::Ok: break;
        case editor::OffscreenRenderStatus::NoContext: return fail("cannot render without a display: " + error);
        case editor::OffscreenRenderStatus::Failed: return fail(error);
    }
    if (!editor::writeScreenshot(out, result.width, result.height, result.rgba, &error)) return fail(error);
    const editor::OrbitCamera& c = result.camera;
    std::fprintf(stderr,
                 "render: %llu instances; loaded in %.2f s, instantiated and settled in %.2f s; frame %.1f ms, "
                 "%llu triangles (%s, %s)\n"
                 "render: camera %.3f,%.3f,%.3f,%.3f,%.2f,%.2f\n",
                 (unsigned long long)result.instances, result.load_seconds, result.instantiate_seconds,
                 result.frame_ms.empty() ? 0.0 : result.frame_ms.back(), (unsigned long long)result.triangles,
                 result.renderer.c_str(), result.platform.c_str(), c.target.x, c.target.y, c.target.z,
                 c.distance_m, glm::degrees(c.yaw_rad), glm::degrees(c.pitch_rad));
    std::printf("wrote %s (%dx%d)\n", out.c_str(), result.width, result.height);
    return 0;
}

}  // namespace ug::cli
