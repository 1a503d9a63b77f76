// The particle systems' strands in the editor (issue 14): the loader grew them once with the document;
// every edit, undo and redo after that moves Document::particlesGeneration(), and the systems go to the
// LiveStrands worker, which re-grows only what the edit reaches. The newest finished strands replace the
// scene's "strands/..." static meshes at the frame boundary, so the view, the export and the replay's
// settled state all see the same strands.
#include <cstdio>
#include <utility>

#include "editor/editor_session.h"

namespace ug::editor {

namespace {

bool isStrandMesh(const MeshInstances& m) { return m.name.rfind("strands/", 0) == 0; }

}  // namespace

void EditorSession::startStrands() {
    live_strands.reset();
    last_strands = LiveStrandsResult{};
    particles_panel = ParticlesPanelState{};
    const Document& d = *scene->doc;
    strands_submitted = strands_shown = d.particlesGeneration();
    if (d.particles()->empty()) return;
    live_strands = std::make_unique<LiveStrands>(doc_options.threads);
    // Grown again in the background at once, though the loader's strands are the same: the regrowers then
    // hold a record, so the first edit is already incremental. The result is not swapped in (same strands).
    live_strands->submit(d.particles(), d.particlesGeneration());
}

bool EditorSession::submitStrands() {
    // A document without systems gets its worker with the first one (New system).
    if (scene && !live_strands && !scene->doc->particles()->empty())
        live_strands = std::make_unique<LiveStrands>(doc_options.threads);
    if (!scene || !live_strands) return false;
    Document& d = *scene->doc;
    if (std::exchange(particles_panel.cancel_requested, false)) cancelStrands();
    if (d.particlesGeneration() == strands_submitted) return false;
    strands_submitted = d.particlesGeneration();
    live_strands->submit(d.particles(), strands_submitted);
    return true;
}

void EditorSession::syncStrands() {
    submitStrands();
    if (!scene || !live_strands) {
        particles_panel.growing = false;
        return;
    }
    Document& d = *scene->doc;
    LiveStrandsResult r;
    // A cancelled growth's edit was undone (cancelStrands): its strands never show.
    if (live_strands->poll(&r) && !r.cancelled) {
        if (r.generation != strands_shown) {
            std::vector<MeshInstances>& statics = scene->static_meshes;
            std::erase_if(statics, isStrandMesh);
            for (MeshInstances& m : r.meshes) statics.push_back(std::move(m));
            showStaticMeshes();
            strands_shown = r.generation;
        }
        if (!r.error.empty()) messages.push_back(r.error);
        char status[160];
        const uint64_t moves = r.report.recomputed + r.report.reused;
        std::snprintf(status, sizeof status, "%llu strands in %.2f s, %.0f %% of the moves re-grown",
                      (unsigned long long)r.strands, r.seconds,
                      moves ? 100.0 * double(r.report.recomputed) / double(moves) : 100.0);
        particles_panel.status = status;
        r.meshes.clear();
        last_strands = std::move(r);
    }
    particles_panel.growing = live_strands->busy();
    particles_panel.progress = live_strands->progress();
    particles_panel.can_cancel = particles_panel.growing && strands_shown != d.particlesGeneration() &&
                                 d.undoRevertsParticles(d.particlesGeneration());
}

void EditorSession::showFreshStrands(std::chrono::milliseconds budget) {
    if (!scene || !submitStrands()) return;
    if (live_strands->waitForResult(budget)) syncStrands();
}

bool EditorSession::cancelStrands() {
    Document& d = *scene->doc;
    const uint64_t generation = d.particlesGeneration();
    if (!live_strands || strands_shown == generation || !d.undoRevertsParticles(generation)) return false;
    const std::string name = d.undoName();
    live_strands->cancel(generation);
    d.undo();
    messages.push_back("Cancelled the strands' growth: \"" + name + "\" undone");
    return true;
}

bool EditorSession::strandsSettled() const {
    return !live_strands || (strands_shown == scene->doc->particlesGeneration() && !live_strands->busy());
}

nlohmann::json EditorSession::strandsJson() const {
    json j = {{"ok", last_strands.error.empty()},
              {"strands", last_strands.strands},
              {"incremental", last_strands.report.incremental},
              {"recomputed", last_strands.report.recomputed},
              {"reused", last_strands.report.reused},
              {"grow_seconds", last_strands.seconds}};
    if (!last_strands.error.empty()) j["error"] = last_strands.error;
    return j;
}

}  // namespace ug::editor
