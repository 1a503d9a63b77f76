// The flat main loop of STYLE.md: poll -> new UI frame -> navigation and panels -> apply finished
// background work -> render -> (screenshot) -> UI on top -> swap.
#include "editor/viewer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <imgui.h>
#include <stb_image_write.h>

#include "editor/gl/renderer.h"
#include "editor/gl/window.h"
#include "editor/navigation.h"
#include "editor/orbit_camera.h"
#include "editor/panels.h"
#include "editor/scene_loader.h"

namespace ug::editor {

namespace {

bool writeScreenshot(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba, std::string* error) {
    // RGB: the default framebuffer of a 24-bit visual has no meaningful alpha.
    std::vector<uint8_t> rgb(size_t(width) * size_t(height) * 3);
    for (size_t i = 0, n = size_t(width) * size_t(height); i < n; ++i) {
        rgb[i * 3 + 0] = rgba[i * 4 + 0];
        rgb[i * 3 + 1] = rgba[i * 4 + 1];
        rgb[i * 3 + 2] = rgba[i * 4 + 2];
    }
    std::error_code ec;
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);
    if (!stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3)) {
        *error = path + ": cannot write the screenshot";
        return false;
    }
    return true;
}

// What "frame all" frames: the cells that hold instances once they are in (a scene's extent is often a
// conservative bound much larger than what fills), else the terrain's surface when there is one (the
// extent pads it by metres above and below), else the extent.
Bounds framingBounds(const SceneData& d, bool instances_ready) {
    if (instances_ready && !d.instances.tile_coord.empty()) {
        const float s = d.instances.tile_size_m;
        Bounds b{glm::vec3(1e30f), glm::vec3(-1e30f)};
        for (const glm::ivec3& t : d.instances.tile_coord) {
            b.lo = glm::min(b.lo, glm::vec3(t) * s);
            b.hi = glm::max(b.hi, glm::vec3(t + 1) * s);
        }
        return b;
    }
    if (!d.has_terrain) return d.job.compiled.extent;
    const Bounds3 b = meshBounds(d.terrain);
    return Bounds{b.min, b.max};
}

double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t i = std::min(v.size() - 1, size_t(q * double(v.size() - 1) + 0.5));
    return v[i];
}

}  // namespace

