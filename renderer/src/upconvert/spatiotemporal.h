// Renderer-private: spatio-temporal upsampling (seed 001, Herzog et al. 2010). Use
// makeMethod("stu-4") or makeMethod("stu-8").
#pragma once

#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "renderer/upconvert.h"

namespace warplab::renderer {

// `step`: the lattice shaded per frame, one pixel in step.x x step.y (2 x 2: a quarter).
std::unique_ptr<UpconversionMethod> makeSpatioTemporal(const DataPaths& paths, const std::string& name,
                                                       glm::ivec2 step);

}  // namespace warplab::renderer
