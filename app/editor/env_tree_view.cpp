#include "editor/env_tree_view.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

namespace ug::editor {

namespace {

bool isHidden(const std::vector<EnvPath>* hidden, const EnvPath& path) {
    return hidden && std::find(hidden->begin(), hidden->end(), path) != hidden->end();
}

void treeRow(const EnvironmentDesc& env, const EnvPath& path, EnvPath* selected, std::vector<EnvPath>* hidden,
             EnvTreeDrop* drop) {
    const EnvNode& node = *envNodeAt(env, path);
    const bool has_children = node.kind == EnvNodeKind::Group || node.kind == EnvNodeKind::Lod;
    ImGui::PushID(int(path.back()));
    if (hidden) {
        bool shown = !isHidden(hidden, path);
        if (ImGui::Checkbox("##eye", &shown)) {
            if (shown) std::erase(*hidden, path);
            else hidden->push_back(path);
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("show / hide in the viewport (view only, not saved)");
        ImGui::SameLine();
    }
    ImGuiTreeNodeFlags flags = ImGuiTreeNodeFlags_OpenOnArrow | ImGuiTreeNodeFlags_SpanAvailWidth;
    if (!has_children) flags |= ImGuiTreeNodeFlags_Leaf | ImGuiTreeNodeFlags_NoTreePushOnOpen;
    if (path == *selected) flags |= ImGuiTreeNodeFlags_Selected;
    const std::string label = envNodeLabel(env, node, path.back());
    const bool open = ImGui::TreeNodeEx("node", flags, "%s", label.c_str());
    if (ImGui::IsItemClicked() && !ImGui::IsItemToggledOpen()) *selected = path;
    if (ImGui::BeginDragDropSource()) {
        ImGui::SetDragDropPayload("UG_ENV_NODE", path.data(), path.size() * sizeof(uint32_t));
        ImGui::Text("%s", label.c_str());
        ImGui::EndDragDropSource();
    }
    if (node.kind == EnvNodeKind::Group && ImGui::BeginDragDropTarget()) {
        if (const ImGuiPayload* p = ImGui::AcceptDragDropPayload("UG_ENV_NODE")) {
            const uint32_t* from = static_cast<const uint32_t*>(p->Data);
            drop->node = EnvPath(from, from + size_t(p->DataSize) / sizeof(uint32_t));
            drop->into = path;
        }
        ImGui::EndDragDropTarget();
    }
    if (open && has_children) {
        for (size_t c = 0; c < node.children.size(); ++c) {
            EnvPath child = path;
            child.push_back(uint32_t(c));
            treeRow(env, child, selected, hidden, drop);
        }
        ImGui::TreePop();
    }
    ImGui::PopID();
}

}  // namespace

std::string envNodeLabel(const EnvironmentDesc& env, const EnvNode& node, size_t index) {
    char label[160];
    const glm::vec3 t = node.transform.translation;
    const char* what = node.kind == EnvNodeKind::Object && node.type < env.types.size() ? env.types[node.type].name.c_str()
                       : node.kind == EnvNodeKind::Reference                          ? node.target.c_str()
                       : node.kind == EnvNodeKind::Lod                                 ? "LOD group"
                                                                                       : "group";
    if (node.kind == EnvNodeKind::Group || node.kind == EnvNodeKind::Lod)
        std::snprintf(label, sizeof label, "%zu  %s of %zu  (%.1f, %.1f)", index, what, node.children.size(), t.x, t.y);
    else
        std::snprintf(label, sizeof label, "%zu  %s  (%.1f, %.1f)", index, what, t.x, t.y);
    return label;
}

void drawEnvTreeRows(const EnvironmentDesc& env, EnvPath* selected, std::vector<EnvPath>* hidden, EnvTreeDrop* drop) {
    for (size_t i = 0; i < env.roots.size(); ++i) treeRow(env, {uint32_t(i)}, selected, hidden, drop);
}

}  // namespace ug::editor
