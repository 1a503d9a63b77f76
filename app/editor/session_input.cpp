#include "editor/editor_session.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "core/atomic_file.h"
#include "core/hash.h"
#include "editor/background_jobs.h"
#include "editor/navigation.h"
#include "editor/session_stats.h"
#include "editor/surface_pick.h"
#include "editor/window_title.h"
#include "instancer/instance_query.h"
#include "instancer/tile_coord.h"

namespace ug::editor {

void EditorSession::drawUi() {
    // ---- UI: navigation, tools, panels, dialogs ----
    stamps_before_frame = pending_stamps.size();
    window.beginUiFrame(scripted);
    // While another document loads, the current one is shown but not edited: it is replaced (and its
    // edits dropped) when the new one is ready, and is editable again if that load fails.
    doc = scene && !loader ? scene->doc.get() : nullptr;
    const ImGuiIO& io = ImGui::GetIO();
    last_fb_w = fb_w;
    last_fb_h = fb_h;
    cursor_px = ImGui::IsMousePosValid() ? glm::vec2(io.MousePos.x * io.DisplayFramebufferScale.x,
                                                     io.MousePos.y * io.DisplayFramebufferScale.y)
                                         : glm::vec2(NAN);
    // The mouse moving or clicking in the viewport takes the keyboard back from a panel's field.
    if (!scripted) giveKeyboardBackToViewport();
    if (scene && !scripted) {
        Bounds selection;
        Primitive selected_prim;
        if (tools.selected != 0 && doc && doc->findPrimitive(tools.selected, nullptr, &selected_prim))
            selection = editBounds(selected_prim);
        // Terrain kinds reach everywhere in XY: nothing sensible to frame.
        for (int a = 0; a < 3; ++a)
            if (!std::isfinite(selection.lo[a]) || !std::isfinite(selection.hi[a])) selection = Bounds{};
        // The wheel zooms toward the ground under the cursor.
        glm::vec3 pivot(0.0f);
        bool has_pivot = false;
        if (io.MouseWheel != 0.0f && std::isfinite(cursor_px.x)) {
            const SurfaceHit g = pickGround(
                *scene->doc, rayThroughPixel(camera.viewProjection(), float(fb_w), float(fb_h), cursor_px));
            has_pivot = g.hit;
            pivot = g.point_m;
        }
        camera_moved |= navigate(&camera, framingBounds(*scene, have_result ? &instances : nullptr),
                                 float(fb_h), &selection, has_pivot ? &pivot : nullptr);
        keepEyeAboveGround(&camera, [this](glm::vec2 xy) { return groundZ(xy); });
    }
    // After navigation: the brush ring and picking use this frame's camera, not the last one's.
    view_proj = camera.viewProjection();
    MenuView menu;
    menu.has_document = doc != nullptr;
    menu.dirty = doc && doc->isDirty();
    menu.undo_name = doc && doc->canUndo() ? doc->undoName() : "";
    menu.redo_name = doc && doc->canRedo() ? doc->redoName() : "";
    menu.recent_files = recent_files;
    drawMainMenu(menu, &requests, &tools, &windows);
    drawStatisticsPanel(view, &windows.statistics);
    drawRenderPanel(view, &render_settings, &windows.render);
    {
        std::string tools_message;
        drawToolsPanel(doc, view.type_names, &tools, &tools_message, &windows.tools);
        if (!tools_message.empty()) messages.push_back(tools_message);
    }
    std::string inspector_message;
    drawInspector(doc, view.type_names, &tools, &requests, &inspector_message, &windows.inspector);
    if (!inspector_message.empty()) messages.push_back(inspector_message);
    drawGhostTilePanel(doc, &ghost_panel, &windows.ghost_tile);
    {
        std::string particles_message;
        particles_panel.place_at = glm::vec3(glm::vec2(camera.target), groundZ(glm::vec2(camera.target)));
        drawParticlesPanel(doc, &particles_panel, &particles_message, &windows.particles);
        if (!particles_message.empty()) messages.push_back(particles_message);
        environment_panel.place_at = particles_panel.place_at;
        std::string environment_message;
        drawEnvironmentPanel(doc, &environment_panel, &environment_message, &windows.environment);
        if (!environment_message.empty()) messages.push_back(environment_message);
    }
    if (doc && ghost_panel.build && !ghost_job) {
        std::string job_error;
        ghost_job = doc->startGhostTileJob(ghost_panel.pending, &job_error);
        ghost_job_doc = doc;
        ghost_job_action = -1;
        if (!ghost_job) {
            messages.push_back(job_error);
            ghost_panel.last_outcome = "refused: " + job_error;
        }
    }
    if (ghost_job && ghost_panel.cancel) ghost_job->cancel();
    ghost_panel.build = ghost_panel.cancel = false;
    {
        OutlinerView outliner;
        outliner.type_names = view.type_names;
        outliner.instances_per_type = view.instances_per_type;
        if (scene)
            for (const DetailLodMesh& m : scene->meshes) outliner.colors.push_back(m.color);
        drawOutliner(doc, outliner, &type_visible, &tools, &environment_panel, &requests, &windows.outliner);
        for (size_t t = 0; t < type_visible.size(); ++t) renderer->setTypeVisible(t, type_visible[t] != 0);
        inst_view.pending = scene && !settled;
        std::string panel_message;
        drawInstantiationPanel(doc, view.type_names, inst_view, &panel_message, &windows.instantiation);
        if (!panel_message.empty()) messages.push_back(panel_message);
        ExportView export_view;
        export_view.has_document = doc != nullptr && store != nullptr && settled;  // the settled set
        export_view.running = export_job != nullptr;
        export_view.can_cancel = export_job && export_job->stage() == ExportStage::Gathering;
        export_view.progress = export_job ? export_job->progress() : 0.0f;
        export_view.stage = export_job ? exportStageName(export_job->stage()) : "";
        export_view.last_result = export_result;
        drawExportPanel(export_view, &export_settings, &requests, &windows.export_panel);
    }

}

void EditorSession::mouseTools() {
    const ImGuiIO& io = ImGui::GetIO();
    markers.clear();
    brush_probe.drawn = false;
    // Mouse tools: not while a panel has the mouse, Alt is held (Alt + left drag orbits) or a replay
    // stroke is running.
    const bool replay_stroke = replay.started && !replay.finishing;
    if (doc && have_result && !scripted && !replay_stroke && asking_recovery.empty() &&
        prompt == Prompt::None) {
        const glm::vec2 cursor(io.MousePos.x * io.DisplayFramebufferScale.x,
                               io.MousePos.y * io.DisplayFramebufferScale.y);
        const Ray ray = rayThroughPixel(view_proj, float(fb_w), float(fb_h), cursor);
        const bool mouse_free = !io.WantCaptureMouse && !io.KeyAlt;
        if (windows.particles && particles_panel.placing != ParticlePart::None) {
            placeParticlePart(ray, mouse_free);
        } else if (windows.environment && environment_panel.placing) {
            placeFromPalette(ray, mouse_free);
        } else if (windows.environment && environment_panel.brush_on) {
            // A weather brush takes the left button from the tool while it is on; its ring shows where.
            const SurfaceHit ground = pickGround(*doc, ray);
            const WeatherSettings& weather = environment_panel.weather;
            if (ground.hit && mouse_free)
                addBrushMarker(*doc, ground.point_m,
                               weather.brush == WeatherBrush::Footprints ? kFootprintStrideM : weather.radius_m, true,
                               &markers);
            std::string walk_error;
            bool ok = true;
            const uint64_t generation = doc->environmentGeneration();
            if (ground.hit && mouse_free && ImGui::IsMouseClicked(ImGuiMouseButton_Left))
                ok = weather_stroke.begin(doc, weather, ground.point_m, &walk_error);
            else if (ground.hit && weather_stroke.active() && ImGui::IsMouseDown(ImGuiMouseButton_Left))
                ok = weather_stroke.drag(ground.point_m, &walk_error);
            if (!ok) messages.push_back(walk_error);
            noteEnvStamp(generation, -1);
        } else if (tools.tool == ToolKind::Select) {
            // Click picks; dragging the picked primitive moves it (Shift: up and down). With the Particles
            // window open, its system's handles (attractors, generators, cutters) are picked first; with the Environment window open, its
            // objects next.
            // The selected environmental node's turn and scale handles (env_handles.h).
            EnvHandleFrame handles;
            const bool has_handles = windows.environment && !environment_panel.selected.empty() &&
                                     envHandleFrame(*doc, environment_panel.selected, &handles);
            if (mouse_free && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
                const ParticleHandle particle =
                    windows.particles ? pickParticleHandle(*doc, particles_panel.selected, view_proj, float(fb_w),
                                                      float(fb_h), cursor, 20.0f)
                                      : ParticleHandle{};
                const EnvHandle handle =
                    !particle && has_handles
                        ? pickEnvHandle(handles, view_proj, float(fb_w), float(fb_h), cursor, 12.0f)
                        : EnvHandle::None;
                // Ctrl + click: the node inside a group.
                const EnvPath env_node =
                    !particle && handle == EnvHandle::None && windows.environment
                        ? pickEnvNode(*doc, view_proj, float(fb_w), float(fb_h), cursor, 25.0f, io.KeyCtrl)
                        : EnvPath{};
                particles_panel.selected_handle = particle;
                if (!env_node.empty()) environment_panel.selected = env_node;
                if (particle) {
                    tools.selected = 0;
                    particle_drag.begin(doc, particles_panel.selected, particle, ray);
                } else if (handle != EnvHandle::None) {
                    tools.selected = 0;
                    env_handle_drag.begin(doc, environment_panel.selected, handle, ray);
                } else if (!env_node.empty()) {
                    tools.selected = 0;
                    env_drag.begin(doc, env_node, ray);
                } else {
                    tools.selected = pickPrimitive(*doc, view_proj, float(fb_w), float(fb_h), cursor, 20.0f);
                    if (tools.selected != 0) move_drag.begin(doc, tools.selected, ray);
                }
            } else if (particle_drag.active() && ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
                std::string move_error;
                if (!particle_drag.drag(ray, io.KeyShift, &move_error)) messages.push_back(move_error);
            } else if (env_drag.active() && ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
                std::string move_error;
                const uint64_t generation = doc->environmentGeneration();
                if (!env_drag.drag(ray, &move_error)) messages.push_back(move_error);
                noteEnvStamp(generation, -1);
            } else if (env_handle_drag.active() && ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
                std::string handle_error;
                const uint64_t generation = doc->environmentGeneration();
                if (!env_handle_drag.drag(ray, io.KeyCtrl, &handle_error)) messages.push_back(handle_error);
                noteEnvStamp(generation, -1);
            } else if (move_drag.active() && ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
                const uint64_t generation = doc->live().generation();
                std::string move_error;
                if (!move_drag.drag(ray, io.KeyShift, &move_error)) messages.push_back(move_error);
                if (doc->live().generation() != generation)
                    pending_stamps.push_back({doc->live().generation(), Clock::now(), -1});
            }
        } else {
            // The marker shows where the brush works: for Sculpt, where the material lands.
            const SurfaceHit hit = tools.tool == ToolKind::Sculpt
                                       ? sculptLanding(*doc, tools.brush.sculpt_type, ray)
                                       : pickBrushSurface(*doc, tools.brush, ray);
            if (hit.hit && mouse_free) {
                const size_t first = markers.lines.size();
                addBrushMarker(*doc, hit.point_m, tools.brush.radius_m, !hit.on_pile, &markers);
                glm::vec3 sum(0.0f);
                for (size_t i = first; i < markers.lines.size(); ++i) sum += markers.lines[i].position;
                const glm::vec3 ring_centre = sum / float(std::max<size_t>(1, markers.lines.size() - first));
                brush_probe = {true, hit.on_pile, hit.point_m,
                               projectToPixel(view_proj, float(fb_w), float(fb_h), ring_centre)};
            }
            const int before = stroke.stamps();
            std::string stroke_error;
            bool ok = true;
            if (mouse_free && ImGui::IsMouseClicked(ImGuiMouseButton_Left))
                ok = stroke.begin(doc, tools.tool, tools.brush, ray, now_s, &stroke_error);
            else if (stroke.active() && ImGui::IsMouseDown(ImGuiMouseButton_Left))
                ok = stroke.drag(ray, now_s, &stroke_error);
            if (!ok) messages.push_back(stroke_error);
            if (stroke.stamps() > before)
                pending_stamps.push_back({doc->live().generation(), Clock::now(), -1});
        }
        if (stroke.active() && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
            // The statistics keep each mouse sculpt stroke's pile (tests drive the mouse with xdotool).
            if (stroke.tool() == ToolKind::Sculpt && !stroke.stampPoints().empty() && !options.stats_path.empty())
                result->sculpt_strokes.push_back(pileRecord(*doc, stroke));
            stroke.end();
        }
        if (move_drag.active() && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) move_drag.end();
        if (particle_drag.active() && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) particle_drag.end();
        if (env_drag.active() && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) env_drag.end();
        if (env_handle_drag.active() && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) env_handle_drag.end();
        if (weather_stroke.active() && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) weather_stroke.end();
    }

}

void EditorSession::placeFromPalette(const Ray& ray, bool mouse_free) {
    // The palette's type at what the cursor points at (the ground, or the top of an object), shown by a
    // ring; a click places it (one undo step) and disarms the palette, unless Shift is held (place more).
    EnvironmentPanelState& p = environment_panel;
    if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false) || size_t(p.add_type) >= doc->project().environment.types.size()) {
        p.placing = false;
        return;
    }
    glm::vec3 at;
    if (!mouse_free || !placementPoint(*doc, ray, &at)) return;
    addBrushMarker(*doc, at, 0.3f, false, &markers);
    if (!ImGui::IsMouseClicked(ImGuiMouseButton_Left)) return;
    EnvironmentDesc env = doc->project().environment;
    EnvNode node;
    node.type = uint32_t(p.add_type);
    node.transform.translation = at;
    env.roots.push_back(std::move(node));
    std::string place_error;
    const uint64_t generation = doc->environmentGeneration();
    if (doc->setEnvironment(env, "Add " + env.types[size_t(p.add_type)].name, &place_error)) {
        p.selected = {uint32_t(env.roots.size() - 1)};
        noteEnvStamp(generation, -1);
    } else {
        messages.push_back(place_error);
    }
    p.placing = ImGui::GetIO().KeyShift;
}

