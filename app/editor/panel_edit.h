// What a panel's widgets did, in one frame, to the copy of a document part they edit (the Particles and
// Environment windows): a drag is live inside a stroke (one undo step when it ends); a typed field or a
// button is applied once, when finished. Needs an ImGui frame (call right after the widget).
#pragma once

#include <imgui.h>

namespace ug::editor {

struct PanelEdit {
    bool changed = false;      // the copy differs: apply it
    bool drag_started = false; // a drag began this frame: open a stroke before applying
    bool drag_ended = false;   // a drag ended: close the stroke after
};

// A drag widget: live, inside a stroke.
inline void dragged(bool changed, PanelEdit* e) {
    e->changed |= changed;
    e->drag_started |= ImGui::IsItemActivated();
    e->drag_ended |= ImGui::IsItemDeactivated();
}

// A typed field or a button: applied once, when finished.
inline void finished(PanelEdit* e) { e->changed |= ImGui::IsItemDeactivatedAfterEdit(); }

}  // namespace ug::editor
