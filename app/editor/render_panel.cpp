#include <imgui.h>

#include <algorithm>

#include "editor/panels.h"

namespace ug::editor {

void drawRenderPanel(const StatisticsView& v, RenderSettings* settings, bool* open) {
    if (!*open) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + 10, vp->Pos.y + vp->Size.y - 10), ImGuiCond_FirstUseEver, ImVec2(0, 1));
    ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Render", open)) {
        ImGui::End();
        return;
    }
    // LOD switches by the on-screen size of a type's largest object; the order lod1 > lod2 > impostor is
    // kept by clamping each slider to its neighbours, so the LOD bands never overlap.
    LodSettings& lod = settings->lod;
    ImGui::TextUnformatted("LOD switch (object diameter, px)");
    ImGui::SliderFloat("LOD 1 below", &lod.lod1_px, 1.0f, 400.0f, "%.0f px");
    lod.lod1_px = std::max(lod.lod1_px, lod.lod2_px);
    ImGui::SliderFloat("LOD 2 below", &lod.lod2_px, 1.0f, 200.0f, "%.0f px");
    lod.lod2_px = std::clamp(lod.lod2_px, lod.impostor_px, lod.lod1_px);
    ImGui::SliderFloat("impostor below", &lod.impostor_px, 0.0f, 100.0f, "%.0f px");
    lod.impostor_px = std::min(lod.impostor_px, lod.lod2_px);
    ImGui::Separator();
    // Light that shows contact; each costs llvmpipe a share of the frame (docs/benchmarks.md).
    ImGui::Checkbox("sun shadows", &settings->look.shadows);
    ImGui::SameLine();
    ImGui::Checkbox("ambient occlusion", &settings->look.ambient_occlusion);
    ImGui::Separator();
    ImGui::Checkbox("primitive hulls", &settings->hulls);
    ImGui::Checkbox("tile grid", &settings->tile_grid);
    ImGui::Checkbox("anchors", &settings->anchors);
    ImGui::Checkbox("sphere sets", &settings->sphere_sets);
    ImGui::SliderFloat("overlay radius", &settings->overlay_radius_m, 0.5f, 20.0f, "%.1f m");
    ImGui::Separator();
    ImGui::Text("draws %llu (multi-draw), commands %llu", (unsigned long long)v.draw_calls,
                (unsigned long long)v.indirect_commands);
    ImGui::Text("triangles %llu, points %llu", (unsigned long long)v.triangles, (unsigned long long)v.points);
    ImGui::Text("LOD 0/1/2/impostor: %llu / %llu / %llu / %llu", (unsigned long long)v.lod_instances[0],
                (unsigned long long)v.lod_instances[1], (unsigned long long)v.lod_instances[2],
                (unsigned long long)v.lod_instances[3]);
    ImGui::Text("tiles resident %llu, visible %llu", (unsigned long long)v.tiles_resident,
                (unsigned long long)v.tiles_visible);
    ImGui::Text("last upload: %llu tiles, %.1f KiB", (unsigned long long)v.tiles_uploaded,
                double(v.bytes_uploaded) / 1024.0);
    ImGui::End();
}

}  // namespace ug::editor
