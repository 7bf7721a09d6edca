// Shader programs built from GLSL files under shaders/, read at run time.
#pragma once

#include <string>
#include <vector>

#include "gl/objects.h"

namespace warplab::gl {

struct ShaderStage {
    GLenum stage = GL_VERTEX_SHADER;  // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, ...
    std::string file;  // relative to the shader directory, e.g. "conventional.vert"
    // Files of shared functions (no #version line) compiled in before `file`, in order; GLSL
    // has no #include. Errors in them are reported with their own name and line.
    std::vector<std::string> includes = {};
};

struct ProgramDesc {
    std::string shaderDir;  // folder holding the .vert/.frag/... files
    std::vector<ShaderStage> stages;
    std::vector<std::string> defines;  // "NAME VALUE" lines injected after #version
};

// Compiles and links. Errors (missing file, compile or link failure) throw GlError with a
// message naming the file, and driver messages rewritten to "file:line" form.
Program buildProgram(const ProgramDesc& desc);

// Uniform location, or -1; a name the program lacks is not an error (drivers drop unused
// uniforms), so setters accept -1 silently as GL does.
GLint uniform(const Program& program, const char* name);

}  // namespace warplab::gl
