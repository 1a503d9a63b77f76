// Structural edits of the environmental-object tree (issue 13: group, ungroup, regroup, instance a group),
// on the description (env_desc.h), GL-free. Nodes are named by their path of child indices from the roots
// ({2}: the third root; {2, 0}: its first child). Every edit keeps each object where it is in the world
// (up to float rounding: transforms are composed or inverted), except instancing, which adds one.
// Errors name the path and the reason; on failure the description is unchanged.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "env/env_desc.h"

namespace ug {

using EnvPath = std::vector<uint32_t>;

std::string envPathText(const EnvPath& path);  // "/tree/2/children/0"
EnvNode* envNodeAt(EnvironmentDesc* env, const EnvPath& path);  // null when the path leads nowhere
const EnvNode* envNodeAt(const EnvironmentDesc& env, const EnvPath& path);

// The transform from the node's space to the world (its ancestors' and its own, composed).
EnvTransform envWorldTransform(const EnvironmentDesc& env, const EnvPath& path);
// Sets the node's transform (in its parent's space) so that its world transform is `world`: how the view's
// handles move, turn and scale a nested node. False (nothing changed) when the path leads nowhere.
bool setEnvWorldTransform(EnvironmentDesc* env, const EnvPath& path, const EnvTransform& world);

// The compiled scene's objects (EnvScene::objects, in tree order, references expanded) that the node
// expands to: [*first, *first + *count). False when the path leads nowhere.
bool envObjectRange(const EnvironmentDesc& env, const EnvPath& path, size_t* first, size_t* count);
// The deepest tree node that object `object` belongs to: the object's own node, or the reference it was
// expanded from (a reusable group's insides are not tree nodes). Empty when there is no such object.
EnvPath envPathOfObject(const EnvironmentDesc& env, size_t object);

// A mask over the compiled scene's `objects` objects: 1 for those the nodes at `paths` expand to. Empty
// when none is marked (paths that lead nowhere are skipped).
std::vector<uint8_t> envObjectMask(const EnvironmentDesc& env, const std::vector<EnvPath>& paths, size_t objects);

// The node becomes the only child of a new group standing where it stood (the group takes its transform,
// the node the identity). The group is at the same path.
bool groupEnvNode(EnvironmentDesc* env, const EnvPath& path, std::string* error);
// A group is replaced by its children, in order, each placed in its parent's space. Refused for a group
// with fields or effect overrides of its own (they would be lost) and for other kinds.
bool ungroupEnvNode(EnvironmentDesc* env, const EnvPath& path, std::string* error);
// The node moves into `group` (a Group node; not the node itself nor inside it), last among its children,
// placed so that it stays where it was. *moved: its new path.
bool moveEnvNodeInto(EnvironmentDesc* env, const EnvPath& node, const EnvPath& group, EnvPath* moved,
                     std::string* error);
// A top-level group becomes the named group `name` (EnvironmentDesc::groups, §3.2) and, in its place, a
// reference to it with its transform; then `addEnvReference` places it again anywhere.
bool makeEnvGroupReusable(EnvironmentDesc* env, const EnvPath& path, const std::string& name, std::string* error);
bool addEnvReference(EnvironmentDesc* env, const std::string& name, const EnvTransform& at, std::string* error);

}  // namespace ug
