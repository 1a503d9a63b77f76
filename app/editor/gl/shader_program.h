// GLSL programs loaded at run time from shaders/ (found like the assets: $UG_SHADERS, next to the binary,
// or the source tree), so a shader can be edited without a rebuild. Every shader gets shaders/lighting.glsl
// (the sky, sun and fog model all surfaces share) inserted after its #version line, so a vertex shader can
// light per vertex where per-pixel light costs too much (the impostors).
#pragma once

#include <string>
#include <vector>

namespace ug::editor::gl {

// $UG_SHADERS, else <exe>/../shaders or <exe>/../../shaders, else the source tree's shaders/.
std::string shadersDir();

struct ShaderProgram {
    unsigned id = 0;
    std::string name;  // "instanced_detail.vert + lit_surface.frag", for messages
};

// Compiles and links `vert` and `frag` (file names under `dir`), then checks the program's interface:
// each name in `uniforms` must be an active uniform (a renamed or optimised-away uniform is a bug that
// would otherwise draw silently wrong). Errors carry the file and the driver's log. `defines` (e.g.
// "SHADOW_CASTER") are #defined in both stages: one source serves two passes that must agree.
bool loadProgram(const std::string& dir, const std::string& vert, const std::string& frag,
                 const std::vector<const char*>& uniforms, ShaderProgram* out, std::string* error,
                 const std::vector<const char*>& defines = {});
void destroyProgram(ShaderProgram* program);

}  // namespace ug::editor::gl
