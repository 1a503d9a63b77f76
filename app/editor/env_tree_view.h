// The environmental-object tree as rows of a window (ImGui), shared by the Environment window and the
// Outliner: one row per node (objects and references by their type or group, groups by their size),
// nested groups open on their arrow; a click selects (the selection is one, shared by both windows and
// the view's handles); a node dragged onto a group asks to move into it. With `hidden` given, each row has
// an eye: hidden nodes' objects and their effects are not drawn (view only, not saved; kept by the node's
// place in the tree).
#pragma once

#include <string>
#include <vector>

#include "env/env_tree_edits.h"

namespace ug::editor {

// A row dropped onto a group this frame (empty `into`: none).
struct EnvTreeDrop {
    EnvPath node, into;
};

std::string envNodeLabel(const EnvironmentDesc& env, const EnvNode& node, size_t index);

// Every root and, where open, its subtree. Needs an ImGui window.
void drawEnvTreeRows(const EnvironmentDesc& env, EnvPath* selected, std::vector<EnvPath>* hidden, EnvTreeDrop* drop);

}  // namespace ug::editor
