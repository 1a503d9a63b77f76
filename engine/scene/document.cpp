#include "scene/document.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/hash.h"
#include "env/env_effects.h"
#include "scene/scene_particles.h"

namespace ug {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string absolutePath(const std::string& path) {
    std::error_code ec;
    fs::path p = fs::absolute(path, ec);
    if (ec) p = path;
    return p.lexically_normal().string();
}

bool sameBounds(const Bounds& a, const Bounds& b) { return a.lo == b.lo && a.hi == b.hi; }

// The extent the document instantiates: the project's, or derived from the densities as the CLI derives
// it from the saved file. Unlike compileScene, a scene with no density yet (a new project, everything
// erased) is fine: its extent is empty and it has no instances.
bool documentExtent(const Project& project, const CompiledScene& scene, const std::string& name, Bounds* out,
                    std::string* error) {
    if (project.extent) {
        *out = *project.extent;
        return true;
    }
    const Bounds e = computeSceneExtent(project, scene);
    bool flat = false;
    for (int a = 0; a < 3; ++a) flat = flat || !(e.lo[a] < e.hi[a]);
    if (e.empty() || flat) {
        *out = Bounds{};
        return true;
    }
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(e.lo[a]) || !std::isfinite(e.hi[a])) {
            *error = name + ": /extent: required because a density is unbounded (give the project an extent)";
            return false;
        }
    *out = e;
    return true;
}

// A path written in the project (relative to old_dir unless absolute) as the project in new_dir must
// write it. Absolute paths stay absolute; a path that cannot be made relative becomes absolute.
std::string rebasePath(const std::string& path, const fs::path& old_dir, const fs::path& new_dir) {
    if (path.empty() || fs::path(path).is_absolute()) return path;
    const fs::path target = (old_dir / path).lexically_normal();
    const fs::path rel = target.lexically_relative(new_dir);
    return rel.empty() ? target.string() : rel.string();
}

int64_t unixNow() {
    return std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch())
        .count();
}

}  // namespace

std::string defaultConfigDir() {
    if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg && *xdg) return (fs::path(xdg) / "undergrowth").string();
    if (const char* home = std::getenv("HOME"); home && *home)
        return (fs::path(home) / ".config" / "undergrowth").string();
    return "";
}

// ---- recent files ------------------------------------------------------------------------------------------

std::vector<std::string> loadRecentFiles(const std::string& config_dir) {
    std::vector<std::string> files;
    if (config_dir.empty()) return files;
    std::string text, error;
    if (!readTextFile((fs::path(config_dir) / "recent.json").string(), &text, &error)) return files;
    const json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (!j.is_object() || !j.contains("files") || !j["files"].is_array()) return files;
    for (const json& f : j["files"])
        if (f.is_string() && files.size() < kMaxRecentFiles) files.push_back(f.get<std::string>());
    return files;
}

bool addRecentFile(const std::string& config_dir, const std::string& path, std::string* error) {
    if (config_dir.empty()) return true;
    const std::string abs = absolutePath(path);
    std::vector<std::string> files = loadRecentFiles(config_dir);
    std::erase(files, abs);
    files.insert(files.begin(), abs);
    if (files.size() > kMaxRecentFiles) files.resize(kMaxRecentFiles);
    std::error_code ec;
    fs::create_directories(config_dir, ec);
    const json j = {{"format", "undergrowth-recent"}, {"files", files}};
    return writeTextFileAtomically((fs::path(config_dir) / "recent.json").string(), j.dump(2) + "\n", error);
}

// ---- recovery ----------------------------------------------------------------------------------------------

namespace {

std::string recoveryKey(const std::string& project_path) {
    if (project_path.empty()) return "untitled";
    const std::string abs = absolutePath(project_path);
    return hex64(hashBytes(abs.data(), abs.size())).substr(2);  // without "0x"
}

std::string recoveryMetaPath(const std::string& config_dir, const std::string& project_path) {
    return (fs::path(config_dir) / "recovery" / (recoveryKey(project_path) + ".meta.json")).string();
}

// The particle systems edited since the last save live in their own files until then, not in the
// project: the autosave keeps them beside the project's recovery file.
std::string recoveryParticlesPath(const std::string& config_dir, const std::string& project_path) {
    return (fs::path(config_dir) / "recovery" / (recoveryKey(project_path) + ".particles.json")).string();
}

}  // namespace

std::string recoveryPath(const std::string& config_dir, const std::string& project_path) {
    return (fs::path(config_dir) / "recovery" / (recoveryKey(project_path) + ".json")).string();
}

