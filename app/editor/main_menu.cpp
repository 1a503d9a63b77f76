#include <GLFW/glfw3.h>  // key codes only (ImGui 1.86 indexes io.KeysDown by GLFW keys)
#include <imgui.h>

#include "editor/panels.h"

namespace ug::editor {

void drawMainMenu(UiRequests* requests, bool* show_statistics) {
    const ImGuiIO& io = ImGui::GetIO();
    if (!io.WantCaptureKeyboard) {
        if (ImGui::IsKeyPressed(GLFW_KEY_F12, false)) requests->screenshot = true;
        if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_Q, false)) requests->quit = true;
    }
    if (!ImGui::BeginMainMenuBar()) return;
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("Screenshot", "F12")) requests->screenshot = true;
        ImGui::Separator();
        if (ImGui::MenuItem("Quit", "Ctrl+Q")) requests->quit = true;
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Window")) {
        ImGui::MenuItem("Statistics", nullptr, show_statistics);
        ImGui::EndMenu();
    }
    ImGui::EndMainMenuBar();
}

}  // namespace ug::editor
