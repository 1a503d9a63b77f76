// The Ghost Tile panel (issue 4): edits a pending copy of the tile's settings, raises Build / Cancel for the
// main loop (which owns the background GhostTileJob), shows the document's tile statistics (Ghost Tile
// Table 1: #N, #E, ρ, time, memory) and previews the selected type's collision spheres.
#include <imgui.h>

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <cstring>

#include "editor/panels.h"

namespace ug::editor {

namespace {

const char* const kAnchorModes[] = {"authored", "center", "sphere centers", "surface"};
const char* const kOrientationModes[] = {"uniform random", "tilt"};
const char* const kPositionModes[] = {"uniform", "jittered"};

// The pending copy follows the document (opened, build applied, undone, redone) unless the user has
// edits of their own in it.
void syncWithDocument(const Document& doc, GhostTilePanelState* s) {
    const bool stale = s->synced_doc != &doc || s->synced_generation != doc.tileGeneration();
    if (!stale) return;
    const bool untouched = s->synced_doc != &doc || s->pending == s->synced;
    s->synced = ghostTileSpec(doc.project());
    s->synced_doc = &doc;
    s->synced_generation = doc.tileGeneration();
    if (untouched) s->pending = s->synced;
    s->selected_type = std::clamp(s->selected_type, 0, std::max(0, int(s->pending.types.size()) - 1));
}

void editPath(const char* label, std::string* path) {
    char buffer[1024];
    std::snprintf(buffer, sizeof(buffer), "%s", path->c_str());
    if (ImGui::InputText(label, buffer, sizeof(buffer))) *path = buffer;
}

void editType(DetailModelSource* model, DetailTypeSettings* type) {
    ImGui::TextDisabled("model");
    editPath("file", &model->mesh_path);
    ImGui::DragFloat("model scale", &model->scale, 0.01f, 0.001f, 1000.0f, "%.3f");
    ImGui::Checkbox("Y up (glTF)", &model->y_up);
    int anchor = int(model->anchor_mode);
    if (ImGui::Combo("anchors", &anchor, kAnchorModes, IM_ARRAYSIZE(kAnchorModes)))
        model->anchor_mode = AnchorMode(anchor);
    if (model->anchor_mode == AnchorMode::SphereCenters || model->anchor_mode == AnchorMode::Surface) {
        int count = int(model->anchor_count);
        if (ImGui::InputInt("anchor count", &count)) model->anchor_count = uint32_t(std::clamp(count, 1, 4096));
    } else if (model->anchor_mode == AnchorMode::Authored) {
        ImGui::TextDisabled("%zu authored anchors (from the project file)", model->authored_anchors.size());
    }

    ImGui::TextDisabled("candidates");
    // Typed as a wide integer so an absurd count reaches the validation (and its message) unclipped.
    int64_t count = type->candidate_count;
    const int64_t step = 10;
    if (ImGui::InputScalar("count", ImGuiDataType_S64, &count, &step))
        type->candidate_count = uint32_t(std::clamp<int64_t>(count, 0, int64_t(UINT32_MAX)));
    ImGui::DragFloatRange2("scale range", &type->scale_min, &type->scale_max, 0.01f, 0.01f, 100.0f, "%.2f");
    int position = int(type->position);
    if (ImGui::Combo("positions", &position, kPositionModes, IM_ARRAYSIZE(kPositionModes)))
        type->position = PositionMode(position);
    OrientationDistribution& o = type->orientation;
    int mode = int(o.mode);
    if (ImGui::Combo("orientation", &mode, kOrientationModes, IM_ARRAYSIZE(kOrientationModes))) {
        o.mode = OrientationMode(mode);
        if (o.mode == OrientationMode::Tilt && o.tilt_ranges.empty()) o.tilt_ranges.push_back(TiltRange{});
    }
    if (o.mode == OrientationMode::Tilt) {
        // Tilt ranges: min / max angle from +Z and the weight a range is chosen with (paper Fig. 7).
        for (size_t r = 0; r < o.tilt_ranges.size(); ++r) {
            ImGui::PushID(int(r));
            TiltRange& t = o.tilt_ranges[r];
            ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.55f);
            ImGui::DragFloatRange2("##tilt", &t.min_deg, &t.max_deg, 0.5f, 0.0f, 180.0f, "%.0f deg");
            ImGui::SameLine();
            ImGui::SetNextItemWidth(60.0f);
            ImGui::DragFloat("##weight", &t.weight, 0.01f, 0.01f, 100.0f, "w %.2f");
            ImGui::SameLine();
            const bool remove = o.tilt_ranges.size() > 1 && ImGui::SmallButton("x");
            ImGui::PopID();
            if (remove) {
                o.tilt_ranges.erase(o.tilt_ranges.begin() + long(r));
                break;
            }
        }
        if (ImGui::SmallButton("+ tilt range")) o.tilt_ranges.push_back(TiltRange{});
    }
}

void drawStatistics(const Document& doc) {
    const GhostTile& tile = doc.ghostTile();
    const GhostTileStats& st = tile.stats;
    // Table 1 of the paper counts arcs: #E is twice the colliding pairs, ρ = #E / 2#N.
    ImGui::Text("#N %u candidates, #E %" PRIu64 " arcs (%" PRIu64 " pairs)", st.candidate_count, 2 * st.pair_count,
                st.pair_count);
    ImGui::Text("rho %.1f collisions per candidate", st.rho);
    ImGui::Text("built in %.3f s (%s)", st.build_seconds, cacheOutcomeName(doc.cacheOutcome()));
    ImGui::Text("graph %.1f KiB, %.2f bytes/pair; with frames %.1f KiB", double(st.graph_bytes) / 1024.0,
                st.bytes_per_pair, double(st.total_bytes) / 1024.0);
    const CandidateSet& c = tile.candidates;
    for (uint32_t t = 0; t < c.typeCount() && t < doc.project().detail_types.size(); ++t)
        ImGui::BulletText("%s: %u candidates", doc.project().detail_types[t].model.name.c_str(),
                          c.type_begin[t + 1] - c.type_begin[t]);
}

// The model's spheres as circles in three orthographic views: top (X right, Y up), front (X, Z) and side
// (Y, Z), on one scale so the views compare.
void drawSpherePreview(const DetailModel& model) {
    const float gap = 8.0f;
    const float side = std::clamp((ImGui::GetContentRegionAvail().x - 2.0f * gap) / 3.0f, 60.0f, 220.0f);
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    ImGui::Dummy(ImVec2(3.0f * side + 2.0f * gap, side + ImGui::GetTextLineHeight()));
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const float reach = std::max(1e-6f, model.bounds.radius);
    const float scale = 0.45f * side / reach;
    const int axes[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    const char* const names[3] = {"top (x, y)", "front (x, z)", "side (y, z)"};
    for (int v = 0; v < 3; ++v) {
        const ImVec2 lo(origin.x + float(v) * (side + gap), origin.y);
        const ImVec2 hi(lo.x + side, lo.y + side);
        draw->AddRectFilled(lo, hi, IM_COL32(30, 33, 38, 255));
        draw->AddRect(lo, hi, IM_COL32(90, 90, 100, 255));
        const ImVec2 mid(0.5f * (lo.x + hi.x), 0.5f * (lo.y + hi.y));
        auto project = [&](const glm::vec3& p) {
            const glm::vec3 q = p - model.bounds.center;
            // Screen Y grows downwards: flip so +Y / +Z point up.
            return ImVec2(mid.x + scale * q[axes[v][0]], mid.y - scale * q[axes[v][1]]);
        };
        draw->PushClipRect(lo, hi, true);
        for (const Sphere& s : model.spheres)
            draw->AddCircle(project(s.center), std::max(1.0f, scale * s.radius), IM_COL32(120, 200, 255, 170), 24);
        for (const glm::vec3& a : model.anchors) {
            const ImVec2 p = project(a);
            draw->AddCircleFilled(p, 2.0f, IM_COL32(255, 190, 80, 255));
        }
        draw->AddCircle(project(model.bounds.center), scale * model.bounds.radius, IM_COL32(110, 110, 110, 200), 48);
        draw->PopClipRect();
        draw->AddText(ImVec2(lo.x, hi.y), IM_COL32(180, 180, 180, 255), names[v]);
    }
}

}  // namespace

void drawGhostTilePanel(const Document* doc, GhostTilePanelState* s, bool* open) {
    if (!*open) return;
    ImGui::SetNextWindowPos(ImVec2(350, 30), ImGuiCond_FirstUseEver);
    // As tall as the viewport allows: settings, statistics and the sphere views fit without scrolling.
    ImGui::SetNextWindowSize(ImVec2(460, std::min(830.0f, ImGui::GetMainViewport()->Size.y - 40.0f)),
                             ImGuiCond_FirstUseEver);
    if (!beginDocumentPanel("Ghost Tile", open, doc != nullptr)) return;
    syncWithDocument(*doc, s);
    GhostTileSpec& p = s->pending;
    const bool modified = !(p == ghostTileSpec(doc->project()));

    if (ImGui::CollapsingHeader("Settings", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::BeginDisabled(s->running);
        ImGui::DragFloat("tile size (m)", &p.settings.tile_size_m, 0.01f, 0.01f, 1000.0f, "%.3f");
        ImGui::DragFloat("delta (m)", &p.settings.delta_m, 0.0005f, -1.0f, 1.0f, "%.4f");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("collision threshold: d(A, B) <= delta collides; < 0 lets objects interpenetrate");
        ImGui::InputScalar("seed", ImGuiDataType_U64, &p.settings.seed);
        if (!p.types.empty()) {
            std::vector<const char*> names;
            for (const DetailTypeSettings& t : p.types) names.push_back(t.name.c_str());
            ImGui::Combo("detail type", &s->selected_type, names.data(), int(names.size()));
            const size_t t = size_t(std::clamp(s->selected_type, 0, int(p.types.size()) - 1));
            ImGui::PushID(int(t));
            editType(&p.models[t], &p.types[t]);
            ImGui::PopID();
        }
        ImGui::EndDisabled();

        ImGui::Separator();
        if (s->running) {
            ImGui::ProgressBar(s->progress, ImVec2(-80.0f, 0.0f));
            ImGui::SameLine();
            if (ImGui::Button("Cancel")) s->cancel = true;
        } else {
            ImGui::BeginDisabled(!modified);
            if (ImGui::Button("Build")) s->build = true;
            ImGui::SameLine();
            if (ImGui::Button("Revert")) p = ghostTileSpec(doc->project());
            ImGui::EndDisabled();
            ImGui::SameLine();
            ImGui::TextDisabled(modified ? "edited, not built" : "as the document");
        }
        if (!s->last_outcome.empty()) ImGui::TextWrapped("%s", s->last_outcome.c_str());
    }
    if (ImGui::CollapsingHeader("Statistics", ImGuiTreeNodeFlags_DefaultOpen)) drawStatistics(*doc);
    if (ImGui::CollapsingHeader("Collision spheres", ImGuiTreeNodeFlags_DefaultOpen)) {
        const size_t t = size_t(std::max(0, s->selected_type));
        if (t < doc->models().size()) {
            const DetailModel& m = doc->models()[t];
            ImGui::Text("%s: %zu spheres, %zu anchors, radius %.3f m", m.name.c_str(), m.spheres.size(),
                        m.anchors.size(), m.bounds.radius);
            drawSpherePreview(m);
        }
    }
    ImGui::End();
}

}  // namespace ug::editor
