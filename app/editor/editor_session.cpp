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
#include "editor/session_stats.h"
#include "editor/window_title.h"
#include "instancer/instance_query.h"
#include "instancer/tile_coord.h"

namespace ug::editor {

namespace {
// The share of the Statistics window's bar that opening a document's files takes (DocumentLoader::progress);
// its first instantiation takes the rest.
constexpr float kOpenShare = 0.25f;
}  // namespace

EditorSession::EditorSession(const ViewerOptions& o, ViewerResult* r, std::string* e)
    : options(o), result(r), error(e), scripted(o.frames > 0), messages(r->messages) {}

ViewerStatus EditorSession::start() {
    gl::WindowOptions window_options;
    window_options.width = options.width;
    window_options.height = options.height;
    window_options.vsync = !scripted;
    switch (window.open(window_options, error)) {
        case gl::OpenStatus::Ok:
            break;
        case gl::OpenStatus::NoDisplay:
            return ViewerStatus::NoDisplay;
        case gl::OpenStatus::Failed:
            return ViewerStatus::Failed;
    }
    renderer = std::make_unique<gl::Renderer>();  // only with a context: its destructor frees GL objects
    if (!renderer->init(gl::shadersDir(), error)) return ViewerStatus::Failed;
    *result = ViewerResult{};  // (messages, a reference to result->messages, stays bound)
    result->scene = options.scene_path;
    result->gl_version = window.glVersion();
    result->renderer = window.rendererName();
    result->window_width = options.width;
    result->window_height = options.height;
    doc_options.cache_dir = options.cache_dir;
    doc_options.config_dir = options.config_dir;
    doc_options.threads = options.threads;
    doc_options.autosave_interval_s = options.autosave_interval_s;
    camera.aspect = float(options.width) / float(options.height);
    render_settings.lod = options.lod;
    render_settings.look = options.look;
    view.scene = options.scene_path;
    view.gl_version = window.glVersion();
    view.renderer = window.rendererName();
    recent_files = loadRecentFiles(options.config_dir);
    last_fb_w = options.width;
    last_fb_h = options.height;
    return requestOpen(options.scene_path, options.recover) ? ViewerStatus::Ok : ViewerStatus::Failed;
}

ViewerStatus EditorSession::run() {
    if (const ViewerStatus started = start(); started != ViewerStatus::Ok) return started;
    while (true) {
        frame_start = Clock::now();
        window.pollEvents();
        fb_w = 0;
        fb_h = 0;
        window.framebufferSize(&fb_w, &fb_h);
        if (fb_w <= 0 || fb_h <= 0) continue;  // minimised
        camera.aspect = float(fb_w) / float(fb_h);
        now_s = std::chrono::duration<double>(frame_start - start_time).count();
        if (!applyFinishedWork()) return ViewerStatus::Failed;
        updateStatus();
        drawUi();
        mouseTools();
        handleEditRequests();
        handleFileRequests();
        handleDialogs();
        if (!stepReplay()) return ViewerStatus::Failed;
        showFreshResults();
        const auto render_start = Clock::now();
        if (!renderFrame()) return ViewerStatus::Failed;
        last_render_ms = std::chrono::duration<double, std::milli>(Clock::now() - render_start).count();
        if (!afterFrame()) break;
    }
    result->frames_measured = int(frame_ms.size());
    result->frame_ms = percentile(frame_ms, 0.5);
    result->frame_ms_p95 = percentile(frame_ms, 0.95);
    // The statistics describe the document as it was left: its final instance set, not a stale one.
    if (scene && !scripted && !options.stats_path.empty()) {
        scene->doc->live().waitIdle();
        LiveResult last;
        if (scene->doc->live().poll(&last) && last.generation >= scene->doc->tileLiveGeneration()) store = last.store;
    }
    fillDocumentResult();
    if (!scripted) writeInteractiveStats();
    return ViewerStatus::Ok;
}

void EditorSession::showFreshResults() {
    const auto deadline =
        Clock::now() + std::chrono::milliseconds(int64_t(std::clamp(last_render_ms, 0.0, kFreshWaitMaxMs)));
    const auto left = [&] {
        return std::max(std::chrono::milliseconds(0),
                        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()));
    };
    waitForStampUpdate(left());
    showFreshEnvironment(left());
    showFreshStrands(left());
}

void EditorSession::waitForStampUpdate(std::chrono::milliseconds budget) {
    if (!scene || pending_stamps.size() <= stamps_before_frame) return;
    scene->doc->live().waitIdleFor(budget);
}

void EditorSession::updateStatus() {
    // Long background jobs show in the Statistics window too, whichever panel started them.
    view.pending = loader != nullptr || ghost_job != nullptr || export_job != nullptr ||
                   (scene && (!settled || !have_result));
    // Opening a document: the loader's stages are the first quarter of the bar, its first full
    // instantiation (seconds on a big field) the rest; later, a full run's own progress (a seed or a
    // strategy change; an incremental update is short and shows as done).
    const bool first_result = scene && !have_result;
    const float open_progress =
        loader ? kOpenShare * loader->progress()
               : kOpenShare + (1.0f - kOpenShare) * (scene ? scene->doc->live().fullRunProgress() : 0.0f);
    view.progress = ghost_job    ? ghost_job->progress()
                    : export_job ? export_job->progress()
                    : settled    ? 1.0f
                    : loader || first_result ? open_progress
                    : scene                  ? scene->doc->live().fullRunProgress()
                                             : 0.0f;
    view.status = loader         ? "loading scene\xE2\x80\xA6"
                  : !scene       ? "no document"
                  : first_result ? "instantiating\xE2\x80\xA6"
                  : ghost_job    ? "building the Ghost Tile\xE2\x80\xA6"
                  : export_job   ? "exporting glTF\xE2\x80\xA6"
                  : view.pending ? "pending\xE2\x80\xA6"
                                 : "ready";

}

