// The methods that shade part of every displayed frame -- spatio-temporal upsampling (stu-4,
// stu-8; seed 001) and adaptive frameless sampling (frameless-8; seed 002) -- and the conventional
// renderer's lattice, geometry-only and masked passes they are built from, on cases whose
// answer is known.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "gl/gl_test_support.h"
#include "renderer/upconvert.h"
#include "upconvert/frameless.h"

namespace warplab {
namespace {

constexpr int kW = 128;
constexpr int kH = 72;
constexpr double kRefresh = 120.0;

scene::FrameDescription still(double t) {
    const auto shooter = testing::shooterScene(kW, kH, 4, 6.0);
    scene::FrameDescription f{shooter.restingCamera(), shooter.snapshot(t)};
    f.scene.objects.clear();
    return f;
}

scene::FrameDescription moving(double t) {
    const auto shooter = testing::shooterScene(kW, kH, 4, 6.0);
    return {shooter.restingCamera(), shooter.snapshot(t)};
}

// One method instance per test, fed displayed frames in order.
class Upsampler {
public:
    explicit Upsampler(const std::string& name)
        : method_((testing::glContext(), renderer::makeMethod(name, testing::sourceDataPaths()))) {}
    renderer::DisplayImages frame(const scene::FrameDescription& f, int width = kW, int height = kH) {
        renderer::UpconversionInput input;
        input.displayTime = f.scene.time;
        input.camera = f.camera;
        input.scene = &f.scene;
        renderer::DisplayFrame display(width, height);
        method_->produce(input, display);
        return renderer::readBack(display);
    }
    renderer::UpconversionMethod& method() { return *method_; }

private:
    std::unique_ptr<renderer::UpconversionMethod> method_;
};

int maxChannelDifference(const image::ImageRGBA8& a, int ax, int ay, const image::ImageRGBA8& b, int bx, int by) {
    const std::uint8_t* p = a.at(ax, ay);
    const std::uint8_t* q = b.at(bx, by);
    return std::max({std::abs(p[0] - q[0]), std::abs(p[1] - q[1]), std::abs(p[2] - q[2])});
}

// One phase of the lattice pass, read back (top-down): its pixel (X, r) is the frame's pixel
// (X * step.x + phase.x, r * step.y + step.y - 1 - phase.y), as the next test checks.
renderer::GBufferImages renderLattice(const scene::FrameDescription& f, glm::ivec2 step, glm::ivec2 phase) {
    renderer::ShadingOptions shading;
    shading.latticeStep = step;
    shading.latticePhase = phase;
    renderer::ConventionalRenderer lattice(testing::sourceDataPaths(), shading);
    renderer::GBuffer low(kW / step.x, kH / step.y);
    lattice.render(f, low);
    return renderer::readBack(low);
}

// The lattice pass shades the frame's own pixel centres: its pixel (X, Y) is the frame's pixel
// (X * step + phase), counted bottom-up, for every phase.
TEST(Lattice, ShadesTheFramesPixelCentres) {
    testing::glContext();
    const scene::FrameDescription f = moving(0.3);
    const renderer::GBufferImages truth = testing::renderFrame(f, kW, kH);
    for (const glm::ivec2 step : {glm::ivec2(2, 2), glm::ivec2(4, 2)})
        for (int py = 0; py < step.y; ++py)
            for (int px = 0; px < step.x; ++px) {
                const renderer::GBufferImages shown = renderLattice(f, step, {px, py});
                int colourOff = 0, idOff = 0;
                for (int r = 0; r < shown.colour.height; ++r)
                    for (int x = 0; x < shown.colour.width; ++x) {
                        // Read back top-down: the lattice's row r is GL row h - 1 - r, which is
                        // the frame's GL row (h - 1 - r) * step + phase, its top-down row below.
                        const int fx = x * step.x + px, fy = r * step.y + (step.y - 1 - py);
                        colourOff += maxChannelDifference(shown.colour, x, r, truth.colour, fx, fy) > 2;
                        idOff += shown.ids.at(x, r) != truth.ids.at(fx, fy);
                    }
                const int n = shown.colour.width * shown.colour.height;
                const std::string where = "step " + std::to_string(step.x) + "x" + std::to_string(step.y) + " phase " +
                    std::to_string(px) + "," + std::to_string(py);
                // Silhouette pixels may fall either way of an edge in the last bit of the shift.
                // The panel seams are a step function of the surface point: a centre within
                // rounding of a seam's edge may fall either way.
                EXPECT_LE(idOff, n / 100) << where;
                EXPECT_LE(colourOff, 3 * n / 100) << where;
            }
}

TEST(Lattice, APhaseOutsideItsStepIsRefused) {
    testing::glContext();
    renderer::ShadingOptions shading;
    shading.latticeStep = {2, 2};
    shading.latticePhase = {2, 0};
    EXPECT_THROW(renderer::ConventionalRenderer(testing::sourceDataPaths(), shading), std::invalid_argument);
}

// The geometry pass writes what a full render writes, except colour.
TEST(Lattice, TheGeometryPassHasTheFullRendersIdsAndDepth) {
    testing::glContext();
    const scene::FrameDescription f = moving(0.3);
    const renderer::GBufferImages truth = testing::renderFrame(f, kW, kH);
    renderer::ShadingOptions shading;
    shading.geometryOnly = true;
    renderer::ConventionalRenderer geometry(testing::sourceDataPaths(), shading);
    renderer::GBuffer target(kW, kH);
    geometry.render(f, target);
    const renderer::GBufferImages shown = renderer::readBack(target);
    EXPECT_EQ(shown.ids.data, truth.ids.data);
    EXPECT_EQ(shown.depth.data, truth.depth.data);
    EXPECT_EQ(shown.velocity.data, truth.velocity.data);
    EXPECT_NE(shown.colour.pixels, truth.colour.pixels);
}

TEST(SpatioTemporal, ShadesExactlyItsBudgetEveryFrame) {
    for (const auto& [name, share] : {std::pair<std::string, int>{"stu-4", 4}, {"stu-8", 8}, {"frameless-8", 8}}) {
        Upsampler stu(name);
        EXPECT_DOUBLE_EQ(stu.method().info().shadedShare, 1.0 / share);
        for (int k = 0; k < 3; ++k) {
            stu.frame(moving(1.0 + k / kRefresh));
            EXPECT_EQ(stu.method().lastShadedSamples(), static_cast<double>(kW * kH / share)) << name;
        }
    }
}

// The exact samples of a still scene: every phase of the lattice pass put where it shades.
// They are the full render but for the rasteriser's ties -- a pixel centre on an edge of the
// geometry to the last bit falls either side in a pass whose projection is shifted (at 128x72
// a hangar edge runs through the centres of column 107): 49 pixels, 38.5 dB for 2x2 and 37.4 dB
// for 4x2, the most a filter of these samples can reach here.
image::ImageRGBA8 exactSamples(const scene::FrameDescription& f, glm::ivec2 step) {
    image::ImageRGBA8 exact = testing::renderFrame(f, kW, kH).colour;
    for (int py = 0; py < step.y; ++py)
        for (int px = 0; px < step.x; ++px) {
            const image::ImageRGBA8 low = renderLattice(f, step, {px, py}).colour;
            for (int r = 0; r < low.height; ++r)
                for (int x = 0; x < low.width; ++x)
                    std::copy_n(low.at(x, r), 4, exact.at(x * step.x + px, r * step.y + step.y - 1 - py));
        }
    return exact;
}

// A still scene: each frame shades another phase of the lattice, so within a cycle every pixel
// has its own exact sample, and the picture must converge to those samples (Herzog et al.
// section 4: a static scene needs "up to 16 frames" of a 4x4 lattice "to produce an accurate
// result"), not to a blend of them with the neighbours'. The paper's pixel filter alone (its
// fall-off at most 4) settled at 27.5 dB (stu-4) and 23.9 dB (stu-8) against the full render;
// now four cycles reach the exact samples' 38.5 and 37.7 dB (stu-8's own-sample test leaves
// a few tie pixels to the neighbours', a little nearer the full render than the ties).
TEST(SpatioTemporal, AStillSceneConvergesToItsExactSamples) {
    const scene::FrameDescription f = still(0.0);
    const renderer::GBufferImages truth = testing::renderFrame(f, kW, kH);
    for (const auto& [name, step] : {std::pair<std::string, glm::ivec2>{"stu-4", {2, 2}}, {"stu-8", {4, 2}}}) {
        const image::ImageRGBA8 exact = exactSamples(f, step);
        const int cycle = step.x * step.y;
        Upsampler stu(name);
        const double first = image::psnr(stu.frame(f).colour, truth.colour);
        renderer::DisplayImages shown;
        for (int k = 1; k < 4 * cycle; ++k) shown = stu.frame(still(k / kRefresh));
        const double toTruth = image::psnr(shown.colour, truth.colour);
        const double ceiling = image::psnr(exact, truth.colour);
        int differ = 0;  // pixels off the exact samples by more than rounding
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) differ += maxChannelDifference(shown.colour, x, y, exact, x, y) > 1;
        const std::string report = name + ": " + std::to_string(first) + " dB at the first frame, " +
            std::to_string(toTruth) + " after four cycles, the exact samples " + std::to_string(ceiling) + "; " +
            std::to_string(differ) + " pixels off them";
        EXPECT_GT(toTruth, 37.0) << report;
        EXPECT_GT(toTruth, ceiling - 0.2) << report;
        EXPECT_LE(differ, 8) << report;  // a few tie pixels may take a neighbour's sample (2 measured)
        EXPECT_GT(toTruth, first + 15.0) << report;
    }
}

// Frameless sampling's filter narrows where the scene is still: after two cycles of its eighth
// the picture is within 2 dB of where it settles (after ten at most), far better than the first
// frame, and it settles at 31.0 dB at this size.
TEST(Frameless, AStillSceneSettlesWithinTwoCycles) {
    const renderer::GBufferImages truth = testing::renderFrame(still(0.0), kW, kH);
    constexpr int kCycle = 8;
    Upsampler frameless("frameless-8");
    const double first = image::psnr(frameless.frame(still(0.0)).colour, truth.colour);
    double afterTwoCycles = first, last = first;
    for (int k = 1; k < 10 * kCycle; ++k) {
        last = image::psnr(frameless.frame(still(k / kRefresh)).colour, truth.colour);
        if (k == 2 * kCycle - 1) afterTwoCycles = last;
    }
    const std::string report = std::to_string(first) + " dB at the first frame, " + std::to_string(afterTwoCycles) +
        " after two cycles, " + std::to_string(last) + " after ten";
    EXPECT_GT(afterTwoCycles, first + 3.0) << report;
    EXPECT_GT(afterTwoCycles, last - 2.0) << report;
    EXPECT_GT(last, 29.5) << report;
}

// Mean PSNR over frames 16 to 63 of a run started at t = 2 s, the camera turning at yawRate.
double meanPsnrOverARun(const std::string& name, double yawRate) {
    Upsampler stu(name);
    double squaredError = 0.0;
    int frames = 0;
    for (int k = 0; k < 64; ++k) {
        scene::FrameDescription f = moving(2.0 + k / kRefresh);
        f.camera.yaw += static_cast<float>(yawRate * k / kRefresh);
        const auto shown = stu.frame(f);
        if (k < 16) continue;
        squaredError += std::pow(10.0, -image::psnr(shown.colour, testing::renderFrame(f, kW, kH).colour) / 10.0);
        ++frames;
    }
    return -10.0 * std::log10(squaredError / frames);
}

// Near-still content: the target moves, the camera and the hangar do not. The hangar is still
// and converges as above; the target is filtered as the paper says. Measured 37.9 dB (stu-4) and
// 36.8 (stu-8); 27.5 and 23.7 with the paper's pixel filter everywhere. A turning camera
// (0.6 rad/s) leaves no pixel still, so the paper's filter alone makes the picture: 23.6 and
// 22.1 dB, the same as before still pixels were told apart; the bound allows 0.2 dB.
TEST(SpatioTemporal, NearStillContentGainsAndATurningCameraLosesNothing) {
    for (const auto& [name, target, turning] :
         {std::tuple<std::string, double, double>{"stu-4", 36.5, 23.4}, {"stu-8", 35.5, 21.9}}) {
        EXPECT_GT(meanPsnrOverARun(name, 0.0), target) << name;
        EXPECT_GT(meanPsnrOverARun(name, 0.6), turning) << name;
    }
}

// The target moves over a still background: where it was, the background shows again, and the
// history there (the target's colour) must be rejected, not blended in. The game's red target
// changes the picture's luminance where it leaves, which the temporal gradient sees too; a
// target dimmed to the wall's luminance (the gradient compares luminance) leaves only the depth
// and id test to reject its history (Herzog et al. section 3.2, Figure 3).
TEST(SpatioTemporal, TheTrailOfAMovingTargetIsNotGhosted) {
    const auto dimmed = [](scene::FrameDescription f) {
        for (auto& o : f.scene.objects) o.colour *= 0.58f;  // luminance 42 of 255, the wall's here
        return f;
    };
    for (const bool dim : {false, true})
        for (const std::string name : {"stu-4", "stu-8", "frameless-8"}) {
            const auto at = [&](double t) { return dim ? dimmed(moving(t)) : moving(t); };
            Upsampler stu(name);
            renderer::DisplayImages shown;
            const double t0 = 2.0;
            // Long enough for the history to weigh its most (uMaxHistoryWeight); the trail is what
            // the target covered kTrail frames before the last.
            constexpr int kFrames = 48, kTrail = 8;
            for (int k = 0; k < kFrames; ++k) shown = stu.frame(at(t0 + k / kRefresh));
            const renderer::GBufferImages truth = testing::renderFrame(at(t0 + (kFrames - 1) / kRefresh), kW, kH);
            const renderer::GBufferImages before =
                testing::renderFrame(at(t0 + (kFrames - 1 - kTrail) / kRefresh), kW, kH);
            // The trail: background now, the target kTrail frames before.
            int trail = 0, ghosts = 0;
            double error = 0.0;
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x) {
                    if (truth.ids.at(x, y) >= scene::kIdTarget || before.ids.at(x, y) < scene::kIdTarget) continue;
                    ++trail;
                    const int d = maxChannelDifference(shown.colour, x, y, truth.colour, x, y);
                    error += d;
                    ghosts += d > 24;
                }
            const std::string which = name + (dim ? ", dimmed target" : ", red target");
            ASSERT_GT(trail, 10) << which << ": the target must have moved off some pixels";
            // Measured 2.1 and 4.1 levels (stu-4, stu-8) with the test, 12 to 17 without it.
            EXPECT_LT(error / trail, 6.0) << which;
            EXPECT_LE(ghosts, 2) << which << ": " << ghosts << " of " << trail << " trail pixels ghosted";
        }
}

