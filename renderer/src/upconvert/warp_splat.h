// Renderer-private: warp extrapolation by forward splatting, in compute (OpenGL 4.3). Use
// makeMethod("warp-splat").
#pragma once

#include "renderer/upconvert.h"

namespace warplab::renderer {

struct WarpSplatSettings {
    // Display pixels a triangle may span on a side before it is left to the hole fill: far
    // beyond any surface's stretch between two neighbouring source pixels (a 1.5 m step
    // towards a wall 2 m away magnifies it 4x), short of the near plane's slivers.
    int maxSpanPx = 32;
    // How far the resolve looks for a hole's background, as a share of the display height: a
    // disocclusion is as wide as the foreground moved against the background in one source
    // period (the bench's fastest sphere: about 6 % of the height).
    float holeReach = 0.08f;
};

// Throws std::runtime_error with methodUnavailable's sentence where the context has no compute.
std::unique_ptr<UpconversionMethod> makeWarpSplat(const DataPaths& paths, const std::string& name,
                                                  const WarpSplatSettings& settings);

}  // namespace warplab::renderer