bool findRecovery(const std::string& config_dir, const std::string& project_path, RecoveryInfo* out) {
    if (config_dir.empty()) return false;
    const std::string data = recoveryPath(config_dir, project_path);
    std::string text, error;
    if (!readTextFile(recoveryMetaPath(config_dir, project_path), &text, &error)) return false;
    const json meta = json::parse(text, nullptr, false);
    const std::string abs = project_path.empty() ? std::string() : absolutePath(project_path);
    // The meta names the path it belongs to: a hash collision (or a hand-copied folder) is not a recovery.
    if (!meta.is_object() || meta.value("format", "") != "undergrowth-recovery" || meta.value("path", "") != abs)
        return false;
    std::error_code ec;
    const auto recovery_time = fs::last_write_time(data, ec);
    if (ec) return false;
    if (!abs.empty()) {
        std::error_code ec2;
        const auto file_time = fs::last_write_time(abs, ec2);
        // Saved after the autosave (by this or another program): the file is newer, nothing to recover.
        if (!ec2 && file_time >= recovery_time) return false;
    }
    if (out) {
        out->project_path = abs;
        out->recovery_path = data;
        out->saved_unix_s = meta.value("saved_unix_s", int64_t(0));
    }
    return true;
}

void discardRecovery(const std::string& config_dir, const std::string& project_path) {
    if (config_dir.empty()) return;
    std::error_code ec;
    // The meta goes first: without it the data file is never offered.
    fs::remove(recoveryMetaPath(config_dir, project_path), ec);
    fs::remove(recoveryPath(config_dir, project_path), ec);
    fs::remove(recoveryParticlesPath(config_dir, project_path), ec);
}

// ---- Document: loading -------------------------------------------------------------------------------------

std::unique_ptr<Document> Document::open(const std::string& path, const DocumentOptions& options,
                                         std::string* error) {
    Project project;
    if (!loadProject(path, &project, error)) return nullptr;
    std::unique_ptr<Document> doc(new Document());
    if (!doc->load(std::move(project), path, options, error)) return nullptr;
    std::string ignored;  // a recent list that cannot be written is not worth failing the open for
    addRecentFile(options.config_dir, path, &ignored);
    return doc;
}

std::unique_ptr<Document> Document::recover(const std::string& path, const DocumentOptions& options,
                                            std::string* error) {
    RecoveryInfo info;
    if (!findRecovery(options.config_dir, path, &info)) {
        *error = path + ": no recovery file newer than the project in '" +
                 (fs::path(options.config_dir) / "recovery").string() + "'";
        return nullptr;
    }
    std::string text;
    if (!readTextFile(info.recovery_path, &text, error)) return nullptr;
    Project project;
    if (!parseProject(text, info.recovery_path, &project, error)) return nullptr;
    // The autosave wrote the paths as the project has them: relative to the project's own folder.
    project.base_dir = fs::path(path).parent_path().string();
    project.source = path;
    std::unique_ptr<Document> doc(new Document());
    if (!doc->load(std::move(project), path, options, error)) return nullptr;
    doc->saved_state_ = ~uint64_t(0);  // unsaved until the user saves it
    if (!doc->recoverParticles(recoveryParticlesPath(options.config_dir, path), error)) return nullptr;
    return doc;
}

bool Document::recoverParticles(const std::string& file, std::string* error) {
    if (!fs::exists(file)) return true;
    std::string text;
    if (!readTextFile(file, &text, error)) return false;
    const json j = json::parse(text, nullptr, false);
    const auto fail = [&](const std::string& why) {
        *error = file + ": " + why;
        return false;
    };
    if (!j.is_object() || j.value("format", "") != "undergrowth-recovery-particles" || !j.contains("systems") ||
        !j["systems"].is_array())
        return fail("not an autosave of particle systems");
    if (j["systems"].size() != particles_->size())
        return fail("holds " + std::to_string(j["systems"].size()) + " particle systems, the project " +
                    std::to_string(particles_->size()));
    std::vector<ParticleSystemFile> systems;
    for (size_t i = 0; i < particles_->size(); ++i) {
        ParticleSystemFile s;
        // Read as if from the particle file itself: a mesh generator's model is named relative to it.
        const std::string source = resolveProjectPath(project_, project_.particles[i].file);
        std::string why;
        if (!parseParticleSystem(j["systems"][i], source, &s, &why))
            return fail("/systems/" + std::to_string(i) + ": " + why);
        s.file_name = (*particles_)[i].file_name;
        s.scene.terrain = terrain_;
        if (!placeSystem(*environment_, compiled_, true, &s.scene, &why))
            return fail("/systems/" + std::to_string(i) + ": " + why);
        systems.push_back(std::move(s));
    }
    particles_ = std::make_shared<const std::vector<ParticleSystemFile>>(std::move(systems));
    ++particles_generation_;
    return true;
}

