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
#include "particles/particle_output.h"
#include "scene/project.h"
#include "scene/scene_compile.h"
#include "scene/scene_particles.h"

namespace ug::cli {

namespace fs = std::filesystem;

namespace {

constexpr const char* kUsage =
    "usage: undergrowth render SCENE.json -o PICTURE.png [--camera tx,ty,tz,distance,yaw_deg,pitch_deg]\n"
    "       [--size WxH] [--threads N] [--cache DIR] [--no-shadows] [--no-ao] [--frames N] [--orbit DEG]\n"
    "       [--particles PARTICLES.json]   (a particle system's strands drawn into the scene)\n"
    "  --size: each side in [16, 16384], at most 67,108,864 pixels (8192 x 8192); default 1280x720\n"
    "  --camera: orbit target (metres), distance (metres, > 0), yaw (degrees; -90 looks from -Y) and\n"
    "            pitch (degrees above the horizon, in [-89, 89]); default: the editor's opening view;\n"
    "            an eye under the ground is raised above it (the pitch, then the target), as in the editor\n"
    "  --no-shadows, --no-ao: leave out the sun's shadows, the ambient occlusion (faster on llvmpipe)\n"
    "  --frames N: render N frames (1-1000) and report their median time; the picture is the last\n"
    "  --orbit DEG: with --frames, turn the camera DEG degrees about its target each frame (-45 to 45),\n"
    "               as an orbit drag does";
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
    if (!parseNumberList("--camera", text, &v, error)) return false;
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

double medianMs(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
}

// The scene's environment compiled (a scene without one places nothing) and `system` placed among its
// objects (scene/scene_particles.h).
bool placeAmongSceneObjects(const std::string& scene_path, ParticleScene* system, std::string* error) {
    Project project;
    if (!loadProject(scene_path, &project, error)) return false;
    if (project.environment.empty()) return placeAmongObjects(nullptr, system, error);
    std::shared_ptr<const HeightField> terrain;
    if (!loadTerrain(project, &terrain, error)) return false;
    EnvScene env;
    if (!compileEnvScene(project.environment, project.base_dir, scene_path, terrain, &env, error)) return false;
    return placeAmongObjects(&env, system, error);
}

}  // namespace

int runRenderCommand(int argc, char** argv) {
    Args args;
    std::string error;
    if (!parseArgs(argc, argv, 2,
                   {"-o", "--out", "--camera", "--size", "--threads", "--cache", "--frames", "--orbit", "--particles"},
                   {"--no-shadows", "--no-ao"}, &args, &error))
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
    options.look.shadows = !args.has("--no-shadows");
    options.look.ambient_occlusion = !args.has("--no-ao");
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
    if (args.has("--frames")) {
        long f = 0;
        if (!parseInt("--frames", args.get("--frames"), 1, 1000, &f, &error)) return usageError(error);
        options.frames = int(f);
    }
    if (args.has("--orbit")) {
        std::vector<double> deg;
        if (!parseNumberList("--orbit", args.get("--orbit"), &deg, &error)) return usageError(error);
        if (deg.size() != 1 || !(std::fabs(deg[0]) <= 45.0))
            return usageError("--orbit: expected one number of degrees in [-45, 45], got '" + args.get("--orbit") + "'");
        // One frame never turns: the flag would be ignored without a word.
        if (options.frames < 2) return usageError("--orbit: turns the camera between frames: give --frames 2 or more");
        options.orbit_deg_per_frame = float(deg[0]);
    }
    if (args.has("--camera")) {
        editor::OrbitCamera camera;
        if (!parseCamera(args.get("--camera"), &camera, &error)) return usageError(error);
        options.camera = camera;
    }

    if (args.has("--particles")) {
        // A particle system's strands drawn into the scene, as `grow` exports them.
        const std::string path = args.get("--particles");
        ParticleSystemFile system;
        Strands strands;
        if (!loadParticleSystem(path, &system, &error)) return fail(error);
        // Among the scene's environmental objects, as the scene's own systems grow (its terrain stays out:
        // the figures' samples grow over it, not on it).
        if (!placeAmongSceneObjects(options.scene_path, &system.scene, &error)) return fail(path + ": " + error);
        if (!appendParticleSystemMeshes(system, options.threads, &strands, &options.extra_static_meshes, &error))
            return fail(path + ": " + error);
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
                 "render: %llu instances; loaded in %.2f s, instantiated and settled in %.2f s; frame %.1f ms "
                 "(median of %zu), %llu triangles (%s, %s)\n"
                 "render: the sun's shadow map drawn in %d of %zu frames (%llu triangles, %llu sprites)\n"
                 "render: camera %.3f,%.3f,%.3f,%.3f,%.2f,%.2f\n",
                 (unsigned long long)result.instances, result.load_seconds, result.instantiate_seconds,
                 medianMs(result.frame_ms), result.frame_ms.size(), (unsigned long long)result.triangles,
                 result.renderer.c_str(), result.platform.c_str(), result.shadow_map_draws, result.frame_ms.size(),
                 (unsigned long long)result.shadow_triangles, (unsigned long long)result.shadow_points,
                 c.target.x, c.target.y, c.target.z,
                 c.distance_m, glm::degrees(c.yaw_rad), glm::degrees(c.pitch_rad));
    if (result.eye_raised_frames > 0)
        std::fprintf(stderr,
                     "render: the eye was under the ground in %d of %zu frames and was raised above it, as the "
                     "editor does (the camera above is the last frame's)\n",
                     result.eye_raised_frames, result.frame_ms.size());
    std::printf("wrote %s (%dx%d)\n", out.c_str(), result.width, result.height);
    return 0;
}

}  // namespace ug::cli
