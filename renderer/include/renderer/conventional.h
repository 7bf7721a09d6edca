// The conventional renderer (seed 004 section 5.2.3): Phong shading of the hangar and the
// moving objects into an offscreen G-buffer with four attachments -- colour, depth, object id
// and world-space velocity per fragment -- which later passes (warp, reprojection, HUD, the
// window blit, readback) consume.
#pragma once

#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "image/image.h"
#include "scene/scene.h"

namespace warplab::renderer {

// Where shaders/, assets/ and analysis/ are found at run time.
struct DataPaths {
    std::string shaderDir;
    std::string assetDir;
    std::string analysisDir;  // Python scripts the bench calls for its plot
};

// Offscreen frame buffer: RGBA8 colour, 32-bit float depth, R32UI object id, RGBA32F velocity
// (xyz used). Owns GL objects, so create and destroy it while the context is current.
class GBuffer {
public:
    GBuffer(int width, int height);  // throws std::invalid_argument outside 1..scene::kMaxImageSize
    ~GBuffer();
    GBuffer(GBuffer&&) noexcept;
    GBuffer& operator=(GBuffer&&) noexcept;

    int width() const;
    int height() const;

    struct Impl;  // GL side, see renderer/gbuffer_gl.h (renderer-private)
    Impl& impl() { return *impl_; }
    const Impl& impl() const { return *impl_; }

private:
    std::unique_ptr<Impl> impl_;
};

// The G-buffer read back into plain images, rows top-down.
struct GBufferImages {
    image::ImageRGBA8 colour;
    image::ImageF depth;  // window-space depth in [0, 1] as stored; 1 = far plane / sky
    image::ImageU32 ids;  // scene::ObjectId per pixel, 0 where nothing was drawn
    image::ImageF velocity;  // 3 channels, world-space m/s
};

GBufferImages readBack(const GBuffer& gbuffer);

// Shading parameters. Defaults are the study scene's.
struct ShadingOptions {
    // The hangar's panel seams: detail that makes reprojection errors visible in the metrics.
    bool panelPattern = true;
    // Extra per-fragment work (hash iterations), so the bench can make a conventional frame as
    // expensive as a real game's and show where upconversion starts to pay. 0 = none.
    int shadingCost = 0;
    // Supersampling antialiasing: colour is the box-filter mean of N x N samples per pixel, at
    // the centres of its N x N sub-pixels; N = 1 is off, 1..scene::kMaxSupersampling are
    // valid. Depth, ids, velocity and flow stay those of the pixel centre, bit for bit as with N = 1, since the game scores
    // the reticle's pixel and the warp reads them there; only colour is antialiased, so that a
    // method's bilinear resampling is judged against an antialiased truth.
    int supersampling = 1;
    // Shading a lattice of a larger frame's pixels, one phase at a time (spatio-temporal
    // upsampling's low-resolution shading, Herzog et al. 2010 section 3.2): the target's pixel
    // (X, Y) is shaded at the centre of the frame's pixel (X * latticeStep.x + latticePhase.x,
    // Y * latticeStep.y + latticePhase.y), counted from the bottom left as GL counts, and the
    // frame is the target's size times latticeStep -- a translation in post-perspective space,
    // at no cost. Spheres are drawn as finely as the frame needs. {1, 1} is a whole frame.
    glm::ivec2 latticeStep{1, 1};
    glm::ivec2 latticePhase{0, 0};
    // Depth, ids and velocity only, colour left as cleared: the geometry pass of a deferred
    // renderer, for methods that shade part of the frame themselves.
    bool geometryOnly = false;
    // Shade only the pixels marked nonzero in this GL texture (GL_R8UI, the target's size), the
    // rest left as cleared: adaptive frameless sampling's scattered samples, at the cost a
    // rasteriser pays for them. 0 = every pixel.
    unsigned sampleMask = 0;
};

class ConventionalRenderer {
public:
    // Loads the hangar model and builds the shader programs; throws AssetError or
    // gl::GlError with a message naming the file.
    // A supersampling outside 1..scene::kMaxSupersampling throws std::invalid_argument naming
    // the value, here and in setShading.
    explicit ConventionalRenderer(const DataPaths& paths, ShadingOptions shading = {});
    ~ConventionalRenderer();
    ConventionalRenderer(const ConventionalRenderer&) = delete;
    ConventionalRenderer& operator=(const ConventionalRenderer&) = delete;

    void render(const scene::FrameDescription& frame, GBuffer& target);
    // The same, and in the same pass (a fourth render target) the backward flow field of seed
    // 000 eq. 2 towards `flowTo`, the previous I-frame: what bidirectional reprojection needs
    // of every I-frame besides its colour and depth.
    void render(const scene::FrameDescription& frame, GBuffer& target, const scene::FrameDescription& flowTo);
    void setShading(const ShadingOptions& shading);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Copies a G-buffer's colour to the window's default framebuffer, scaled to fit.
void blitToDefaultFramebuffer(const GBuffer& gbuffer, int drawableWidth, int drawableHeight);

// Reads the window's back buffer (what the next swap shows): the window's screenshot.
image::ImageRGBA8 readDefaultFramebuffer(int width, int height);

}  // namespace warplab::renderer