std::unique_ptr<Document> Document::create(Project project, const std::string& path, const DocumentOptions& options,
                                           std::string* error) {
    std::unique_ptr<Document> doc(new Document());
    if (!doc->load(std::move(project), path, options, error)) return nullptr;
    return doc;
}

bool Document::load(Project project, const std::string& path, const DocumentOptions& options, std::string* error) {
    options_ = options;
    path_ = path;
    project_ = std::move(project);
    for (const DetailTypeDesc& t : project_.detail_types)
        assets_.model_files.push_back(modelFileStamp(resolveProjectPath(project_, t.model.mesh_path)));
    if (project_.source.empty() && !path.empty()) project_.source = path;
    LoadedScene scene;
    if (!loadScene(project_, SceneLoadOptions{.cache_dir = options.cache_dir, .threads = options.threads,
                                              .allow_empty_extent = true},
                   &scene, error))
        return false;
    terrain_ = scene.terrain;
    assets_.outcome = scene.outcome;
    assets_.tile = std::move(scene.tile);
    assets_.models = std::move(scene.models);
    live_assets_ = assets_;
    compiled_ = std::move(scene.compiled);
    environment_ = std::move(scene.environment);
    variant_models_ = std::move(scene.variant_models);
    particles_ = std::move(scene.particles);
    saved_particles_ = particles_;
    densities_.clear();
    for (const DetailTypeDesc& t : project_.detail_types) densities_.push_back(editableDensityFor(t.density, &next_id_));
    live_ = std::make_unique<LiveInstancer>(options.threads);
    live_->reset(instancerInput(), settleInputOf());
    return true;
}

Document::~Document() = default;

InstancerInput Document::instancerInput() const { return instancerInputFor(compiled_); }

InstancerInput Document::instancerInputFor(const CompiledScene& compiled) const {
    return instancerInputOf(*assets_.tile, *assets_.models, compiled, project_.instantiation_seed);
}

SettleInput Document::settleInputOf() const {
    return settleInput(project_, terrain_, *assets_.tile, *assets_.models, environment_.get());
}

// ---- Document: primitives and edits ------------------------------------------------------------------------

std::vector<uint64_t> Document::primitiveIds(size_t type) const {
    std::vector<uint64_t> ids;
    if (type >= densities_.size()) return ids;
    for (uint64_t id : densities_[type].ids)
        if (id != 0) ids.push_back(id);
    return ids;
}

bool Document::findPrimitive(uint64_t id, size_t* type, Primitive* out) const {
    for (size_t t = 0; t < densities_.size(); ++t) {
        const int64_t k = findUserPrimitive(densities_[t], id);
        if (k < 0) continue;
        if (type) *type = t;
        if (out) *out = userPrimitive(project_.detail_types[t].density, size_t(k));
        return true;
    }
    return false;
}

bool Document::commit(EditEffect& effect, std::string* error) {
    CompiledScene next;
    next.terrain = compiled_.terrain;
    next.environment = compiled_.environment;
    next.types = compiled_.types;
    EditEffect all = effect;
    std::shared_ptr<const EnvScene> env = environment_;
    if (effect.environment && !compileEditedEnvironment(&env, &all, error)) return false;
    next.environment = env;
    // The particle systems grow among the objects: an edit of either places them again. Systems that grow
    // on detail instances are placed again after any edit of what is instantiated: the instances in their
    // boxes may depend on candidates far away (a chain of conflicts), so no dirty region is trusted here.
    const bool details = anySystemOnDetails() &&
                         (effect.environment || effect.particles || effect.tile || all.full || !all.types.empty());
    std::shared_ptr<const std::vector<ParticleSystemFile>> placed;
    for (size_t t : all.types)
        if (!compileDetailType(project_, t, terrain_, &next.types[t], error, next.environment)) return false;
    if (!documentExtent(project_, next, path_.empty() ? project_.name : path_, &next.extent, error)) return false;
    if ((effect.environment || effect.particles || details) && !placeParticles(*env, next, details, &placed, error))
        return false;
    if (placed) effect.particles = true;
    const bool extent_changed = !sameBounds(next.extent, compiled_.extent);
    compiled_ = std::move(next);
    if (!live_->pending()) {
        retired_.clear();
        retired_environments_.clear();
    }
    if (effect.tile) {
        retired_.push_back(live_assets_);
        live_assets_ = assets_;
        ++tile_generation_;
    }
    if (placed) particles_ = std::move(placed);
    if (effect.particles) ++particles_generation_;
    bool support_moved = false;
    if (effect.environment) {
        support_moved = !sameRestSurfaces(*environment_, *env);
        // The live worker may still settle on the old objects (SettleInput points at them).
        retired_environments_.push_back(environment_);
        environment_ = env;
        ++environment_generation_;
    }
    if (all.full || extent_changed) {
        const uint64_t generation = live_->reset(instancerInput(), settleInputOf());
        if (effect.tile) tile_live_generation_ = generation;
    } else if (effect.environment) {
        live_->submit(compiled_.types, all.dirty, settleInputOf(), support_moved);
    } else if (!all.types.empty()) {
        live_->submit(compiled_.types, all.dirty);
    }
    return true;
}

