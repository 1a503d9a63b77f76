// The Outliner: detail types as layers, like a paint program's. Each layer shows its colour, its instance
// count, an eye (visibility) and a brush (paint with this type alone); under it the user primitives (the
// editable children of the type's root Blend, edit_commands.h) and a one-line summary of the whole density
// tree, so the artist sees where the density comes from, including the parts that are not editable here.
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <utility>

#include "editor/panels.h"
#include "scene/sculpt_pile.h"

namespace ug::editor {

namespace {

// "file: 3 primitives (2 segment, 1 terrain_layer), 2 nodes (1 intersection, 1 union)": what the root
// reaches (the arrays may hold removed primitives until compaction) less the user primitives, listed
// below it. note: once edited, a tree whose root was not a Blend shows one more blend node (the editor's
// wrapper, edit_commands.h).
std::string densitySummary(const DensityField& f, const std::vector<Primitive>& user) {
    if (f.root == kNoNode) return "file: no density (0 everywhere)";
    std::map<std::string, int> prims, nodes;
    int prim_count = 0, node_count = 0;
    // Explicit stack: a deep hand-written tree must not overflow the UI thread's stack.
    std::vector<uint32_t> stack{nodeChild(f.root)};
    while (!stack.empty()) {
        const uint32_t ref = stack.back();
        stack.pop_back();
        const uint32_t i = childIndex(ref);
        if (isPrimitiveChild(ref)) {
            if (i < f.primitives.size()) ++prims[primitiveKindName(f.primitives[i].kind)], ++prim_count;
            continue;
        }
        if (i >= f.nodes.size()) continue;
        const FieldNode& n = f.nodes[i];
        ++nodes[fieldOpName(n.op)];
        ++node_count;
        for (uint32_t c = 0; c < n.child_count && n.first_child + c < f.children.size(); ++c)
            stack.push_back(f.children[n.first_child + c]);
    }
    for (const Primitive& p : user)
        if (--prims[primitiveKindName(p.kind)] == 0) prims.erase(primitiveKindName(p.kind));
    prim_count -= int(user.size());
    auto list = [](const std::map<std::string, int>& m) {
        std::string s;
        for (const auto& [name, count] : m) s += (s.empty() ? "" : ", ") + std::to_string(count) + " " + name;
        return s;
    };
    return "file: " + std::to_string(prim_count) + " primitives (" + list(prims) + "), " +
           std::to_string(node_count) + " nodes (" + list(nodes) + ")";
}

}  // namespace

void drawOutliner(const Document* doc, const OutlinerView& view, std::vector<uint8_t>* visible,
                  ToolState* tools, EnvironmentPanelState* environment, UiRequests* requests, bool* open) {
    if (!*open) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x - 10, vp->Pos.y + 260), ImGuiCond_FirstUseEver,
                            ImVec2(1, 0));
    ImGui::SetNextWindowSize(ImVec2(340, 300), ImGuiCond_FirstUseEver);
    if (!beginDocumentPanel("Outliner", open, doc != nullptr)) return;
    const size_t types = std::min(view.type_names.size(), doc->project().detail_types.size());
    visible->resize(types, 1);
    // A new selection (a click in the view) opens its type's row, so the user sees what was picked.
    static uint64_t revealed = 0;
    size_t reveal_type = SIZE_MAX;
    if (tools->selected != revealed) {
        revealed = tools->selected;
        if (revealed != 0) doc->findPrimitive(revealed, &reveal_type, nullptr);
    }
    for (size_t t = 0; t < types; ++t) {
        ImGui::PushID(int(t));
        const glm::vec3 c = t < view.colors.size() ? view.colors[t] : glm::vec3(0.6f);
        ImGui::ColorButton("##swatch", ImVec4(c.x, c.y, c.z, 1.0f), ImGuiColorEditFlags_NoTooltip,
                           ImVec2(ImGui::GetFrameHeight(), ImGui::GetFrameHeight()));
        ImGui::SameLine();
        bool shown = (*visible)[t] != 0;
        if (ImGui::Checkbox("##eye", &shown)) (*visible)[t] = shown ? 1 : 0;
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("show / hide in the viewport (view only, not saved)");
        ImGui::SameLine();
        if (ImGui::SmallButton("paint")) {
            tools->tool = ToolKind::Paint;
            tools->brush.type_mix.assign(types, 0.0f);
            tools->brush.type_mix[t] = 1.0f;
            tools->brush.sculpt_type = t;
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("paint with this type alone");
        ImGui::SameLine();
        const std::vector<uint64_t> ids = doc->primitiveIds(t);
        const uint64_t count = t < view.instances_per_type.size() ? view.instances_per_type[t] : 0;
        const std::string label = view.type_names[t] + "  " + std::to_string(count);
        std::vector<uint64_t> user_ids;
        std::vector<Primitive> user;
        for (const uint64_t id : ids) {
            Primitive p;
            if (!doc->findPrimitive(id, nullptr, &p)) continue;
            user_ids.push_back(id);
            user.push_back(p);
        }
        if (t == reveal_type) ImGui::SetNextItemOpen(true);
        if (ImGui::TreeNodeEx(
                "##layer", ImGuiTreeNodeFlags_SpanAvailWidth | (t == 0 ? ImGuiTreeNodeFlags_DefaultOpen : 0),
                "%s", label.c_str())) {
            ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
            ImGui::TextWrapped("%s", densitySummary(doc->project().detail_types[t].density, user).c_str());
            ImGui::PopStyleColor();
            if (ids.empty()) ImGui::TextDisabled("no user primitives");
            // A brush stroke is one row (one unit: tools.h), at its first primitive; the selection is
            // shown on the row of the stroke that holds it.
            Primitive chosen;
            const uint32_t chosen_stroke =
                tools->selected != 0 && doc->findPrimitive(tools->selected, nullptr, &chosen) ? chosen.stroke : 0;
            // One pass counts each stroke; its row takes the count, and the stroke's later primitives
            // (count already taken: 0) have no row.
            std::map<uint32_t, size_t> stroke_sizes;
            for (const Primitive& p : user)
                if (p.stroke != 0) ++stroke_sizes[p.stroke];
            for (size_t k = 0; k < user.size(); ++k) {
                const uint64_t id = user_ids[k];
                const Primitive& p = user[k];
                size_t members = 1;
                if (p.stroke != 0) {
                    members = std::exchange(stroke_sizes[p.stroke], 0);
                    if (members == 0) continue;
                }
                ImGui::PushID(static_cast<int>(id));
                char text[160];
                // A sculpted pile is one cone however long the brush was held (tools.h): named as such.
                const char* kind = isPileCone(p) ? "pile" : primitiveKindName(p.kind);
                if (members > 1)
                    std::snprintf(text, sizeof(text), "stroke %u: %zu %s%s  from (%.2f, %.2f, %.2f) w %.2f", p.stroke,
                                  members, kind, p.kind == PrimitiveKind::Box ? "es" : "s", p.center_m.x, p.center_m.y,
                                  p.center_m.z, p.weight);
                else
                    std::snprintf(text, sizeof(text), "%s #%llu  (%.2f, %.2f, %.2f) r %.2f w %.2f", kind,
                                  (unsigned long long)id, p.center_m.x, p.center_m.y, p.center_m.z, p.radius_m, p.weight);
                const bool selected = tools->selected == id || (p.stroke != 0 && p.stroke == chosen_stroke);
                if (ImGui::Selectable(text, selected) && !selected) tools->selected = id;
                if (ImGui::BeginPopupContextItem()) {
                    tools->selected = id;
                    if (ImGui::MenuItem("Duplicate", "Ctrl+D")) requests->duplicate_selected = true;
                    if (ImGui::MenuItem("Delete", "Delete")) requests->delete_selected = true;
                    ImGui::EndPopup();
                }
                ImGui::PopID();
            }
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
    ImGui::Separator();
    const bool has_selection = tools->selected != 0;
    if (!has_selection) ImGui::BeginDisabled();
    if (ImGui::Button("Duplicate")) requests->duplicate_selected = true;
    ImGui::SameLine();
    if (ImGui::Button("Delete")) requests->delete_selected = true;
    if (!has_selection) ImGui::EndDisabled();
    const EnvironmentDesc& env = doc->project().environment;
    if (!env.roots.empty()) {
        ImGui::Separator();
        // Edited in Window > Environment (and with the Select tool in the view while it is open).
        if (ImGui::TreeNodeEx("##environment", ImGuiTreeNodeFlags_DefaultOpen | ImGuiTreeNodeFlags_SpanAvailWidth,
                              "Environmental objects  %zu", env.roots.size())) {
            if (!envNodeAt(env, environment->selected)) environment->selected.clear();
            drawEnvTreeRows(env, &environment->selected, &environment->hidden, &requests->env_drop);
            ImGui::TreePop();
        }
    }
    ImGui::End();
}

}  // namespace ug::editor