EditorSession::json EditorSession::viewportJson() {
    json v;
    const glm::vec3 eye = camera.eye();
    v["camera"] = {{"target", vec3Json(camera.target)},
                   {"eye", vec3Json(eye)},
                   {"distance", camera.distance_m},
                   {"yaw_deg", glm::degrees(camera.yaw_rad)},
                   {"pitch_deg", glm::degrees(camera.pitch_rad)}};
    if (scene) v["eye_ground_z"] = groundZ(glm::vec2(eye));
    v["framebuffer"] = {last_fb_w, last_fb_h};
    if (std::isfinite(cursor_px.x)) {
        v["cursor_px"] = {cursor_px.x, cursor_px.y};
        if (scene) {
            const Ray ray = rayThroughPixel(camera.viewProjection(), float(last_fb_w), float(last_fb_h), cursor_px);
            const SurfaceHit g = pickGround(*scene->doc, ray);
            if (g.hit) v["ground_under_cursor"] = vec3Json(g.point_m);
        }
    }
    v["brush"] = {{"drawn", brush_probe.drawn}};
    if (brush_probe.drawn) {
        v["brush"]["center"] = vec3Json(brush_probe.center);
        v["brush"]["on_pile"] = brush_probe.on_pile;
        v["brush"]["ring_center_px"] = {brush_probe.ring_center_px.x, brush_probe.ring_center_px.y};
    }
    v["tool"] = toolName(tools.tool);
    v["brush_radius"] = tools.brush.radius_m;
    v["statistics_scene"] = view.scene;
    v["statistics_status"] = view.status;
    v["statistics_progress"] = view.progress;
    v["imgui_wants_keyboard"] = ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard;
    return v;
}

void EditorSession::fillDocumentResult() {
    result->viewport = viewportJson();
    result->window_title = window.title();
    if (!scene) return;
    Document& d = *scene->doc;
    result->document_path = d.path();
    result->dirty = d.isDirty();
    result->undo_name = d.canUndo() ? d.undoName() : "";
    result->user_primitives = 0;
    for (size_t t = 0; t < d.project().detail_types.size(); ++t)
        result->user_primitives += d.primitiveIds(t).size();
    result->type_names.clear();
    for (const DetailLodMesh& m : scene->meshes) result->type_names.push_back(m.name);
    if (!d.particles()->empty()) {
        json systems = json::array();
        for (const ParticleSystemFile& s : *d.particles()) {
            const auto xyz = [](glm::vec3 p) { return json::array({p.x, p.y, p.z}); };
            json attractors = json::array(), generators = json::array(), cutters = json::array(),
                 charge_keys = json::array();
            for (const Attractor& a : s.scene.attractors) {
                attractors.push_back(xyz(a.a_m));
                json keys = json::array();
                for (const ChargeKey& k : a.charge) keys.push_back({k.step, k.charge});
                charge_keys.push_back(std::move(keys));
            }
            for (const ParticleGenerator& g : s.scene.generators) generators.push_back(xyz(g.center_m));
            for (const Cutter& c : s.scene.cutters) cutters.push_back(xyz(c.center_m));
            systems.push_back({{"name", s.name},
                               {"attractors", std::move(attractors)},
                               {"charge_keys", std::move(charge_keys)},
                               {"generators", std::move(generators)},
                               {"cutters", std::move(cutters)}});
        }
        // Where the open window's system's dots are on screen: a driven session grabs them there.
        json handles_px = json::array();
        if (windows.particles && particles_panel.selected < d.particles()->size()) {
            const glm::mat4 camera_view_proj = camera.viewProjection();  // the camera now, after a replayed view
            for (const ParticleHandlePoint& h : particleHandlePoints((*d.particles())[particles_panel.selected].scene)) {
                const glm::vec2 px = projectToPixel(camera_view_proj, float(last_fb_w), float(last_fb_h), h.position_m);
                handles_px.push_back({{"part", particlePartName(h.handle.part)}, {"index", h.handle.index}, {"tilt", h.handle.tilt}, {"px", {px.x, px.y}}});
            }
        }
        const ParticleHandle picked = particles_panel.selected_handle;
        result->particles = {{"systems", std::move(systems)},
                             {"selected_system", particles_panel.selected},
                             {"selected_attractor",
                              picked.part == ParticlePart::Attractor ? json(picked.index) : json(nullptr)},
                             {"selected_handle", picked ? json{{"part", particlePartName(picked.part)}, {"tilt", picked.tilt},
                                                               {"index", picked.index}}
                                                        : json(nullptr)},
                             {"handles_px", std::move(handles_px)},
                             {"strands_settled", strandsSettled()},
                             {"last", strandsJson()}};
    }
    if (live_environment) result->environment = environmentJson();
    if (store) {
        result->instances = store->instanceCount();
        result->instances_per_type = perTypeCounts(*store, d.ghostTile().candidates);
        result->instance_store_hash = instanceStoreHash(*store);
    }
}

void EditorSession::writeInteractiveStats() {
    if (options.stats_path.empty()) return;
    fillDocumentResult();
    std::string write_error;
    if (!writeTextFileAtomically(options.stats_path, viewerStatsJson(*result, options.lod).dump(2) + "\n",
                                 &write_error))
        messages.push_back(write_error);
}

}  // namespace ug::editor
