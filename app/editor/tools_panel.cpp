#include <imgui.h>

#include "editor/panels.h"

namespace ug::editor {

void drawToolsPanel(const std::vector<std::string>& type_names, ToolState* s, bool* open) {
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
