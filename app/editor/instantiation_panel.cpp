// The Instantiation window: what InstancingDesc (scene/project.h) exposes per detail type, the seed, and
// the live instancer's statistics with a plot of the recent run times.
//
// Undo granularity: widgets edit a copy; the document gets one setInstancing / setSeed when an edit is
// finished (a drag released, a field left, a combo or checkbox clicked), so dragging a slider is one undo
// step and one re-instantiation instead of one per frame.
#include <imgui.h>

#include <algorithm>

#include "editor/panels.h"

namespace ug::editor {

namespace {

constexpr PriorityStrategy kStrategies[] = {PriorityStrategy::Random, PriorityStrategy::Elevation,
                                            PriorityStrategy::DistanceToBoundary};

// Edits one type's desc; true when an edit finished and should be committed.
bool editInstancing(InstancingDesc* d) {
    bool commit = false;
    if (ImGui::BeginCombo("strategy", priorityStrategyName(d->strategy))) {
        for (const PriorityStrategy s : kStrategies)
            if (ImGui::Selectable(priorityStrategyName(s), s == d->strategy)) {
                d->strategy = s;
                commit = true;
            }
        ImGui::EndCombo();
    }
    if (d->strategy != PriorityStrategy::Random) {
        ImGui::DragFloat("layer (m)", &d->layer_m, 0.001f, 0.001f, 10.0f, "%.3f",
                         ImGuiSliderFlags_AlwaysClamp);
        commit |= ImGui::IsItemDeactivatedAfterEdit();
    }
    OrientationDesc& o = d->orientation;
    commit |= ImGui::Checkbox("orientation constraint", &o.enabled);
    if (o.enabled) {
        ImGui::Indent();
        int kind = int(o.kind);
        commit |= ImGui::RadioButton("direction", &kind, int(DirectionFieldKind::Constant));
        ImGui::SameLine();
        commit |= ImGui::RadioButton("density gradient", &kind, int(DirectionFieldKind::Gradient));
        o.kind = DirectionFieldKind(kind);
        if (o.kind == DirectionFieldKind::Constant) {
            ImGui::DragFloat3("up", &o.direction.x, 0.01f, -1.0f, 1.0f);
            if (ImGui::IsItemDeactivatedAfterEdit()) {
                // The project requires a unit, non-zero direction: normalise, or fall back to +Z.
                const float len = glm::length(o.direction);
                o.direction = len > 1e-6f ? o.direction / len : glm::vec3(0.0f, 0.0f, 1.0f);
                commit = true;
            }
        }
        ImGui::SliderFloat("max angle (deg)", &o.max_angle_deg, 0.0f, 180.0f, "%.0f",
                           ImGuiSliderFlags_AlwaysClamp);
        commit |= ImGui::IsItemDeactivatedAfterEdit();
        ImGui::Unindent();
    }
    SizeDesc& s = d->size;
    commit |= ImGui::Checkbox("size constraint", &s.enabled);
    if (s.enabled) {
        ImGui::Indent();
        if (s.kind == SizeFieldKind::Constant) {
            ImGui::DragFloat("target scale", &s.target, 0.01f, 0.01f, 100.0f, "%.2f",
                             ImGuiSliderFlags_AlwaysClamp);
            commit |= ImGui::IsItemDeactivatedAfterEdit();
        } else {
            // The ramp's field is a density tree from the file; only its mapping is edited here.
            ImGui::TextDisabled("ramp over a field from the file");
            float values[2] = {s.value_lo, s.value_hi}, scales[2] = {s.scale_lo, s.scale_hi};
            ImGui::DragFloat2("values lo/hi", values, 0.01f);
            if (ImGui::IsItemDeactivatedAfterEdit() && values[0] < values[1]) {
                s.value_lo = values[0];
                s.value_hi = values[1];
                commit = true;
            }
            ImGui::DragFloat2("scales lo/hi", scales, 0.01f, 0.01f, 100.0f, "%.2f",
                              ImGuiSliderFlags_AlwaysClamp);
            if (ImGui::IsItemDeactivatedAfterEdit()) {
                s.scale_lo = scales[0];
                s.scale_hi = scales[1];
                commit = true;
            }
        }
        ImGui::DragFloat("tolerance", &s.tolerance, 0.005f, 0.0f, 10.0f, "%.3f",
                         ImGuiSliderFlags_AlwaysClamp);
        commit |= ImGui::IsItemDeactivatedAfterEdit();
        ImGui::Unindent();
    }
    return commit;
}

void drawStatistics(const InstantiationView& v) {
    if (!v.have_result) {
        ImGui::TextDisabled("no result yet");
        return;
    }
    const InstanceStats& s = v.stats;
    ImGui::Text("#I %llu   #R %llu   (%llu candidates tested)", (unsigned long long)s.instances,
                (unsigned long long)s.rejected, (unsigned long long)s.candidates_tested);
    ImGui::Text("rejected: culled %llu, density %llu, constraint %llu, collision %llu",
                (unsigned long long)s.culled, (unsigned long long)s.density_rejected,
                (unsigned long long)s.constraint_rejected, (unsigned long long)s.collision_rejected);
    ImGui::Text("%s run: %llu dirty tiles, %llu changed", v.full ? "full" : "incremental",
                (unsigned long long)s.tiles_touched, (unsigned long long)v.changed_tiles);
    ImGui::Text("last update %.1f ms%s", s.seconds * 1e3, v.pending ? "  (running...)" : "");
    if (!v.update_ms.empty()) {
        const float top = *std::max_element(v.update_ms.begin(), v.update_ms.end());
        char overlay[48];
        std::snprintf(overlay, sizeof(overlay), "max %.1f ms", top);
        ImGui::PlotLines("##updates", v.update_ms.data(), int(v.update_ms.size()), 0, overlay, 0.0f,
                         top * 1.1f,
                         ImVec2(ImGui::GetContentRegionAvail().x, 60));  // 1.86 plots take no -1 width
    }
}

}  // namespace

void drawInstantiationPanel(Document* doc, const std::vector<std::string>& type_names,
                            const InstantiationView& view, std::string* message, bool* open) {
    if (!*open) return;
    // Bottom right, collapsed at first: the middle of the viewport is where the user paints.
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x - 10, vp->Pos.y + vp->Size.y - 10), ImGuiCond_FirstUseEver,
                            ImVec2(1, 1));
    ImGui::SetNextWindowSize(ImVec2(380, 380), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
    if (!beginDocumentPanel("Instantiation", open, doc != nullptr)) return;
    drawStatistics(view);  // first: what the artist watches while editing below
    ImGui::Separator();
    std::string error;
    // The seed: a copy while its field is being edited (see the top of the file).
    static uint64_t seed_edit = 0;
    if (!ImGui::IsAnyItemActive()) seed_edit = doc->project().instantiation_seed;
    ImGui::SetNextItemWidth(160);
    ImGui::InputScalar("seed", ImGuiDataType_U64, &seed_edit);
    bool seed_commit = ImGui::IsItemDeactivatedAfterEdit();
    ImGui::SameLine();
    if (ImGui::Button("next")) {
        seed_edit = doc->project().instantiation_seed + 1;
        seed_commit = true;
    }
    if (seed_commit && seed_edit != doc->project().instantiation_seed && !doc->setSeed(seed_edit, &error))
        *message = error;

    // One copy per type, refreshed from the document whenever nothing is being edited.
    static std::vector<InstancingDesc> editing;
    const std::vector<DetailTypeDesc>& types = doc->project().detail_types;
    if (editing.size() != types.size() || !ImGui::IsAnyItemActive()) {
        editing.resize(types.size());
        for (size_t t = 0; t < types.size(); ++t) editing[t] = types[t].instancing;
    }
    for (size_t t = 0; t < types.size(); ++t) {
        ImGui::PushID(int(t));
        const char* name = t < type_names.size() ? type_names[t].c_str() : types[t].model.name.c_str();
        if (ImGui::CollapsingHeader(name, t == 0 ? ImGuiTreeNodeFlags_DefaultOpen : 0)) {
            if (editInstancing(&editing[t]) && !doc->setInstancing(t, editing[t], &error)) {
                *message = error;
                editing[t] = types[t].instancing;
            }
        }
        ImGui::PopID();
    }
    ImGui::End();
}

}  // namespace ug::editor
