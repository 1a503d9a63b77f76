#include "editor/offscreen_render.h"

#include <chrono>

#include "editor/default_view.h"
#include "editor/gl/offscreen_context.h"
#include "editor/gl/renderer.h"
#include "editor/gl/shader_program.h"
#include "editor/scene_snapshot.h"
#include "editor/tools.h"

namespace ug::editor {

OffscreenRenderStatus renderSceneOffscreen(const OffscreenRenderOptions& options, OffscreenRenderResult* result,
                                           std::string* error) {
    *result = OffscreenRenderResult{};
    // Declared first, destroyed last: the renderer and the target free GL objects in its context.
    gl::OffscreenContext context;
    if (context.open(error) != gl::OffscreenStatus::Ok) return OffscreenRenderStatus::NoContext;
    result->gl_version = context.glVersion();
    result->renderer = context.rendererName();
    result->platform = context.platform();
    if (options.width > context.maxSize() || options.height > context.maxSize()) {
        *error = std::to_string(options.width) + "x" + std::to_string(options.height) + ": larger than " +
                 result->renderer + " can render (at most " + std::to_string(context.maxSize()) + " a side)";
        return OffscreenRenderStatus::Failed;
    }
    gl::OffscreenTarget target;
    if (!target.create(options.width, options.height, error)) return OffscreenRenderStatus::Failed;
    gl::Renderer renderer;
    if (!renderer.init(gl::shadersDir(), error)) return OffscreenRenderStatus::Failed;

    SceneSnapshot snap;
    SceneSnapshotOptions snap_options;
    snap_options.scene_path = options.scene_path;
    snap_options.cache_dir = options.cache_dir;
    snap_options.threads = options.threads;
    if (!loadSceneSnapshot(snap_options, &snap, error)) return OffscreenRenderStatus::Failed;
    result->load_seconds = snap.load_seconds;
    result->instantiate_seconds = snap.instantiate_seconds;
    result->instances = snap.tiles.instanceCount();
    renderer.setLook(options.look);
    renderer.setScene(snap.extent(), snap.terrain(), &snap.scene.meshes, snap.candidates(), snap.tileSize(),
                      &snap.scene.terrain_material);
    snap.scene.static_meshes.insert(snap.scene.static_meshes.end(), options.extra_static_meshes.begin(),
                                    options.extra_static_meshes.end());
    renderer.setStaticMeshes(&snap.scene.static_meshes);
    renderer.uploadTiles(&snap.tiles, snap.uploads);

    const float aspect = float(options.width) / float(options.height);
    OrbitCamera camera = options.camera ? *options.camera : defaultView(snap.framing(), aspect);
    camera.aspect = aspect;
    // As in the editor, the eye never goes below the ground (a --camera given low over a hill, or an orbit
    // turning it behind one): from under the terrain the picture is the sky seen through its underside.
    const auto ground = [&snap](glm::vec2 xy) { return groundHeightAt(*snap.scene.doc, xy); };
    for (int frame = 0; frame < options.frames; ++frame) {
        if (frame > 0) camera.yaw_rad += glm::radians(options.orbit_deg_per_frame);
        if (keepEyeAboveGround(&camera, ground)) ++result->eye_raised_frames;
        const auto t0 = std::chrono::steady_clock::now();
        target.bind();
        renderer.render(camera, options.width, options.height, options.lod);
        context.finish();
        result->frame_ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        const gl::RenderStats& frame_stats = renderer.stats();
        if (frame_stats.shadow_map_draws > 0) {
            ++result->shadow_map_draws;
            result->shadow_triangles = frame_stats.shadow_triangles;
            result->shadow_points = frame_stats.shadow_points;
        }
    }
    result->camera = camera;  // the last frame's: the picture's
    const gl::RenderStats& rs = renderer.stats();
    result->triangles = rs.triangles;
    result->points = rs.points;
    result->draw_calls = rs.draw_calls;
    result->lod_instances = rs.lod_instances;
    target.readPixels(&result->rgba);
    result->width = options.width;
    result->height = options.height;
    // The snapshot (declared after the renderer) goes first: the renderer forgets what points into it now.
    renderer.clearScene();
    return OffscreenRenderStatus::Ok;
}

}  // namespace ug::editor