bool Document::anySystemOnDetails() const {
    for (const ParticleSystemFile& s : *particles_)
        if (growsOnDetails(s.scene)) return true;
    return false;
}

bool Document::placeSystem(const EnvScene& environment, const CompiledScene& compiled, bool on_details,
                           ParticleScene* scene, std::string* error) const {
    if (!placeAmongObjects(&environment, scene, error)) return false;
    if (!on_details || !growsOnDetails(*scene)) return true;
    const InstancerInput instancer = instancerInputFor(compiled);
    const SettleInput settle = settleInput(project_, terrain_, *assets_.tile, *assets_.models, &environment);
    if (settle.settings.enabled && !validateSettleInput(settle, error)) return false;
    const DetailPlacement placement{
        .instancer = &instancer, .settle = &settle, .models = assets_.models, .threads = options_.threads};
    return placeOnDetails(placement, scene, error);
}

bool Document::placeParticles(const EnvScene& environment, const CompiledScene& compiled, bool on_details,
                              std::shared_ptr<const std::vector<ParticleSystemFile>>* placed, std::string* error) const {
    std::vector<ParticleSystemFile> systems = *particles_;
    bool changed = false;
    for (size_t i = 0; i < systems.size(); ++i) {
        ParticleScene& scene = systems[i].scene;
        const ParticleScene& before = (*particles_)[i].scene;
        if (!placeSystem(environment, compiled, on_details, &scene, error)) {
            *error = "particles[" + std::to_string(i) + "] (" + systems[i].name + "): " + *error;
            return false;
        }
        changed = changed || scene.obstacles != before.obstacles || scene.detail_obstacles != before.detail_obstacles;
        for (size_t g = 0; g < scene.generators.size(); ++g)
            changed = changed || scene.generators[g].mesh != before.generators[g].mesh;
        for (size_t a = 0; a < scene.attractors.size(); ++a)
            changed = changed || scene.attractors[a].points != before.attractors[a].points;
    }
    if (changed) *placed = std::make_shared<const std::vector<ParticleSystemFile>>(std::move(systems));
    return true;
}

bool Document::compileEditedEnvironment(std::shared_ptr<const EnvScene>* env, EditEffect* effect, std::string* error) {
    auto edited = std::make_shared<EnvScene>();
    if (!compileEnvScene(project_.environment, project_.base_dir, path_.empty() ? project_.name : path_, terrain_,
                         edited.get(), error, environment_.get()))
        return false;
    // The scattered types read their density from the environment: where it changed, so did they.
    const std::vector<Bounds> dirty = envDirtyRegion(*environment_, *edited);
    for (size_t t = 0; t < project_.detail_types.size(); ++t)
        if (project_.detail_types[t].scatter.enabled) effect->addType(t);
    effect->dirty.insert(effect->dirty.end(), dirty.begin(), dirty.end());
    *env = std::move(edited);
    return true;
}

bool Document::execute(std::unique_ptr<Command> command, std::string* error) {
    EditEffect effect;
    if (!command->apply(target(), &effect, error)) return false;
    if (!commit(effect, error)) {
        EditEffect undone;
        command->revert(target(), &undone);
        return false;
    }
    ++edit_count_;
    const uint64_t particles_generation = effect.particles ? particles_generation_ : 0;
    if (stroke_) {
        stroke_->push(std::move(command));
        if (particles_generation) stroke_particles_generation_ = particles_generation;
    } else {
        undo_.push_back(Step{std::move(command), next_state_++, particles_generation});
        if (undo_.size() > kMaxUndoSteps) undo_.erase(undo_.begin());
    }
    redo_.clear();
    return true;
}

uint64_t Document::addPrimitive(size_t type, const Primitive& prim, std::string* error) {
    const uint64_t id = next_id_;
    if (!execute(std::make_unique<AddPrimitiveCommand>(type, prim, id), error)) return 0;
    ++next_id_;
    return id;
}

