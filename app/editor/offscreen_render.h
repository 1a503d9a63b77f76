// A scene rendered to pixels with no display (`undergrowth render`, the bench's render rows without a
// window): an EGL context (gl/offscreen_context.h), the scene prepared as the editor prepares it
// (scene_snapshot.h), the viewport renderer drawing into a framebuffer object, and the pixels read back.
// The picture is the editor's viewport without the UI: same renderer, same default view (default_view.h).
//
//   OffscreenRenderOptions options{.scene_path = "assets/scenes/meadow.json", .width = 1280, .height = 720};
//   OffscreenRenderResult result;
//   switch (renderSceneOffscreen(options, &result, &error)) { ... }   // result.rgba: rows top-down
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "editor/orbit_camera.h"
#include "editor/render_data.h"

namespace ug::editor {

struct OffscreenRenderOptions {
    std::string scene_path;
    std::string cache_dir = "out/cache";
    int threads = 0;
    int width = 1280;
    int height = 720;
    std::optional<OrbitCamera> camera;  // none: the default view (default_view.h); its aspect is replaced
    int frames = 1;  // frames rendered and timed (each ends with glFinish); the picture is the last one's
    // Each frame after the first turns the camera this far about its target (yaw): an orbit drag, whose
    // frames cannot reuse what a still view keeps (the bench's orbit row).
    float orbit_deg_per_frame = 0.0f;
    LodSettings lod;
    ViewportLook look;
    // Drawn with the scene's own static meshes (`render --particles`: strand tubes), names unique.
    std::vector<MeshInstances> extra_static_meshes;
};

struct OffscreenRenderResult {
    std::vector<uint8_t> rgba;  // width x height RGBA8, rows top-down
    int width = 0, height = 0;
    OrbitCamera camera;         // the camera used
    int eye_raised_frames = 0;  // frames whose eye was under the ground and was raised above it (keepEyeAboveGround)
    uint64_t instances = 0;
    uint64_t triangles = 0;     // the last frame's (terrain + static meshes + detail meshes)
    uint64_t points = 0;        // the last frame's impostor point sprites
    uint64_t draw_calls = 0;
    std::array<uint64_t, kLodCount> lod_instances{};
    double load_seconds = 0.0;         // the document: models, Ghost Tile, terrain mesh, LODs
    double instantiate_seconds = 0.0;  // the settled instantiation, packed
    std::vector<double> frame_ms;      // per frame: render + glFinish (no UI, no swap)
    int shadow_map_draws = 0;          // frames that drew the sun's shadow map (the others kept it)
    uint64_t shadow_triangles = 0, shadow_points = 0;  // what the last of those drew into it
    std::string gl_version, renderer, platform;  // platform: "EGL surfaceless" or "EGL pbuffer"
};

enum class OffscreenRenderStatus {
    Ok,
    NoContext,  // no EGL or no OpenGL 4.3 core context without a display (*error says what to install)
    Failed,     // the scene failed to load, a shader failed, or the size is beyond the context's limit
};

// Contract: width and height in [1, 16384], frames >= 1 (the CLI refuses other values up front).
OffscreenRenderStatus renderSceneOffscreen(const OffscreenRenderOptions& options, OffscreenRenderResult* result,
                                           std::string* error);

}  // namespace ug::editor
