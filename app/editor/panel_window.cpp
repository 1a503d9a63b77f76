#include <imgui.h>

#include "editor/panels.h"

namespace ug::editor {

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
