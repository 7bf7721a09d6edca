#include "gl/program.h"

#include <fstream>
#include <regex>
#include <sstream>

#include "gl/check.h"

namespace warplab::gl {
namespace {

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw GlError("cannot read shader file '" + path + "'");
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Keeps the file's own #version line first, injects the defines and the include files (each
// as GLSL source-string number k, counted from 1), then a #line so that the driver's line
// numbers are the file's line numbers again (source string 0).
std::string assemble(const std::string& source, const std::vector<std::string>& defines,
                     const std::vector<std::string>& includeSources, const std::string& path) {
    const auto versionPos = source.find("#version");
    if (versionPos == std::string::npos) throw GlError("shader file '" + path + "' has no #version line");
    const auto lineEnd = source.find('\n', versionPos);
    if (lineEnd == std::string::npos) throw GlError("shader file '" + path + "' has no body");
    int versionLine = 1;
    for (std::size_t i = 0; i < versionPos; ++i)
        if (source[i] == '\n') ++versionLine;
    std::string out = source.substr(0, lineEnd + 1);
    for (const auto& d : defines) out += "#define " + d + "\n";
    for (std::size_t k = 0; k < includeSources.size(); ++k)
        out += "#line 1 " + std::to_string(k + 1) + "\n" + includeSources[k] + "\n";
    // "#line N 0": the next line is line N of source string 0, the only string we pass.
    out += "#line " + std::to_string(versionLine + 1) + " 0\n";
    out += source.substr(lineEnd + 1);
    return out;
}

// Mesa prints "0:12(5): error: ...", NVIDIA "0(12) : error ..."; both become "file:12: ...",
// where source string 0 is the stage's file and k >= 1 its k-th include.
std::string nameFileInLog(const std::string& log, const std::vector<std::string>& paths) {
    std::string out = log;
    for (std::size_t k = 0; k < paths.size(); ++k) {
        const std::string n = std::to_string(k);
        const std::regex mesa("(^|\\n)" + n + R"(:(\d+)\((\d+)\):)");
        const std::regex nvidia("(^|\\n)" + n + R"(\((\d+)\) ?:)");
        out = std::regex_replace(out, mesa, "$1" + paths[k] + ":$2:$3:");
        out = std::regex_replace(out, nvidia, "$1" + paths[k] + ":$2:");
    }
    return out;
}

const char* stageName(GLenum stage) {
    switch (stage) {
        case GL_VERTEX_SHADER: return "vertex";
        case GL_FRAGMENT_SHADER: return "fragment";
        case GL_GEOMETRY_SHADER: return "geometry";
        case GL_TESS_CONTROL_SHADER: return "tessellation control";
        case GL_TESS_EVALUATION_SHADER: return "tessellation evaluation";
        case GL_COMPUTE_SHADER: return "compute";
        default: return "unknown-stage";
    }
}

// The info log of a shader or program object (GL has a pair of getters for each).
template <typename GetIv, typename GetLog>
std::string infoLog(GLuint object, GetIv getIv, GetLog getLog) {
    GLint length = 0;
    getIv(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 1 ? length : 1), '\0');
    getLog(object, length, nullptr, log.data());
    return log.c_str();
}

}  // namespace

Program buildProgram(const ProgramDesc& desc) {
    std::vector<Shader> shaders;
    std::string names;
    for (const auto& stage : desc.stages) {
        const std::string path = desc.shaderDir + "/" + stage.file;
        std::vector<std::string> paths{path}, includeSources;
        for (const auto& include : stage.includes) {
            paths.push_back(desc.shaderDir + "/" + include);
            includeSources.push_back(readFile(paths.back()));
        }
        const std::string source = assemble(readFile(path), desc.defines, includeSources, path);
        Shader shader = Shader::create(stage.stage);
        const char* text = source.c_str();
        glShaderSource(shader.id(), 1, &text, nullptr);
        glCompileShader(shader.id());
        GLint ok = GL_FALSE;
        glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
        if (ok != GL_TRUE)
            throw GlError(std::string(stageName(stage.stage)) + " shader '" + path + "' failed to compile:\n" +
                          nameFileInLog(infoLog(shader.id(), glGetShaderiv, glGetShaderInfoLog), paths));
        names += (names.empty() ? "" : " + ") + stage.file;
        shaders.push_back(std::move(shader));
    }
    Program program = Program::create();
    for (const auto& s : shaders) glAttachShader(program.id(), s.id());
    glLinkProgram(program.id());
    for (const auto& s : shaders) glDetachShader(program.id(), s.id());
    GLint ok = GL_FALSE;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE)
        throw GlError("shader program " + names +
                      " failed to link: " + infoLog(program.id(), glGetProgramiv, glGetProgramInfoLog));
    checkErrors(("building shader program " + names).c_str());
    return program;
}

GLint uniform(const Program& program, const char* name) { return glGetUniformLocation(program.id(), name); }

}  // namespace warplab::gl
