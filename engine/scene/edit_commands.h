// The editor's edits of a project, as undoable commands (issue 4, "Document"; docs/architecture.md "Editor").
//
// Editable density. A detail type's density stays the project's DensityField (the file format does not
// change); what the editor adds, moves and deletes are the primitive children of its root Blend, the
// "user primitives". Each gets a stable id (uint64, never 0) kept beside the field in an EditableDensity,
// never in the file, so a selection or an undo step still names the right primitive after other edits.
// Children of the root that are operator nodes (a polyline, an intersection) are "locked": they keep
// their place in the blend, with id 0, and are not edited here.
//
// Editable form (makeEditable): the root is a Blend, it is the last node, and its children are the last
// entries of DensityField::children. Then appending a child is a push_back, removing one erases from the
// tail range, and replacing one overwrites its primitive in place; a removed primitive stays in the array
// unreferenced (an "orphan") until compaction rebuilds the field, so a long session never grows the field
// without bound. A field whose root is not a Blend (an intersection at the root) is wrapped on the first
// edit: root = Blend(old tree), the old tree being one locked child.
//
// Exactness: a field's values depend only on the tree (operators and children in order), not on where its
// primitives sit in the arrays (density_field.h). Every operation here keeps the root's child order, and
// an undo puts a primitive back at the position it came from, so undo gives back the same values bit for
// bit, hence the same instances (docs/architecture.md "undo is cheap and exact").
//
// Commands mutate an EditTarget and report an EditEffect: which types' settings changed (to recompile),
// where their fields changed (dirty bounds: old ∪ new support of what changed; infinite for terrain
// kinds, the instantiator clips to the extent), and whether everything must be instantiated again (a
// strategy or seed change). The Document (document.h) owns the target, the undo stack and the recompile.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "field/bounds.h"
#include "field/density_field.h"
#include "field/primitive.h"
#include "scene/project.h"

namespace ug {

// Compaction reclaims orphans once there are more than this many and more than live primitives.
constexpr uint32_t kMinOrphansBeforeCompaction = 32;

struct EditableDensity {
    std::vector<uint64_t> ids;  // one per child of the root Blend, in order; 0 = a locked child
    uint32_t orphans = 0;       // primitives in the field no longer referenced (removed ones)
};

// The field rebuilt from its root by a post-order walk, dropping unreachable nodes and primitives: the
// same arrays the project reader gives for the saved field. Values are unchanged, bit for bit.
DensityField compactDensity(const DensityField& field);

// The ids for a field as loaded: a fresh id (from *next_id, incremented) for every primitive child of a
// Blend root, 0 for node children; none when the root is not a Blend (it is wrapped on the first edit).
EditableDensity editableDensityFor(const DensityField& field, uint64_t* next_id);

// Puts the field in editable form (see above); ids stay parallel to the root's children. Compacts when the
// root is not at the tail (only happens for hand-built fields), wraps a non-Blend root, and makes an
// empty field (root == kNoNode) an empty Blend.
void makeEditable(DensityField* field, EditableDensity* ed);

// The root child position of a user primitive, or -1.
int64_t findUserPrimitive(const EditableDensity& ed, uint64_t id);
// The primitive at a root child position that holds a user primitive (ids[position] != 0).
const Primitive& userPrimitive(const DensityField& field, size_t position);

// Editable form is required (makeEditable) for these; they keep it.
void insertUserPrimitive(DensityField* field, EditableDensity* ed, size_t position, const Primitive& prim,
                         uint64_t id);
void replaceUserPrimitive(DensityField* field, const EditableDensity& ed, size_t position, const Primitive& prim);
// Removes the child (it must be a user primitive); compacts when the orphans pass the threshold.
void eraseUserPrimitive(DensityField* field, EditableDensity* ed, size_t position);

// Where a primitive's value may be non-zero: primitiveBounds, or everything for the terrain kinds (their
// height field is not attached to the document's field; the instantiator clips to the extent).
Bounds editBounds(const Primitive& prim);

// ---- commands ------------------------------------------------------------------------------------------

struct TileAssets;  // ghost_tile_command.h

struct ParticleSystemFile;  // particles/particle_json.h
using ParticleSystems = std::shared_ptr<const std::vector<ParticleSystemFile>>;

struct EditTarget {
    Project* project = nullptr;
    std::vector<EditableDensity>* densities = nullptr;  // one per detail type
    TileAssets* assets = nullptr;                       // the Ghost Tile and models (ghost_tile_command.h)
    ParticleSystems* particles = nullptr;               // the project's systems, placed (particle_commands.h)
};

struct EditEffect {
    std::vector<size_t> types;  // detail types whose settings changed (ascending, unique)
    std::vector<Bounds> dirty;  // where their fields changed
    bool full = false;          // instantiate everything again (strategy, constraints, seed)
    bool tile = false;          // the Ghost Tile and models were swapped (implies full)
    bool particles = false;     // the particle systems changed (their strands grow again)
    bool environment = false;   // the environmental objects changed (compiled again, effects follow)

