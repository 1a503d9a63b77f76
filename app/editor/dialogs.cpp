#include <GLFW/glfw3.h>  // key codes only: the ImGui 1.86 GLFW backend indexes io.KeysDown by them
#include <imgui.h>

#include <cstring>

#include "editor/panels.h"

namespace ug::editor {

namespace {

void centerNext() {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.5f, vp->Pos.y + vp->Size.y * 0.5f),
                            ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
}

// Dialog keys, as in the desktop's own dialogs: Enter takes the default (safe) answer, Escape cancels.
bool enterPressed() {
    return ImGui::IsKeyPressed(GLFW_KEY_ENTER, false) || ImGui::IsKeyPressed(GLFW_KEY_KP_ENTER, false);
}
bool escapePressed() { return ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false); }

}  // namespace

DialogAnswer drawRecoveryDialog(const std::string& path, const std::string& saved_when) {
    const char* title = "Recover unsaved work?";
    if (!ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
    centerNext();
    DialogAnswer answer = DialogAnswer::Pending;
    if (ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("An autosave of %s", path.c_str());
        ImGui::Text("(%s) is newer than the file.", saved_when.c_str());
        // Enter recovers; no key drops the autosave (that takes a click on the second button).
        if (ImGui::Button("Recover (Enter)") || enterPressed()) answer = DialogAnswer::Yes;
        ImGui::SameLine();
        if (ImGui::Button("Open the saved file")) answer = DialogAnswer::No;
        if (answer != DialogAnswer::Pending) ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
    }
    return answer;
}

DialogAnswer drawUnsavedDialog(const std::string& path, const std::string& what) {
    const char* title = "Unsaved changes";
    if (!ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
    centerNext();
    DialogAnswer answer = DialogAnswer::Pending;
    if (ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("%s has unsaved changes. Save them before you %s?", path.c_str(), what.c_str());
        if (ImGui::Button("Save (Enter)") || enterPressed()) answer = DialogAnswer::Yes;
        ImGui::SameLine();
        if (ImGui::Button("Discard (D)") || ImGui::IsKeyPressed(GLFW_KEY_D, false)) answer = DialogAnswer::No;
        ImGui::SameLine();
        if (ImGui::Button("Cancel (Esc)") || escapePressed()) answer = DialogAnswer::Cancel;
        if (answer != DialogAnswer::Pending) ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
    }
    return answer;
}

namespace {

// A modal path field with a confirm button (Save As, Open). One buffer: only one is open at a time.
DialogAnswer drawPathDialog(const char* title, const char* confirm, bool* open, std::string* path) {
    if (!*open) return DialogAnswer::Pending;
    static char buffer[1024] = "";
    if (!ImGui::IsPopupOpen(title)) {
        std::strncpy(buffer, path->c_str(), sizeof(buffer) - 1);
        buffer[sizeof(buffer) - 1] = '\0';
        ImGui::OpenPopup(title);
    }
    centerNext();
    DialogAnswer answer = DialogAnswer::Pending;
    if (ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::SetNextItemWidth(480);
        if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
        const bool enter =
            ImGui::InputText("path", buffer, sizeof(buffer), ImGuiInputTextFlags_EnterReturnsTrue);
        if ((ImGui::Button(confirm) || enter) && buffer[0]) answer = DialogAnswer::Yes;
        ImGui::SameLine();
        if (ImGui::Button("Cancel (Esc)") || escapePressed()) answer = DialogAnswer::Cancel;
        if (answer != DialogAnswer::Pending) {
            if (answer == DialogAnswer::Yes) *path = buffer;
            *open = false;
            ImGui::CloseCurrentPopup();
        }
        ImGui::EndPopup();
    }
    return answer;
}

}  // namespace

DialogAnswer drawSaveAsDialog(bool* open, std::string* path) {
    return drawPathDialog("Save As", "Save", open, path);
}

DialogAnswer drawOpenDialog(bool* open, std::string* path) {
    return drawPathDialog("Open", "Open", open, path);
}

void drawMessages(std::vector<std::string>* messages) {
    if (messages->empty()) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.5f, vp->Pos.y + 40), ImGuiCond_Appearing,
                            ImVec2(0.5f, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(520, 0), ImGuiCond_Appearing);
    if (ImGui::Begin("Messages", nullptr, ImGuiWindowFlags_NoCollapse)) {
        for (const std::string& m : *messages) {
            ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.55f, 0.45f, 1.0f));
            ImGui::TextWrapped("%s", m.c_str());
            ImGui::PopStyleColor();
        }
        if (ImGui::Button("Dismiss")) messages->clear();
    }
    ImGui::End();
}

}  // namespace ug::editor