bool Document::setPrimitive(uint64_t id, const Primitive& prim, std::string* error) {
    return execute(std::make_unique<SetPrimitiveCommand>(id, prim), error);
}

bool Document::removePrimitive(uint64_t id, std::string* error) {
    return execute(std::make_unique<RemovePrimitiveCommand>(id), error);
}

uint64_t Document::duplicatePrimitive(uint64_t id, glm::vec3 offset_m, std::string* error) {
    size_t type = 0;
    Primitive prim;
    if (!findPrimitive(id, &type, &prim)) {
        *error = "no primitive with id " + std::to_string(id);
        return 0;
    }
    prim.stroke = 0;  // a lone copy joins no stroke
    return addPrimitive(type, translatedPrimitive(prim, offset_m), error);
}

namespace {

// fn(id, primitive) for every user primitive, in type then blend order.
template <typename Fn>
void eachUserPrimitive(const std::vector<EditableDensity>& densities, const Project& project, Fn fn) {
    for (size_t t = 0; t < densities.size(); ++t)
        for (size_t k = 0; k < densities[t].ids.size(); ++k)
            if (densities[t].ids[k] != 0) fn(densities[t].ids[k], userPrimitive(project.detail_types[t].density, k));
}

}  // namespace

std::vector<uint64_t> Document::strokeMembers(uint64_t id) const {
    Primitive prim;
    if (!findPrimitive(id, nullptr, &prim)) return {};
    if (prim.stroke == 0) return {id};
    std::vector<uint64_t> members;
    eachUserPrimitive(densities_, project_, [&](uint64_t member, const Primitive& p) {
        if (p.stroke == prim.stroke) members.push_back(member);
    });
    return members;
}

uint32_t Document::newStrokeTag() const {
    uint32_t largest = 0;
    eachUserPrimitive(densities_, project_,
                      [&](uint64_t, const Primitive& p) { largest = std::max(largest, p.stroke); });
    // Tags come from files too; past the last one, the first free tag above 0 (never reached in practice).
    return largest < UINT32_MAX ? largest + 1 : 1;
}

bool Document::setPrimitives(const std::vector<std::pair<uint64_t, Primitive>>& edits, const std::string& name,
                             std::string* error) {
    if (edits.empty()) return true;
    auto compound = std::make_unique<CompoundCommand>(name);
    for (const auto& [id, prim] : edits) compound->push(std::make_unique<SetPrimitiveCommand>(id, prim));
    return execute(std::move(compound), error);
}

bool Document::removePrimitives(const std::vector<uint64_t>& ids, const std::string& name, std::string* error) {
    if (ids.empty()) return true;
    auto compound = std::make_unique<CompoundCommand>(name);
    for (uint64_t id : ids) compound->push(std::make_unique<RemovePrimitiveCommand>(id));
    return execute(std::move(compound), error);
}

std::vector<uint64_t> Document::duplicatePrimitives(const std::vector<uint64_t>& ids, glm::vec3 offset_m,
                                                    std::string* error) {
    return duplicatePrimitives(ids, std::vector<glm::vec3>(ids.size(), offset_m), error);
}

std::vector<uint64_t> Document::duplicatePrimitives(const std::vector<uint64_t>& ids,
                                                    const std::vector<glm::vec3>& offsets_m, std::string* error) {
    if (ids.empty()) return {};
    if (offsets_m.size() != ids.size()) {
        *error = "duplicate: " + std::to_string(offsets_m.size()) + " offsets for " + std::to_string(ids.size()) +
                 " primitives";
        return {};
    }
    auto compound = std::make_unique<CompoundCommand>(ids.size() == 1 ? "Duplicate primitive" : "Duplicate stroke");
    std::vector<uint64_t> copies;
    std::vector<std::pair<uint32_t, uint32_t>> retag;  // old stroke -> new stroke
    uint32_t next_tag = newStrokeTag();
    for (size_t k = 0; k < ids.size(); ++k) {
        const uint64_t id = ids[k];
        size_t type = 0;
        Primitive prim;
        if (!findPrimitive(id, &type, &prim)) {
            *error = "no primitive with id " + std::to_string(id);
            return {};
        }
        if (prim.stroke != 0) {
            auto it = std::find_if(retag.begin(), retag.end(), [&](const auto& r) { return r.first == prim.stroke; });
            if (it == retag.end()) it = retag.insert(retag.end(), {prim.stroke, next_tag++});
            prim.stroke = it->second;
        }
        const uint64_t copy = next_id_ + copies.size();
        compound->push(std::make_unique<AddPrimitiveCommand>(type, translatedPrimitive(prim, offsets_m[k]), copy));
        copies.push_back(copy);
    }
    if (!execute(std::move(compound), error)) return {};
    next_id_ += copies.size();
    return copies;
}

