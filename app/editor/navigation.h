// Blender-like viewport navigation from Dear ImGui's input state (mouse and keys the GLFW backend feeds):
//   middle drag: orbit;  Shift + middle drag: pan;  Ctrl + middle drag: zoom;  wheel: zoom;
//   Alt + left drag: orbit (for touchpads without a middle button);
//   1 / 3 / 7 (top row or keypad): front / side / top view;  Home: frame the whole scene;
//   F or . (period, keypad too): frame the selection (the whole scene when nothing is selected).
// Input that ImGui wants (a panel under the mouse, a text field) is left to ImGui.
#pragma once

#include "editor/orbit_camera.h"
#include "field/bounds.h"

namespace ug::editor {

// Returns true when the camera moved. selection: what F frames (null or empty: the scene).
bool navigate(OrbitCamera* camera, const Bounds& scene_extent, float viewport_height_px,
              const Bounds* selection = nullptr);

}  // namespace ug::editor
