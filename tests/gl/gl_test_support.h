// Shared by the GL tests: one headless context per test binary, the source tree's data,
// the shooter scene at small sizes, and reference-image comparison with approval.
#pragma once

#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "physics/target_scene.h"
#include "renderer/context.h"
#include "renderer/conventional.h"
#include "renderer/upconvert.h"

namespace warplab::testing {

// The context every GL test draws with: OSMesa unless WARPLAB_TEST_GL=egl|window.
renderer::GlContext& glContext();
renderer::DataPaths sourceDataPaths();

// Renders a frame at width x height and reads the G-buffer back.
renderer::GBufferImages renderFrame(const scene::FrameDescription& frame, int width, int height);

// A conventionally rendered source frame kept with its read-back buffers.
struct RenderedSource {
    std::unique_ptr<renderer::SourceFrame> frame;
    renderer::GBufferImages images;
};
// With flowTo, the render also writes its backward flow towards that frame (bidirectional
// reprojection's I-frame pass).
// With a band, the source is rendered that far beyond the width x height view on each side.
RenderedSource renderSource(const scene::FrameDescription& frame, int width, int height,
                            const scene::FrameDescription* flowTo = nullptr, renderer::GuardBand band = {});

// Makes the displayed frame with a registered method (methods are built once per name).
renderer::DisplayImages produceFrame(const std::string& method, const renderer::UpconversionInput& input, int width,
                                     int height);
// The same from one source, seen from `camera` at displayTime (warps, rotation, holds).
renderer::DisplayImages produceFrom(const std::string& method, const RenderedSource& source,
                                    const scene::CameraState& camera, double displayTime, int width, int height);

// The shooter scene sized for a width x height image, target spawned from `seed`.
physics::TargetScene shooterScene(int width, int height, std::uint64_t seed = 1, double speed = 2.0);

// Pixels left black by a method where the ground truth is not. "Black" robustly: a method's
// colour is a source colour or a blend of two and the scene is almost never black, so a black
// pixel (every channel below 8) where the truth is not dark (some channel 32 or more) is one
// nothing was drawn into.
int blackWhereTruthIsNot(const image::ImageRGBA8& shown, const image::ImageRGBA8& truth);

// Camera turned so the reticle (image centre) is on `point`.
scene::CameraState aimedAt(scene::CameraState camera, const glm::vec3& point);

// The warps' moving-sphere case: `start`'s target made a 0.6 m sphere at (-1, 4, -6) moving
// with `velocity`, the camera aimed at `aim`; `later` is the same `frames` display frames
// (120 Hz) on, the sphere moved by its velocity.
struct SpherePass {
    scene::FrameDescription start, later;
    double dt = 0.0;
};
SpherePass sphereMovingAcross(scene::FrameDescription start, const glm::vec3& velocity, const glm::vec3& aim,
                              int frames);

// Thresholds for comparing a render with a reference, each with its reason.
struct ImageThresholds {
    // Mean |difference| over all channels: shading arithmetic may differ in the last bits
    // between rasterisers/CPUs (llvmpipe's AVX2 vs AVX-512 paths); 0.75 of 255 catches any
    // real change of lighting or geometry, which moves the mean by whole units.
    double mean = 0.75;
    // A pixel counts as different above this per-channel difference...
    int pixelThreshold = 24;
    // ...and at most this share of pixels may be: silhouette pixels whose centre lies within
    // rounding of a triangle edge can fall on either side on another rasteriser.
    double maxShareOver = 0.004;
};

// Compares `actual` with tests/references/<name>.png. On failure writes actual and diff PNGs
// to the test output folder and names them. With WARPLAB_APPROVE=1 it (re)writes the
// reference instead and passes; scripts/approve-references.sh does that.
::testing::AssertionResult matchesReference(const std::string& name, const image::ImageRGBA8& actual,
                                            const ImageThresholds& thresholds = {});
::testing::AssertionResult imagesMatch(const image::ImageRGBA8& expected, const image::ImageRGBA8& actual,
                                       const std::string& label, const ImageThresholds& thresholds = {});

std::string testOutputDir();

}  // namespace warplab::testing