bool Document::setInstancing(size_t type, const InstancingDesc& desc, std::string* error) {
    return execute(std::make_unique<SetInstancingCommand>(type, desc), error);
}

bool Document::setAngleOfRepose(size_t type, float deg, std::string* error) {
    return execute(std::make_unique<SetAngleOfReposeCommand>(type, deg), error);
}

bool Document::setSeed(uint64_t seed, std::string* error) {
    return execute(std::make_unique<SetSeedCommand>(seed), error);
}

bool Document::setEnvironment(const EnvironmentDesc& environment, const std::string& name, std::string* error) {
    if (!validateEnvironmentEdit(environment, path_.empty() ? project_.name : path_, error)) return false;
    return execute(std::make_unique<SetEnvironmentCommand>(environment, name), error);
}

bool Document::setParticleSystem(size_t index, const ParticleSystemFile& system, std::string* error) {
    if (index >= particles_->size() || index >= project_.particles.size()) {
        *error = "no particle system " + std::to_string(index) + " (the project has " +
                 std::to_string(particles_->size()) + ")";
        return false;
    }
    std::string why;
    if (!validateParticleScene(system.scene, &why) || !savableParticleSystem(system, &why)) {
        *error = "particles[" + std::to_string(index) + "] (" + (*particles_)[index].name + "): " + why;
        return false;
    }
    auto after = std::make_shared<const std::vector<ParticleSystemFile>>(
        withParticleSystem(project_, *particles_, index, system));
    return execute(std::make_unique<SetParticleSystemsCommand>(std::move(after)), error);
}

bool Document::addParticleSystem(const ParticleSystemFile& system, std::string* error) {
    if (project_.base_dir.empty() || path_.empty()) {
        *error = "save the project first: a particle system is a file beside it";
        return false;
    }
    ParticleSystemFile placed = system;
    const auto taken = [&](const std::string& name) {
        for (const ParticleSystemFile& s : *particles_)
            if (s.name == name) return true;
        return false;
    };
    for (int n = 2; taken(placed.name); ++n) placed.name = system.name + "_" + std::to_string(n);
    placed.file_name = placed.name;
    placed.scene.terrain = terrain_;
    std::string why;
    if (!placeSystem(*environment_, compiled_, true, &placed.scene, &why) || !validateParticleScene(placed.scene, &why) ||
        !savableParticleSystem(placed, &why)) {
        *error = "new particle system (" + placed.name + "): " + why;
        return false;
    }
    ParticleSystemRef ref;
    ref.file = newParticleFileName(project_, placed.name);
    const fs::path file = resolveProjectPath(project_, ref.file);
    std::error_code ec;
    fs::create_directories(file.parent_path(), ec);
    if (ec) {
        *error = file.parent_path().string() + ": " + ec.message();
        return false;
    }
    if (!writeTextFileAtomically(file.string(), particleSystemToJson(placed).dump(2) + "\n", error)) return false;
    return execute(std::make_unique<AddParticleSystemCommand>(std::move(ref), std::move(placed)), error);
}

bool Document::setParticleEntry(size_t index, const std::string& name, glm::vec3 offset_m, std::string* error) {
    if (index >= particles_->size() || index >= project_.particles.size()) {
        *error = "no particle system " + std::to_string(index);
        return false;
    }
    const ParticleSystemFile& system = (*particles_)[index];
    const std::string shown = name.empty() ? system.file_name : name;
    for (char c : shown)
        if (c == '/' || (unsigned char)(c) < 0x20) {
            *error = "particles[" + std::to_string(index) + "].name: '" + shown +
                     "' has a '/' or a control character (it names the glTF mesh strands/<name>)";
            return false;
        }
    for (size_t i = 0; i < particles_->size(); ++i)
        if (i != index && (*particles_)[i].name == shown) {
            *error = "particles[" + std::to_string(index) + "].name: another system is named '" + shown + "'";
            return false;
        }
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(offset_m[a]) || std::abs(offset_m[a]) > kMaxParticleCoordinate_m) {
            *error = "particles[" + std::to_string(index) + "].offset_m: not finite or beyond 1e5 m";
            return false;
        }
    ParticleSystemRef after = project_.particles[index];
    after.name = name;
    after.offset_m = offset_m;
    if (after == project_.particles[index]) return true;
    const bool renamed = after.name != project_.particles[index].name;
    // Moved past the limit by the offset, a part would be refused by the commit; say where first.
    ParticleScene moved = system.scene;
    translateParticleScene(&moved, offset_m - project_.particles[index].offset_m);
    std::string why;
    if (!validateParticleScene(moved, &why)) {
        *error = "particles[" + std::to_string(index) + "].offset_m: " + why;
        return false;
    }
    return execute(std::make_unique<SetParticleEntryCommand>(index, std::move(after),
                                                             renamed ? "Rename particle system" : "Move particle system"),
                   error);
}

