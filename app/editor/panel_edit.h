// What a panel's widgets did, in one frame, to the copy of a document part they edit (the Particles and
// Environment windows): a drag is live inside a stroke (one undo step when it ends); a typed field or a
// button is applied once, when finished. Needs an ImGui frame (call right after the widget).
#pragma once

#include <imgui.h>

#include <string>

#include "scene/document.h"

namespace ug::editor {

struct PanelEdit {
    bool changed = false;      // the copy differs: apply it
    bool drag_started = false; // a drag began this frame: open a stroke before applying
    bool drag_ended = false;   // a drag ended: close the stroke after
    std::string name;          // the undo step's name where the widget gives one (else the panel's)
};

// A drag widget: live, inside a stroke.
inline void dragged(bool changed, PanelEdit* e) {
    e->changed |= changed;
    e->drag_started |= ImGui::IsItemActivated();
    e->drag_ended |= ImGui::IsItemDeactivated();
}

// A typed field or a button: applied once, when finished.
inline void finished(PanelEdit* e) { e->changed |= ImGui::IsItemDeactivatedAfterEdit(); }

// The undo step's name for what the widget just called did, when it did something ("Move object").
inline void named(PanelEdit* e, std::string name) {
    if (ImGui::IsItemActive() || ImGui::IsItemDeactivated()) e->name = std::move(name);
}

// The frame's edit applied to the document: a stroke opened when a drag starts, `apply(name, &error)` (the
// document's edit, false when it refuses) when the copy changed, the stroke closed when the drag ends;
// `name` is e.name, or `default_name` when the widget gave none. A refusal is kept in *last_error (the
// window shows it) and reported in *message.
template <class Apply>
void commitPanelEdit(Document* doc, const PanelEdit& e, const char* default_name, Apply apply, std::string* last_error,
                     std::string* message) {
    const std::string name = e.name.empty() ? std::string(default_name) : e.name;
    if (e.drag_started && !doc->inStroke()) doc->beginStroke(name);
    if (e.changed) {
        std::string error;
        if (apply(name, &error)) {
            last_error->clear();
        } else {
            *last_error = error;
            *message = error;
        }
    }
    if (e.drag_ended && doc->inStroke()) doc->endStroke();
}

}  // namespace ug::editor
