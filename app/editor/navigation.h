// Blender-like viewport navigation from Dear ImGui's input state (mouse and keys the GLFW backend feeds):
//   middle drag: orbit;  Shift + middle drag: pan;  Ctrl + middle drag: zoom;  wheel: zoom;
//   Alt + left drag: orbit (for touchpads without a middle button);
//   1 / 3 / 7 (top row or keypad): front / side / top view;  Home: frame the whole scene;
//   F or . (period, keypad too): frame the selection (the whole scene when nothing is selected).
// The wheel zooms toward the ground under the cursor.
// Input that ImGui wants (a panel under the mouse, a text field) is left to ImGui.
#pragma once

#include "editor/orbit_camera.h"
#include "field/bounds.h"

namespace ug::editor {

// Returns true when the camera moved. selection: what F frames (null or empty: the scene). zoom_pivot: the
// world point under the cursor (the ground it shows); the wheel zooms toward it (null: toward the target).
bool navigate(OrbitCamera* camera, const Bounds& scene_extent, float viewport_height_px,
              const Bounds* selection = nullptr, const glm::vec3* zoom_pivot = nullptr);

// Gives the keyboard back to the viewport after a panel's field had it. Dear ImGui keeps a text or number
// field active (io.WantCaptureKeyboard: every shortcut is ignored) until Enter, Escape or a click
// elsewhere, so a user who typed a value and went back to the viewport found B, S, E, Q, Ctrl+Z... dead.
// Called every frame after NewFrame, before the shortcuts: when the mouse moves or clicks over the viewport
// (no panel under it, no button held since before, no dialog open), the field is ended (keeping its value)
// and no window keeps the focus. Returns true when it took the keyboard back.
bool giveKeyboardBackToViewport();

}  // namespace ug::editor
