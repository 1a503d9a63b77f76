// runViewer runs an EditorSession (editor_session.h: the state, and one file per subsystem), whose loop is
// the flat main loop of STYLE.md: poll -> apply finished background work (an opened document, a live
// instancing result) -> new UI frame -> navigation, tools, panels, dialogs -> replay step -> render ->
// (screenshot) -> UI on top -> swap -> stamp timings, replay bookkeeping, autosave.
//
// Live results reach the GPU per tile: the renderer's instance buffers are resident (render_data.h
// ResidentTiles: every tile owns a slot per detail type), so a result re-packs from the store only the
// tiles it changed (LiveResult::changed_tiles) and uploads only their slots; a full result (first open,
// LiveResult::full) rebuilds them all. The next frame rebuilds the indirect commands (cull + LOD per tile).
//
// Statistics of a replay, per action (ViewerResult::actions): "action", "frame" (when it started), "uploads"
// ({"tiles", "bytes"} per live result taken while the action ran), "uploaded_tiles" (every tile re-uploaded
// then, [x, y, z]), "tiles_resident", "stamps", "instances_before"/"_after", "per_type_before"/"_after",
// "instance_store_hash_before"/"_after"; for strokes "stamp_points"; for strokes and moves "box" {min, max}
// (the changed primitives' supports grown by twice the largest object reach, so collisions at the rim count
// as inside), "inside_before"/"_after" and "outside_before"/"_after" per
// type (instance origins, instance_query.h), "stamp_to_frame_ms" (per stamp, wall clock from the edit to
// the end of the first frame that shows its result). "before" is the settled state the action started
// from, "after" the settled state once the live instancer is idle and its result is on screen.
// Panels' actions add: export "ok", "error", "exported_instances", "export_seconds"; open and new "ok",
// "error", "document" (their "before" is the replaced document's); set_visible "drawn_instances_before"/
// "_after" (the renderer's instances drawn in the frame before and the frame after); move "id",
// "from_center", "to_center", "moves"; ghost_tile "ghost_tile" (replay.h); sculpt strokes "pile" (pileRecord:
// the pile's centroid, height, radius and volume around the first stamp's ground point, the cones it left)
// and "user_primitives_before"/"_after" (the sculpt type's). Mouse sculpt strokes are kept in
// ViewerResult::sculpt_strokes ("sculpt_strokes"), so a session driven by real input is judged the same way.
#include "editor/viewer.h"

#include <algorithm>

#include "core/hash.h"
#include "editor/default_view.h"
#include "editor/editor_session.h"

namespace ug::editor {

namespace {

// Per source of the environment edits: how many, and their median and 95th percentile (ms).
nlohmann::json envStampsJson(const std::map<std::string, std::vector<double>>& by) {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [source, ms] : by)
        j[source] = {{"stamps", ms.size()}, {"p50", percentile(ms, 0.5)}, {"p95", percentile(ms, 0.95)}};
    return j;
}

}  // namespace

using nlohmann::json;

namespace {

// Either view holds the environmental objects and their effects too, when the scene has any.
Bounds withStaticMeshes(const EditorScene& s, const Bounds& b) {
    return s.static_meshes.empty() ? b : unite(b, staticMeshesBounds(s.static_meshes));
}

}  // namespace

// What "frame all" frames (default_view.h).
Bounds framingBounds(const EditorScene& s, const ResidentTiles* instances) {
    return withStaticMeshes(s, editor::framingBounds(s.doc->compiled().extent, s.has_terrain ? &s.terrain : nullptr,
                                                     instances));
}

// The view a scene opens on (default_view.h); Home frames everything (framingBounds).
Bounds openingBounds(const EditorScene& s, const ResidentTiles& instances) {
    return withStaticMeshes(
        s, editor::openingBounds(s.doc->compiled().extent, s.has_terrain ? &s.terrain : nullptr, &instances, s.meshes));
}

double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t i = std::min(v.size() - 1, size_t(q * double(v.size() - 1) + 0.5));
    return v[i];
}

ViewerStatus runViewer(const ViewerOptions& options, ViewerResult* result, std::string* error) {
    EditorSession session(options, result, error);
    return session.run();
}

json viewerStatsJson(const ViewerResult& r, const LodSettings& lod) {
    json per_type = json::object();
    for (size_t i = 0; i < r.type_names.size(); ++i)
        per_type[r.type_names[i]] = i < r.instances_per_type.size() ? r.instances_per_type[i] : 0;
    return {
        {"scene", r.scene},
        {"instances", r.instances},
        {"instances_per_type", per_type},
        {"instance_store_hash", hex64(r.instance_store_hash)},
        {"instantiate_seconds", r.instantiate_seconds},
        {"frames_measured", r.frames_measured},
        {"frame_ms", r.frame_ms},
        {"frame_ms_p95", r.frame_ms_p95},
        {"triangles", r.triangles},
        {"impostor_points", r.points},
        {"draw_calls", r.draw_calls},
        {"lod_instances",
         {{"lod0", r.lod_instances[0]},
          {"lod1", r.lod_instances[1]},
          {"lod2", r.lod_instances[2]},
          {"impostor", r.lod_instances[3]}}},
        {"lod_settings_px", {{"lod1", lod.lod1_px}, {"lod2", lod.lod2_px}, {"impostor", lod.impostor_px}}},
        {"tiles_visible", r.tiles_visible},
        {"tiles_culled", r.tiles_culled},
        {"indirect_commands", r.indirect_commands},
        {"tiles_resident", r.tiles_resident},
        {"tiles_uploaded", r.tiles_uploaded},
        {"bytes_uploaded", r.bytes_uploaded},
        {"upload_tiles_p50", percentile(r.upload_tiles, 0.5)},
        {"tile_update_ms_max", r.tile_update_ms_max},
        {"gl_version", r.gl_version},
        {"renderer", r.renderer},
        {"window", {r.window_width, r.window_height}},
        {"framebuffer", {r.framebuffer_width, r.framebuffer_height}},
        {"screenshot", r.screenshot},
        {"document",
         {{"path", r.document_path},
          {"recovered", r.recovered},
          {"dirty", r.dirty},
          {"undo_name", r.undo_name},
          {"user_primitives", r.user_primitives},
          {"autosaves", r.autosaves}}},
        {"stamps", r.stamp_to_frame_ms.size()},
        {"stamp_to_frame_ms_p50", percentile(r.stamp_to_frame_ms, 0.5)},
        {"stamp_to_frame_ms_p95", percentile(r.stamp_to_frame_ms, 0.95)},
        {"repack_ms_max", r.repack_ms_max},
        {"actions", r.actions},
        {"sculpt_strokes", r.sculpt_strokes},
        {"messages", r.messages},
        {"viewport", r.viewport},
        {"particles", r.particles},
        {"environment", r.environment},
        {"env_stamp_to_frame_ms", envStampsJson(r.env_stamp_to_frame_ms)},
        {"static_swaps", r.static_swaps},
        {"window_title", r.window_title}};
}

}  // namespace ug::editor
