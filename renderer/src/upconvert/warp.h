// Renderer-private: warp extrapolation (seed 004 sections 4.2.2-4.3.5, 5.2.4-5.2.6). Use
// makeMethod("warp-full" | "warp-nofix" | "warp-sparse4" | "warp-sparse8" | "warp-sparse16").
#pragma once

#include "renderer/upconvert.h"

namespace warplab::renderer {

struct WarpSettings {
    int patchSize = 0;  // 0 = full-density mesh; 4, 8, 16 = tessellated sparse mesh
    bool disocclusionFix = true;  // the geometry-shader fix of section 5.2.5
    // A triangle whose normal is within this many degrees of perpendicular to the source view
    // ray is a disocclusion sheet.
    float sheetAngleDeg = 85.0f;
    // ...and whose far corner is this many times farther from the source eye than its near one.
    float sheetDepthRatio = 1.03f;
    float depthJump = 0.03f;  // relative linear-depth jump that makes a patch subdivide
    float velocityJump = 0.05f;  // m/s velocity jump that does too
};

std::unique_ptr<UpconversionMethod> makeWarp(const DataPaths& paths, const std::string& name,
                                             const WarpSettings& settings);

}  // namespace warplab::renderer