// The bench times a pass several times over: a repeat of a frame shows the same picture, and
// the frame after it is what it would have been without the repeat.
TEST(SpatioTemporal, ARepeatedFrameChangesNothing) {
    Upsampler once("stu-4"), twice("stu-4");
    for (int k = 0; k < 5; ++k) {
        const scene::FrameDescription f = moving(3.0 + k / kRefresh);
        const auto a = once.frame(f);
        const auto b = twice.frame(f);
        const auto c = twice.frame(f);
        EXPECT_EQ(a.colour.pixels, b.colour.pixels) << k;
        EXPECT_EQ(b.colour.pixels, c.colour.pixels) << k;
    }
}

TEST(SpatioTemporal, ADisplayTheLatticeDoesNotDivideIsRefused) {
    Upsampler stu("stu-8");
    try {
        stu.frame(still(5.0), 130, 72);
        FAIL() << "a 130-pixel-wide display was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("130x72"), std::string::npos) << e.what();
    }
}

// The target moves over a still background seen by a still camera: after the controller has
// watched it a while, the cells it crosses get more of the frame's samples than the still ones.
TEST(Frameless, TheControllerSamplesWhereTheSceneMoves) {
    Upsampler frameless("frameless-8");
    const double t0 = 4.0;
    constexpr int kFrames = 24;
    for (int k = 0; k < kFrames; ++k) frameless.frame(moving(t0 + k / kRefresh));
    const renderer::SamplePlacement placed = renderer::lastPlacement(frameless.method());
    const renderer::GBufferImages last = testing::renderFrame(moving(t0 + (kFrames - 1) / kRefresh), kW, kH);
    // Cells (bottom-up) the target covers now, against cells it has not come near.
    double onTarget = 0.0, still = 0.0;
    int targetCells = 0, stillCells = 0;
    for (int cy = 0; cy < placed.cellsY; ++cy)
        for (int cx = 0; cx < placed.cellsX; ++cx) {
            int target = 0;
            for (int y = 0; y < placed.cell; ++y)
                for (int x = 0; x < placed.cell; ++x)
                    target += last.ids.at(cx * placed.cell + x, kH - 1 - (cy * placed.cell + y)) >= scene::kIdTarget;
            const int n = placed.counts[static_cast<std::size_t>(cy) * placed.cellsX + cx];
            if (target > placed.cell * placed.cell / 4) {
                onTarget += n;
                ++targetCells;
            } else if (target == 0) {
                still += n;
                ++stillCells;
            }
        }
    ASSERT_GT(targetCells, 0);
    const double mean = (onTarget + still) / (targetCells + stillCells);
    EXPECT_GT(onTarget / targetCells, 1.5 * still / stillCells)
        << onTarget / targetCells << " samples per cell on the target, " << still / stillCells << " elsewhere (mean "
        << mean << ")";
}

}  // namespace
}  // namespace warplab
