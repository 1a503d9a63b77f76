#include "editor/navigation.h"

#include <GLFW/glfw3.h>  // key codes only: the ImGui 1.86 GLFW backend indexes io.KeysDown by them
#include <imgui.h>
#include <imgui_internal.h>  // ClearActiveID: 1.86 has no public way to deactivate an item

namespace ug::editor {

bool navigate(OrbitCamera* camera, const Bounds& extent, float viewport_height_px, const Bounds* selection,
              const glm::vec3* zoom_pivot) {
    ImGuiIO& io = ImGui::GetIO();
    const OrbitCamera before = *camera;
    if (!io.WantCaptureMouse) {
        const ImVec2 d = io.MouseDelta;
        const bool middle = ImGui::IsMouseDown(ImGuiMouseButton_Middle);
        const bool alt_left = io.KeyAlt && ImGui::IsMouseDown(ImGuiMouseButton_Left);
        if ((middle || alt_left) && (d.x != 0.0f || d.y != 0.0f)) {
            if (io.KeyShift)
                pan(camera, d.x, d.y, viewport_height_px);
            else if (io.KeyCtrl)
                zoom(camera, -d.y * 0.02f);
            else
                orbit(camera, d.x, d.y);
        }
        if (io.MouseWheel != 0.0f) {
            if (zoom_pivot)
                zoomToward(camera, io.MouseWheel, *zoom_pivot);
            else
                zoom(camera, io.MouseWheel);
        }
    }
    auto moved = [&] {
        return camera->target != before.target || camera->distance_m != before.distance_m ||
               camera->yaw_rad != before.yaw_rad || camera->pitch_rad != before.pitch_rad;
    };
    if (io.WantCaptureKeyboard) return moved();
    auto pressed = [](int a, int b) { return ImGui::IsKeyPressed(a, false) || ImGui::IsKeyPressed(b, false); };
    if (pressed(GLFW_KEY_1, GLFW_KEY_KP_1)) setPreset(camera, ViewPreset::Front);
    if (pressed(GLFW_KEY_3, GLFW_KEY_KP_3)) setPreset(camera, ViewPreset::Side);
    if (pressed(GLFW_KEY_7, GLFW_KEY_KP_7)) setPreset(camera, ViewPreset::Top);
    const bool frame_all = ImGui::IsKeyPressed(GLFW_KEY_HOME, false);
    const bool frame_selected = pressed(GLFW_KEY_F, GLFW_KEY_PERIOD) || ImGui::IsKeyPressed(GLFW_KEY_KP_DECIMAL, false);
    if (frame_all || frame_selected) {
        OrbitCamera framed = *camera;
        const bool has_selection = selection && !selection->empty();
        frameBounds(frame_selected && has_selection ? *selection : extent, &framed);
        // Keep the current direction of view; only the target and the distance change.
        camera->target = framed.target;
        camera->distance_m = framed.distance_m;
    }
    return moved();
}

bool giveKeyboardBackToViewport() {
    const ImGuiIO& io = ImGui::GetIO();
    if (!io.WantCaptureKeyboard) return false;
    // A dialog's field (Open, Save As) keeps the keyboard wherever the mouse goes; so does a panel's
    // field while the mouse is over a panel.
    if (ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId)) return false;
    if (ImGui::IsWindowHovered(ImGuiHoveredFlags_AnyWindow)) return false;
    bool clicked = false;
    for (int b = 0; b < ImGuiMouseButton_COUNT; ++b) clicked |= ImGui::IsMouseClicked(b);
    // A button held since before (a slider dragged out of its panel) is the panel's drag: it goes on.
    if (!clicked && ImGui::IsAnyMouseDown()) return false;
    const bool moved = io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f;
    if (!clicked && !moved) return false;
    ImGui::ClearActiveID();  // the field keeps what was typed (ImGui applies each edit as it is made)
    ImGui::SetWindowFocus(nullptr);
    return true;
}

}  // namespace ug::editor
