#include <imgui.h>

#include "editor/panels.h"

namespace ug::editor {

bool* windowToggle(WindowToggles* w, const std::string& name) {
    const std::pair<const char*, bool*> toggles[] = {
        {"statistics", &w->statistics}, {"tools", &w->tools},         {"inspector", &w->inspector},
        {"ghost_tile", &w->ghost_tile}, {"render", &w->render},       {"outliner", &w->outliner},
        {"instantiation", &w->instantiation}, {"export", &w->export_panel}, {"particles", &w->particles},
        {"environment", &w->environment}};
    for (const auto& [n, toggle] : toggles)
        if (name == n) return toggle;
    return nullptr;
}

bool beginDocumentPanel(const char* title, bool* open, bool has_document) {
    if (!ImGui::Begin(title, open)) {
        ImGui::End();
        return false;
    }
    if (!has_document) {
        ImGui::TextDisabled("no document");
        ImGui::End();
        return false;
    }
    return true;
}

}  // namespace ug::editor
