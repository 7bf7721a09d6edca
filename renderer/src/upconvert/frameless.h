// Renderer-private: adaptive frameless sampling, rasterised (seed 002, Dayal et al. 2005). Use
// makeMethod("frameless-8").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "renderer/upconvert.h"

namespace warplab::renderer {

// `share`: one pixel in `share` shaded per displayed frame (8: an eighth).
std::unique_ptr<UpconversionMethod> makeFrameless(const DataPaths& paths, const std::string& name, int share);

// Where the controller put the last frame's samples: counts per cell, rows bottom-up (GL's).
struct SamplePlacement {
    int cell = 0;  // pixels per cell side
    int cellsX = 0, cellsY = 0;
    std::vector<int> counts;
};
// Throws std::invalid_argument if `method` is not a frameless method.
SamplePlacement lastPlacement(const UpconversionMethod& method);

}  // namespace warplab::renderer
