// Editing the project's environmental objects (issue 13: the editor's Environment window, its weather
// brushes and the object handles). The description (env/env_desc.h) is replaced as a whole, one undo step
// (or one stamp of a stroke: a drag, a footprint trail); the Document compiles it again, reusing the loaded
// meshes, and reports where the effects change (envDirtyRegion). Descriptions are small (a tree of
// transforms and fields; meshes are not part of them), so a copy per step costs little.
#pragma once

#include <string>

#include "env/env_desc.h"
#include "env/env_tree_edits.h"
#include "scene/edit_commands.h"

namespace ug {

class SetEnvironmentCommand : public Command {
public:
    SetEnvironmentCommand(EnvironmentDesc after, std::string name) : after_(std::move(after)), name_(std::move(name)) {}
    std::string name() const override { return name_; }
    bool apply(EditTarget target, EditEffect* effect, std::string* error) override;
    void revert(EditTarget target, EditEffect* effect) override;

private:
    EnvironmentDesc after_, before_;
    std::string name_;
};

// Checks an edited description as the project reader checks a file (env/env_json.h: ranges, finite
// numbers, types that exist, the tree's depth and size), with the errors placed by JSON Pointer under
// `source` ("street.json: /environment/tree/3/scale: ..."). The editor's edits go through here.
bool validateEnvironmentEdit(const EnvironmentDesc& env, const std::string& source, std::string* error);

// A footprint (Fig. 3, step 6): an occlusion point field on the ground at `at` (world space) that keeps
// most of the snow off a foot-sized disc.
EnvFieldDesc footprintField(glm::vec3 at);

}  // namespace ug
