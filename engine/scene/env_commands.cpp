#include "scene/env_commands.h"

#include "env/env_json.h"
#include "field/primitive.h"

namespace ug {

// The type library stays the project's: a Save As to another folder rewrites its mesh paths, and an undo
// step made before it must not bring back paths relative to the old folder.
bool SetEnvironmentCommand::apply(EditTarget t, EditEffect* effect, std::string* error) {
    if (after_.types.size() != t.project->environment.types.size()) {
        *error = "environment edit: the type library changed under the edit (" + std::to_string(after_.types.size()) +
                 " types, the project has " + std::to_string(t.project->environment.types.size()) + ")";
        return false;
    }
    before_ = t.project->environment;
    std::vector<EnvTypeDesc> types = std::move(t.project->environment.types);
    t.project->environment = after_;
    t.project->environment.types = std::move(types);
    effect->environment = true;
    return true;
}

void SetEnvironmentCommand::revert(EditTarget t, EditEffect* effect) {
    std::vector<EnvTypeDesc> types = std::move(t.project->environment.types);
    t.project->environment = before_;
    t.project->environment.types = std::move(types);
    effect->environment = true;
}

namespace {

// A type index out of the library cannot even be written (the file names types); the rest the reader
// checks. Depth is bounded before recursing (a generator gone wrong).
bool typesExist(const EnvNode& node, size_t types, const std::string& pointer, int depth, std::string* error) {
    if (depth > kMaxEnvTreeDepth) {
        *error = pointer + ": the tree is deeper than " + std::to_string(kMaxEnvTreeDepth) + " levels";
        return false;
    }
    if (node.kind == EnvNodeKind::Object && node.type >= types) {
        *error = pointer + ": no environmental-object type " + std::to_string(node.type) + " (the library has " +
                 std::to_string(types) + ")";
        return false;
    }
    for (size_t c = 0; c < node.children.size(); ++c)
        if (!typesExist(node.children[c], types, pointer + "/children/" + std::to_string(c), depth + 1, error))
            return false;
    return true;
}

}  // namespace

bool validateEnvironmentEdit(const EnvironmentDesc& env, const std::string& source, std::string* error) {
    for (size_t i = 0; i < env.roots.size(); ++i)
        if (!typesExist(env.roots[i], env.types.size(), "/environment/tree/" + std::to_string(i), 0, error)) {
            *error = source + ": " + *error;
            return false;
        }
    for (size_t g = 0; g < env.groups.size(); ++g)
        if (!typesExist(env.groups[g].group, env.types.size(), "/environment/groups/" + std::to_string(g), 0, error)) {
            *error = source + ": " + *error;
            return false;
        }
    const nlohmann::json j = environmentToJson(env);
    JsonReader reader(source, error);
    EnvironmentDesc read;
    return readEnvironment(reader, j, "/environment", &read);
}

EnvFieldDesc footprintField(glm::vec3 at) {
    // The street sample's footprints: a boot-sized support, most but not all of the snow pressed away.
    constexpr float kFootprintRadiusM = 0.13f, kFootprintOcclusion = 0.85f;
    EnvFieldDesc f;
    f.channel = EnvChannel::Occlusion;
    f.value = kFootprintOcclusion;
    f.shape = makePoint(at, kFootprintRadiusM, kFootprintOcclusion);
    return f;
}

}  // namespace ug