    void addType(size_t type);
    void merge(const EditEffect& other);
};

class Command {
public:
    virtual ~Command() = default;
    virtual std::string name() const = 0;  // for the Edit menu: "Add primitive", "Stroke", ...
    // Applies (first time and redo). False with *error when it cannot apply (an unknown id, a bad value);
    // then nothing changed.
    virtual bool apply(EditTarget target, EditEffect* effect, std::string* error) = 0;
    // Reverts a successful apply(); the target is as apply() left it (the undo stack guarantees it).
    virtual void revert(EditTarget target, EditEffect* effect) = 0;
};

// Adds `prim` at the end of `type`'s root blend with the id `id` (chosen by the caller so redo gives the
// same id back). Used for duplicates too.
class AddPrimitiveCommand : public Command {
public:
    AddPrimitiveCommand(size_t type, const Primitive& prim, uint64_t id) : type_(type), prim_(prim), id_(id) {}
    std::string name() const override { return "Add primitive"; }
    bool apply(EditTarget target, EditEffect* effect, std::string* error) override;
    void revert(EditTarget target, EditEffect* effect) override;

private:
    size_t type_;
    Primitive prim_;
    uint64_t id_;
};

// Replaces the primitive `id` (move, radius, weight, any member).
class SetPrimitiveCommand : public Command {
public:
    SetPrimitiveCommand(uint64_t id, const Primitive& prim) : id_(id), new_(prim) {}
    std::string name() const override { return "Edit primitive"; }
    bool apply(EditTarget target, EditEffect* effect, std::string* error) override;
    void revert(EditTarget target, EditEffect* effect) override;

private:
    uint64_t id_;
    Primitive new_;
    Primitive old_;
    size_t type_ = 0;
};

class RemovePrimitiveCommand : public Command {
public:
    explicit RemovePrimitiveCommand(uint64_t id) : id_(id) {}
    std::string name() const override { return "Delete primitive"; }
    bool apply(EditTarget target, EditEffect* effect, std::string* error) override;
    void revert(EditTarget target, EditEffect* effect) override;

private:
    uint64_t id_;
    Primitive old_;
    size_t type_ = 0;
    size_t position_ = 0;
};

// A type's instancing settings (strategy, layer, orientation and size constraints): instantiates all again.
// The slope a sculpted pile of `type` keeps (DetailTypeDesc::angle_of_repose_deg): only the sculpt brush
// reads it, so nothing is instantiated again.
class SetAngleOfReposeCommand : public Command {
public:
    SetAngleOfReposeCommand(size_t type, float deg) : type_(type), new_(deg) {}
    std::string name() const override { return "Angle of repose"; }
    bool apply(EditTarget target, EditEffect* effect, std::string* error) override;
    void revert(EditTarget target, EditEffect* effect) override;

private:
    size_t type_;
    float new_, old_ = 0.0f;
};

class SetInstancingCommand : public Command {
public:
    SetInstancingCommand(size_t type, InstancingDesc desc) : type_(type), new_(std::move(desc)) {}
    std::string name() const override { return "Instancing settings"; }
    bool apply(EditTarget target, EditEffect* effect, std::string* error) override;
    void revert(EditTarget target, EditEffect* effect) override;

private:
    size_t type_;
    InstancingDesc new_;
    InstancingDesc old_;
};

// The project's instantiation seed: instantiates all again.
class SetSeedCommand : public Command {
public:
    explicit SetSeedCommand(uint64_t seed) : new_(seed) {}
    std::string name() const override { return "Instantiation seed"; }
    bool apply(EditTarget target, EditEffect* effect, std::string* error) override;
    void revert(EditTarget target, EditEffect* effect) override;

private:
    uint64_t new_;
    uint64_t old_ = 0;
};

// Several commands as one undo step (a brush stroke's stamps). apply() runs them in order, revert() in
// reverse. An open stroke pushes commands the Document has already applied (each stamp as it comes, so the
// user sees it fill); a batch (Document::setPrimitives) pushes unapplied ones and applies the whole.
class CompoundCommand : public Command {
public:
    explicit CompoundCommand(std::string name) : name_(std::move(name)) {}
    std::string name() const override { return name_; }
    bool apply(EditTarget target, EditEffect* effect, std::string* error) override;
    void revert(EditTarget target, EditEffect* effect) override;
    void push(std::unique_ptr<Command> applied) { commands_.push_back(std::move(applied)); }
    size_t size() const { return commands_.size(); }
    bool empty() const { return commands_.empty(); }

private:
    std::string name_;
    std::vector<std::unique_ptr<Command>> commands_;
};

}  // namespace ug
