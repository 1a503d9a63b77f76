#include "scene/particle_commands.h"

#include <filesystem>
#include <set>

namespace ug {

namespace {

std::string entryFile(const Project& project, size_t index) {
    return std::filesystem::path(resolveProjectPath(project, project.particles[index].file)).lexically_normal().string();
}

}  // namespace

std::vector<ParticleSystemFile> withParticleSystem(const Project& project, const std::vector<ParticleSystemFile>& systems,
                                                   size_t index, const ParticleSystemFile& system) {
    std::vector<ParticleSystemFile> out = systems;
    const std::string file = entryFile(project, index);
    const glm::vec3 offset = project.particles[index].offset_m;
    for (size_t j = 0; j < out.size() && j < project.particles.size(); ++j) {
        if (j == index) {
            out[j] = system;
            continue;
        }
        if (entryFile(project, j) != file) continue;
        ParticleSystemFile copy = system;
        copy.name = out[j].name;
        translateParticleScene(&copy.scene, project.particles[j].offset_m - offset);
        out[j] = std::move(copy);
    }
    return out;
}

bool SetParticleSystemsCommand::apply(EditTarget t, EditEffect* effect, std::string*) {
    before_ = *t.particles;
    *t.particles = after_;
    effect->particles = true;
    return true;
}

void SetParticleSystemsCommand::revert(EditTarget t, EditEffect* effect) {
    *t.particles = before_;
    effect->particles = true;
}

std::vector<ParticleFileWrite> particleFilesToWrite(const Project& project, const std::vector<ParticleSystemFile>& systems,
                                                    const std::vector<ParticleSystemFile>& saved) {
    std::vector<ParticleFileWrite> out;
    std::set<std::string> written;
    for (size_t i = 0; i < systems.size() && i < project.particles.size(); ++i) {
        if (i < saved.size() && particleSystemToJson(systems[i]) == particleSystemToJson(saved[i])) continue;
        const std::string file = entryFile(project, i);
        if (!written.insert(file).second) continue;
        ParticleSystemFile own = systems[i];
        own.name = own.file_name.empty() ? own.name : own.file_name;
        translateParticleScene(&own.scene, -project.particles[i].offset_m);
        out.push_back({file, particleSystemToJson(own).dump(2) + "\n"});
    }
    return out;
}

}  // namespace ug