void EditorSession::placeParticlePart(const Ray& ray, bool mouse_free) {
    // A ring where the part would go and its normal; a click adds it to the shown system (one undo step)
    // and disarms, unless Shift is held (place more).
    ParticlesPanelState& p = particles_panel;
    const std::vector<ParticleSystemFile>& systems = *doc->particles();
    if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false) || p.selected >= systems.size()) {
        p.placing = ParticlePart::None;
        return;
    }
    // The instances as they are drawn (settled), placed again only when the result on screen changes.
    if (p.place_on_details && (pick_store != store || pick_drops != drops)) {
        pick_instances = store ? placeInstances(*store, doc->ghostTile(), drops.get()) : std::vector<PlacedInstance>{};
        pick_store = store;
        pick_drops = drops;
    }
    const ScenePick pick = pickSceneSurface(*doc, ray, p.place_on_details ? std::span<const PlacedInstance>(pick_instances)
                                                                          : std::span<const PlacedInstance>());
    if (!mouse_free || !pick.hit.hit) return;
    addBrushMarker(*doc, pick.hit.point_m, 0.1f, false, &markers);
    const glm::vec3 orange(1.0f, 0.75f, 0.1f);  // the armed button's colour
    markers.lines.push_back({pick.hit.point_m, orange});
    markers.lines.push_back({pick.hit.point_m + pick.hit.normal * 0.3f, orange});
    if (!ImGui::IsMouseClicked(ImGuiMouseButton_Left)) return;
    ParticleSystemFile system = systems[p.selected];
    // On the ground of a project with a terrain, a generator is dropped onto it as the terrain's are.
    const bool on_terrain = pick.object < 0 && pick.instance < 0 && system.scene.terrain != nullptr;
    // A generator on a detail instance grows on its type's instances there (moss on the rocks around the
    // click): one instance alone is re-made whenever its tile is instantiated again.
    const bool on_details = p.placing == ParticlePart::Generator && pick.instance >= 0 &&
                            pick.detail_type < doc->project().detail_types.size();
    const ParticleHandle added =
        on_details ? addDetailsGenerator(&system.scene, doc->project().detail_types[pick.detail_type].model.name, pick.hit.point_m)
                   : addParticlePart(&system.scene, p.placing, pick.hit.point_m, pick.hit.normal, on_terrain);
    std::string place_error;
    doc->beginStroke(std::string("Place ") + particlePartName(p.placing));
    const bool ok = doc->setParticleSystem(p.selected, system, &place_error);
    doc->endStroke();
    if (ok) {
        p.selected_handle = added;
        p.last_error.clear();
    } else {
        p.last_error = place_error;
        messages.push_back(place_error);
    }
    if (!ImGui::GetIO().KeyShift) p.placing = ParticlePart::None;
}

float EditorSession::groundZ(glm::vec2 xy) const { return scene ? groundHeightAt(*scene->doc, xy) : -1.0e30f; }

}  // namespace ug::editor
