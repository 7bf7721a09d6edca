// Renderer-private factories of the baseline methods; use makeMethod() from outside.
#pragma once

#include "renderer/upconvert.h"

namespace warplab::renderer {

std::unique_ptr<UpconversionMethod> makeHold(const DataPaths& paths, double rateHz);
std::unique_ptr<UpconversionMethod> makeBlend(const DataPaths& paths);

}  // namespace warplab::renderer
