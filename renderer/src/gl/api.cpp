#include "gl/api.h"

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <utility>

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

namespace {

// WARPLAB_GL_VERSION as (major, minor); nullopt when unset or empty.
std::optional<std::pair<int, int>> versionCap() {
    const char* text = std::getenv(kGlVersionCapVariable);
    if (text == nullptr || *text == '\0') return std::nullopt;
    int major = 0, minor = 0;
    char end = 0;
    if (std::sscanf(text, "%d.%d%c", &major, &minor, &end) != 2 || major < 1 || minor < 0)
        throw std::runtime_error(std::string(kGlVersionCapVariable) + "='" + text +
                                 "' is not an OpenGL version such as 4.1");
    return std::pair(major, minor);
}

}  // namespace

bool hasCompute(std::string* why) {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    const GLubyte* version = glGetString(GL_VERSION);
    std::string driver = version != nullptr ? std::string(reinterpret_cast<const char*>(version)) : std::string();
    if (const auto cap = versionCap(); cap && *cap < std::pair<int, int>(major, minor)) {
        driver = "capped by " + std::string(kGlVersionCapVariable) + "; the driver's is " + std::to_string(major) +
            "." + std::to_string(minor) + (driver.empty() ? "" : ", " + driver);
        major = cap->first;
        minor = cap->second;
    }
    std::string problem;
    if (major < 4 || (major == 4 && minor < 3))
        problem = "this context is OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
            (driver.empty() ? std::string() : " (" + driver + ")");
#define WARPLAB_GL(type, name) \
    if (problem.empty() && fn::name == nullptr) problem = "this context lacks " #name;
#include "gl/functions_compute.inc"
#undef WARPLAB_GL
    if (why != nullptr) *why = problem;
    return problem.empty();
}

}  // namespace warplab::gl
