#include <imgui.h>

#include "editor/panels.h"

namespace ug::editor {

void drawStatisticsPanel(const StatisticsView& v, bool* open) {
    if (!*open) return;
    ImGui::SetNextWindowPos(ImVec2(10, 30), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Statistics", open)) {
        ImGui::End();
        return;
    }
    ImGui::Text("%s", v.scene.c_str());
    if (v.pending) {
        ImGui::Text("%s", v.status.c_str());
        ImGui::ProgressBar(v.progress, ImVec2(-1, 0));
    } else {
        ImGui::TextWrapped("%s", v.status.c_str());
    }
    ImGui::Separator();
    ImGui::Text("instances %llu (%.2f s)", (unsigned long long)v.instances, v.instantiate_seconds);
    if (ImGui::BeginTable("types", 2, ImGuiTableFlags_RowBg)) {
        for (size_t i = 0; i < v.type_names.size(); ++i) {
            ImGui::TableNextRow();
            ImGui::TableSetColumnIndex(0);
            ImGui::TextUnformatted(v.type_names[i].c_str());
            ImGui::TableSetColumnIndex(1);
            ImGui::Text("%llu", (unsigned long long)(i < v.instances_per_type.size() ? v.instances_per_type[i] : 0));
        }
        ImGui::EndTable();
    }
    ImGui::Separator();
    ImGui::Text("frame %.1f ms (avg %.1f ms)", v.frame_ms, v.frame_ms_avg);
    ImGui::Text("triangles %llu, points %llu, draws %llu", (unsigned long long)v.triangles, (unsigned long long)v.points,
                (unsigned long long)v.draw_calls);
    ImGui::Text("LOD 0/1/2/impostor: %llu / %llu / %llu / %llu", (unsigned long long)v.lod_instances[0],
                (unsigned long long)v.lod_instances[1], (unsigned long long)v.lod_instances[2],
                (unsigned long long)v.lod_instances[3]);
    ImGui::Text("tiles visible %llu, culled %llu", (unsigned long long)v.tiles_visible, (unsigned long long)v.tiles_culled);
    ImGui::Text("indirect commands %llu; last upload %llu tiles, %.1f KiB", (unsigned long long)v.indirect_commands,
                (unsigned long long)v.tiles_uploaded, double(v.bytes_uploaded) / 1024.0);
    ImGui::Separator();
    ImGui::TextWrapped("%s", v.renderer.c_str());
    ImGui::TextWrapped("OpenGL %s", v.gl_version.c_str());
    if (!v.last_message.empty()) ImGui::TextWrapped("%s", v.last_message.c_str());
    ImGui::End();
}

}  // namespace ug::editor
