#include "editor/editor_session.h"

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
#include "editor/window_title.h"
#include "instancer/instance_query.h"
#include "instancer/tile_coord.h"

namespace ug::editor {

bool EditorSession::stepReplay() {
    // ---- replay: start or advance the current action ----
    if (doc && have_result && replay.index < options.replay.size() && !replay.finishing) {
        const ReplayAction& a = options.replay[replay.index];
        std::string op_error;
        if (!replay.started && frame_index >= a.frame && settled) {
            replay.started = true;
            replay.record = json{{"action", replayKindName(a.kind)}, {"frame", frame_index}};
            replay.before = store;
            replay.stamp_ms.clear();
            // Counted now, with the candidates `store` indexes: a Ghost Tile action or its undo swaps them.
            const InstanceStore none;
            const InstanceStore& now = store ? *store : none;
            replay.record["instances_before"] = now.instanceCount();
            replay.record["per_type_before"] =
                perTypeJson(view.type_names, perTypeCounts(now, doc->ghostTile().candidates));
            replay.record["instance_store_hash_before"] = hex64(instanceStoreHash(now));
            const bool is_stroke = a.kind == ReplayKind::PaintStroke ||
                                   a.kind == ReplayKind::SculptStroke ||
                                   a.kind == ReplayKind::EraseStroke;
            if (is_stroke ? !startReplayStroke(a) : !runReplayAction(a)) return false;
        } else if (replay.started && move_drag.active()) {
            const uint64_t generation = doc->live().generation();
            if (replay.step < replay.path.size() &&
                !move_drag.drag(rayDownOnto(*doc, replay.path[replay.step]), false, &op_error))
                messages.push_back(op_error);
            if (doc->live().generation() != generation)
                pending_stamps.push_back({doc->live().generation(), Clock::now(), int(replay.index)});
            if (++replay.step >= replay.path.size()) {
                Primitive p;
                doc->findPrimitive(move_drag.id(), nullptr, &p);
                replay.record["moves"] = move_drag.moves();
                replay.record["to_center"] = {p.center_m.x, p.center_m.y, p.center_m.z};
                // Old and new supports (of the whole stroke): where the move can change instances.
                recordChangeBox(unite(replay.moved_from, strokeBounds(*doc, move_drag.id(), &replay.record["to_centers"])));
                move_drag.end();
                replay.finishing = true;
            }
        } else if (replay.started && (env_drag.active() || env_handle_drag.active() || weather_stroke.active())) {
            stepEnvReplay();
        } else if (replay.started && a.kind == ReplayKind::GhostTile) {
            replay.finishing = !ghost_job;  // the job was applied or reported at this frame's start
        } else if (replay.started && stroke.active()) {
            // One brush position per frame; the virtual clock advances one hold interval per step so a
            // sculpt stroke stamps at every step, whatever the frame rate.
            const int before = stroke.stamps();
            if (replay.step < replay.path.size() &&
                !stroke.drag(strokeRay(a, replay.path[replay.step]),
                             double(replay.step) * kSculptHoldInterval_s, &op_error))
                messages.push_back(op_error);
            if (stroke.stamps() > before)
                pending_stamps.push_back({doc->live().generation(), Clock::now(), int(replay.index)});
            if (++replay.step >= replay.path.size()) {
                replay.record["stamps"] = stroke.stamps();
                json points = json::array();
                for (const glm::vec3& p : stroke.stampPoints()) points.push_back({p.x, p.y, p.z});
                replay.record["stamp_points"] = points;
                if (stroke.tool() == ToolKind::Sculpt && !stroke.stampPoints().empty())
                    recordPile(stroke);
                recordChangeBox(stroke.changedBounds());
                stroke.end();
                replay.finishing = true;
            }
        }
    }

    return true;
}

// Where an action's edits changed the fields, grown by twice the largest object reach (collisions at the
// rim count as inside): its statistics count instances inside and outside it.
void EditorSession::recordChangeBox(Bounds box) {
    const float grow = 2.0f * reach_m + std::max(0.0f, scene->doc->ghostTile().settings.delta_m);
    box.lo -= grow;
    box.hi += grow;
    replay.record["box"] = {{"min", {box.lo.x, box.lo.y, box.lo.z}}, {"max", {box.hi.x, box.hi.y, box.hi.z}}};
}

// The union of the supports of `id`'s stroke (Document::strokeMembers), and its members' centres ([x, y, z]
// each, in strokeMembers' order) in *centres: a test sees every member move, not just the one grabbed.
Bounds EditorSession::strokeBounds(const Document& d, uint64_t id, nlohmann::json* centres) {
    Bounds all;
    *centres = nlohmann::json::array();
    for (uint64_t member : d.strokeMembers(id)) {
        Primitive p;
        if (!d.findPrimitive(member, nullptr, &p)) continue;
        all = unite(all, editBounds(p));
        centres->push_back({p.center_m.x, p.center_m.y, p.center_m.z});
    }
    return all;
}

void EditorSession::recordPile(const BrushStroke& st) {
    replay.record["pile"] = pileRecord(*doc, st);
    replay.record["user_primitives_after"] = doc->primitiveIds(st.sculptType()).size();
}

size_t EditorSession::replayType(const std::string& name) {
    const auto it = std::find(view.type_names.begin(), view.type_names.end(), name);
    if (it != view.type_names.end()) return size_t(it - view.type_names.begin());
    *error = "replay: action " + std::to_string(replay.index) + ": no detail type '" + name + "'";
    return kNoType;
}

// A replayed brush's ray: straight down onto the point, or ("from_camera") the ray the mouse over that
// point's ground would cast from the current view.
Ray EditorSession::strokeRay(const ReplayAction& a, glm::vec2 xy) const {
    const Ray down = rayDownOnto(*doc, xy);
    if (!a.from_camera) return down;
    const SurfaceHit ground = pickGround(*doc, down);
    const glm::vec3 eye = camera.eye();
    const glm::vec3 to = ground.hit ? ground.point_m : glm::vec3(xy, 0.0f);
    return Ray{eye, glm::normalize(to - eye)};
}

// A stroke's first step: the brush from the action, the stroke begun at the path's first point.
bool EditorSession::startReplayStroke(const ReplayAction& a) {
    std::string op_error;
    BrushSettings brush = tools.brush;
    brush.radius_m = a.radius_m;
    brush.strength = a.strength;
    brush.falloff_m = a.falloff_m;
    brush.subtract = a.subtract;
    brush.type_mix.assign(view.type_names.size(), 0.0f);
    json types = json::object();
    for (const auto& [name, weight] : a.types) {
        const size_t t = replayType(name);
        if (t == kNoType) return false;
        brush.type_mix[t] = weight;
        brush.sculpt_type = t;
        types[name] = weight;
    }
    // Paint and erase work on the ground unless the script names a pile ("surface").
    if (a.kind != ReplayKind::SculptStroke) brush.sculpt_type = SIZE_MAX;
    if (!a.surface.empty()) {
        brush.sculpt_type = replayType(a.surface);
        if (brush.sculpt_type == kNoType) return false;
    }
    replay.record["types"] = types;
    replay.record["radius"] = a.radius_m;
    const ToolKind tool = a.kind == ReplayKind::PaintStroke    ? ToolKind::Paint
                          : a.kind == ReplayKind::SculptStroke ? ToolKind::Sculpt
                                                               : ToolKind::Erase;
    if (tool == ToolKind::Sculpt && brush.sculpt_type < view.type_names.size())
        replay.record["user_primitives_before"] = doc->primitiveIds(brush.sculpt_type).size();
    replay.path = strokePath(a);
    replay.step = 0;
    if (!stroke.begin(doc, tool, brush, strokeRay(a, replay.path[0]), 0.0, &op_error))
        messages.push_back(op_error);
    if (stroke.stamps() > 0)
        pending_stamps.push_back({doc->live().generation(), Clock::now(), int(replay.index)});
    replay.step = 1;
    return true;
}

// Any other action, started (a move or a Ghost Tile build runs on over the next frames).
bool EditorSession::runReplayAction(const ReplayAction& a) {
    std::string op_error;
    bool continue_move = false;  // a move runs over the next frames
    switch (a.kind) {
        case ReplayKind::Undo:
            replay.record["ok"] = doc->undo();
            break;
        case ReplayKind::Redo:
            replay.record["ok"] = doc->redo();
            break;
        case ReplayKind::Save:
        case ReplayKind::SaveAs: {
            const bool ok = a.kind == ReplayKind::Save ? doc->save(&op_error)
                                                       : doc->saveAs(a.path, &op_error);
            replay.record["ok"] = ok;
            if (!ok) {
                replay.record["error"] = op_error;
                messages.push_back("Save failed: " + op_error);
            }
            replay.record["path"] = a.kind == ReplayKind::Save ? doc->path() : a.path;
            break;
        }
        case ReplayKind::Screenshot:
            (a.ui ? ui_screenshot_path : screenshot_request_path) = a.path;
            screenshot_overlays = a.overlays;
            replay.record["path"] = a.path;
            break;
        case ReplayKind::Move: {
            // The user primitive whose centre is nearest `from` in XY, dragged by the
            // Select tool's MoveDrag on rays straight down (one position per frame).
            uint64_t nearest = 0;
            float nearest_d = 1e30f;
            for (size_t t = 0; t < view.type_names.size(); ++t)
                for (uint64_t id : doc->primitiveIds(t)) {
                    Primitive p;
                    if (!doc->findPrimitive(id, nullptr, &p)) continue;
                    const float d = glm::length(glm::vec2(p.center_m) - a.points.front());
                    if (d < nearest_d) {
                        nearest_d = d;
                        nearest = id;
                    }
                }
            Primitive p;
            if (nearest != 0 && doc->findPrimitive(nearest, nullptr, &p) &&
                move_drag.begin(doc, nearest, rayDownOnto(*doc, a.points.front()))) {
                tools.selected = nearest;
                replay.record["id"] = nearest;
                replay.record["from_center"] = {p.center_m.x, p.center_m.y, p.center_m.z};
                replay.moved_from = strokeBounds(*doc, nearest, &replay.record["from_centers"]);
                replay.record["stroke_ids"] = doc->strokeMembers(nearest);
                replay.path = strokePath(a);
                replay.step = 0;
                continue_move = true;
            } else {
                replay.record["ok"] = false;
                messages.push_back("replay: move: no movable user primitive");
            }
            break;
        }
        case ReplayKind::GhostTile: {
            // Builds in the background like the panel's Build; the action ends when the job has
            // ended and (if it was applied) the new tile's result is on screen.
            GhostTileSpec spec = ghostTileSpec(doc->project());
            if (!applyReplayGhostTile(a, &spec, &op_error) ||
                !(ghost_job = doc->startGhostTileJob(std::move(spec), &op_error))) {
                replay.record["ghost_tile"] = {{"ok", false}, {"error", op_error}};
                messages.push_back(op_error);
            } else {
                ghost_job_doc = doc;
                ghost_job_action = int(replay.index);
            }
            break;
        }
        case ReplayKind::SetAttractor: {
            windows.particles = true;  // the edit shows there, as for the menu
            const auto& systems = *doc->particles();
            if (a.system >= systems.size() || a.attractor >= systems[a.system].scene.attractors.size()) {
                *error = "set_attractor: no attractor " + std::to_string(a.attractor) + " in particle system " +
                         std::to_string(a.system) + " (the document has " + std::to_string(systems.size()) + ")";
                return false;
            }
            ParticleSystemFile system = systems[a.system];
            Attractor& at = system.scene.attractors[a.attractor];
            if (a.has_a) at.a_m = a.a_m;
            if (!std::isnan(a.influence_m)) at.influence_m = a.influence_m;
            if (!std::isnan(a.charge)) at.charge = {ChargeKey{0, a.charge}};
            replay.record["ok"] = doc->setParticleSystem(a.system, system, &op_error);
            if (!op_error.empty()) replay.record["error"] = op_error;
            replay.record["undo_name"] = doc->canUndo() ? doc->undoName() : "";
            if (a.cancel) {
                // As the window's Cancel while the edit grows: the growth stops and the edit is undone.
                replay.record["cancelled"] = cancelStrands();
            }
            break;
        }
        case ReplayKind::ParticleEntry: {
            windows.particles = true;
            if (a.system >= doc->project().particles.size()) {
                *error = "particle_entry: no particle system " + std::to_string(a.system);
                return false;
            }
            const ParticleSystemRef& entry = doc->project().particles[a.system];
            replay.record["ok"] = doc->setParticleEntry(a.system, a.entry_name.value_or(entry.name),
                                                        a.entry_offset.value_or(entry.offset_m), &op_error);
            if (!op_error.empty()) replay.record["error"] = op_error;
            replay.record["undo_name"] = doc->canUndo() ? doc->undoName() : "";
            break;
        }
        case ReplayKind::SetSeed:
            replay.record["seed"] = a.seed;
            replay.record["ok"] = doc->setSeed(a.seed, &op_error);
            break;
        case ReplayKind::SetInstancing: {
            const size_t t = replayType(a.type);
            if (t == kNoType) return false;
            InstancingDesc desc = doc->project().detail_types[t].instancing;
            replay.record["type"] = a.type;
            replay.record["ok"] =
                applyInstancingChanges(a.instancing_json, &desc, &op_error) &&
                doc->setInstancing(t, desc, &op_error);
            replay.record["strategy"] =
                priorityStrategyName(doc->project().detail_types[t].instancing.strategy);
            break;
        }
        case ReplayKind::Export: {
            export_settings.path = a.path;
            export_settings.plain_nodes = a.plain_nodes;
            export_settings.chunk_size_m =
                a.chunk_m > 0.0f ? a.chunk_m : doc->project().chunk_size_m;
            requests.start_export = true;  // started below, the way the Export button does
            export_record = json();
            windows.export_panel = true;  // its progress shows there, as for the menu
            replay.record["path"] = a.path;
            break;
        }
        case ReplayKind::SetVisible: {
            replay.record["static_triangles_before"] = renderer->stats().static_triangles;
            if (!a.node_path.empty()) {
                if (!envNodeAt(doc->project().environment, a.node_path)) {
                    *error = "set_visible: no environmental node " + envPathText(a.node_path);
                    return false;
                }
                replay.record["node"] = a.node_path;
                replay.record["visible"] = a.visible;
                std::erase(environment_panel.hidden, a.node_path);
                if (!a.visible) environment_panel.hidden.push_back(a.node_path);
                if (scene) showStaticMeshes();  // this frame already draws it so
                break;
            }
            const size_t t = replayType(a.type);
            if (t == kNoType) return false;
            replay.record["type"] = a.type;
            replay.record["visible"] = a.visible;
            replay.record["drawn_instances_before"] = renderer->stats().instances_drawn;
            type_visible.resize(view.type_names.size(), 1);
            type_visible[t] = a.visible ? 1 : 0;
            renderer->setTypeVisible(t, a.visible);  // this frame already draws it so
            break;
        }
        case ReplayKind::Open:
        case ReplayKind::New:
            load_error.clear();
            if (a.kind == ReplayKind::New)
                startNew();
            else
                requestOpen(a.path, RecoverChoice::Ask);
            replay.record["path"] = a.path;
            break;
        case ReplayKind::View:
            if (a.has_target) camera.target = a.target;
            if (a.distance_m > 0.0f) camera.distance_m = a.distance_m;
            if (!std::isnan(a.yaw_deg)) camera.yaw_rad = glm::radians(a.yaw_deg);
            if (!std::isnan(a.pitch_deg)) camera.pitch_rad = glm::radians(a.pitch_deg);
            camera_moved = true;
            break;
        case ReplayKind::EnvView:
            windows.environment = true;
            environment_panel.view.on = a.channel != "off";
            channelMapFromName(a.channel, &environment_panel.view.channel);  // checked when read
            environment_panel.view.height_m = a.value;
            environment_panel.view.surfaces = a.on_surface;
            break;
        case ReplayKind::ShowWindow:
            *windowToggle(&windows, a.window) = a.visible;  // the name was checked when the script was read
            break;
        default:
            if (editsEnvironment(a.kind)) return startEnvReplayAction(a);  // finishing set there (drags run on)
            break;
    }
    if (!continue_move) replay.finishing = a.kind != ReplayKind::GhostTile || !ghost_job;
    return true;
}

void EditorSession::finishReplayAction() {
    Document& d = *scene->doc;
    const CandidateSet& c = d.ghostTile().candidates;
    const std::vector<std::string>& names = view.type_names;
    json& r = replay.record;
    const InstanceStore empty;
    const InstanceStore& before = replay.before ? *replay.before : empty;
    r["instances_after"] = store->instanceCount();
    r["per_type_after"] = perTypeJson(names, perTypeCounts(*store, c));
    r["instance_store_hash_after"] = hex64(instanceStoreHash(*store));
    const ReplayKind kind = options.replay[replay.index].kind;
    if (kind == ReplayKind::Export) r.update(export_record);
    if (kind == ReplayKind::SetVisible) {
        r["drawn_instances_after"] = renderer->stats().instances_drawn;
        r["static_triangles_after"] = renderer->stats().static_triangles;
    }
    if (kind == ReplayKind::SetAttractor) r["particles"] = strandsJson();
    if (kind == ReplayKind::EnvView && environment_panel.view.on) {
        updateChannelMap();
        r["channel_map"] = {{"channel", channelMapName(environment_panel.view.channel)},
                            {"lo", channel_map.lo},
                            {"hi", channel_map.hi},
                            {"cells", channel_map.values.size()},
                            {"surface_triangles", channel_map.surface_triangles}};
    }
    if (live_environment && editsEnvironment(kind)) r["environment"] = environmentJson();
    if (kind == ReplayKind::View) {
        r["eye"] = vec3Json(camera.eye());
        r["target"] = vec3Json(camera.target);
        r["eye_ground_z"] = groundZ(glm::vec2(camera.eye()));
    }
    if (kind == ReplayKind::Open || kind == ReplayKind::New) {
        r["camera_target"] = vec3Json(camera.target);
        r["camera_eye"] = vec3Json(camera.eye());
        r["ok"] = load_error.empty();
        if (!load_error.empty()) r["error"] = load_error;
        r["document"] = d.path();
    }
    if (r.contains("pile")) {
        r["pile"]["instances"] = pileInstancesJson(d, *store, r["pile"]);
        r["pile"]["instances_before"] = pileInstancesJson(d, before, r["pile"]);
    }
    if (r.contains("box")) {
        auto corner = [&](const char* key) {
            const json& v = r["box"][key];
            return glm::vec3(v[0].get<float>(), v[1].get<float>(), v[2].get<float>());
        };
        const Bounds box{corner("min"), corner("max")};
        const float s = d.ghostTile().settings.tile_size_m;
        const BoxCounts b = countInstancesInBox(before, c, s, box),
                        a = countInstancesInBox(*store, c, s, box);
        r["inside_before"] = perTypeJson(names, b.inside);
        r["inside_after"] = perTypeJson(names, a.inside);
        r["outside_before"] = perTypeJson(names, b.outside);
        r["outside_after"] = perTypeJson(names, a.outside);
        r["stamp_to_frame_ms"] = replay.stamp_ms;
    }
    r["dirty"] = d.isDirty();
    r["undo_name"] = d.canUndo() ? d.undoName() : "";  // what Edit > Undo would now say
    r["uploads"] = replay.uploads;
    json tiles = json::array();
    for (uint64_t key : replay.uploaded_tiles) {
        const glm::ivec3 t = unpackTile(key);
        tiles.push_back({t.x, t.y, t.z});
    }
    r["uploaded_tiles"] = tiles;
    r["tiles_resident"] = instances.tileCount();
    r["tile_size_m"] = instances.tile_size_m;
    result->actions.push_back(r);
    replay = ReplayState{replay.index + 1};
    if (replay.index >= options.replay.size() && !scripted && !stats_written) {
        writeInteractiveStats();
        stats_written = true;
    }
}

}  // namespace ug::editor
