// Private: one factory per headless backend (the window's is createWindow, public in
// renderer/window.h), each in its own file so that the headers of OSMesa, EGL and SDL (which
// each drag in their own idea of GL) never meet.
#pragma once

#include <memory>

#include "renderer/context.h"

namespace warplab::renderer {

std::unique_ptr<GlContext> createOsmesaContext(const ContextOptions& options);
std::unique_ptr<GlContext> createEglContext(const ContextOptions& options);

}  // namespace warplab::renderer
