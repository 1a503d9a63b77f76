// The Environment window (issue 13): the environmental objects of the project. The global fields (a
// value everywhere: snow depth, temperature, humidity, ...) are dragged live; the tree's top level lists
// the objects and groups, the selected one's place, turn and size are dragged (or the object is dragged
// in the view with the Select tool); Add places the palette's type on the ground under the view's centre;
// Duplicate and Delete; the footprint brush's switch. The snow and icicles follow every change in the
// background (live_environment.h).
//
// Every edit goes through Document::setEnvironment, which refuses an invalid environment with the field
// named (the window shows why; the document keeps the last valid one). Undo granularity as in the
// Particles window (panel_edit.h).
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "editor/env_tree_view.h"
#include "editor/panel_edit.h"
#include "editor/panels.h"

namespace ug::editor {

namespace {

// The weather brushes' switch and settings (used in the view: env_tools.h WeatherStroke).
void weatherBrush(EnvironmentPanelState* state) {
    ImGui::Checkbox("Weather brush (drag on the ground)", &state->brush_on);
    WeatherSettings& w = state->weather;
    int brush = int(w.brush);
    const char* names[kWeatherBrushCount];
    for (int k = 0; k < kWeatherBrushCount; ++k) names[k] = weatherBrushName(WeatherBrush(k));
    if (ImGui::Combo("brush", &brush, names, kWeatherBrushCount)) w.brush = WeatherBrush(brush);
    if (w.brush != WeatherBrush::Footprints) {
        ImGui::SliderFloat("brush radius (m)", &w.radius_m, 0.1f, 3.0f, "%.2f");
        if (w.brush != WeatherBrush::Erase) ImGui::SliderFloat("brush strength", &w.strength, 0.1f, 3.0f, "%.2f");
    }
}

// The channel view: which channel (or the shelter), the slice's height, and the legend of the last map.
void channelView(EnvironmentPanelState* state) {
    ChannelMapSettings& v = state->view;
    ImGui::Checkbox("show on a slice over the ground", &v.on);
    ImGui::Checkbox("and on the objects' surfaces", &v.surfaces);
    const char* names[kChannelMapChannels];
    for (int c = 0; c < kChannelMapChannels; ++c) names[c] = channelMapName(c);
    ImGui::Combo("channel", &v.channel, names, kChannelMapChannels);
    ImGui::SliderFloat("slice height (m)", &v.height_m, 0.0f, 4.0f, "%.2f");
    if (!v.on) return;
    // The legend: the ramp in five steps, its ends' values.
    ImGui::Text("%.3g", state->view_lo);
    for (int k = 0; k < 5; ++k) {
        const glm::vec3 c = channelMapColor(float(k) / 4.0f);
        ImGui::SameLine();
        ImGui::PushID(k);
        ImGui::ColorButton("##ramp", ImVec4(c.x, c.y, c.z, 1.0f), ImGuiColorEditFlags_NoTooltip, ImVec2(24, 14));
        ImGui::PopID();
    }
    ImGui::SameLine();
    ImGui::Text("%.3g", state->view_hi);
}

void editGlobalFields(EnvironmentDesc* env, PanelEdit* e) {
    size_t local = 0;
    for (size_t i = 0; i < env->global_fields.size(); ++i) {
        EnvFieldDesc& f = env->global_fields[i];
        if (!f.everywhere) {
            ++local;
            continue;
        }
        ImGui::PushID(int(i));
        // Temperatures are degrees; the other channels are fractions or metres of snow.
        const bool temperature = f.channel == EnvChannel::Temperature;
        dragged(ImGui::DragFloat(envChannelName(f.channel), &f.value, temperature ? 0.1f : 0.005f,
                                 temperature ? -40.0f : 0.0f, temperature ? 40.0f : 2.0f,
                                 temperature ? "%.1f C" : "%.3f"),
                e);
        named(e, std::string("Set ") + envChannelName(f.channel));
        ImGui::PopID();
    }
    ImGui::TextDisabled("%zu local fields (footprints, warm and wet spots)", local);
}

// A structural edit's outcome, applied to the edited copy (env_tree_edits.h) as the undo step `name`; a
// refusal is reported.
void structural(bool ok, const char* name, const std::string& why, PanelEdit* e, std::string* message) {
    if (ok) {
        e->changed = true;
        e->name = name;
    } else {
        *message = why;
    }
}

// The selected node's transform (in its parent's space), and the tree's edits: Duplicate, Delete, Group,
// Ungroup, Make reusable (a top-level group becomes a named group and a reference to it), Instance (one
// more reference to a reusable group, at the view's centre).
void editSelected(EnvironmentDesc* env, EnvironmentPanelState* state, PanelEdit* e, std::string* message) {
    EnvPath& path = state->selected;
    EnvNode& node = *envNodeAt(env, path);
    ImGui::Text("%s  %s", envPathText(path).c_str(), envNodeLabel(*env, node, path.back()).c_str());
    dragged(ImGui::DragFloat3("position (m)", &node.transform.translation.x, 0.01f), e);
    named(e, "Move object");
    dragged(ImGui::DragFloat("turn (deg)", &node.transform.yaw_deg, 0.5f, -360.0f, 360.0f), e);
    named(e, "Turn object");
    dragged(ImGui::DragFloat("scale", &node.transform.scale, 0.005f, 0.05f, 20.0f), e);
    named(e, "Scale object");
    std::vector<EnvNode>& siblings = path.size() == 1 ? env->roots : envNodeAt(env, EnvPath(path.begin(), path.end() - 1))->children;
    std::string why;
    if (ImGui::Button("Duplicate")) {
        EnvNode copy = node;
        copy.transform.translation.x += 0.5f;  // beside the original, not inside it
        siblings.push_back(std::move(copy));
        path.back() = uint32_t(siblings.size() - 1);
        e->changed = true;
        e->name = "Duplicate object";
        return;
    }
    ImGui::SameLine();
    if (ImGui::Button("Delete")) {
        siblings.erase(siblings.begin() + std::ptrdiff_t(path.back()));
        path.clear();
        e->changed = true;
        e->name = "Delete object";
        return;
    }
    ImGui::SameLine();
    if (ImGui::Button("Group")) return structural(groupEnvNode(env, path, &why), "Group", why, e, message);
    if (node.kind == EnvNodeKind::Group) {
        ImGui::SameLine();
        if (ImGui::Button("Ungroup")) {
            structural(ungroupEnvNode(env, path, &why), "Ungroup", why, e, message);
            return;
        }
        if (path.size() == 1) {
            ImGui::SameLine();
            if (ImGui::Button("Make reusable")) {
                std::string name = "group_" + std::to_string(env->groups.size() + 1);
                structural(makeEnvGroupReusable(env, path, name, &why), "Make group reusable", why, e, message);
                return;
            }
        }
    }
    if (node.kind == EnvNodeKind::Reference) {
        ImGui::SameLine();
        if (ImGui::Button("Instance")) {
            EnvTransform at = node.transform;
            at.translation = state->place_at;
            const std::string target = node.target;
            structural(addEnvReference(env, target, at, &why), "Instance group", why, e, message);
            if (e->changed) path = {uint32_t(env->roots.size() - 1)};
        }
    }
}

void palette(EnvironmentDesc* env, EnvironmentPanelState* state, PanelEdit* e) {
    state->add_type = std::clamp(state->add_type, 0, int(env->types.size()) - 1);
    if (ImGui::BeginCombo("type", env->types[size_t(state->add_type)].name.c_str())) {
        for (size_t t = 0; t < env->types.size(); ++t)
            if (ImGui::Selectable(env->types[t].name.c_str(), int(t) == state->add_type)) state->add_type = int(t);
        ImGui::EndCombo();
    }
    if (ImGui::Button("Add at the view's centre")) {
        EnvNode node;
        node.kind = EnvNodeKind::Object;
        node.type = uint32_t(state->add_type);
        node.transform.translation = state->place_at;
        env->roots.push_back(std::move(node));
        state->selected = {uint32_t(env->roots.size() - 1)};
        e->changed = true;
        e->name = "Add " + env->types[size_t(state->add_type)].name;
    }
    // The pictures: a click picks the type and arms "place by clicking in the view" (on the ground or on
    // top of another object); a second click on the same picture disarms it.
    constexpr float kSide = 0.5f * float(kPaletteThumbnailPx);
    const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
    for (size_t t = 0; t < env->types.size() && t < state->thumbnails.size(); ++t) {
        ImGui::PushID(int(t));
        const bool chosen = int(t) == state->add_type;
        const ImVec4 frame = chosen && state->placing ? ImVec4(1.0f, 0.75f, 0.1f, 1.0f)
                             : chosen                  ? ImVec4(0.35f, 0.55f, 0.9f, 1.0f)
                                                       : ImVec4(0.2f, 0.2f, 0.22f, 1.0f);
        ImGui::PushStyleColor(ImGuiCol_Button, frame);
        // Rows come bottom-up from the renderer: the picture is flipped back by its coordinates.
        if (ImGui::ImageButton(reinterpret_cast<ImTextureID>(uintptr_t(state->thumbnails[t])), ImVec2(kSide, kSide),
                               ImVec2(0, 1), ImVec2(1, 0), 2)) {
            state->placing = !(chosen && state->placing);
            state->add_type = int(t);
        }
        ImGui::PopStyleColor();
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s: click, then click in the view to place it", env->types[t].name.c_str());
        ImGui::PopID();
        const float next = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + kSide + 4.0f;
        if (t + 1 < env->types.size() && next < right) ImGui::SameLine();
    }
    if (state->placing)
        ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.1f, 1.0f), "click in the view to place a %s (Esc: stop)",
                           env->types[size_t(state->add_type)].name.c_str());
}

}  // namespace

