#include "env/env_tree_edits.h"

#include <algorithm>
#include <cmath>

namespace ug {

namespace {

constexpr float kDegToRad = 3.14159265358979f / 180.0f;

glm::vec3 rotateZ(glm::vec3 p, float deg) {
    const float c = std::cos(deg * kDegToRad), s = std::sin(deg * kDegToRad);
    return {c * p.x - s * p.y, s * p.x + c * p.y, p.z};
}

// parent ∘ child, as a transform of the child in the parent's parent's space.
EnvTransform composed(const EnvTransform& parent, const EnvTransform& child) {
    EnvTransform out;
    out.translation = parent.translation + rotateZ(parent.scale * child.translation, parent.yaw_deg);
    out.yaw_deg = parent.yaw_deg + child.yaw_deg;
    out.scale = parent.scale * child.scale;
    return out;
}

// The transform that, under `parent`, places a child where `world` places it.
EnvTransform relativeTo(const EnvTransform& parent, const EnvTransform& world) {
    EnvTransform out;
    out.translation = rotateZ(world.translation - parent.translation, -parent.yaw_deg) / parent.scale;
    // Kept in [-180, 180]: a handle turned round and round must not walk the saved yaw towards the
    // loader's bound (the same placement, and a file that stays readable).
    out.yaw_deg = std::remainder(world.yaw_deg - parent.yaw_deg, 360.0f);
    out.scale = world.scale / parent.scale;
    return out;
}

std::vector<EnvNode>* siblingsOf(EnvironmentDesc* env, const EnvPath& path) {
    if (path.empty()) return nullptr;
    if (path.size() == 1) return &env->roots;
    EnvNode* parent = envNodeAt(env, EnvPath(path.begin(), path.end() - 1));
    return parent ? &parent->children : nullptr;
}

// The transform from the node's space to the world: its ancestors' and its own, composed.
EnvTransform worldOf(const EnvironmentDesc& env, const EnvPath& path) {
    EnvTransform world;
    for (size_t k = 1; k <= path.size(); ++k)
        world = composed(world, envNodeAt(env, EnvPath(path.begin(), path.begin() + std::ptrdiff_t(k)))->transform);
    return world;
}

// How many objects the node expands to (references followed; the compiled tree has no cycles and at most
// kMaxEnvTreeDepth levels, which bounds the recursion).
size_t objectCount(const EnvironmentDesc& env, const EnvNode& node, int depth = 0) {
    if (depth > kMaxEnvTreeDepth) return 0;
    switch (node.kind) {
        case EnvNodeKind::Object: return 1;
        case EnvNodeKind::Reference:
            for (const NamedEnvGroup& g : env.groups)
                if (g.name == node.target) return objectCount(env, g.group, depth + 1);
            return 0;
        case EnvNodeKind::Group:
        case EnvNodeKind::Lod: break;
    }
    size_t n = 0;
    for (const EnvNode& c : node.children) n += objectCount(env, c, depth + 1);
    return n;
}

bool fail(std::string* error, const EnvPath& path, const std::string& why) {
    *error = envPathText(path) + ": " + why;
    return false;
}

}  // namespace

std::string envPathText(const EnvPath& path) {
    std::string s = "/tree";
    for (size_t k = 0; k < path.size(); ++k) s += (k == 0 ? "/" : "/children/") + std::to_string(path[k]);
    return s;
}

EnvNode* envNodeAt(EnvironmentDesc* env, const EnvPath& path) {
    if (path.empty() || path[0] >= env->roots.size()) return nullptr;
    EnvNode* node = &env->roots[path[0]];
    for (size_t i = 1; i < path.size(); ++i) {
        if (path[i] >= node->children.size()) return nullptr;
        node = &node->children[path[i]];
    }
    return node;
}

const EnvNode* envNodeAt(const EnvironmentDesc& env, const EnvPath& path) {
    return envNodeAt(const_cast<EnvironmentDesc*>(&env), path);
}

EnvTransform envWorldTransform(const EnvironmentDesc& env, const EnvPath& path) { return worldOf(env, path); }

bool setEnvWorldTransform(EnvironmentDesc* env, const EnvPath& path, const EnvTransform& world) {
    EnvNode* node = envNodeAt(env, path);
    if (!node) return false;
    node->transform = relativeTo(worldOf(*env, EnvPath(path.begin(), path.end() - 1)), world);
    return true;
}

bool envObjectRange(const EnvironmentDesc& env, const EnvPath& path, size_t* first, size_t* count) {
    if (!envNodeAt(env, path)) return false;
    size_t before = 0;
    const std::vector<EnvNode>* siblings = &env.roots;
    for (size_t k = 0; k < path.size(); ++k) {
        for (uint32_t i = 0; i < path[k]; ++i) before += objectCount(env, (*siblings)[i]);
        siblings = &(*siblings)[path[k]].children;
    }
    *first = before;
    *count = objectCount(env, *envNodeAt(env, path));
    return true;
}

EnvPath envPathOfObject(const EnvironmentDesc& env, size_t object) {
    EnvPath path;
    const std::vector<EnvNode>* siblings = &env.roots;
    for (;;) {
        size_t i = 0;
        for (; i < siblings->size(); ++i) {
            const size_t n = objectCount(env, (*siblings)[i]);
            if (object < n) break;
            object -= n;
        }
        if (i == siblings->size()) return {};
        path.push_back(uint32_t(i));
        const EnvNode& node = (*siblings)[i];
        if (node.kind != EnvNodeKind::Group && node.kind != EnvNodeKind::Lod) return path;
        siblings = &node.children;
    }
}

std::vector<uint8_t> envObjectMask(const EnvironmentDesc& env, const std::vector<EnvPath>& paths, size_t objects) {
    std::vector<uint8_t> mask;
    for (const EnvPath& path : paths) {
        size_t first = 0, count = 0;
        if (!envObjectRange(env, path, &first, &count) || count == 0) continue;
        mask.resize(objects, 0);
        for (size_t o = first; o < std::min(objects, first + count); ++o) mask[o] = 1;
    }
    return mask;
}

bool groupEnvNode(EnvironmentDesc* env, const EnvPath& path, std::string* error) {
    EnvNode* node = envNodeAt(env, path);
    if (!node) return fail(error, path, "no such node");
    EnvNode group;
    group.kind = EnvNodeKind::Group;
    group.transform = node->transform;
    node->transform = EnvTransform{};
    group.children.push_back(std::move(*node));
    *node = std::move(group);
    return true;
}

bool ungroupEnvNode(EnvironmentDesc* env, const EnvPath& path, std::string* error) {
    const EnvNode* node = envNodeAt(*env, path);
    if (!node) return fail(error, path, "no such node");
    if (node->kind != EnvNodeKind::Group) return fail(error, path, "only a group can be ungrouped");
    if (!node->fields.empty() || !node->overrides.empty())
        return fail(error, path, "the group has fields or effect overrides of its own, which ungrouping would lose");
    std::vector<EnvNode>* siblings = siblingsOf(env, path);
    EnvNode group = std::move((*siblings)[path.back()]);
    siblings->erase(siblings->begin() + std::ptrdiff_t(path.back()));
    for (EnvNode& child : group.children) child.transform = composed(group.transform, child.transform);
    siblings->insert(siblings->begin() + std::ptrdiff_t(path.back()), std::make_move_iterator(group.children.begin()),
                     std::make_move_iterator(group.children.end()));
    return true;
}

bool moveEnvNodeInto(EnvironmentDesc* env, const EnvPath& node, const EnvPath& group, EnvPath* moved,
                     std::string* error) {
    if (!envNodeAt(*env, node)) return fail(error, node, "no such node");
    const EnvNode* target = envNodeAt(*env, group);
    if (!target) return fail(error, group, "no such node");
    if (target->kind != EnvNodeKind::Group) return fail(error, group, "not a group");
    if (group.size() >= node.size() && std::equal(node.begin(), node.end(), group.begin()))
        return fail(error, node, "cannot move a node into itself or its own subtree");
    const EnvTransform world = worldOf(*env, node);
    const EnvTransform group_world = worldOf(*env, group);
    std::vector<EnvNode>* siblings = siblingsOf(env, node);
    EnvNode taken = std::move((*siblings)[node.back()]);
    siblings->erase(siblings->begin() + std::ptrdiff_t(node.back()));
    // Removing the node shifts the group's path when they share a parent and the node came first.
    EnvPath g = group;
    if (g.size() >= node.size() && std::equal(node.begin(), node.end() - 1, g.begin()) && g[node.size() - 1] > node.back())
        --g[node.size() - 1];
    EnvNode* into = envNodeAt(env, g);
    // Under the group it must land where its old ancestors put it.
    taken.transform = relativeTo(group_world, world);
    into->children.push_back(std::move(taken));
    g.push_back(uint32_t(into->children.size() - 1));
    if (moved) *moved = g;
    return true;
}

bool makeEnvGroupReusable(EnvironmentDesc* env, const EnvPath& path, const std::string& name, std::string* error) {
    const EnvNode* node = envNodeAt(*env, path);
    if (!node) return fail(error, path, "no such node");
    if (path.size() != 1 || node->kind != EnvNodeKind::Group)
        return fail(error, path, "only a group at the tree's top level can be made reusable");
    if (name.empty()) return fail(error, path, "a reusable group needs a name");
    for (const NamedEnvGroup& g : env->groups)
        if (g.name == name) return fail(error, path, "a group named \"" + name + "\" exists already");
    NamedEnvGroup named{name, std::move(env->roots[path[0]])};
    EnvNode reference;
    reference.kind = EnvNodeKind::Reference;
    reference.target = name;
    reference.transform = named.group.transform;
    named.group.transform = EnvTransform{};
    env->groups.push_back(std::move(named));
    env->roots[path[0]] = std::move(reference);
    return true;
}

bool addEnvReference(EnvironmentDesc* env, const std::string& name, const EnvTransform& at, std::string* error) {
    if (std::none_of(env->groups.begin(), env->groups.end(), [&](const NamedEnvGroup& g) { return g.name == name; })) {
        *error = "no reusable group named \"" + name + "\"";
        return false;
    }
    EnvNode reference;
    reference.kind = EnvNodeKind::Reference;
    reference.target = name;
    reference.transform = at;
    env->roots.push_back(std::move(reference));
    return true;
}

}  // namespace ug
