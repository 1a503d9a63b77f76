// The environmental objects in the editor (issue 13): every edit, undo and redo of the environment moves
// Document::environmentGeneration(); the compiled environment then goes to the LiveEnvironment worker,
// which updates the snow and icicles only where the edit reached. The newest finished meshes replace the
// scene's "env/", "snow/" and "icicles/" static meshes at the frame boundary, so the view, the export
// and the replay's settled state see the same effects. The detail instances (scattered leaves, what
// rests on a bench) follow through the live instancer (Document::setEnvironment).
#include <cstdio>

#include "editor/editor_session.h"
#include "env/env_json.h"
#include "env/env_outputs.h"

namespace ug::editor {

namespace {

bool isEnvironmentMesh(const MeshInstances& m) {
    return m.name.rfind("env/", 0) == 0 || m.name.rfind("snow/", 0) == 0 || m.name.rfind("icicles/", 0) == 0;
}

}  // namespace

void EditorSession::startEnvironment() {
    live_environment.reset();
    last_environment = LiveEnvironmentResult{};
    environment_panel = EnvironmentPanelState{};
    pending_env_stamps.clear();
    const Document& d = *scene->doc;
    environment_submitted = environment_shown = d.environmentGeneration();
    renderer->releaseThumbnails();
    palette_coverage.clear();
    if (d.project().environment.types.empty()) return;  // nothing can be placed
    live_environment = std::make_unique<LiveEnvironment>(doc_options.threads, d.environment(), scene->env_effects);
    // The palette's pictures, rendered once per document by the renderer (the window only shows them), in
    // the types' colours (their textures are not baked for this: tens of ms each).
    for (const EnvObjectType& type : d.environment()->types()) {
        float coverage = 0.0f;
        Material flat = type.desc.material;
        flat.texture = TextureKind::None;
        const SurfaceMaterial look = resolveMaterial(flat, type.mesh->base_color);
        environment_panel.thumbnails.push_back(renderer->meshThumbnail(*type.mesh, look, kPaletteThumbnailPx, &coverage));
        palette_coverage.push_back(coverage);
    }
}

void EditorSession::syncEnvironment() {
    if (!scene || !live_environment) {
        environment_panel.computing = false;
        return;
    }
    // The Outliner's eyes: the view changes when the objects they hide do.
    if (scene->env_scene &&
        envObjectMask(scene->env_scene->desc(), environment_panel.hidden, scene->env_scene->objects().size()) !=
            env_hidden_drawn)
        showStaticMeshes();
    submitEnvironment();
    LiveEnvironmentResult r;
    if (!live_environment->poll(&r)) {
        environment_panel.computing = live_environment->busy();
        return;
    }
    if (r.effects) {
        std::vector<MeshInstances>& statics = scene->static_meshes;
        std::erase_if(statics, isEnvironmentMesh);
        statics.insert(statics.begin(), std::make_move_iterator(r.meshes.begin()), std::make_move_iterator(r.meshes.end()));
        scene->env_effects = r.effects;
        scene->env_scene = r.scene;
        environment_shown = r.generation;
        showStaticMeshes();
    }
    if (!r.error.empty()) messages.push_back(r.error);
    char status[160];
    const EnvEffectsStats& s = r.effects ? r.effects->stats : EnvEffectsStats{};
    std::snprintf(status, sizeof status, "%llu snow triangles, %llu icicles, in %.0f ms (%s)",
                  (unsigned long long)s.snow_triangles, (unsigned long long)s.icicles, 1000.0 * r.seconds,
                  r.dirty_boxes ? "updated where the edit reached" : "nothing changed");
    environment_panel.status = status;
    r.meshes.clear();
    last_environment = std::move(r);
    environment_panel.computing = live_environment->busy();
}

bool EditorSession::submitEnvironment() {
    Document& d = *scene->doc;
    if (d.environmentGeneration() == environment_submitted) return false;
    environment_submitted = d.environmentGeneration();
    live_environment->submit(d.environment(), environment_submitted);
    // Instances packed from now on pick their look (wet, dry) in the edited environment.
    scene->looks.environment = d.environment();
    return true;
}

void EditorSession::showFreshEnvironment(std::chrono::milliseconds budget) {
    if (!scene || !live_environment || !submitEnvironment()) return;
    if (live_environment->waitForResult(budget)) syncEnvironment();
}

void EditorSession::showStaticMeshes() {
    env_hidden_drawn.clear();
    if (scene->env_scene && scene->env_effects)
        env_hidden_drawn =
            envObjectMask(scene->env_scene->desc(), environment_panel.hidden, scene->env_scene->objects().size());
    drawn_static_meshes.clear();
    if (!env_hidden_drawn.empty()) {
        // The scene's list stays whole (the export writes it); the view draws a copy without the hidden
        // objects (the meshes are shared, so their levels of detail and buffers are kept).
        drawn_static_meshes = envMeshInstances(*scene->env_scene, *scene->env_effects, &env_hidden_drawn);
        for (const MeshInstances& m : scene->static_meshes)
            if (!isEnvironmentMesh(m)) drawn_static_meshes.push_back(m);
    }
    renderer->setStaticMeshes(env_hidden_drawn.empty() ? &scene->static_meshes : &drawn_static_meshes);
    const gl::RenderStats& rs = renderer->stats();
    result->static_swaps.push_back({rs.static_entries_uploaded, rs.static_entries_kept});
}

void EditorSession::noteEnvStamp(uint64_t generation_before, int action) {
    if (scene && scene->doc->environmentGeneration() != generation_before)
        pending_env_stamps.push_back({scene->doc->environmentGeneration(), Clock::now(), action});
}

void EditorSession::timeEnvStamps(Clock::time_point frame_end) {
    std::erase_if(pending_env_stamps, [&](const PendingStamp& p) {
        if (p.generation > environment_shown) return false;
        const char* by = p.action >= 0 && size_t(p.action) < options.replay.size()
                             ? replayKindName(options.replay[size_t(p.action)].kind)
                             : "mouse";
        result->env_stamp_to_frame_ms[by].push_back(
            std::chrono::duration<double, std::milli>(frame_end - p.time).count());
        return true;
    });
}

void EditorSession::updateChannelMap() {
    // A 10 m street at 0.1 m cells: 10,000 samples with their shelter rays, and its objects' vertices, a few
    // tens of ms, once per change.
    constexpr float kChannelMapCellM = 0.1f;
    const ChannelMapKey key{doc, doc->environmentGeneration(), environment_panel.view};
    if (key == channel_map_key) return;
    channel_map = buildChannelMap(*doc, environment_panel.view, kChannelMapCellM);
    channel_map_key = key;
    environment_panel.view_lo = channel_map.lo;
    environment_panel.view_hi = channel_map.hi;
    renderer->setChannelOverlay(channel_map.geometry.hull);
}

bool EditorSession::environmentSettled() const {
    return !live_environment ||
           (environment_shown == scene->doc->environmentGeneration() && !live_environment->busy());
}

nlohmann::json EditorSession::environmentJson() const {
    const Document& d = *scene->doc;
    const EnvironmentDesc& env = d.project().environment;
    size_t local_fields = 0;
    for (const EnvFieldDesc& f : env.global_fields) local_fields += f.everywhere ? 0 : 1;
    // Objects as placed: references to reusable groups expanded (the compiled scene's).
    json j = {{"objects", d.environment()->objects().size()},
              {"roots", env.roots.size()},
              {"global_fields", env.global_fields.size() - local_fields},
              {"local_fields", local_fields},
              {"generation", d.environmentGeneration()},
              {"settled", environmentSettled()},
              {"brush", environment_panel.brush_on ? weatherBrushName(environment_panel.weather.brush) : "off"},
              {"tree", environmentToJson(env)["tree"]},
              {"palette_coverage", palette_coverage}};
    if (scene->env_effects) {
        const EnvEffectsStats& s = scene->env_effects->stats;
        j["snow_triangles"] = s.snow_triangles;
        j["icicles"] = s.icicles;
        j["classes_reused"] = s.classes_reused;
    }
    j["last"] = {{"ok", last_environment.error.empty()},
                 {"seconds", last_environment.seconds},
                 {"dirty_boxes", last_environment.dirty_boxes}};
    if (!last_environment.error.empty()) j["last"]["error"] = last_environment.error;
    return j;
}

}  // namespace ug::editor
