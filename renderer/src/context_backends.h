// Private: one factory per backend, each in its own file so that the headers of OSMesa,
// EGL and SDL (which each drag in their own idea of GL) never meet.
#pragma once

#include <memory>

#include "renderer/context.h"

namespace warplab::renderer {

std::unique_ptr<GlContext> createOsmesaContext(const ContextOptions& options);
std::unique_ptr<GlContext> createEglContext(const ContextOptions& options);
std::unique_ptr<GlContext> createWindowContext(const ContextOptions& options);

}  // namespace warplab::renderer
