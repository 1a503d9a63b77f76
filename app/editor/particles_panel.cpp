// The Particles window (issue 14): the project's particle systems, one at a time. Generators, attractors
// (their place, reach and charge keys, with a(t) drawn and edited on its plot: charge_curve.h), cutters
// and the walk are edited in place, parts added at the view's centre and removed; New system adds a grass
// patch in a new file. The strands re-grow in the background as they change (live_strands.h), re-growing
// only what an attractor's move reaches.
//
// Undo granularity: a drag (a position, a reach, a charge) is one stroke, so the strands follow the mouse
// and the whole drag is one undo step; typed fields (counts, steps, the seed) and buttons are one step each
// when finished. Every edit goes through Document::setParticleSystem, which refuses an invalid system
// with the field named (the panel shows why; the document keeps the last valid one).
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "editor/charge_curve.h"
#include "editor/panel_edit.h"
#include "editor/panels.h"

namespace ug::editor {

namespace {

const char* const kAttractorKinds[] = {"point", "segment", "sphere", "mesh", "objects"};
const char* const kGeneratorKinds[] = {"rectangle", "sphere", "box", "mesh", "objects"};
const char* const kCutterKinds[] = {"plane", "sphere", "box"};
const char* const kActionKinds[] = {"stop", "kill", "split", "countdown", "turn"};
const char* const kActionModes[] = {"one action", "a table, by priority", "a table, at random"};
const char* const kCutterSides[] = {"above the threshold", "below the threshold"};

// A list entry of the system (a generator, an attractor or a cutter): a tree node, highlighted while its
// dot is the one picked in the view, with a remove button beside it.
struct PartRow {
    bool open = false;
    bool remove = false;
};
PartRow partRow(const char* label, bool selected, bool removable) {
    ImGuiTreeNodeFlags flags = ImGuiTreeNodeFlags_DefaultOpen;
    if (selected) flags |= ImGuiTreeNodeFlags_Selected;
    PartRow row;
    row.open = ImGui::TreeNodeEx(label, flags);
    if (removable) {
        ImGui::SameLine();
        row.remove = ImGui::SmallButton("remove");
    }
    return row;
}

void editGenerator(ParticleGenerator* g, PanelEdit* e) {
    // An objects generator is where its objects are: no centre of its own.
    if (g->kind != GeneratorKind::Objects) dragged(ImGui::DragFloat3("centre (m)", &g->center_m.x, 0.01f), e);
    switch (g->kind) {
        case GeneratorKind::Rectangle:
            dragged(ImGui::DragFloat3("half side u (m)", &g->axis_u_m.x, 0.005f), e);
            dragged(ImGui::DragFloat3("half side v (m)", &g->axis_v_m.x, 0.005f), e);
            e->changed |= ImGui::Checkbox("on the terrain", &g->on_terrain);
            break;
        case GeneratorKind::Sphere:
            dragged(ImGui::DragFloat("radius (m)", &g->radius_m, 0.005f, 0.001f, 1e4f), e);
            break;
        case GeneratorKind::Box:
            dragged(ImGui::DragFloat3("half extents (m)", &g->half_extents_m.x, 0.005f, 0.001f, 1e4f), e);
            break;
        case GeneratorKind::Mesh:
            ImGui::TextDisabled("%s", g->mesh_file.c_str());
            dragged(ImGui::DragFloat("scale", &g->scale, 0.01f, 0.01f, 1e4f), e);
            break;
        case GeneratorKind::Objects:
            ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
            ImGui::TextWrapped("the '%s' objects' surfaces", g->object_type.c_str());
            ImGui::PopStyleColor();
            dragged(ImGui::DragFloat("below (m)", &g->max_height_m, 0.01f, 0.0f, 1e3f), e);
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("seeds only below this height in each object; 0: the whole object");
            e->changed |= ImGui::Checkbox("sides only", &g->sides_only);
            break;
        case GeneratorKind::Details:
            ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
            ImGui::TextWrapped("the '%s' instances in the box", g->detail_type.c_str());
            ImGui::PopStyleColor();
            dragged(ImGui::DragFloat3("half extents (m)", &g->half_extents_m.x, 0.005f, 0.001f, 1e4f), e);
            dragged(ImGui::DragFloat("lowest normal z", &g->min_normal_z, 0.01f, -1.0f, 1.0f), e);
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("faces steeper than this do not seed; -1: every face");
            break;
    }
    ImGui::InputScalar("count", ImGuiDataType_U32, &g->count);
    finished(e);
    dragged(ImGui::DragFloat("heading cone (deg)", &g->heading_cone_deg, 0.2f, 0.0f, 179.0f), e);
}

// a(t) over the walk's steps, drawn and edited on the plot (charge_curve.h): drag a key, double-click to
// add one on the curve, right-click to remove one. A drag is one undo step.
void chargeCurve(std::vector<ChargeKey>* keys, uint32_t steps, PanelEdit* e) {
    const ImVec2 size(std::max(120.0f, ImGui::GetContentRegionAvail().x), 72.0f);
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton("a(t)", size, ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
    ImGuiStorage* store = ImGui::GetStateStorage();
    const ImGuiID dragged_key = ImGui::GetID("dragged key"), frozen_lo = ImGui::GetID("lo"), frozen_hi = ImGui::GetID("hi");
    ChargeCurveFrame f;
    f.min_px = {p0.x + 8.0f, p0.y + 6.0f};
    f.max_px = {p0.x + size.x - 8.0f, p0.y + size.y - 6.0f};
    f.steps = std::max<uint32_t>(1, steps);
    const bool dragging = ImGui::IsItemActive() && store->GetInt(dragged_key, -1) >= 0;
    // The range is frozen while a key is dragged, so the curve does not rescale under the mouse.
    if (dragging) {
        f.lo = store->GetFloat(frozen_lo, -1.0f);
        f.hi = store->GetFloat(frozen_hi, 1.0f);
    } else {
        chargeCurveRange(*keys, &f.lo, &f.hi);
    }
    const glm::vec2 mouse(ImGui::GetIO().MousePos.x, ImGui::GetIO().MousePos.y);
    const size_t hovered_key = ImGui::IsItemHovered() ? nearestChargeKey(*keys, f, mouse, 8.0f) : kNoChargeKey;
    if (ImGui::IsItemActivated() && ImGui::IsMouseClicked(ImGuiMouseButton_Left) && hovered_key != kNoChargeKey) {
        store->SetInt(dragged_key, int(hovered_key));
        store->SetFloat(frozen_lo, f.lo);
        store->SetFloat(frozen_hi, f.hi);
        e->drag_started = true;
        e->name = "Edit a(t)";
    }
    if (dragging) {
        e->name = "Edit a(t)";
        if (moveChargeKey(keys, size_t(store->GetInt(dragged_key, 0)), chargeKeyAtPixel(f, mouse))) e->changed = true;
    }
    if (ImGui::IsItemDeactivated() && store->GetInt(dragged_key, -1) >= 0) {
        store->SetInt(dragged_key, -1);
        e->drag_ended = true;
        e->name = "Edit a(t)";
    }
    if (ImGui::IsItemHovered() && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left) && hovered_key == kNoChargeKey) {
        ChargeKey key = chargeKeyAtPixel(f, mouse);
        key.charge = chargeAt(*keys, key.step);  // on the curve: adding a key changes nothing until it moves
        if (insertChargeKey(keys, key) != kNoChargeKey) {
            e->changed = true;
            e->name = "Add a(t) key";
        }
    }
    if (ImGui::IsItemHovered() && ImGui::IsMouseClicked(ImGuiMouseButton_Right) && removeChargeKey(keys, hovered_key)) {
        e->changed = true;
        e->name = "Remove a(t) key";
    }

    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddRectFilled(p0, ImVec2(p0.x + size.x, p0.y + size.y), ImGui::GetColorU32(ImGuiCol_FrameBg));
    const glm::vec2 zero_a = chargeKeyPixel(f, {0, 0.0f}), zero_b = chargeKeyPixel(f, {f.steps, 0.0f});
    draw->AddLine(ImVec2(zero_a.x, zero_a.y), ImVec2(zero_b.x, zero_b.y), IM_COL32(140, 140, 140, 160));
    ImVec2 line[130];
    const int n = int(std::size(line));
    for (int i = 0; i < n; ++i) {
        const uint32_t step = uint32_t(uint64_t(i) * f.steps / uint64_t(n - 1));
        const glm::vec2 q = chargeKeyPixel(f, {step, chargeAt(*keys, step)});
        line[i] = ImVec2(q.x, q.y);
    }
    draw->AddPolyline(line, n, ImGui::GetColorU32(ImGuiCol_PlotLines), 0, 1.5f);
    for (size_t k = 0; k < keys->size(); ++k) {
        const glm::vec2 q = chargeKeyPixel(f, (*keys)[k]);
        const bool hot = k == hovered_key || (dragging && int(k) == store->GetInt(dragged_key, -1));
        draw->AddCircleFilled(ImVec2(q.x, q.y), hot ? 5.0f : 3.5f,
                              hot ? IM_COL32(255, 220, 90, 255) : ImGui::GetColorU32(ImGuiCol_PlotLinesHovered));
    }
    // The range's ends at the right (a key at step 0 sits on the left edge), the steps at the bottom.
    const ImU32 text = ImGui::GetColorU32(ImGuiCol_TextDisabled);
    char label[48];
    std::snprintf(label, sizeof label, "%+.2g", double(f.hi));
    draw->AddText(ImVec2(p0.x + size.x - ImGui::CalcTextSize(label).x - 4.0f, p0.y), text, label);
    std::snprintf(label, sizeof label, "%+.2g", double(f.lo));
    draw->AddText(ImVec2(p0.x + size.x - ImGui::CalcTextSize(label).x - 4.0f, p0.y + size.y - ImGui::GetFontSize()),
                  text, label);
    std::snprintf(label, sizeof label, "step %u", f.steps);
    draw->AddText(ImVec2(f.max_px.x - ImGui::CalcTextSize(label).x - 40.0f, p0.y + size.y - ImGui::GetFontSize()),
                  text, label);
    if (hovered_key != kNoChargeKey)
        ImGui::SetTooltip("step %u: %.2f", (*keys)[hovered_key].step, double((*keys)[hovered_key].charge));
    else if (ImGui::IsItemHovered())
        ImGui::SetTooltip("a(t) over %u steps: drag a key, double-click to add one, right-click to remove one", f.steps);
}

void editCharge(std::vector<ChargeKey>* keys, uint32_t steps, PanelEdit* e) {
    chargeCurve(keys, steps, e);
    for (size_t k = 0; k < keys->size(); ++k) {
        ImGui::PushID(int(k));
        ChargeKey& key = (*keys)[k];
        ImGui::SetNextItemWidth(70);
        ImGui::InputScalar("step", ImGuiDataType_U32, &key.step);
        finished(e);
        ImGui::SameLine();
        ImGui::SetNextItemWidth(90);
        dragged(ImGui::DragFloat("charge", &key.charge, 0.02f, -kMaxChargeMagnitude, kMaxChargeMagnitude), e);
        if (keys->size() > 1) {
            ImGui::SameLine();
            if (ImGui::SmallButton("x")) {
                removeChargeKey(keys, k);
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
    if (a->kind == AttractorKind::Objects) {
        // Its points follow the project's objects (placed when the scene or the system changes).
        ImGui::TextWrapped("%zu points on the '%s' objects within reach", a->points ? a->points->size() : size_t(0),
                           a->object_type.c_str());
        dragged(ImGui::DragFloat("reach (m)", &a->influence_m, 0.005f, 0.0f, 1e4f), e);
        editCharge(&a->charge, steps, e);
        return;
    }
    if (a->kind == AttractorKind::Mesh) {
        // Its points come from the file's model: no other kind turns into one here.
        ImGui::Text("%u points on %s", a->point_count, a->mesh_file.c_str());
        dragged(ImGui::DragFloat("scale", &a->scale, 0.01f, 0.01f, 1e4f), e);
    } else if (ImGui::Combo("kind", &kind, kAttractorKinds, 3)) {
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

// One action's fields; a state's action (not one in a table) also says how the state acts: by it alone
// or by a table of actions taken by priority or at random, whose rows are edited here.
void editAction(StrandAction* action, PanelEdit* e, bool in_table = false) {
    if (!in_table) {
        int mode = int(actionMode(*action));
        if (ImGui::Combo("acts by", &mode, kActionModes, IM_ARRAYSIZE(kActionModes))) {
            setActionMode(action, ActionMode(mode));
            e->changed = true;
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("a table: the first action that can act (priority) or one drawn by weight (random)");
    }
    if (!action->table.empty()) {
        std::vector<StrandAction>& table = action->table;
        for (size_t i = 0; i < table.size(); ++i) {
            ImGui::PushID(int(i));
            ImGui::Separator();
            ImGui::TextDisabled("%zu.", i + 1);
            if (table.size() > 1) {
                ImGui::SameLine();
                if (ImGui::SmallButton("remove")) {
                    table.erase(table.begin() + std::ptrdiff_t(i));
                    e->changed = true;
                    ImGui::PopID();
                    break;
                }
            }
            editAction(&table[i], e, true);
            if (action->choice == ActionChoice::Random)
                dragged(ImGui::DragFloat("weight", &table[i].weight, 0.05f, 0.01f, 1e6f, "%.2f"), e);
            ImGui::PopID();
        }
        if (table.size() < kMaxActionTable && ImGui::SmallButton("+ action")) {
            table.push_back(StrandAction{});
            e->changed = true;
        }
        return;
    }
    int kind = int(action->kind);
    if (ImGui::Combo("action", &kind, kActionKinds, IM_ARRAYSIZE(kActionKinds))) {
        action->kind = StrandActionKind(kind);
        e->changed = true;
    }
    if (action->kind == StrandActionKind::Split) {
        ImGui::InputScalar("children", ImGuiDataType_U32, &action->split_count);
        finished(e);
        dragged(ImGui::DragFloat("split cone (deg)", &action->split_angle_deg, 0.5f, 0.0f, 179.0f), e);
    }
    if (action->kind == StrandActionKind::Countdown) {
        ImGui::InputScalar("steps##countdown", ImGuiDataType_U32, &action->countdown_steps);
        finished(e);
        // countdown_then is Stop or Kill, the enum's first two.
        int then = int(action->countdown_then);
        if (ImGui::Combo("then", &then, kActionKinds, 2)) {
            action->countdown_then = StrandActionKind(then);
            e->changed = true;
        }
    }
    if (action->kind == StrandActionKind::Turn)
        dragged(ImGui::DragFloat("turn (deg)", &action->turn_angle_deg, 0.5f, 0.1f, 180.0f), e);
}

void editCutter(Cutter* c, PanelEdit* e) {
    dragged(ImGui::DragFloat3("centre (m)", &c->center_m.x, 0.01f), e);
    switch (c->kind) {
        case CutterKind::Plane: {
            glm::vec3 n = c->normal;
            if (ImGui::DragFloat3("normal", &n.x, 0.01f, -1.0f, 1.0f) && glm::length(n) > 1e-3f) {
                c->normal = glm::normalize(n);  // the document keeps a unit normal
                e->changed = true;
            }
            dragged(false, e);  // the drag's stroke (its change is marked above, once normalised)
            break;
        }
        case CutterKind::Sphere: dragged(ImGui::DragFloat("radius (m)", &c->radius_m, 0.005f, 0.0f, 1e4f), e); break;
        case CutterKind::Box:
            dragged(ImGui::DragFloat3("half extents (m)", &c->half_extents_m.x, 0.005f, 0.0f, 1e4f), e);
            break;
    }
    dragged(ImGui::DragFloat("threshold (m)", &c->threshold_m, 0.005f), e);
    int side = int(c->side);
    if (ImGui::Combo("triggers", &side, kCutterSides, 2)) {
        c->side = CutterSide(side);
        e->changed = true;
    }
    editAction(&c->action, e);
}

// A critical state's action, folded under the state's name (each with its own ids: the rows repeat).
void stateActionRow(const char* state, StrandAction* action, PanelEdit* e) {
    if (!ImGui::TreeNode(state)) return;
    editAction(action, e);
    ImGui::TreePop();
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
    ImGui::SameLine();
    e->changed |= ImGui::Checkbox("retry", &w->retry_refused);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("a refused move gives way to the next-fittest trial (a vine slides along a wall)");
    stateActionRow("on collision", &w->on_collision, e);
    ImGui::InputScalar("age limit", ImGuiDataType_U32, &w->max_age_steps);
    finished(e);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("a strand acts after this many steps (0: no limit)");
    if (w->max_age_steps > 0) stateActionRow("at the age limit", &w->on_age, e);
    // Beyond 100 steps the file is refused (validateParticleScene): the slider stops there.
    dragged(ImGui::DragFloat("keep (m)", &w->keep_distance_m, 0.0005f, 0.0f, 100.0f * w->step_length_m, "%.4f"),
            e);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Strands keep this far from other strands' earlier segments (0: off)");
    if (w->keep_distance_m > 0.0f) stateActionRow("when crowded", &w->on_distance, e);
}

// "Click to place": the next left click in the view puts a new part on what it meets (surface_pick.h;
// session_input.cpp places it); the armed button is framed, pressing it again disarms.
void placeButtons(ParticlesPanelState* state) {
    ImGui::TextUnformatted("Place:");
    for (const ParticlePart part : {ParticlePart::Generator, ParticlePart::Attractor, ParticlePart::Cutter}) {
        ImGui::SameLine();
        const bool armed = state->placing == part;
        if (armed) ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(1.0f, 0.75f, 0.1f, 0.8f));
        if (ImGui::SmallButton(particlePartName(part))) state->placing = armed ? ParticlePart::None : part;
        if (armed) ImGui::PopStyleColor();
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("then click the ground or an object in the view to put a new %s there (Shift: several; Esc: stop)",
                              particlePartName(part));
    }
    // On the same row: the window's layout below stays where users (and the X-driven test) find it.
    ImGui::SameLine();
    ImGui::Checkbox("on details", &state->place_on_details);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Clicks meet the detail instances too; a generator placed on one grows on the instances\n"
                          "of its type within half a metre (moss on the rocks). Off: the ground under them.");
}

// The rows of one of the system's lists: each part's tree node (highlighted while its dot is the one
// picked in the view) with its fields, and a remove button while the list has more than `keep` parts.
template <class T, class Label, class Edit>
void partRows(std::vector<T>* list, size_t keep, ParticlePart part, ParticlesPanelState* state, PanelEdit* e,
              Label label, Edit edit) {
    for (size_t i = 0; i < list->size(); ++i) {
        ImGui::PushID(int(part) * 1000 + int(i));
        const PartRow row = partRow(label(i).c_str(), state->selected_handle.part == part && state->selected_handle.index == i, list->size() > keep);
        if (row.open) {
            edit(&(*list)[i]);
            ImGui::TreePop();
        }
        ImGui::PopID();
        if (row.remove) {
            list->erase(list->begin() + std::ptrdiff_t(i));
            e->changed = true;
            e->name = std::string("Remove ") + particlePartName(part);
            if (state->selected_handle.part == part) state->selected_handle = {};  // its index moved on
            break;
        }
    }
}

std::string partLabel(const char* part, size_t i, const char* kind) {
    char label[64];
    std::snprintf(label, sizeof label, "%s %zu (%s)", part, i, kind);
    return label;
}

// "New system": a grass patch at the view's centre in a new file beside the project (Document::
// addParticleSystem), selected at once. One undo step. True when it was added: the document's systems
// are then another vector (references into the old one dangle).
bool newSystemButton(Document* doc, ParticlesPanelState* state, std::string* message) {
    if (!ImGui::Button("New system")) {
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("a patch of grass strands at the view's centre, in a new file beside the project");
        return false;
    }
    std::string error;
    if (doc->addParticleSystem(newGrassSystem(state->place_at, doc->terrain() != nullptr), &error)) {
        state->selected = doc->particles()->size() - 1;
        state->selected_handle = {};
        state->last_error.clear();
        return true;
    }
    state->last_error = error;
    *message = error;
    return false;
}

// The selected entry of the project's list: its name (empty: the file's own) and offset, which move every
// part of the system at once (its file is unchanged). A rename is one undo step, a drag of the offset one.
void editEntry(Document* doc, ParticlesPanelState* state, std::string* message) {
    ParticleSystemRef& entry = state->editing_entry;
    PanelEdit e;
    char name[256];
    std::snprintf(name, sizeof(name), "%s", entry.name.c_str());
    if (ImGui::InputTextWithHint("name", state->editing.file_name.c_str(), name, sizeof(name))) entry.name = name;
    finished(&e);
    named(&e, "Rename particle system");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", ("the system's name in this project (its file: " + entry.file + ")").c_str());
    dragged(ImGui::DragFloat3("offset (m)", &entry.offset_m.x, 0.01f), &e);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("moves every generator, attractor and cutter of this entry");
    commitPanelEdit(
        doc, e, "Move particle system",
        [&](const std::string&, std::string* error) {
            return doc->setParticleEntry(state->selected, entry.name, entry.offset_m, error);
        },
        &state->last_error, message);
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
        ImGui::TextWrapped("The project has no particle system: New system grows a patch of grass strands at the "
                           "view's centre, to edit from here.");
        newSystemButton(doc, state, message);
        if (!state->last_error.empty()) ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "%s", state->last_error.c_str());
        ImGui::End();
        return;
    }
    state->selected = std::min(state->selected, systems.size() - 1);
    ImGui::SetNextItemWidth(std::max(80.0f, ImGui::GetContentRegionAvail().x - 160.0f));
    if (ImGui::BeginCombo("system", systems[state->selected].name.c_str())) {
        for (size_t i = 0; i < systems.size(); ++i)
            if (ImGui::Selectable(systems[i].name.c_str(), i == state->selected)) {
                state->selected = i;
                state->selected_handle = {};
            }
        ImGui::EndCombo();
    }
    ImGui::SameLine();
    if (newSystemButton(doc, state, message)) {
        ImGui::End();  // drawn from the new system next frame
        return;
    }
    if (state->growing) {
        char label[32];
        std::snprintf(label, sizeof label, "growing %d %%", int(100.0f * state->progress));
        ImGui::ProgressBar(state->progress, ImVec2(state->can_cancel ? -70.0f : -1.0f, 0.0f), label);
        if (state->can_cancel) {
            ImGui::SameLine();
            if (ImGui::Button("Cancel")) state->cancel_requested = true;
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("stop growing and undo the edit");
        }
    } else {
        ImGui::TextDisabled("%s", state->status.c_str());
    }
    if (!state->last_error.empty()) ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "%s", state->last_error.c_str());

    if (!ImGui::IsAnyItemActive() || state->editing_doc != doc || state->editing_index != state->selected) {
        state->editing = systems[state->selected];
        state->editing_entry = doc->project().particles[state->selected];
        state->editing_doc = doc;
        state->editing_index = state->selected;
    }
    ParticleSystemFile& system = state->editing;
    ParticleScene& scene = system.scene;
    PanelEdit e;
    const glm::vec3 at = state->place_at, kUp(0.0f, 0.0f, 1.0f);
    placeButtons(state);
    if (ImGui::CollapsingHeader("Generators")) {
        // A system keeps a generator: a particle file without one does not load.
        partRows(&scene.generators, 1, ParticlePart::Generator, state, &e,
                 [&](size_t i) { return partLabel("generator", i, kGeneratorKinds[size_t(scene.generators[i].kind)]); },
                 [&](ParticleGenerator* g) { editGenerator(g, &e); });
        if (ImGui::Button("Add generator")) {
            addParticlePart(&scene, ParticlePart::Generator, at, kUp, scene.terrain != nullptr);
            e.changed = true;
            e.name = "Add generator";
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("a 0.5 m square of 400 strands on the ground at the view's centre");
    }
    if (ImGui::CollapsingHeader("Attractors", ImGuiTreeNodeFlags_DefaultOpen)) {
        partRows(&scene.attractors, 0, ParticlePart::Attractor, state, &e,
                 [&](size_t i) { return partLabel("attractor", i, kAttractorKinds[size_t(scene.attractors[i].kind)]); },
                 [&](Attractor* a) { editAttractor(a, scene.walk.steps, &e); });
        if (ImGui::Button("Add attractor")) {
            addParticlePart(&scene, ParticlePart::Attractor, at, kUp, false);
            e.changed = true;
            e.name = "Add attractor";
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("a point 30 cm above the view's centre, attracting within 30 cm");
    }
    if (ImGui::CollapsingHeader("Cutters")) {
        partRows(&scene.cutters, 0, ParticlePart::Cutter, state, &e,
                 [&](size_t i) { return partLabel("cutter", i, kCutterKinds[size_t(scene.cutters[i].kind)]); },
                 [&](Cutter* c) { editCutter(c, &e); });
        if (ImGui::Button("Add cutter")) {
            addParticlePart(&scene, ParticlePart::Cutter, at, kUp, false);
            e.changed = true;
            e.name = "Add cutter";
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("a horizontal plane 20 cm above the view's centre that stops the strands");
    }
    if (ImGui::CollapsingHeader("Walk")) editWalk(&scene.walk, &e);

    commitPanelEdit(
        doc, e, "Edit particles",
        [&](const std::string&, std::string* error) { return doc->setParticleSystem(state->selected, system, error); },
        &state->last_error, message);
    ImGui::Separator();
    // Out of the project's list (its file stays on disk); one undo step, so no question asked.
    if (ImGui::Button("Remove system")) {
        std::string error;
        if (doc->removeParticleSystem(state->selected, &error)) {
            state->selected_handle = {};
            state->last_error.clear();
        } else {
            state->last_error = error;
            *message = error;
        }
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("take this system out of the project (its file stays; Ctrl+Z brings it back)");
    // Last, so that opening it moves nothing above.
    if (ImGui::CollapsingHeader("Name and offset")) editEntry(doc, state, message);
    ImGui::End();
}

}  // namespace ug::editor