void drawEnvironmentPanel(Document* doc, EnvironmentPanelState* state, std::string* message, bool* open) {
    if (!*open) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    // Beside the Statistics window, short enough to leave the view below it.
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + 350, vp->Pos.y + 30), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(360, std::min(470.0f, vp->Size.y - 60.0f)), ImGuiCond_FirstUseEver);
    if (!beginDocumentPanel("Environment", open, doc != nullptr)) return;
    if (doc->project().environment.types.empty()) {
        ImGui::TextWrapped("The project has no environmental-object types. Add a library to its \"environment\" "
                           "(docs/scene-format.md) and open it again.");
        ImGui::End();
        return;
    }
    if (state->computing) ImGui::TextDisabled("computing the snow and icicles...");
    else ImGui::TextDisabled("%s", state->status.c_str());
    if (!state->last_error.empty()) ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "%s", state->last_error.c_str());

    if (!ImGui::IsAnyItemActive() || state->editing_doc != doc) {
        state->editing = doc->project().environment;
        state->editing_doc = doc;
    }
    EnvironmentDesc& env = state->editing;
    if (!envNodeAt(env, state->selected)) state->selected.clear();
    PanelEdit e;
    weatherBrush(state);
    if (ImGui::CollapsingHeader("Global fields", ImGuiTreeNodeFlags_DefaultOpen)) editGlobalFields(&env, &e);
    if (ImGui::CollapsingHeader("Objects", ImGuiTreeNodeFlags_DefaultOpen)) {
        palette(&env, state, &e);
        ImGui::BeginChild("tree", ImVec2(0, 110), true);
        EnvTreeDrop drop;
        drawEnvTreeRows(env, &state->selected, nullptr, &drop);
        ImGui::EndChild();
        if (!drop.into.empty()) {
            std::string why;
            EnvPath moved;
            structural(moveEnvNodeInto(&env, drop.node, drop.into, &moved, &why), "Move into group", why, &e, message);
            if (e.changed) state->selected = moved;
        } else if (!state->selected.empty()) {
            editSelected(&env, state, &e, message);
        }
    }

    if (ImGui::CollapsingHeader("View a channel")) channelView(state);

    commitPanelEdit(
        doc, e, "Edit environment",
        [&](const std::string& name, std::string* error) { return doc->setEnvironment(env, name, error); },
        &state->last_error, message);
    ImGui::End();
}

}  // namespace ug::editor
