#include "editor/document_loader.h"

#include <algorithm>

#include "env/env_outputs.h"
#include "mesh/terrain_mesh.h"
#include "scene/scene_particles.h"

namespace ug::editor {

DocumentLoader::DocumentLoader(LoadRequest request)
    : request_(std::move(request)), scene_(std::make_unique<EditorScene>()) {
    thread_ = std::thread([this] { work(); });
}

DocumentLoader::~DocumentLoader() {
    if (thread_.joinable()) thread_.join();
}

void DocumentLoader::work() {
    EditorScene& s = *scene_;
    std::string error;
    auto failWith = [&](const std::string& message) {
        error_ = message;
        phase_.store(LoadPhase::Failed, std::memory_order_release);
    };
    if (request_.new_from_template) {
        Project project;
        if (!loadProject(request_.scene_path, &project, &error)) return failWith("New: " + error);
        for (DetailTypeDesc& t : project.detail_types) t.density = DensityField{};
        project.name = "untitled";
        s.doc = Document::create(std::move(project), "", request_.options, &error);
    } else {
        s.doc = request_.recover ? Document::recover(request_.scene_path, request_.options, &error)
                                 : Document::open(request_.scene_path, request_.options, &error);
    }
    if (!s.doc) return failWith(error);
    progress_.store(0.7f);
    const Document& doc = *s.doc;
    if (doc.terrain()) {
        // 512 cells a side at most: the meadow's 80 x 80 samples stay exact, a large image is decimated.
        // The mesh covers the terrain's whole rectangle, not only the extent: a brush may paint anywhere on
        // it.
        const HeightField& hf = *doc.terrain();
        Bounds rect = doc.compiled().extent;
        const glm::vec2 lo = hf.origin(),
                        hi = lo + hf.cellSize() * glm::vec2(hf.width() - 1, hf.height() - 1);
        if (rect.empty())
            rect = Bounds{glm::vec3(lo, hf.minHeight() - 1.0f), glm::vec3(hi, hf.maxHeight() + 1.0f)};
        if (!heightFieldMesh(hf, rect, 512, &s.terrain, &error))
            return failWith(request_.scene_path + ": terrain mesh: " + error);
        s.has_terrain = true;
    }
    progress_.store(0.85f);
    // The materials bake their textures (a few hundred ms): here, off the UI thread.
    const SceneMaterials looks = doc.materials();
    s.looks = doc.looks();
    s.meshes = buildLookMeshes(s.looks, doc.ghostTile().candidates, &looks);
    s.terrain_material = looks.terrain;
    if (!doc.environment()->empty()) {
        progress_.store(0.9f);
        auto fx = std::make_shared<EnvEffects>();
        if (!computeEnvEffects(*doc.environment(), {.threads = request_.options.threads}, fx.get(), &error))
            return failWith(request_.scene_path + ": " + error);
        s.static_meshes = envMeshInstances(*doc.environment(), *fx);
        s.env_effects = std::move(fx);
        s.env_scene = doc.environment();
    }
    if (!doc.particles()->empty()) {
        // The strands the CLI's exports carry (scene/scene_particles.h); the editor's export takes them
        // from here with the environment's meshes.
        progress_.store(0.95f);
        SceneStrandStats strands;
        if (!growSceneParticles(*doc.particles(), request_.scene_path, request_.options.threads, nullptr,
                                &s.static_meshes, &strands, &error))
            return failWith(error);
    }
    progress_.store(1.0f);
    phase_.store(LoadPhase::Ready, std::memory_order_release);
}

}  // namespace ug::editor
