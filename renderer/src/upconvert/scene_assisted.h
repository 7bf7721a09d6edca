// Renderer-private: scene-assisted bidirectional reprojection (seed 000 section 4). Use
// makeMethod("scene-assisted").
#pragma once

#include "renderer/upconvert.h"

namespace warplab::renderer {

std::unique_ptr<UpconversionMethod> makeSceneAssisted(const DataPaths& paths);

}  // namespace warplab::renderer
