#include "editor/editor_session.h"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/hash.h"
#include "editor/background_jobs.h"
#include "editor/navigation.h"
#include "editor/screenshot.h"
#include "editor/session_stats.h"
#include "editor/window_title.h"
#include "instancer/instance_query.h"
#include "instancer/tile_coord.h"

namespace ug::editor {

bool EditorSession::renderFrame() {
    // ---- render ----
    // (A stamp made this frame was waited for in showFreshResults.)
    if (!takeLiveResult()) return false;
    // The camera never goes below the ground, whatever moved it (navigation, a replayed view, framing).
    if (scene) keepEyeAboveGround(&camera, [this](glm::vec2 xy) { return groundZ(xy); });
    // The skeleton overlays (Window > Skeleton overlays) and the Render panel's overlays (tile grid,
    // anchors, sphere sets) are separate toggles: one does not hide the others.
    if (doc && have_result && (screenshot_request_path.empty() || screenshot_overlays)) {
        if (tools.show_markers) {
            const PrimitiveMarkersKey key{doc, doc->live().generation(), doc->tileGeneration(), tools.selected,
                                          render_settings.hulls};
            if (!(key == primitive_markers_key)) {
                primitive_markers.clear();
                addPrimitiveMarkers(*doc, scene->meshes, tools.selected, &primitive_markers);
                if (render_settings.hulls)
                    addPrimitiveHulls(*doc, scene->meshes, tools.selected, &primitive_markers);
                primitive_markers_key = key;
            }
            markers.append(primitive_markers);
        }
        // The Particles window's system, while the window is open.
        if (windows.particles && particles_panel.selected < doc->particles()->size())
            addParticleMarkers((*doc->particles())[particles_panel.selected], particles_panel.selected_handle,
                               &markers);
        // The selected environmental node's ring with its turn and scale handles, for the Select tool.
        EnvHandleFrame handles;
        if (windows.environment && tools.tool == ToolKind::Select && !environment_panel.brush_on &&
            envHandleFrame(*doc, environment_panel.selected, &handles))
            addEnvHandleMarkers(handles, env_handle_drag.handle(), &markers);
        const float r = render_settings.overlay_radius_m;
        const CandidateSet& c = doc->ghostTile().candidates;
        if (render_settings.tile_grid) addTileOverlay(instances, camera.target, r, &markers);
        if (render_settings.anchors) addAnchorOverlay(instances, c, scene->meshes, camera.target, r, &markers);
        if (render_settings.sphere_sets) addSphereOverlay(instances, c, doc->models(), camera.target, r, &markers);
    }
    if (!screenshot_request_path.empty() && !screenshot_overlays) markers.clear();
    // The Environment window's channel view, while it is on: uploaded when it changes, not every frame.
    const bool channel_view = doc && have_result && windows.environment && environment_panel.view.on &&
                              (screenshot_request_path.empty() || screenshot_overlays);
    if (channel_view) updateChannelMap();
    renderer->showChannelOverlay(channel_view);
    renderer->setMarkers(markers);
    renderer->setLook(render_settings.look);
    renderer->render(camera, fb_w, fb_h, render_settings.lod);
    const gl::RenderStats& rs = renderer->stats();
    view.triangles = rs.triangles;
    view.points = rs.points;
    view.draw_calls = rs.draw_calls;
    view.lod_instances = rs.lod_instances;
    view.tiles_visible = rs.tiles_visible;
    view.tiles_culled = rs.tiles_culled;
    view.tiles_resident = rs.tiles_resident;
    view.indirect_commands = rs.indirect_commands;

    // The screenshot is the viewport alone, read before the UI is drawn over it.
    const bool last_scripted_frame = scripted && replay.index >= options.replay.size() && settled &&
                                     frames_after_done + 1 >= options.frames;
    if (screenshot_requested || !screenshot_request_path.empty() ||
        (last_scripted_frame && !options.screenshot_path.empty())) {
        std::string path =
            screenshot_request_path.empty() ? options.screenshot_path : screenshot_request_path;
        if (path.empty() || (screenshot_requested && !scripted && screenshot_count > 0))
            path = std::filesystem::path(options.scene_path).stem().string() + "-screenshot-" +
                   std::to_string(++screenshot_count) + ".png";
        else
            ++screenshot_count;
        renderer->readPixels(fb_w, fb_h, &pixels);
        std::string write_error;
        if (writeScreenshot(path, fb_w, fb_h, pixels, &write_error)) {
            view.last_message = "saved " + path;
            result->screenshot = path;
        } else {
            messages.push_back(write_error);
            if (scripted) {
                *error = write_error;
                return false;
            }
        }
        screenshot_request_path.clear();
        // F12 in an interactive run with --stats also rewrites the statistics (a driven session reads
        // the viewport's state after each step).
        if (screenshot_requested && !scripted) writeInteractiveStats();
    }
    window.renderUi();
    if (!ui_screenshot_path.empty()) {
        renderer->readPixels(fb_w, fb_h, &pixels);
        std::string write_error;
        if (!writeScreenshot(ui_screenshot_path, fb_w, fb_h, pixels, &write_error))
            messages.push_back(write_error);
        ui_screenshot_path.clear();
    }
    if (options.finish_each_frame) window.finish();
    window.swapBuffers();

    return true;
}

bool EditorSession::afterFrame() {
    // ---- after the frame: stamp timings, replay bookkeeping, autosave ----
    const gl::RenderStats& rs = renderer->stats();
    const auto frame_end = Clock::now();
    timeEnvStamps(frame_end);
    for (size_t i = 0; i < pending_stamps.size();) {
        if (have_result && pending_stamps[i].generation <= shown_generation) {
            const double ms =
                std::chrono::duration<double, std::milli>(frame_end - pending_stamps[i].time).count();
            result->stamp_to_frame_ms.push_back(ms);
            view.stamp_to_frame_ms = ms;
            if (pending_stamps[i].action == int(replay.index)) replay.stamp_ms.push_back(ms);
            pending_stamps.erase(pending_stamps.begin() + long(i));
        } else {
            ++i;
        }
    }
    const bool settled_now = scene && have_result && !scene->doc->live().pending() &&
                             shown_generation == scene->doc->live().generation() && sideJobsSettled();
    // An open, a new document or an export finishes when its background work did (and, for a document
    // that loaded, once its first result is on screen).
    const bool export_waiting = replay.finishing && replay.index < options.replay.size() &&
                                options.replay[replay.index].kind == ReplayKind::Export &&
                                (export_job || export_record.is_null());
    if (replay.finishing && settled_now && scene && !loader && !export_waiting) finishReplayAction();
    autosave();

    const double ms = std::chrono::duration<double, std::milli>(frame_end - frame_start).count();
    view.frame_ms = std::chrono::duration<double, std::milli>(frame_end - last_frame_end).count();
    view.frame_ms_avg =
        view.frame_ms_avg == 0.0 ? view.frame_ms : 0.95 * view.frame_ms_avg + 0.05 * view.frame_ms;
    last_frame_end = frame_end;
    if (have_result) {
        ++frame_index;
        frame_ms.push_back(ms);
        result->triangles = rs.triangles;
        result->points = rs.points;
        result->draw_calls = rs.draw_calls;
        result->lod_instances = rs.lod_instances;
        result->tiles_visible = rs.tiles_visible;
        result->tiles_culled = rs.tiles_culled;
        result->indirect_commands = rs.indirect_commands;
        result->tiles_uploaded = rs.tiles_uploaded;
        result->bytes_uploaded = rs.bytes_uploaded;
        result->tiles_resident = rs.tiles_resident;
        result->framebuffer_width = fb_w;
        result->framebuffer_height = fb_h;
        result->instantiate_seconds = view.instantiate_seconds;
        if (scripted && replay.index >= options.replay.size() && settled_now &&
            ++frames_after_done >= options.frames)
            return false;
    }
    if (quitting) return false;
    return true;
}

}  // namespace ug::editor
