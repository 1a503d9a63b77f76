#include "scene/edit_commands.h"

#include <algorithm>
#include <cassert>

namespace ug {

namespace {

// Post-order, children before parents: the order the project reader appends them (field_json.cpp), so a
// compacted field has the arrays a save and reload would give.
uint32_t copySubtree(const DensityField& src, uint32_t ref, DensityField* dst) {
    if (isPrimitiveChild(ref)) return primitiveChild(addPrimitive(dst, src.primitives[childIndex(ref)]));
    const FieldNode& n = src.nodes[ref];
    std::vector<uint32_t> kids;
    kids.reserve(n.child_count);
    for (uint32_t c = 0; c < n.child_count; ++c) kids.push_back(copySubtree(src, src.children[n.first_child + c], dst));
    return nodeChild(addNode(dst, n.op, kids));
}

bool rootIsTailBlend(const DensityField& f) {
    if (f.root == kNoNode || f.root + 1 != f.nodes.size()) return false;
    const FieldNode& r = f.nodes[f.root];
    return r.op == FieldOp::Blend && size_t(r.first_child) + r.child_count == f.children.size();
}

size_t heightFieldCount(const Project& p) { return p.terrain.kind == TerrainKind::None ? 0 : 1; }

bool checkType(const EditTarget& t, size_t type, std::string* error) {
    if (type < t.project->detail_types.size()) return true;
    *error = "no detail type " + std::to_string(type) + " (the project has " +
             std::to_string(t.project->detail_types.size()) + ")";
    return false;
}

bool checkPrimitive(const EditTarget& t, size_t type, const Primitive& prim, std::string* error) {
    std::string reason;
    if (validatePrimitive(prim, 0, heightFieldCount(*t.project), &reason)) return true;
    *error = "detail type '" + t.project->detail_types[type].model.name + "': " + reason;
    return false;
}

bool locate(const EditTarget& t, uint64_t id, size_t* type, size_t* position, std::string* error) {
    if (id != 0)
        for (size_t i = 0; i < t.densities->size(); ++i) {
            const int64_t k = findUserPrimitive((*t.densities)[i], id);
            if (k >= 0) {
                *type = i;
                *position = size_t(k);
                return true;
            }
        }
    if (error) *error = "no primitive with id " + std::to_string(id);
    return false;
}

}  // namespace

DensityField compactDensity(const DensityField& field) {
    DensityField out;
    out.height_fields = field.height_fields;
    if (field.root == kNoNode) return out;
    out.root = copySubtree(field, nodeChild(field.root), &out);
    return out;
}

EditableDensity editableDensityFor(const DensityField& field, uint64_t* next_id) {
    EditableDensity ed;
    if (field.root == kNoNode || field.nodes[field.root].op != FieldOp::Blend) return ed;
    // A primitive referenced from elsewhere too (only possible in hand-built fields) must not be edited in
    // place: it stays locked.
    std::vector<uint32_t> uses(field.primitives.size(), 0);
    for (uint32_t n = 0; n <= field.root; ++n) {
        const FieldNode& node = field.nodes[n];
        for (uint32_t c = 0; c < node.child_count; ++c) {
            const uint32_t ref = field.children[node.first_child + c];
            if (isPrimitiveChild(ref)) ++uses[childIndex(ref)];
        }
    }
    const FieldNode& r = field.nodes[field.root];
    for (uint32_t c = 0; c < r.child_count; ++c) {
        const uint32_t ref = field.children[r.first_child + c];
        ed.ids.push_back(isPrimitiveChild(ref) && uses[childIndex(ref)] == 1 ? (*next_id)++ : 0);
    }
    return ed;
}

void makeEditable(DensityField* field, EditableDensity* ed) {
    if (rootIsTailBlend(*field)) return;
    if (field->root == kNoNode) {
        *field = compactDensity(*field);
        field->root = addNode(field, FieldOp::Blend, {});
        ed->ids.clear();
    } else if (field->nodes[field->root].op != FieldOp::Blend) {
        // Wrap: the old tree becomes one locked child. Its values only gain a +0 (Blend sums from +0),
        // which changes no sign and no positive value.
        assert(ed->ids.empty());
        *field = compactDensity(*field);
        const uint32_t old_root = nodeChild(field->root);
        field->root = addNode(field, FieldOp::Blend, std::span<const uint32_t>(&old_root, 1));
        ed->ids.assign(1, 0);
    } else {
        *field = compactDensity(*field);  // the root's child order, hence ids, is kept
    }
    ed->orphans = 0;
    assert(rootIsTailBlend(*field));
}

int64_t findUserPrimitive(const EditableDensity& ed, uint64_t id) {
    if (id == 0) return -1;
    for (size_t k = 0; k < ed.ids.size(); ++k)
        if (ed.ids[k] == id) return int64_t(k);
    return -1;
}

const Primitive& userPrimitive(const DensityField& field, size_t position) {
    const FieldNode& r = field.nodes[field.root];
    assert(position < r.child_count);
    const uint32_t ref = field.children[r.first_child + position];
    assert(isPrimitiveChild(ref));
    return field.primitives[childIndex(ref)];
}

void insertUserPrimitive(DensityField* field, EditableDensity* ed, size_t position, const Primitive& prim,
                         uint64_t id) {
    assert(rootIsTailBlend(*field) && position <= ed->ids.size());
    const uint32_t ref = primitiveChild(addPrimitive(field, prim));
    FieldNode& r = field->nodes[field->root];
    field->children.insert(field->children.begin() + r.first_child + position, ref);
    ++r.child_count;
    ed->ids.insert(ed->ids.begin() + int64_t(position), id);
}

void replaceUserPrimitive(DensityField* field, const EditableDensity& ed, size_t position, const Primitive& prim) {
    assert(position < ed.ids.size() && ed.ids[position] != 0);
    (void)ed;
    const FieldNode& r = field->nodes[field->root];
    field->primitives[childIndex(field->children[r.first_child + position])] = prim;
}

void eraseUserPrimitive(DensityField* field, EditableDensity* ed, size_t position) {
    assert(rootIsTailBlend(*field) && position < ed->ids.size() && ed->ids[position] != 0);
    FieldNode& r = field->nodes[field->root];
    field->children.erase(field->children.begin() + r.first_child + position);
    --r.child_count;
    ed->ids.erase(ed->ids.begin() + int64_t(position));
    ++ed->orphans;
    // Reclaim when the garbage outweighs what is alive: amortized O(1) per removal, and the field never
    // holds more than about twice what it needs.
    const size_t live = field->primitives.size() - ed->orphans;
    if (ed->orphans > kMinOrphansBeforeCompaction && ed->orphans > live) {
        *field = compactDensity(*field);
        ed->orphans = 0;
    }
}

Bounds editBounds(const Primitive& prim) {
    if (prim.kind == PrimitiveKind::TerrainLayer || prim.kind == PrimitiveKind::TerrainSolid)
        return Bounds::everything();
    return primitiveBounds(prim, nullptr);
}

// ---- EditEffect -----------------------------------------------------------------------------------------

void EditEffect::addType(size_t type) {
    auto it = std::lower_bound(types.begin(), types.end(), type);
    if (it == types.end() || *it != type) types.insert(it, type);
}

void EditEffect::merge(const EditEffect& other) {
    for (size_t t : other.types) addType(t);
    dirty.insert(dirty.end(), other.dirty.begin(), other.dirty.end());
    full = full || other.full;
    tile = tile || other.tile;
    particles = particles || other.particles;
    environment = environment || other.environment;
}

// ---- commands -------------------------------------------------------------------------------------------

bool AddPrimitiveCommand::apply(EditTarget t, EditEffect* effect, std::string* error) {
    if (!checkType(t, type_, error) || !checkPrimitive(t, type_, prim_, error)) return false;
    DensityField& field = t.project->detail_types[type_].density;
    EditableDensity& ed = (*t.densities)[type_];
    makeEditable(&field, &ed);
    insertUserPrimitive(&field, &ed, ed.ids.size(), prim_, id_);
    effect->addType(type_);
    effect->dirty.push_back(editBounds(prim_));
    return true;
}

void AddPrimitiveCommand::revert(EditTarget t, EditEffect* effect) {
    EditableDensity& ed = (*t.densities)[type_];
    const int64_t k = findUserPrimitive(ed, id_);
    assert(k >= 0);
    eraseUserPrimitive(&t.project->detail_types[type_].density, &ed, size_t(k));
    effect->addType(type_);
    effect->dirty.push_back(editBounds(prim_));
}

bool SetPrimitiveCommand::apply(EditTarget t, EditEffect* effect, std::string* error) {
    size_t position = 0;
    if (!locate(t, id_, &type_, &position, error) || !checkPrimitive(t, type_, new_, error)) return false;
    DensityField& field = t.project->detail_types[type_].density;
    EditableDensity& ed = (*t.densities)[type_];
    old_ = userPrimitive(field, position);
    replaceUserPrimitive(&field, ed, position, new_);
    effect->addType(type_);
    effect->dirty.push_back(editBounds(old_));
    effect->dirty.push_back(editBounds(new_));
    return true;
}

void SetPrimitiveCommand::revert(EditTarget t, EditEffect* effect) {
    size_t type = 0, position = 0;
    [[maybe_unused]] const bool found = locate(t, id_, &type, &position, nullptr);
    assert(found && type == type_);
    replaceUserPrimitive(&t.project->detail_types[type].density, (*t.densities)[type], position, old_);
    effect->addType(type);
    effect->dirty.push_back(editBounds(old_));
    effect->dirty.push_back(editBounds(new_));
}

bool RemovePrimitiveCommand::apply(EditTarget t, EditEffect* effect, std::string* error) {
    if (!locate(t, id_, &type_, &position_, error)) return false;
    DensityField& field = t.project->detail_types[type_].density;
    old_ = userPrimitive(field, position_);
    eraseUserPrimitive(&field, &(*t.densities)[type_], position_);
    effect->addType(type_);
    effect->dirty.push_back(editBounds(old_));
    return true;
}

void RemovePrimitiveCommand::revert(EditTarget t, EditEffect* effect) {
    // Back at the same place in the blend: the sum is taken in the same order, so the values are the
    // same bits as before the removal.
    insertUserPrimitive(&t.project->detail_types[type_].density, &(*t.densities)[type_], position_, old_, id_);
    effect->addType(type_);
    effect->dirty.push_back(editBounds(old_));
}

bool SetAngleOfReposeCommand::apply(EditTarget t, EditEffect*, std::string* error) {
    if (!checkType(t, type_, error)) return false;
    if (!(new_ > 0.0f && new_ <= 89.0f)) {
        *error = "angle_of_repose_deg: " + std::to_string(new_) + " is out of range (0, 89]";
        return false;
    }
    old_ = t.project->detail_types[type_].angle_of_repose_deg;
    t.project->detail_types[type_].angle_of_repose_deg = new_;
    return true;
}

void SetAngleOfReposeCommand::revert(EditTarget t, EditEffect*) { t.project->detail_types[type_].angle_of_repose_deg = old_; }

bool SetInstancingCommand::apply(EditTarget t, EditEffect* effect, std::string* error) {
    if (!checkType(t, type_, error)) return false;
    InstancingDesc& desc = t.project->detail_types[type_].instancing;
    old_ = desc;
    desc = new_;
    effect->addType(type_);
    effect->full = true;
    return true;
}

void SetInstancingCommand::revert(EditTarget t, EditEffect* effect) {
    t.project->detail_types[type_].instancing = old_;
    effect->addType(type_);
    effect->full = true;
}

bool SetSeedCommand::apply(EditTarget t, EditEffect* effect, std::string*) {
    old_ = t.project->instantiation_seed;
    t.project->instantiation_seed = new_;
    effect->full = true;
    return true;
}

void SetSeedCommand::revert(EditTarget t, EditEffect* effect) {
    t.project->instantiation_seed = old_;
    effect->full = true;
}

bool CompoundCommand::apply(EditTarget t, EditEffect* effect, std::string* error) {
    EditEffect mine;
    for (size_t k = 0; k < commands_.size(); ++k) {
        if (commands_[k]->apply(t, &mine, error)) continue;
        EditEffect undone;
        for (size_t u = k; u-- > 0;) commands_[u]->revert(t, &undone);
        return false;
    }
    effect->merge(mine);
    return true;
}

void CompoundCommand::revert(EditTarget t, EditEffect* effect) {
    for (size_t k = commands_.size(); k-- > 0;) commands_[k]->revert(t, effect);
}

}  // namespace ug
