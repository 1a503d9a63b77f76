#include "particles/particle_output.h"

#include <memory>

#include <nlohmann/json.hpp>

#include "particles/strand_mesh.h"

namespace ug {

namespace {

std::string strandsExtras(const Strands& strands) {
    nlohmann::json j;
    if (strands.points.size() > kMaxExtrasStrandPoints) {
        j["strands_omitted"] = std::to_string(strands.points.size()) + " points, more than " +
                               std::to_string(kMaxExtrasStrandPoints) + " (the tubes are complete)";
        return j.dump();
    }
    nlohmann::json points = nlohmann::json::array();
    for (const glm::vec3& p : strands.points) points.push_back({p.x, p.y, p.z});
    j["strands"] = {{"radius_m", strands.radii.empty() ? 0.0f : strands.radii[0]},
                    {"offsets", strands.offsets},
                    {"points", points},
                    {"space", "engine: metres, Z up (the mesh's node turns it to glTF's Y up)"}};
    return j.dump();
}

}  // namespace

bool growParticleSystem(const ParticleSystemFile& system, int threads, Strands* strands, MeshInstances* out,
                        std::string* error) {
    return growStrands(system.scene, {.threads = threads}, strands, error) &&
           meshParticleStrands(system, *strands, out, error);
}

bool meshParticleStrands(const ParticleSystemFile& system, const Strands& strands, MeshInstances* out,
                         std::string* error) {
    if (strands.size() == 0) {
        if (error) *error = "no strand grew (every particle was killed or never moved)";
        return false;
    }
    auto mesh = std::make_shared<TriangleMesh>();
    if (!strandMesh(strands, system.mesh, mesh.get(), error)) return false;
    *out = MeshInstances{};
    out->name = "strands/" + system.name;
    out->mesh = mesh;
    out->material = std::make_shared<SurfaceMaterial>(resolveMaterial(system.material, glm::vec3(0.45f, 0.36f, 0.25f)));
    out->extras_json = strandsExtras(strands);
    auto levels = std::make_shared<std::vector<MeshLodLevel>>();
    strandMeshLevels(strands, system.mesh, levels.get());
    if (!levels->empty()) out->lod_levels = std::move(levels);
    return true;
}

bool appendParticleSystemMeshes(const ParticleSystemFile& system, int threads, Strands* strands,
                                std::vector<MeshInstances>* out, std::string* error) {
    MeshInstances tubes;
    if (!growParticleSystem(system, threads, strands, &tubes, error)) return false;
    out->push_back(std::move(tubes));
    for (MeshInstances& surface : generatorSurfaces(system)) out->push_back(std::move(surface));
    return true;
}

std::vector<MeshInstances> generatorSurfaces(const ParticleSystemFile& system) {
    std::vector<MeshInstances> out;
    const auto place = [&](const std::string& part, size_t i, const std::shared_ptr<const TriangleMesh>& mesh,
                           glm::vec3 at, float scale) {
        MeshInstances m;
        m.name = "strands/" + system.name + "/" + part + "_" + std::to_string(i);
        m.mesh = mesh;
        m.instances.push_back(InstanceTransform{at, glm::quat(1.0f, 0.0f, 0.0f, 0.0f), scale});
        out.push_back(std::move(m));
    };
    for (size_t i = 0; i < system.scene.generators.size(); ++i) {
        const ParticleGenerator& g = system.scene.generators[i];
        if (g.kind == GeneratorKind::Mesh && g.mesh) place("surface", i, g.mesh, g.center_m, g.scale);
    }
    for (size_t i = 0; i < system.scene.attractors.size(); ++i) {
        const Attractor& a = system.scene.attractors[i];
        if (a.kind == AttractorKind::Mesh && a.mesh) place("attractor", i, a.mesh, a.a_m, a.scale);
    }
    return out;
}

}  // namespace ug
