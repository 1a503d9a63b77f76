#include <imgui.h>

#include "editor/panel_edit.h"
#include "editor/panels.h"

namespace ug::editor {

namespace {

// The sculpted piles' slope for the pile type, the document's setting (saved with the project).
void angleOfRepose(Document* doc, size_t type, std::string* message) {
    if (!doc || type >= doc->project().detail_types.size()) return;
    float deg = doc->project().detail_types[type].angle_of_repose_deg;
    PanelEdit e;
    dragged(ImGui::SliderFloat("angle of repose (deg)", &deg, 5.0f, 80.0f, "%.0f"), &e);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("the slope a held sculpt grows this type's piles to (gravel ~35)");
    std::string last_error;
    commitPanelEdit(
        doc, e, "Angle of repose", [&](const std::string&, std::string* error) { return doc->setAngleOfRepose(type, deg, error); },
        &last_error, message);
}

}  // namespace

void drawToolsPanel(Document* doc, const std::vector<std::string>& type_names, ToolState* s, std::string* message,
                    bool* open) {
    if (!*open) return;
    ImGui::SetNextWindowPos(ImVec2(10, 420), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Tools", open)) {
        ImGui::End();
        return;
    }
    int tool = int(s->tool);
    ImGui::RadioButton("Select (Q)", &tool, int(ToolKind::Select));
    ImGui::SameLine();
    ImGui::RadioButton("Paint (B)", &tool, int(ToolKind::Paint));
    ImGui::RadioButton("Sculpt (S)", &tool, int(ToolKind::Sculpt));
    ImGui::SameLine();
    ImGui::RadioButton("Erase (E)", &tool, int(ToolKind::Erase));
    s->tool = ToolKind(tool);
    ImGui::Separator();
    BrushSettings& b = s->brush;
    ImGui::SliderFloat("radius (m)", &b.radius_m, 0.1f, 10.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    ImGui::SliderFloat("strength", &b.strength, 0.05f, 5.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    if (s->tool == ToolKind::Paint) {
        ImGui::SliderFloat("falloff (m)", &b.falloff_m, 0.05f, 5.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
        ImGui::Checkbox("subtract", &b.subtract);
    }
    if (s->tool == ToolKind::Sculpt) {
        const char* current = b.sculpt_type < type_names.size() ? type_names[b.sculpt_type].c_str() : "";
        if (ImGui::BeginCombo("pile type", current)) {
            for (size_t i = 0; i < type_names.size(); ++i)
                if (ImGui::Selectable(type_names[i].c_str(), i == b.sculpt_type)) b.sculpt_type = i;
            ImGui::EndCombo();
        }
        angleOfRepose(doc, b.sculpt_type, message);
    } else if (s->tool == ToolKind::Paint || s->tool == ToolKind::Erase) {
        ImGui::TextUnformatted("types and mix weights");
        b.type_mix.resize(type_names.size(), 0.0f);
        for (size_t i = 0; i < type_names.size(); ++i) {
            ImGui::PushID(int(i));
            bool on = b.type_mix[i] > 0.0f;
            if (ImGui::Checkbox("##on", &on)) b.type_mix[i] = on ? 1.0f : 0.0f;
            ImGui::SameLine();
            ImGui::SetNextItemWidth(120);
            ImGui::SliderFloat(type_names[i].c_str(), &b.type_mix[i], 0.0f, 2.0f, "%.2f");
            ImGui::PopID();
        }
    }
    ImGui::Separator();
    ImGui::Checkbox("skeleton overlays", &s->show_markers);
    ImGui::End();
}

}  // namespace ug::editor
