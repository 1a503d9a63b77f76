#include "editor/gl/shader_program.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <epoxy/gl.h>

namespace ug::editor::gl {

namespace fs = std::filesystem;

std::string shadersDir() {
    if (const char* env = std::getenv("UG_SHADERS"); env && *env) return env;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec)
        for (const fs::path& candidate : {exe.parent_path() / ".." / "shaders", exe.parent_path() / ".." / ".." / "shaders"})
            if (fs::exists(candidate / "lighting.glsl", ec)) return candidate.lexically_normal().string();
    return std::string(UG_SOURCE_DIR) + "/shaders";
}

namespace {

bool readText(const fs::path& path, std::string* out, std::string* error) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        *error = path.string() + ": cannot read the shader";
        return false;
    }
    std::stringstream ss;
    ss << in.rdbuf();
    *out = ss.str();
    return true;
}

// Inserts `defines` and `prelude` after the first line (the #version directive, which must come first in
// GLSL); #line keeps the driver's messages on the files' own lines.
std::string withPrelude(const std::string& source, const std::string& defines, const std::string& prelude) {
    const size_t eol = source.find('\n');
    if (eol == std::string::npos) return source + "\n" + defines + prelude;
    return source.substr(0, eol + 1) + defines + "#line 1 1\n" + prelude + "\n#line 2 0\n" + source.substr(eol + 1);
}

GLuint compile(GLenum kind, const std::string& source, const std::string& file, std::string* error) {
    GLuint shader = glCreateShader(kind);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::string log(size_t(std::max(length, 1)), '\0');
        glGetShaderInfoLog(shader, length, nullptr, log.data());
        *error = file + ": does not compile:\n" + log;
        glDeleteShader(shader);
        return 0;
    }
    return shader;
}

}  // namespace

bool loadProgram(const std::string& dir, const std::string& vert, const std::string& frag,
                 const std::vector<const char*>& uniforms, ShaderProgram* out, std::string* error,
                 const std::vector<const char*>& defines) {
    std::string vs, fs_text, lighting;
    if (!readText(fs::path(dir) / vert, &vs, error) || !readText(fs::path(dir) / frag, &fs_text, error) ||
        !readText(fs::path(dir) / "lighting.glsl", &lighting, error))
        return false;
    std::string name = vert + " + " + frag, define_lines;
    for (const char* d : defines) {
        define_lines += "#define " + std::string(d) + " 1\n";
        name += std::string(" (") + d + ")";
    }
    GLuint v = compile(GL_VERTEX_SHADER, withPrelude(vs, define_lines, lighting), (fs::path(dir) / vert).string(), error);
    if (!v) return false;
    GLuint f = compile(GL_FRAGMENT_SHADER, withPrelude(fs_text, define_lines, lighting), (fs::path(dir) / frag).string(), error);
    if (!f) {
        glDeleteShader(v);
        return false;
    }
    GLuint program = glCreateProgram();
    glAttachShader(program, v);
    glAttachShader(program, f);
    glLinkProgram(program);
    glDeleteShader(v);
    glDeleteShader(f);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
        std::string log(size_t(std::max(length, 1)), '\0');
        glGetProgramInfoLog(program, length, nullptr, log.data());
        *error = name + ": does not link:\n" + log;
        glDeleteProgram(program);
        return false;
    }
    for (const char* u : uniforms)
        if (glGetUniformLocation(program, u) < 0) {
            *error = name + ": expected uniform '" + u + "' is missing (renamed, or unused and optimised away)";
            glDeleteProgram(program);
            return false;
        }
    out->id = program;
    out->name = name;
    return true;
}

void destroyProgram(ShaderProgram* program) {
    if (program->id) glDeleteProgram(program->id);
    program->id = 0;
}

}  // namespace ug::editor::gl
