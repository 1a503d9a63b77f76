// Editing the project's particle systems (the editor's Particles panel). A system is replaced as a whole,
// one undo step (or one stamp of a stroke: a drag). The document holds the systems placed (each entry's
// offset applied, scene/scene_particles.h); entries that name the same file are the same system placed
// twice, so an edit of one is an edit of the file and every entry naming it takes it, at its own offset
// and under its own name. The files are written back when the project is saved.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "particles/particle_json.h"
#include "scene/edit_commands.h"
#include "scene/project.h"

namespace ug {

// The systems once entry `index` is `system` (placed): every entry naming the same file takes it too,
// moved by the difference of the offsets, under its own name.
std::vector<ParticleSystemFile> withParticleSystem(const Project& project, const std::vector<ParticleSystemFile>& systems,
                                                   size_t index, const ParticleSystemFile& system);

class SetParticleSystemsCommand : public Command {
public:
    explicit SetParticleSystemsCommand(ParticleSystems after) : after_(std::move(after)) {}
    std::string name() const override { return "Edit particles"; }
    bool apply(EditTarget target, EditEffect* effect, std::string* error) override;
    void revert(EditTarget target, EditEffect* effect) override;

private:
    ParticleSystems after_, before_;
};

// A new system: `ref` appended to the project's "particles" list and `system` (placed) to the systems, one
// undo step; undo takes both away (the file written when it was added stays on disk, unreferenced).
class AddParticleSystemCommand : public Command {
public:
    AddParticleSystemCommand(ParticleSystemRef ref, ParticleSystemFile system)
        : ref_(std::move(ref)), system_(std::move(system)) {}
    std::string name() const override { return "Add particle system"; }
    bool apply(EditTarget target, EditEffect* effect, std::string* error) override;
    void revert(EditTarget target, EditEffect* effect) override;

private:
    ParticleSystemRef ref_;
    ParticleSystemFile system_;
};

// Entry `index` taken out of the project's "particles" list with its system (its file stays on disk), one
// undo step; undo puts both back where they were.
class RemoveParticleSystemCommand : public Command {
public:
    explicit RemoveParticleSystemCommand(size_t index) : index_(index) {}
    std::string name() const override { return "Remove particle system"; }
    bool apply(EditTarget target, EditEffect* effect, std::string* error) override;
    void revert(EditTarget target, EditEffect* effect) override;

private:
    size_t index_;
    ParticleSystemRef ref_;
    ParticleSystemFile system_;
};

// Entry `index` of the project's "particles" list renamed and moved (`after`: its name and offset; the file
// stays), its placed system with it: moved by the difference of the offsets, under the new name (the
// file's own when empty). One undo step; undo gives both back.
class SetParticleEntryCommand : public Command {
public:
    SetParticleEntryCommand(size_t index, ParticleSystemRef after, std::string name)
        : index_(index), after_(std::move(after)), name_(std::move(name)) {}
    std::string name() const override { return name_; }
    bool apply(EditTarget target, EditEffect* effect, std::string* error) override;
    void revert(EditTarget target, EditEffect* effect) override;

private:
    size_t index_;
    ParticleSystemRef after_, before_;
    ParticleSystems systems_before_;
    std::string name_;
};

// What a particle file needs beyond validateParticleScene to load again once saved (a generator);
// false with *why otherwise. The document refuses edits that would save a file it could not open.
bool savableParticleSystem(const ParticleSystemFile& system, std::string* why);

// A file for a new system beside the project, as its "particles" list names it: "particles/<stem>.json",
// or "<stem>_2.json", "_3", ... while that file exists on disk or an entry names it.
std::string newParticleFileName(const Project& project, const std::string& stem);

// A particle file to write when the project is saved.
struct ParticleFileWrite {
    std::string path;  // as the project resolves it
    std::string text;  // the file's JSON (particleSystemToJson)
};

// The files whose systems differ from `saved` (the systems as last loaded or saved), each once, as the file
// holds them: moved back by their entry's offset, under the file's own name. Positions moved back by an
// offset other than 0 may differ from the file's in the last bit.
std::vector<ParticleFileWrite> particleFilesToWrite(const Project& project, const std::vector<ParticleSystemFile>& systems,
                                                    const std::vector<ParticleSystemFile>& saved);

}  // namespace ug