ViewerStatus runViewer(const ViewerOptions& options, ViewerResult* result, std::string* error) {
    const bool scripted = options.frames > 0;
    gl::Window window;
    gl::WindowOptions window_options;
    window_options.width = options.width;
    window_options.height = options.height;
    window_options.vsync = !scripted;
    switch (window.open(window_options, error)) {
        case gl::OpenStatus::Ok: break;
        case gl::OpenStatus::NoDisplay: return ViewerStatus::NoDisplay;
        case gl::OpenStatus::Failed: return ViewerStatus::Failed;
    }
    gl::Renderer renderer;
    if (!renderer.init(gl::shadersDir(), error)) return ViewerStatus::Failed;

    SceneLoader loader({.scene_path = options.scene_path, .cache_dir = options.cache_dir, .threads = options.threads,
                        .quiet = options.quiet});
    OrbitCamera camera;
    camera.aspect = float(options.width) / float(options.height);
    UiRequests requests;
    bool show_statistics = true;
    bool scene_uploaded = false, instances_uploaded = false, camera_moved = false;
    StatisticsView view;
    view.scene = options.scene_path;
    view.gl_version = window.glVersion();
    view.renderer = window.rendererName();
    std::vector<double> frame_ms;
    std::vector<uint8_t> pixels;
    int screenshot_count = 0;
    auto last_frame_end = std::chrono::steady_clock::now();

    *result = ViewerResult{};
    result->scene = options.scene_path;
    result->gl_version = window.glVersion();
    result->renderer = window.rendererName();
    result->window_width = options.width;
    result->window_height = options.height;

    while (!window.shouldClose()) {
        const auto frame_start = std::chrono::steady_clock::now();
        window.pollEvents();
        int fb_w = 0, fb_h = 0;
        window.framebufferSize(&fb_w, &fb_h);
        if (fb_w <= 0 || fb_h <= 0) continue;  // minimised
        camera.aspect = float(fb_w) / float(fb_h);

        // Apply finished background work at the frame boundary.
        const LoadPhase phase = loader.phase();
        if (!scene_uploaded && (phase == LoadPhase::Instantiating || phase == LoadPhase::Ready)) {
            const SceneData& d = loader.data();
            renderer.setScene(d.job.compiled.extent, d.has_terrain ? &d.terrain : nullptr, &d.meshes,
                              d.job.tile.candidates, d.job.tile.settings.tile_size_m);
            frameBounds(framingBounds(d, false), &camera);
            for (const DetailLodMesh& m : d.meshes) view.type_names.push_back(m.name);
            view.instances_per_type.assign(d.meshes.size(), 0);
            scene_uploaded = true;
        }
        if (!instances_uploaded && phase == LoadPhase::Ready) {
            const SceneData& d = loader.data();
            renderer.setInstances(&d.instances);
            view.instances = d.instances.instanceCount();
            view.instances_per_type = d.instances.instances_per_type;
            view.instantiate_seconds = d.stats.seconds;
            instances_uploaded = true;
            // Frame what was instantiated, unless the user already moved the camera.
            if (!camera_moved) frameBounds(framingBounds(d, true), &camera);
        }
        if (phase == LoadPhase::Failed && scripted) {
            *error = loader.error();
            return ViewerStatus::Failed;
        }
        view.pending = phase == LoadPhase::Loading || phase == LoadPhase::Instantiating;
        view.progress = loader.progress();
        view.status = phase == LoadPhase::Loading         ? "loading scene\xE2\x80\xA6"
                      : phase == LoadPhase::Instantiating ? "instantiating\xE2\x80\xA6"
                      : phase == LoadPhase::Ready         ? "ready"
                                                          : "error: " + loader.error();

        window.beginUiFrame();
        if (scene_uploaded && !scripted)
            camera_moved |= navigate(&camera, framingBounds(loader.data(), instances_uploaded), float(fb_h));
        drawMainMenu(&requests, &show_statistics);
        drawStatisticsPanel(view, &show_statistics);

        renderer.render(camera, fb_w, fb_h, options.lod);
        const gl::RenderStats& rs = renderer.stats();
        view.triangles = rs.triangles;
        view.points = rs.points;
        view.draw_calls = rs.draw_calls;
        view.lod_instances = rs.lod_instances;
        view.tiles_visible = rs.tiles_visible;
        view.tiles_culled = rs.tiles_culled;

        // The screenshot is the viewport alone, read before the UI is drawn over it.
        const bool last_scripted_frame = scripted && instances_uploaded && int(frame_ms.size()) + 1 >= options.frames;
        if (requests.screenshot || (last_scripted_frame && !options.screenshot_path.empty())) {
            std::string path = options.screenshot_path;
            if (path.empty() || (!scripted && screenshot_count > 0))
                path = std::filesystem::path(options.scene_path).stem().string() + "-screenshot-" +
                       std::to_string(++screenshot_count) + ".png";
            else
                ++screenshot_count;
            renderer.readPixels(fb_w, fb_h, &pixels);
            std::string write_error;
            if (writeScreenshot(path, fb_w, fb_h, pixels, &write_error)) {
                view.last_message = "saved " + path;
                result->screenshot = path;
            } else {
                view.last_message = write_error;
                if (scripted) {
                    *error = write_error;
                    return ViewerStatus::Failed;
                }
            }
            requests.screenshot = false;
        }
        window.renderUi();
        if (options.finish_each_frame) window.finish();
        window.swapBuffers();

        const auto frame_end = std::chrono::steady_clock::now();
        const double ms = std::chrono::duration<double, std::milli>(frame_end - frame_start).count();
        view.frame_ms = std::chrono::duration<double, std::milli>(frame_end - last_frame_end).count();
        view.frame_ms_avg = view.frame_ms_avg == 0.0 ? view.frame_ms : 0.95 * view.frame_ms_avg + 0.05 * view.frame_ms;
        last_frame_end = frame_end;
        if (instances_uploaded) {
            frame_ms.push_back(ms);
            result->triangles = rs.triangles;
            result->points = rs.points;
            result->draw_calls = rs.draw_calls;
            result->lod_instances = rs.lod_instances;
            result->tiles_visible = rs.tiles_visible;
            result->tiles_culled = rs.tiles_culled;
            result->framebuffer_width = fb_w;
            result->framebuffer_height = fb_h;
            if (scripted && int(frame_ms.size()) >= options.frames) break;
        }
        if (requests.quit) window.requestClose();
    }
    result->frames_measured = int(frame_ms.size());
    result->frame_ms = percentile(frame_ms, 0.5);
    result->frame_ms_p95 = percentile(frame_ms, 0.95);
    if (loader.phase() == LoadPhase::Ready) {
        const SceneData& d = loader.data();
        result->instances = d.instances.instanceCount();
        result->instances_per_type = d.instances.instances_per_type;
        result->instantiate_seconds = d.stats.seconds;
        for (const DetailLodMesh& m : d.meshes) result->type_names.push_back(m.name);
    }
    return ViewerStatus::Ok;
}

nlohmann::json viewerStatsJson(const ViewerResult& r, const LodSettings& lod) {
    nlohmann::json per_type = nlohmann::json::object();
    for (size_t i = 0; i < r.type_names.size(); ++i)
        per_type[r.type_names[i]] = i < r.instances_per_type.size() ? r.instances_per_type[i] : 0;
    return {{"scene", r.scene},
            {"instances", r.instances},
            {"instances_per_type", per_type},
            {"instantiate_seconds", r.instantiate_seconds},
            {"frames_measured", r.frames_measured},
            {"frame_ms", r.frame_ms},
            {"frame_ms_p95", r.frame_ms_p95},
            {"triangles", r.triangles},
            {"impostor_points", r.points},
            {"draw_calls", r.draw_calls},
            {"lod_instances", {{"lod0", r.lod_instances[0]}, {"lod1", r.lod_instances[1]}, {"lod2", r.lod_instances[2]},
                               {"impostor", r.lod_instances[3]}}},
            {"lod_settings_px", {{"lod1", lod.lod1_px}, {"lod2", lod.lod2_px}, {"impostor", lod.impostor_px}}},
            {"tiles_visible", r.tiles_visible},
            {"tiles_culled", r.tiles_culled},
            {"gl_version", r.gl_version},
            {"renderer", r.renderer},
            {"window", {r.window_width, r.window_height}},
            {"framebuffer", {r.framebuffer_width, r.framebuffer_height}},
            {"screenshot", r.screenshot}};
}

}  // namespace ug::editor
