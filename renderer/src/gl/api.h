// Private to renderer/: the OpenGL 4.1 core API as function pointers loaded from the current
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
#undef WARPLAB_GL
}  // namespace fn

using ProcAddressLoader = void* (*)(const char* name);

// Fills every pointer of functions.inc from `loader`. Returns the names it could not find
// (empty when the context offers all of them).
std::vector<std::string> loadFunctions(ProcAddressLoader loader);

}  // namespace warplab::gl

using namespace warplab::gl::fn;  // NOLINT: lets GL code read as GL
