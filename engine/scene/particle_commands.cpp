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

bool AddParticleSystemCommand::apply(EditTarget t, EditEffect* effect, std::string*) {
    t.project->particles.push_back(ref_);
    auto systems = std::make_shared<std::vector<ParticleSystemFile>>(**t.particles);
    systems->push_back(system_);
    *t.particles = std::move(systems);
    effect->particles = true;
    return true;
}

void AddParticleSystemCommand::revert(EditTarget t, EditEffect* effect) {
    t.project->particles.pop_back();
    auto systems = std::make_shared<std::vector<ParticleSystemFile>>(**t.particles);
    systems->pop_back();
    *t.particles = std::move(systems);
    effect->particles = true;
}

bool SetParticleEntryCommand::apply(EditTarget t, EditEffect* effect, std::string* error) {
    if (index_ >= t.project->particles.size() || index_ >= (*t.particles)->size()) {
        *error = "no particle system " + std::to_string(index_);
        return false;
    }
    before_ = t.project->particles[index_];
    systems_before_ = *t.particles;
    auto systems = std::make_shared<std::vector<ParticleSystemFile>>(**t.particles);
    ParticleSystemFile& s = (*systems)[index_];
    translateParticleScene(&s.scene, after_.offset_m - before_.offset_m);
    s.name = after_.name.empty() ? s.file_name : after_.name;
    t.project->particles[index_] = after_;
    *t.particles = std::move(systems);
    effect->particles = true;
    return true;
}

void SetParticleEntryCommand::revert(EditTarget t, EditEffect* effect) {
    t.project->particles[index_] = before_;
    *t.particles = systems_before_;
    effect->particles = true;
}

bool RemoveParticleSystemCommand::apply(EditTarget t, EditEffect* effect, std::string* error) {
    if (index_ >= t.project->particles.size() || index_ >= (*t.particles)->size()) {
        *error = "no particle system " + std::to_string(index_);
        return false;
    }
    ref_ = t.project->particles[index_];
    t.project->particles.erase(t.project->particles.begin() + std::ptrdiff_t(index_));
    auto systems = std::make_shared<std::vector<ParticleSystemFile>>(**t.particles);
    system_ = (*systems)[index_];
    systems->erase(systems->begin() + std::ptrdiff_t(index_));
    *t.particles = std::move(systems);
    effect->particles = true;
    return true;
}

void RemoveParticleSystemCommand::revert(EditTarget t, EditEffect* effect) {
    t.project->particles.insert(t.project->particles.begin() + std::ptrdiff_t(index_), ref_);
    auto systems = std::make_shared<std::vector<ParticleSystemFile>>(**t.particles);
    systems->insert(systems->begin() + std::ptrdiff_t(index_), system_);
    *t.particles = std::move(systems);
    effect->particles = true;
}

bool savableParticleSystem(const ParticleSystemFile& system, std::string* why) {
    if (system.scene.generators.empty()) {
        *why = "generators: at least one generator is needed";
        return false;
    }
    return true;
}

std::string newParticleFileName(const Project& project, const std::string& stem) {
    std::set<std::string> named;
    for (size_t i = 0; i < project.particles.size(); ++i) named.insert(entryFile(project, i));
    for (int n = 1;; ++n) {
        const std::string file = "particles/" + stem + (n == 1 ? "" : "_" + std::to_string(n)) + ".json";
        const std::string path = std::filesystem::path(resolveProjectPath(project, file)).lexically_normal().string();
        std::error_code ec;
        if (!named.count(path) && !std::filesystem::exists(path, ec)) return file;
    }
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
