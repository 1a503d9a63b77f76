#include <GLFW/glfw3.h>  // key codes only (ImGui 1.86 indexes io.KeysDown by GLFW keys)
#include <imgui.h>

#include "editor/panels.h"

namespace ug::editor {

void drawMainMenu(const MenuView& view, UiRequests* requests, ToolState* tools, WindowToggles* windows) {
    const ImGuiIO& io = ImGui::GetIO();
    // Shortcuts only when no text field or panel has the keyboard, and only on the press (no repeat).
    if (!io.WantCaptureKeyboard) {
        auto pressed = [](int key) { return ImGui::IsKeyPressed(key, false); };
        if (pressed(GLFW_KEY_F12)) requests->screenshot = true;
        if (io.KeyCtrl) {
            if (pressed(GLFW_KEY_Q)) requests->quit = true;
            if (pressed(GLFW_KEY_N)) requests->new_document = true;
            if (pressed(GLFW_KEY_O)) requests->open_dialog = true;
            if (pressed(GLFW_KEY_S)) (io.KeyShift ? requests->open_save_as : requests->save) = true;
            if (pressed(GLFW_KEY_Z)) (io.KeyShift ? requests->redo : requests->undo) = true;
            if (pressed(GLFW_KEY_Y)) requests->redo = true;
            if (pressed(GLFW_KEY_D)) requests->duplicate_selected = true;
        } else if (!io.KeyAlt) {
            if (pressed(GLFW_KEY_Q)) tools->tool = ToolKind::Select;
            if (pressed(GLFW_KEY_B)) tools->tool = ToolKind::Paint;
            if (pressed(GLFW_KEY_S)) tools->tool = ToolKind::Sculpt;
            if (pressed(GLFW_KEY_E)) tools->tool = ToolKind::Erase;
            if (pressed(GLFW_KEY_DELETE) || pressed(GLFW_KEY_X)) requests->delete_selected = true;
        }
    }
    if (!ImGui::BeginMainMenuBar()) return;
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("New", "Ctrl+N")) requests->new_document = true;
        if (ImGui::MenuItem("Open...", "Ctrl+O")) requests->open_dialog = true;
        if (ImGui::MenuItem("Save", "Ctrl+S", false, view.has_document)) requests->save = true;
        if (ImGui::MenuItem("Save As...", "Ctrl+Shift+S", false, view.has_document))
            requests->open_save_as = true;
        if (ImGui::BeginMenu("Open Recent", !view.recent_files.empty())) {
            for (const std::string& f : view.recent_files)
                if (ImGui::MenuItem(f.c_str())) requests->open_path = f;
            ImGui::EndMenu();
        }
        ImGui::Separator();
        if (ImGui::MenuItem("Export glTF...", nullptr, false, view.has_document))
            requests->show_export = true;
        ImGui::Separator();
        if (ImGui::MenuItem("Screenshot", "F12")) requests->screenshot = true;
        ImGui::Separator();
        if (ImGui::MenuItem("Quit", "Ctrl+Q")) requests->quit = true;
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Edit")) {
        const std::string undo = view.undo_name.empty() ? "Undo" : "Undo " + view.undo_name;
        const std::string redo = view.redo_name.empty() ? "Redo" : "Redo " + view.redo_name;
        if (ImGui::MenuItem(undo.c_str(), "Ctrl+Z", false, !view.undo_name.empty())) requests->undo = true;
        if (ImGui::MenuItem(redo.c_str(), "Ctrl+Shift+Z", false, !view.redo_name.empty()))
            requests->redo = true;
        ImGui::Separator();
        if (ImGui::MenuItem("Delete", "Delete", false, tools->selected != 0))
            requests->delete_selected = true;
        if (ImGui::MenuItem("Duplicate", "Ctrl+D", false, tools->selected != 0))
            requests->duplicate_selected = true;
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Window")) {
        ImGui::MenuItem("Statistics", nullptr, &windows->statistics);
        ImGui::MenuItem("Tools", nullptr, &windows->tools);
        ImGui::MenuItem("Inspector", nullptr, &windows->inspector);
        ImGui::MenuItem("Ghost Tile", nullptr, &windows->ghost_tile);
        ImGui::MenuItem("Particles", nullptr, &windows->particles);
        ImGui::MenuItem("Environment", nullptr, &windows->environment);
        ImGui::MenuItem("Render", nullptr, &windows->render);
        ImGui::MenuItem("Outliner", nullptr, &windows->outliner);
        ImGui::MenuItem("Instantiation", nullptr, &windows->instantiation);
        ImGui::MenuItem("Export", nullptr, &windows->export_panel);
        ImGui::MenuItem("Skeleton overlays", nullptr, &tools->show_markers);
        ImGui::EndMenu();
    }
    if (view.dirty) ImGui::TextDisabled("  (unsaved changes)");
    ImGui::EndMainMenuBar();
}

}  // namespace ug::editor
