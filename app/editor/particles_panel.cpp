// The Particles window (issue 14): the project's particle systems, one at a time. Generators, attractors
// (their place, reach and charge keys, with a plot of a(t) over the steps), cutters and the walk are
// edited in place; the strands re-grow in the background as they change (live_strands.h), re-growing
// only what an attractor's move reaches.
//
// Undo granularity: a drag (a position, a reach, a charge) is one stroke, so the strands follow the mouse
// and the whole drag is one undo step; typed fields (counts, steps, the seed) and buttons are one step each
// when finished. Every edit goes through Document::setParticleSystem, which refuses an invalid system
// with the field named (the panel shows why; the document keeps the last valid one).
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "editor/panel_edit.h"
#include "editor/panels.h"

namespace ug::editor {

namespace {

const char* const kAttractorKinds[] = {"point", "segment", "sphere"};
const char* const kGeneratorKinds[] = {"rectangle", "sphere", "box", "mesh"};
const char* const kCutterKinds[] = {"plane", "sphere", "box"};
const char* const kActionKinds[] = {"stop", "kill", "split", "countdown"};

void editGenerator(ParticleGenerator* g, PanelEdit* e) {
    ImGui::Text("%s", kGeneratorKinds[size_t(g->kind)]);
    dragged(ImGui::DragFloat3("centre (m)", &g->center_m.x, 0.01f), e);
    ImGui::InputScalar("count", ImGuiDataType_U32, &g->count);
    finished(e);
    dragged(ImGui::DragFloat("heading cone (deg)", &g->heading_cone_deg, 0.2f, 0.0f, 179.0f), e);
}

void editCharge(std::vector<ChargeKey>* keys, uint32_t steps, PanelEdit* e) {
    // a(t) over the walk's steps, as the growth samples it.
    float plot[256];
    const int n = int(std::min<uint32_t>(steps + 1, 256));
    float lo = 0.0f, hi = 0.0f;
    for (int i = 0; i < n; ++i) {
        plot[i] = chargeAt(*keys, uint32_t(uint64_t(i) * steps / std::max(1, n - 1)));
        lo = std::min(lo, plot[i]);
        hi = std::max(hi, plot[i]);
    }
    ImGui::PlotLines("a(t)", plot, n, 0, nullptr, lo - 0.1f, hi + 0.1f, ImVec2(0, 48));
    for (size_t k = 0; k < keys->size(); ++k) {
        ImGui::PushID(int(k));
        ChargeKey& key = (*keys)[k];
        ImGui::SetNextItemWidth(70);
        ImGui::InputScalar("step", ImGuiDataType_U32, &key.step);
        finished(e);
        ImGui::SameLine();
        ImGui::SetNextItemWidth(90);
        dragged(ImGui::DragFloat("charge", &key.charge, 0.02f, -100.0f, 100.0f), e);
        if (keys->size() > 1) {
            ImGui::SameLine();
            if (ImGui::SmallButton("x")) {
                keys->erase(keys->begin() + std::ptrdiff_t(k));
                e->changed = true;
                ImGui::PopID();
                break;
            }
        }
        ImGui::PopID();
    }
    if (ImGui::SmallButton("+ key")) {
        const ChargeKey last = keys->back();
        keys->push_back({last.step + std::max<uint32_t>(1, steps / 4), last.charge});
        e->changed = true;
    }
}

void editAttractor(Attractor* a, uint32_t steps, PanelEdit* e) {
    int kind = int(a->kind);
    if (ImGui::Combo("kind", &kind, kAttractorKinds, 3)) {
        a->kind = AttractorKind(kind);
        if (a->kind == AttractorKind::Segment && a->b_m == a->a_m) a->b_m = a->a_m + glm::vec3(0.2f, 0.0f, 0.0f);
        e->changed = true;
    }
    dragged(ImGui::DragFloat3(a->kind == AttractorKind::Segment ? "a (m)" : "centre (m)", &a->a_m.x, 0.01f), e);
    if (a->kind == AttractorKind::Segment) dragged(ImGui::DragFloat3("b (m)", &a->b_m.x, 0.01f), e);
    if (a->kind == AttractorKind::Sphere) dragged(ImGui::DragFloat("radius (m)", &a->radius_m, 0.005f, 0.001f, 1e4f), e);
    dragged(ImGui::DragFloat("reach (m)", &a->influence_m, 0.005f, 0.0f, 1e4f), e);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("radius of influence; 0: everywhere (an edit re-grows every strand)");
    editCharge(&a->charge, steps, e);
}

void editCutter(Cutter* c, PanelEdit* e) {
    ImGui::Text("%s, triggers %s", kCutterKinds[size_t(c->kind)], c->side == CutterSide::Above ? "above" : "below");
    dragged(ImGui::DragFloat3("centre (m)", &c->center_m.x, 0.01f), e);
    dragged(ImGui::DragFloat("threshold (m)", &c->threshold_m, 0.005f), e);
    int action = int(c->action.kind);
    if (ImGui::Combo("action", &action, kActionKinds, 4)) {
        c->action.kind = StrandActionKind(action);
        e->changed = true;
    }
}

void editWalk(WalkSettings* w, PanelEdit* e) {
    ImGui::InputScalar("seed", ImGuiDataType_U64, &w->seed);
    finished(e);
    ImGui::InputScalar("steps", ImGuiDataType_U32, &w->steps);
    finished(e);
    ImGui::InputScalar("trials", ImGuiDataType_U32, &w->trials);
    finished(e);
    dragged(ImGui::DragFloat("cone (deg)", &w->cone_deg, 0.2f, 0.5f, 179.0f), e);
    dragged(ImGui::DragFloat("step (m)", &w->step_length_m, 0.0005f, 1e-5f, 10.0f, "%.4f"), e);
    dragged(ImGui::DragFloat("radius (m)", &w->strand_radius_m, 0.0001f, 1e-6f, 1.0f, "%.4f"), e);
    e->changed |= ImGui::Checkbox("collisions", &w->collisions);
}

}  // namespace

void drawParticlesPanel(Document* doc, ParticlesPanelState* state, std::string* message, bool* open) {
    if (!*open) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + 350, vp->Pos.y + 30), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(380, std::min(700.0f, vp->Size.y - 60.0f)), ImGuiCond_FirstUseEver);
    if (!beginDocumentPanel("Particles", open, doc != nullptr)) return;
    const std::vector<ParticleSystemFile>& systems = *doc->particles();
    if (systems.empty()) {
        ImGui::TextWrapped("The project has no particle system. Add one to its \"particles\" list "
                           "(docs/scene-format.md) and open it again.");
        ImGui::End();
        return;
    }
    state->selected = std::min(state->selected, systems.size() - 1);
    if (ImGui::BeginCombo("system", systems[state->selected].name.c_str())) {
        for (size_t i = 0; i < systems.size(); ++i)
            if (ImGui::Selectable(systems[i].name.c_str(), i == state->selected)) {
                state->selected = i;
                state->selected_attractor = SIZE_MAX;
            }
        ImGui::EndCombo();
    }
    if (state->growing) ImGui::TextDisabled("growing...");
    else ImGui::TextDisabled("%s", state->status.c_str());
    if (!state->last_error.empty()) ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "%s", state->last_error.c_str());

    if (!ImGui::IsAnyItemActive() || state->editing_doc != doc || state->editing_index != state->selected) {
        state->editing = systems[state->selected];
        state->editing_doc = doc;
        state->editing_index = state->selected;
    }
    ParticleSystemFile& system = state->editing;
    ParticleScene& scene = system.scene;
    PanelEdit e;
    if (ImGui::CollapsingHeader("Generators")) {
        for (size_t i = 0; i < scene.generators.size(); ++i) {
            ImGui::PushID(int(i));
            editGenerator(&scene.generators[i], &e);
            ImGui::Separator();
            ImGui::PopID();
        }
    }
    if (ImGui::CollapsingHeader("Attractors", ImGuiTreeNodeFlags_DefaultOpen)) {
        for (size_t i = 0; i < scene.attractors.size(); ++i) {
            ImGui::PushID(int(100 + i));
            char label[48];
            std::snprintf(label, sizeof label, "attractor %zu (%s)", i, kAttractorKinds[size_t(scene.attractors[i].kind)]);
            ImGuiTreeNodeFlags flags = ImGuiTreeNodeFlags_DefaultOpen;
            if (i == state->selected_attractor) flags |= ImGuiTreeNodeFlags_Selected;  // picked in the view
            const bool open_node = ImGui::TreeNodeEx(label, flags);
            ImGui::SameLine();
            const bool remove = ImGui::SmallButton("remove");
            if (open_node) {
                editAttractor(&scene.attractors[i], scene.walk.steps, &e);
                ImGui::TreePop();
            }
            ImGui::PopID();
            if (remove) {
                scene.attractors.erase(scene.attractors.begin() + std::ptrdiff_t(i));
                e.changed = true;
                break;
            }
        }
        if (ImGui::Button("Add attractor")) {
            // Above the first generator, attracting gently and only nearby: a place to start dragging from.
            Attractor a;
            a.a_m = scene.generators.front().center_m + glm::vec3(0.0f, 0.0f, 0.3f);
            a.influence_m = 0.3f;
            a.charge = {ChargeKey{0, 1.0f}};
            scene.attractors.push_back(a);
            e.changed = true;
        }
    }
    if (!scene.cutters.empty() && ImGui::CollapsingHeader("Cutters")) {
        for (size_t i = 0; i < scene.cutters.size(); ++i) {
            ImGui::PushID(int(200 + i));
            editCutter(&scene.cutters[i], &e);
            ImGui::Separator();
            ImGui::PopID();
        }
    }
    if (ImGui::CollapsingHeader("Walk")) editWalk(&scene.walk, &e);

    commitPanelEdit(
        doc, e, "Edit particles",
        [&](const std::string&, std::string* error) { return doc->setParticleSystem(state->selected, system, error); },
        &state->last_error, message);
    ImGui::End();
}

}  // namespace ug::editor
