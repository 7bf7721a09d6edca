// The methods that shade part of every displayed frame -- spatio-temporal upsampling (stu-4,
// stu-8; seed 001) and adaptive frameless sampling (frameless-8; seed 002) -- and the conventional
// renderer's lattice, geometry-only and masked passes they are built from, on cases whose
// answer is known.
#include <algorithm>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>

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

// The lattice pass shades the frame's own pixel centres: its pixel (X, Y) is the frame's pixel
// (X * step + phase), counted bottom-up, for every phase.
TEST(Lattice, ShadesTheFramesPixelCentres) {
    testing::glContext();
    const scene::FrameDescription f = moving(0.3);
    const renderer::GBufferImages truth = testing::renderFrame(f, kW, kH);
    for (const glm::ivec2 step : {glm::ivec2(2, 2), glm::ivec2(4, 2)})
        for (int py = 0; py < step.y; ++py)
            for (int px = 0; px < step.x; ++px) {
                renderer::ShadingOptions shading;
                shading.latticeStep = step;
                shading.latticePhase = {px, py};
                renderer::ConventionalRenderer lattice(testing::sourceDataPaths(), shading);
                renderer::GBuffer low(kW / step.x, kH / step.y);
                lattice.render(f, low);
                const renderer::GBufferImages shown = renderer::readBack(low);
                int colourOff = 0, idOff = 0;
                for (int r = 0; r < low.height(); ++r)
                    for (int x = 0; x < low.width(); ++x) {
                        // Read back top-down: the lattice's row r is GL row h - 1 - r, which is
                        // the frame's GL row (h - 1 - r) * step + phase, its top-down row below.
                        const int fx = x * step.x + px, fy = r * step.y + (step.y - 1 - py);
                        colourOff += maxChannelDifference(shown.colour, x, r, truth.colour, fx, fy) > 2;
                        idOff += shown.ids.at(x, r) != truth.ids.at(fx, fy);
                    }
                const int n = low.width() * low.height();
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

// A still scene: each frame shades another phase of the lattice and the history gathers them.
// After two cycles of the lattice the picture is within 2 dB of where it settles (after ten
// cycles at most) and far better than the first frame's spatial upsampling alone. Where it
// settles is not the ideal: the paper's pixel filter k (fall-off at most 4, section 3.5) keeps
// mixing the neighbours' samples in, which the hangar's sharp panel seams show (at this size,
// 27.5 dB for stu-4 and 23.9 dB for stu-8; frameless-8, whose filter narrows where the scene is
// still, 31.0 dB).
TEST(SpatioTemporal, AStillSceneSettlesWithinTwoCyclesOfItsLattice) {
    const renderer::GBufferImages truth = testing::renderFrame(still(0.0), kW, kH);
    struct Case {
        std::string name;
        int cycle;
        double settled;  // the least PSNR it must settle at, dB
    };
    for (const Case& c : {Case{"stu-4", 4, 26.5}, Case{"stu-8", 8, 23.0}, Case{"frameless-8", 8, 29.5}}) {
        Upsampler stu(c.name);
        const double first = image::psnr(stu.frame(still(0.0)).colour, truth.colour);
        double afterTwoCycles = first, last = first;
        for (int k = 1; k < 10 * c.cycle; ++k) {
            last = image::psnr(stu.frame(still(k / kRefresh)).colour, truth.colour);
            if (k == 2 * c.cycle - 1) afterTwoCycles = last;
        }
        const std::string report = c.name + ": " + std::to_string(first) + " dB at the first frame, " +
            std::to_string(afterTwoCycles) + " after two cycles, " + std::to_string(last) + " after ten";
        EXPECT_GT(afterTwoCycles, first + 3.0) << report;
        EXPECT_GT(afterTwoCycles, last - 2.0) << report;
        EXPECT_GT(last, c.settled) << report;
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
