// Renderer-private: warp extrapolation (seed 004 sections 4.2.2-4.3.5, 5.2.4-5.2.6). Use
// makeMethod("warp-full" | "warp-nofix" | "warp-sparse4" | "warp-sparse8" | "warp-sparse16").
#pragma once

#include <glm/glm.hpp>

#include "gl/objects.h"
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

// What warp_common.glsl warps `source` with, to the camera and instant of `input` at a display of
// width x height: a banded source's camera is widened to the same pixel pitch (its aspect is
// its own), the display keeps the displayed field of view. Inverted in double: float inversion
// of a perspective matrix with near 0.05 and far 200 costs several bits where depth is most
// compressed. Shared by the mesh warps and warp-splat.
struct WarpMatrices {
    glm::mat4 sourceViewProjection{1.0f}, targetViewProjection{1.0f};
    glm::mat4 sourceInverse{1.0f}, targetInverse{1.0f};
    float dt = 0.0f;  // display time - source time, s
};
WarpMatrices warpMatrices(const SourceFrame& source, const UpconversionInput& input, int width, int height);

// Sets what warp_common.glsl declares on `program`, the current program: `source`'s depth and
// velocity on texture units 0 and 1, the matrices `m`, its eye and size, the instant, and where
// sky pixels go. Shared by every pass that warps with it (the meshes, the patch flags,
// warp-splat's vertices and splat); each adds its own uniforms.
void setWarpUniforms(const gl::Program& program, const SourceFrame& source, const UpconversionInput& input,
                     const WarpMatrices& m);

}  // namespace warplab::renderer
