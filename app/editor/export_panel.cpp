// The Export window: File > Export glTF... (export_job.h runs the engine's exporter in the background).
#include <imgui.h>

#include <cstring>

#include "editor/panels.h"

namespace ug::editor {

void drawExportPanel(const ExportView& view, ExportSettings* settings, UiRequests* requests, bool* open) {
    if (!*open) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.5f, vp->Pos.y + vp->Size.y - 10),
                            ImGuiCond_FirstUseEver, ImVec2(0.5f, 1.0f));
    ImGui::SetNextWindowSize(ImVec2(460, 200), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Export glTF", open)) {
        ImGui::End();
        return;
    }
    static char path[1024] = "";
    if (!ImGui::IsAnyItemActive() || std::strlen(path) == 0) {
        std::strncpy(path, settings->path.c_str(), sizeof(path) - 1);
        path[sizeof(path) - 1] = '\0';
    }
    if (ImGui::InputText("path", path, sizeof(path))) settings->path = path;
    // The format follows the extension (the exporter's rule); the radio buttons rewrite it.
    const bool glb =
        settings->path.size() >= 4 && settings->path.compare(settings->path.size() - 4, 4, ".glb") == 0;
    const bool gltf =
        settings->path.size() >= 5 && settings->path.compare(settings->path.size() - 5, 5, ".gltf") == 0;
    auto setExtension = [&](const char* ext) {
        std::string& p = settings->path;
        const size_t dot = p.find_last_of('.');
        const size_t slash = p.find_last_of('/');
        if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) p.resize(dot);
        p += ext;
    };
    if (ImGui::RadioButton(".glb (binary)", glb)) setExtension(".glb");
    ImGui::SameLine();
    if (ImGui::RadioButton(".gltf (JSON)", gltf)) setExtension(".gltf");
    ImGui::Checkbox("plain nodes (one per instance)", &settings->plain_nodes);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("for viewers without EXT_mesh_gpu_instancing");
    ImGui::DragFloat("chunk size (m)", &settings->chunk_size_m, 0.1f, 0.5f, 1000.0f, "%.1f",
                     ImGuiSliderFlags_AlwaysClamp);
    if (view.running) {
        ImGui::ProgressBar(view.progress, ImVec2(-1, 0), view.stage.c_str());
        if (!view.can_cancel) ImGui::BeginDisabled();
        if (ImGui::Button("Cancel")) requests->cancel_export = true;
        if (!view.can_cancel) ImGui::EndDisabled();
    } else {
        const bool can = view.has_document && (glb || gltf);
        if (!can) ImGui::BeginDisabled();
        if (ImGui::Button("Export")) requests->start_export = true;
        if (!can) ImGui::EndDisabled();
        if (!glb && !gltf) ImGui::TextDisabled("the path must end in .glb or .gltf");
    }
    if (!view.last_result.empty()) ImGui::TextWrapped("%s", view.last_result.c_str());
    ImGui::End();
}

}  // namespace ug::editor
