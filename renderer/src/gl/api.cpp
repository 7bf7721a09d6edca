#include "gl/api.h"

namespace warplab::gl {

namespace fn {
#define WARPLAB_GL(type, name) type name = nullptr;
#include "gl/functions.inc"
#include "gl/functions_compute.inc"
#undef WARPLAB_GL
}  // namespace fn

std::vector<std::string> loadFunctions(ProcAddressLoader loader) {
    std::vector<std::string> missing;
#define WARPLAB_GL(type, name)                        \
    fn::name = reinterpret_cast<type>(loader(#name)); \
    if (fn::name == nullptr) missing.emplace_back(#name);
#include "gl/functions.inc"
#undef WARPLAB_GL
#define WARPLAB_GL(type, name) fn::name = reinterpret_cast<type>(loader(#name));
#include "gl/functions_compute.inc"
#undef WARPLAB_GL
    return missing;
}

bool hasCompute(std::string* why) {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    std::string problem;
    if (major < 4 || (major == 4 && minor < 3)) {
        const GLubyte* version = glGetString(GL_VERSION);
        problem = "this context is OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
            (version != nullptr ? " (" + std::string(reinterpret_cast<const char*>(version)) + ")" : std::string());
    }
#define WARPLAB_GL(type, name) \
    if (problem.empty() && fn::name == nullptr) problem = "this context lacks " #name;
#include "gl/functions_compute.inc"
#undef WARPLAB_GL
    if (why != nullptr) *why = problem;
    return problem.empty();
}

}  // namespace warplab::gl
