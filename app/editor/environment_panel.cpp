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

#include "editor/panel_edit.h"
#include "editor/panels.h"

namespace ug::editor {

namespace {

std::string nodeLabel(const EnvironmentDesc& env, const EnvNode& node, size_t index) {
    char label[160];
    const glm::vec3 t = node.transform.translation;
    const char* what = node.kind == EnvNodeKind::Object && node.type < env.types.size() ? env.types[node.type].name.c_str()
                       : node.kind == EnvNodeKind::Reference                          ? node.target.c_str()
                       : node.kind == EnvNodeKind::Lod                                 ? "LOD group"
                                                                                       : "group";
    std::snprintf(label, sizeof label, "%zu  %s  (%.1f, %.1f)", index, what, t.x, t.y);
    return label;
}

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
        ImGui::PopID();
    }
    ImGui::TextDisabled("%zu local fields (footprints, warm and wet spots)", local);
}

// The selected node's transform, and Duplicate / Delete. Returns false when the node was deleted.
bool editSelected(EnvironmentDesc* env, size_t* selected, PanelEdit* e) {
    EnvNode& node = env->roots[*selected];
    ImGui::Text("%s", nodeLabel(*env, node, *selected).c_str());
    dragged(ImGui::DragFloat3("position (m)", &node.transform.translation.x, 0.01f), e);
    dragged(ImGui::DragFloat("turn (deg)", &node.transform.yaw_deg, 0.5f, -360.0f, 360.0f), e);
    dragged(ImGui::DragFloat("scale", &node.transform.scale, 0.005f, 0.05f, 20.0f), e);
    if (ImGui::Button("Duplicate")) {
        EnvNode copy = node;
        copy.transform.translation.x += 0.5f;  // beside the original, not inside it
        env->roots.push_back(std::move(copy));
        *selected = env->roots.size() - 1;
        e->changed = true;
        return true;
    }
    ImGui::SameLine();
    if (ImGui::Button("Delete")) {
        env->roots.erase(env->roots.begin() + std::ptrdiff_t(*selected));
        *selected = SIZE_MAX;
        e->changed = true;
        return false;
    }
    return true;
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
        state->selected = env->roots.size() - 1;
        e->changed = true;
    }
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
    if (state->selected != SIZE_MAX && state->selected >= env.roots.size()) state->selected = SIZE_MAX;
    PanelEdit e;
    weatherBrush(state);
    if (ImGui::CollapsingHeader("Global fields", ImGuiTreeNodeFlags_DefaultOpen)) editGlobalFields(&env, &e);
    if (ImGui::CollapsingHeader("View a channel")) channelView(state);
    if (ImGui::CollapsingHeader("Objects", ImGuiTreeNodeFlags_DefaultOpen)) {
        palette(&env, state, &e);
        ImGui::BeginChild("tree", ImVec2(0, 110), true);
        for (size_t i = 0; i < env.roots.size(); ++i) {
            ImGui::PushID(int(i));
            if (ImGui::Selectable(nodeLabel(env, env.roots[i], i).c_str(), i == state->selected)) state->selected = i;
            ImGui::PopID();
        }
        ImGui::EndChild();
        if (state->selected != SIZE_MAX) editSelected(&env, &state->selected, &e);
    }

    commitPanelEdit(
        doc, e, "Edit environment",
        [&](std::string* error) { return doc->setEnvironment(env, "Edit environment", error); },
        &state->last_error, message);
    ImGui::End();
}

}  // namespace ug::editor