bool Document::removeParticleSystem(size_t index, std::string* error) {
    return execute(std::make_unique<RemoveParticleSystemCommand>(index), error);
}

std::unique_ptr<GhostTileJob> Document::startGhostTileJob(GhostTileSpec spec, std::string* error) const {
    if (!validateGhostTileSpec(spec, project_, error)) return nullptr;
    GhostTileJobContext context;
    context.base_dir = project_.base_dir;
    context.cache_dir = options_.cache_dir;
    context.threads = options_.threads;
    for (const DetailTypeDesc& t : project_.detail_types) context.current_sources.push_back(t.model);
    context.current_models = assets_.models;
    context.current_files = assets_.model_files;
    return std::make_unique<GhostTileJob>(std::move(spec), std::move(context));
}

bool Document::applyGhostTile(GhostTileBuild build, std::string* error) {
    return execute(std::make_unique<SetGhostTileCommand>(std::move(build)), error);
}

void Document::beginStroke(const std::string& name) {
    if (stroke_) endStroke();
    stroke_ = std::make_unique<CompoundCommand>(name);
}

void Document::endStroke() {
    if (!stroke_) return;
    std::unique_ptr<CompoundCommand> stroke = std::move(stroke_);
    const uint64_t particles_generation = std::exchange(stroke_particles_generation_, 0);
    if (stroke->empty()) return;
    undo_.push_back(Step{std::move(stroke), next_state_++, particles_generation});
    if (undo_.size() > kMaxUndoSteps) undo_.erase(undo_.begin());
}

std::string Document::undoName() const {
    if (stroke_ && !stroke_->empty()) return stroke_->name();
    return undo_.empty() ? std::string() : undo_.back().command->name();
}

std::string Document::redoName() const { return redo_.empty() ? std::string() : redo_.back().command->name(); }

bool Document::undo() {
    endStroke();
    if (undo_.empty()) return false;
    Step step = std::move(undo_.back());
    undo_.pop_back();
    EditEffect effect;
    step.command->revert(target(), &effect);
    std::string error;
    // The state being restored compiled before, so this cannot fail.
    [[maybe_unused]] const bool ok = commit(effect, &error);
    ++edit_count_;
    redo_.push_back(std::move(step));
    return true;
}

bool Document::redo() {
    endStroke();
    if (redo_.empty()) return false;
    Step step = std::move(redo_.back());
    redo_.pop_back();
    EditEffect effect;
    std::string error;
    // It applied and compiled before from this very state, so it does again; should it not, the state is
    // put back and the step stays redoable.
    if (!step.command->apply(target(), &effect, &error)) {
        redo_.push_back(std::move(step));
        return false;
    }
    if (!commit(effect, &error)) {
        EditEffect undone;
        step.command->revert(target(), &undone);
        redo_.push_back(std::move(step));
        return false;
    }
    step.particles_generation = effect.particles ? particles_generation_ : 0;
    ++edit_count_;
    undo_.push_back(std::move(step));
    return true;
}

// ---- Document: files ---------------------------------------------------------------------------------------

bool Document::isDirty() const {
    return currentState() != saved_state_ || (stroke_ && !stroke_->empty());
}

bool Document::save(std::string* error) {
    if (path_.empty()) {
        *error = "the document has no file yet: use Save As";
        return false;
    }
    return saveAs(path_, error);
}

