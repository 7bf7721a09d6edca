// Private to renderer/: the OpenGL 4.1 core API (and, where the context has it, 4.3's compute) as function pointers loaded from the current
// context. Include this instead of any system GL header; code then reads as plain GL
// (glClear(...)) but calls through warplab::gl::fn, which each context fills in.
#pragma once

#include <string>
#include <vector>

#include <GL/glcorearb.h>

namespace warplab::gl {

namespace fn {
#define WARPLAB_GL(type, name) extern type name;
#include "gl/functions.inc"
#include "gl/functions_compute.inc"
#undef WARPLAB_GL
}  // namespace fn

using ProcAddressLoader = void* (*)(const char* name);

// Fills every pointer of functions.inc and functions_compute.inc from `loader`. Returns the
// names of functions.inc it could not find (empty when the context offers all of them); a
// missing compute entry point stays null, for hasCompute() to see.
std::vector<std::string> loadFunctions(ProcAddressLoader loader);

// Whether the current context runs compute shaders: OpenGL 4.3 or later, with every entry point
// of functions_compute.inc loaded. Otherwise `why` (when given) says what it is instead.
// The version is the context's, or WARPLAB_GL_VERSION's where that is lower: what a machine
// whose GL is that old would show (the README, "GL backends"); a value that is no version
// such as 4.1 throws std::runtime_error naming it.
bool hasCompute(std::string* why = nullptr);
inline constexpr const char* kGlVersionCapVariable = "WARPLAB_GL_VERSION";

}  // namespace warplab::gl

using namespace warplab::gl::fn;  // NOLINT: lets GL code read as GL
