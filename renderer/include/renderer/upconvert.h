// Upconversion methods: given the conventionally rendered source frames a condition would have,
// make the frame displayed at some instant. Every method -- sample-and-hold, blend, warp
// extrapolation, bidirectional reprojection and the rest -- sits behind this one interface,
// so the benchmark and the study conditions treat them alike.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "renderer/conventional.h"
#include "image/image.h"
#include "scene/scene.h"

namespace warplab::renderer {

// Pixels a source frame is rendered beyond the displayed frame on each side, at the same
// pixel pitch (a guard band): content a warp turns into view is then really there instead of
// invented at the edge. Only methods whose MethodInfo::acceptsGuardBand say so accept one.
struct GuardBand {
    int x = 0, y = 0;
    bool operator==(const GuardBand& o) const { return x == o.x && y == o.y; }
};
// `fraction` of the displayed width and height on each side, in whole pixels (0.1 = 10 %).
// Throws std::invalid_argument outside [0, scene::kMaxGuardBand].
GuardBand guardBandFor(int width, int height, double fraction);

// A frame rendered conventionally at one instant, kept with what it depicts.
struct SourceFrame {
    // `width` x `height` is the displayed frame's size; the G-buffer adds the band on each side.
    SourceFrame(int width, int height, GuardBand band = {})
        : band(band), gbuffer(width + 2 * band.x, height + 2 * band.y) {}
    // As rendered: with a guard band, the camera's field of view is widened to cover it.
    scene::FrameDescription depicts;
    GuardBand band;
    GBuffer gbuffer;
    // Which render the G-buffer holds, new for each renderSource: what methods cache per source
    // (bidirectional reprojection's flows) is keyed on it, so a source frame re-rendered with
    // other content is never mistaken for the old one.
    std::uint64_t serial = 0;
};

// Renders `frame` conventionally into `source` (widening the camera by the source's band) and
// gives it a new serial. With flowTo, the same pass also writes the backward flow towards that
// frame (ConventionalRenderer::render with flowTo).
void renderSource(ConventionalRenderer& renderer, const scene::FrameDescription& frame, SourceFrame& source,
                  const scene::FrameDescription* flowTo = nullptr);

// The frame a method shows. Attachments as a G-buffer's, but the third holds the method's
// claimed correspondences instead of velocity: xy = the continuous source-image coordinate
// (top-down, pixel centres at +0.5) in the previous source, zw = in the next source, NaN
// where the method claims none (bench measures these against the scene's exact ones).
class DisplayFrame {
public:
    DisplayFrame(int width, int height) : buffer_(width, height) {}
    int width() const { return buffer_.width(); }
    int height() const { return buffer_.height(); }
    GBuffer& buffer() { return buffer_; }
    const GBuffer& buffer() const { return buffer_; }

private:
    GBuffer buffer_;
};

struct DisplayImages {
    image::ImageRGBA8 colour;
    image::ImageU32 ids;  // the object each displayed pixel shows (for scoring cross-checks)
    image::ImageF correspondence;  // 4 channels, see DisplayFrame
};
// `correspondence` false leaves it empty: what a viewer sees is colour and objects only.
DisplayImages readBack(const DisplayFrame& frame, bool correspondence = true);
// A source without a guard band as hold shows it: its colour and ids (no correspondence).
DisplayImages readShown(const SourceFrame& source);

struct UpconversionInput {
    double displayTime = 0.0;
    scene::CameraState camera;  // the view sampled at this display frame
    const SourceFrame* previous = nullptr;  // latest source at or before displayTime (less sourceLagS)
    const SourceFrame* next = nullptr;  // the one after; only for methods with needsNext
    // The scene at the displayed instant; only for methods with needsScene, which rasterise it
    // again (scene-assisted reprojection). Everything else works from the sources' images.
    const scene::SceneSnapshot* scene = nullptr;
    // How the sources were shaded (the bench's shading cost): methods that shade part of each
    // displayed frame themselves (MethodInfo::shadedShare) shade it the same way.
    ShadingOptions shading;
};

struct MethodInfo {
    std::string name;
    std::string description;
    double sourceRateHz = 15.0;  // how often sources are rendered conventionally
    // How long a source waits in the queue before it is shown (a late warp's lagged frame): the
    // bench hands such a method the latest source at or before displayTime - sourceLagS.
    double sourceLagS = 0.0;
    bool needsNext = false;  // uses the following source frame (so shows content later)
    bool reportsCorrespondence = false;
    // Starts from what it computed for the previous displayed frame of the same source
    // interval (bidirectional reprojection's latest-frame initialisation): the bench makes
    // those frames, untimed, before timing one.
    bool usesEarlierFrames = false;
    bool needsScene = false;  // reads UpconversionInput::scene
    // Takes the next source's backward flow from its own render when it was rendered with one
    // towards the previous source (ConventionalRenderer::render with flowTo, seed 000's MRT
    // I-frame pass); draws it itself otherwise.
    bool usesSourceFlow = false;
    // A motion-blurred frame: the mean of this many instants spread evenly over the source
    // interval [previous, next] (the exposure). The bench compares it with the mean of as
    // many conventional renders (brute force). 0 = an instant, as every other method.
    int exposureSamples = 0;
    // Shows what a source's guard band (SourceFrame::band) holds as the view turns: the warps.
    // The bench renders such a method's sources with the band, as a study's warp condition does.
    bool takesGuardBand = false;
    // Accepts a banded source at all: the methods above, and the holds, which show its inside
    // (a warp condition's frames at its render instants).
    bool acceptsGuardBand = false;
    // Shades part of every displayed frame itself, at the displayed instant (spatio-temporal
    // upsampling, adaptive frameless sampling): this share of the display's pixels, exactly, from
    // the scene (needsScene), after a geometry pass over all of them. 0 = shows only what the
    // conventional sources hold.
    double shadedShare = 0.0;
    // Builds its picture up over consecutive displayed frames (a history reprojected into each):
    // the bench makes this many displayed frames before the one it times, untimed, as a session
    // would have made them. 0 = each frame from its sources alone.
    int historyFrames = 0;
    // Places its shaded samples where the picture needs them (adaptive frameless sampling), not
    // on a fixed pattern.
    bool adaptivePlacement = false;
};

// One stage of a method's pass, timed apart for the bench (UpconversionMethod::timeStages).
struct StageTime {
    std::string name;
    double wallMs = 0.0;
};

class UpconversionMethod {
public:
    virtual ~UpconversionMethod() = default;
    virtual const MethodInfo& info() const = 0;
    // Draws the displayed frame into `out` (same size as the sources). GL state it changes
    // is restored to the defaults the other passes assume.
    virtual void produce(const UpconversionInput& input, DisplayFrame& out) = 0;
    // Work done once per source frame (or pair) rather than per displayed frame -- e.g. the
    // flow fields of bidirectional reprojection's I-frames. produce() does it when needed;
    // the bench calls it first so that the displayed frame's own pass is timed alone.
    virtual void prepare(const UpconversionInput& /*input*/) {}
    // Triangles the last produce() drew (after tessellation), for the bench; NaN for
    // image-space methods that draw no mesh.
    virtual double lastTriangleCount() { return std::numeric_limits<double>::quiet_NaN(); }
    // Pixels the last produce() had shaded (the lattice it rendered, the samples it placed), for methods with
    // a shadedShare; NaN for the rest.
    virtual double lastShadedSamples() { return std::numeric_limits<double>::quiet_NaN(); }
    // For methods with a shadedShare: per displayed pixel (rows top-down), how long before the
    // displayed instant the newest sample shaded behind it was made, seconds. Empty: every pixel
    // shows shading made at the displayed instant.
    virtual std::vector<float> lastSampleAges() { return {}; }
    // For the bench: with `on`, produce() also ends each of its stages with glFinish and times
    // it (warp-splat: splat, resolve), and lastStageTimes() gives those of the last produce().
    // Methods of one stage have none to give; without `on`, none is timed and none given.
    virtual void timeStages(bool /*on*/) {}
    virtual std::vector<StageTime> lastStageTimes() const { return {}; }
};

// Throws std::invalid_argument naming the method when `source` does not fit `out`: its G-buffer
// must be the display's size plus its band, and a band only where info.acceptsGuardBand.
void checkSourceSize(const SourceFrame& source, const DisplayFrame& out, const MethodInfo& info);

// All registered method names, in the order the bench reports them.
std::vector<std::string> methodNames();
// Throws std::invalid_argument naming the unknown method and listing the known ones; needs no
// GL context, so a command line can be checked before one is made.
void requireMethod(const std::string& name);
// Throws as requireMethod for an unknown name, and std::runtime_error with
// methodUnavailable's sentence where the current context cannot run it.
std::unique_ptr<UpconversionMethod> makeMethod(const std::string& name, const DataPaths& paths);
// Why the current GL context cannot run the method, in one sentence ("warp-splat needs OpenGL
// 4.3 compute shaders; this context is OpenGL 4.1 (...)"); "" when it can. Throws as
// requireMethod for an unknown name.
std::string methodUnavailable(const std::string& name);
// What a study shows instead of a method the context cannot run (warp-splat: warp-sparse8, the
// mesh warp of warp15to120); "" where there is nothing to fall back on.
std::string methodFallback(const std::string& name);

}  // namespace warplab::renderer