bool Document::saveAs(const std::string& path, std::string* error) {
    const fs::path old_dir = fs::absolute(project_.base_dir.empty() ? fs::path(".") : fs::path(project_.base_dir));
    const fs::path new_dir = fs::absolute(fs::path(path).has_parent_path() ? fs::path(path).parent_path() : ".");
    const bool moved = old_dir.lexically_normal() != new_dir.lexically_normal();
    Project saved = project_;
    if (moved) {
        for (DetailTypeDesc& t : saved.detail_types)
            t.model.mesh_path = rebasePath(t.model.mesh_path, old_dir.lexically_normal(), new_dir.lexically_normal());
        for (EnvTypeDesc& t : saved.environment.types)
            t.mesh_path = rebasePath(t.mesh_path, old_dir.lexically_normal(), new_dir.lexically_normal());
        if (saved.terrain.kind == TerrainKind::Image)
            saved.terrain.image_path =
                rebasePath(saved.terrain.image_path, old_dir.lexically_normal(), new_dir.lexically_normal());
        for (ParticleSystemRef& ref : saved.particles)
            ref.file = rebasePath(ref.file, old_dir.lexically_normal(), new_dir.lexically_normal());
    }
    // The edited particle files first: each write is atomic, and a project saved after them never names
    // a file that holds an older system than the one shown.
    for (const ParticleFileWrite& file : particleFilesToWrite(project_, *particles_, *saved_particles_))
        if (!writeTextFileAtomically(file.path, file.text, error)) {
            if (error->find(file.path) == std::string::npos) *error = file.path + ": " + *error;
            return false;
        }
    saved_particles_ = particles_;
    if (!saveProject(path, saved, error)) {
        if (error->find(path) == std::string::npos) *error = path + ": " + *error;
        return false;  // nothing in memory changed
    }
    // Only the paths and where it came from differ; the densities (and their ids) are the same objects'
    // copies, so keep ours and take the rewritten paths.
    if (moved) {
        for (size_t t = 0; t < project_.detail_types.size(); ++t)
            project_.detail_types[t].model.mesh_path = saved.detail_types[t].model.mesh_path;
        // The environment's meshes too: before, a second save after a Save As elsewhere wrote them
        // relative to the old folder.
        for (size_t t = 0; t < project_.environment.types.size(); ++t)
            project_.environment.types[t].mesh_path = saved.environment.types[t].mesh_path;
        project_.terrain.image_path = saved.terrain.image_path;
        project_.particles = saved.particles;
        project_.base_dir = fs::path(path).parent_path().string();
    }
    project_.source = path;
    const std::string old_path = path_;
    path_ = path;
    endStroke();
    saved_state_ = currentState();
    autosaved_edits_ = edit_count_;
    change_seen_s_ = -1.0;
    discardRecovery(options_.config_dir, old_path);
    if (old_path != path) discardRecovery(options_.config_dir, path);
    std::string ignored;
    addRecentFile(options_.config_dir, path, &ignored);
    return true;
}

bool Document::autosave(std::string* error) {
    if (options_.config_dir.empty()) {
        *error = "autosave: no config folder to write the recovery file to";
        return false;
    }
    const std::string data = recoveryPath(options_.config_dir, path_);
    std::error_code ec;
    fs::create_directories(fs::path(data).parent_path(), ec);
    if (ec) {
        *error = fs::path(data).parent_path().string() + ": cannot create the folder: " + ec.message();
        return false;
    }
    // Data first, then the meta that makes it visible to findRecovery: a crash between them leaves an
    // older meta pointing at newer data, which is still a good recovery.
    const json meta = {{"format", "undergrowth-recovery"},
                       {"path", path_.empty() ? std::string() : absolutePath(path_)},
                       {"saved_unix_s", unixNow()}};
    // The edited particle systems (none: no file, so an older one is not recovered later).
    const std::string particles = recoveryParticlesPath(options_.config_dir, path_);
    if (particleFilesToWrite(project_, *particles_, *saved_particles_).empty()) {
        fs::remove(particles, ec);
    } else {
        json systems = json::array();
        for (const ParticleSystemFile& s : *particles_) systems.push_back(particleSystemToJson(s));
        const json j = {{"format", "undergrowth-recovery-particles"}, {"systems", std::move(systems)}};
        if (!writeTextFileAtomically(particles, j.dump() + "\n", error)) return false;
    }
    if (!writeTextFileAtomically(data, projectToJson(project_), error) ||
        !writeTextFileAtomically(recoveryMetaPath(options_.config_dir, path_), meta.dump(2) + "\n", error))
        return false;
    autosaved_edits_ = edit_count_;
    change_seen_s_ = -1.0;
    return true;
}

bool Document::maybeAutosave(double now_s, std::string* error) {
    if (!isDirty() || autosaved_edits_ == edit_count_) {
        change_seen_s_ = -1.0;
        return false;
    }
    if (change_seen_s_ < 0.0) change_seen_s_ = now_s;
    if (now_s - change_seen_s_ < options_.autosave_interval_s) return false;
    return autosave(error);
}

void Document::close() {
    endStroke();
    if (live_) live_->waitIdle();
    discardRecovery(options_.config_dir, path_);
}

LiveResult Document::waitForResult() {
    live_->waitIdle();
    retired_.clear();
    return live_->latest();
}

}  // namespace ug
