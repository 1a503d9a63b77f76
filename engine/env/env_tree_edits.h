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
