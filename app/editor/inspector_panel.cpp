#include <imgui.h>

#include <cfloat>

#include "editor/panels.h"
#include "editor/tools.h"
#include "scene/sculpt_pile.h"

namespace ug::editor {

void drawInspector(Document* doc, const std::vector<std::string>& type_names, ToolState* s,
                   UiRequests* requests, std::string* message, bool* open) {
    if (!*open) return;
    // Top right, clear of the Statistics window on the left.
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x - 10, vp->Pos.y + 30), ImGuiCond_FirstUseEver, ImVec2(1, 0));
    // As tall as what it shows: sized once to "Nothing selected" it clipped a primitive's fields, and a
    // fixed taller window would cover the view where nothing is selected.
    ImGui::SetNextWindowSizeConstraints(ImVec2(300, 0), ImVec2(300, FLT_MAX));
    if (!ImGui::Begin("Inspector", open, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::End();
        return;
    }
    size_t type = 0;
    Primitive prim;
    if (!doc || s->selected == 0 || !doc->findPrimitive(s->selected, &type, &prim)) {
        s->selected = 0;
        ImGui::TextWrapped("Nothing selected. Select (Q) and click a primitive's centre.");
        ImGui::End();
        return;
    }
    ImGui::Text("%s #%llu (%s)", isPileCone(prim) ? "pile (cone)" : primitiveKindName(prim.kind), (unsigned long long)s->selected,
                type < type_names.size() ? type_names[type].c_str() : "?");
    // A brush stroke is one thing: the fields below move it and scale its weights and radii together.
    const size_t members = doc->strokeMembers(s->selected).size();
    if (members > 1)
        ImGui::TextWrapped("Stroke %u: %zu primitives, edited, moved and deleted together.", prim.stroke, members);
    // The widgets edit a copy; the document gets one SetPrimitive when an edit is finished (the drag
    // released, the field left), so a drag is one undo step and the instancer is fed once.
    static uint64_t editing_id = 0;
    static Primitive editing;
    if (editing_id != s->selected || !ImGui::IsAnyItemActive()) {
        editing_id = s->selected;
        editing = prim;
    }
    bool commit = false;
    ImGui::DragFloat3("centre (m)", &editing.center_m.x, 0.01f);
    commit |= ImGui::IsItemDeactivatedAfterEdit();
    if (editing.kind == PrimitiveKind::Segment) {
        ImGui::DragFloat3("end (m)", &editing.end_m.x, 0.01f);
        commit |= ImGui::IsItemDeactivatedAfterEdit();
    }
    if (editing.kind == PrimitiveKind::Disc) {
        ImGui::DragFloat("disc radius (m)", &editing.disc_radius_m, 0.01f, 0.0f, 100.0f);
        commit |= ImGui::IsItemDeactivatedAfterEdit();
    }
    ImGui::DragFloat("radius (m)", &editing.radius_m, 0.01f, 0.01f, 100.0f);
    commit |= ImGui::IsItemDeactivatedAfterEdit();
    ImGui::DragFloat("weight", &editing.weight, 0.01f, -100.0f, 100.0f);
    commit |= ImGui::IsItemDeactivatedAfterEdit();
    if (commit) {
        std::string error;
        if (!doc->setPrimitives(strokeEdit(*doc, s->selected, editing), members > 1 ? "Edit stroke" : "Edit primitive",
                                &error))
            *message = error;
    }
    if (ImGui::Button("Delete")) requests->delete_selected = true;
    ImGui::SameLine();
    if (ImGui::Button("Duplicate")) requests->duplicate_selected = true;
    ImGui::End();
}

}  // namespace ug::editor
