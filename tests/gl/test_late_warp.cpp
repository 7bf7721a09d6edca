// Late warp (Kim et al., HPG 2020; NVIDIA Reflex 2 Frame Warp): a lagged frame re-projected to
// the camera of the displayed instant, by rotation alone ("rotation") or with depth and
// velocities (the warp), judged against conventional renders of that instant and against the
// scene's exact correspondences (bench/ground_truth.h), not against the method's own maths.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/bench.h"
#include "bench/ground_truth.h"
#include "bench/sequences.h"
#include "gl/gl_test_support.h"
#include "image/image.h"

namespace warplab {
namespace {

constexpr int kW = 160;
constexpr int kH = 90;

// A still hangar (no target), so that only the camera's turn changes the view.
scene::FrameDescription stillHangar() {
    auto shooter = testing::shooterScene(kW, kH, 1, 2.0);
    scene::FrameDescription still{shooter.restingCamera(), shooter.snapshot(0.0)};
    still.scene.objects.clear();
    still.camera.yaw = 0.0f;
    still.camera.pitch = 0.0f;
    return still;
}

renderer::DisplayImages show(const std::string& method, const testing::RenderedSource& source,
                             const scene::CameraState& camera, double displayTime) {
    return testing::produceFrom(method, source, camera, displayTime, kW, kH);
}

// Mean |difference| over R, G and B, 0..255 units.
double meanAbsError(const image::ImageRGBA8& a, const image::ImageRGBA8& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        if (i % 4 != 3) sum += std::abs(int(a.pixels[i]) - int(b.pixels[i]));
    return sum / (3.0 * a.width * a.height);
}

glm::vec2 reportedAt(const renderer::DisplayImages& shown, std::size_t i) {
    return {shown.correspondence.data[4 * i], shown.correspondence.data[4 * i + 1]};
}

bool finite(glm::vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

const renderer::GuardBand kBand = renderer::guardBandFor(kW, kH, 0.1);

// A turn of a few degrees between the source and the display: rotation is exact for a static
// scene seen from one eye, so what is left is bilinear resampling of an aliased 160x90 source
// at every edge and panel seam (7.6 levels, the same as the full-mesh depth warp's, which is
// exact here too). Holding the source shows every surface some 5 px off: 27 levels. The 10 %
// band holds what the turn brings into view.
TEST(LateWarp, RotationOfAStaticSceneMatchesAConventionalRenderAtTheDisplayCamera) {
    const scene::FrameDescription still = stillHangar();
    scene::FrameDescription turned = still;
    turned.camera.yaw = glm::radians(4.0f);
    turned.camera.pitch = glm::radians(-2.0f);
    const auto source = testing::renderSource(still, kW, kH, nullptr, kBand);
    const auto truth = testing::renderFrame(turned, kW, kH);
    const auto rotated = show("rotation", source, turned.camera, 0.0);
    const auto held = show("hold60", source, turned.camera, 0.0);
    const double rotationError = meanAbsError(rotated.colour, truth.colour);
    const double holdError = meanAbsError(held.colour, truth.colour);
    const double warpError = meanAbsError(show("warp-full", source, turned.camera, 0.0).colour, truth.colour);
    RecordProperty("rotation_mae", std::to_string(rotationError));
    RecordProperty("hold_mae", std::to_string(holdError));
    EXPECT_GT(holdError, 15.0) << "the turn must change the view for this test to mean anything";
    EXPECT_LT(rotationError, 0.35 * holdError);
    // Resampling alone: a quarter level either way of the depth warp's floor.
    EXPECT_NEAR(rotationError, warpError, 0.25);
    EXPECT_EQ(testing::blackWhereTruthIsNot(rotated.colour, truth.colour), 0);
}

// The reported source coordinate is where the scene says the surface was, for 95 % of pixels
// within 0.1 px (the rest sit on silhouettes, where float rounding picks a side at this small
// size); and where the turn looks past a source without a band, the claim is NaN while the
// colour is the edge's, never black.
TEST(LateWarp, RotationReportsTheExactSourceCoordinateAndNoneOffTheSource) {
    const scene::FrameDescription still = stillHangar();
    scene::FrameDescription turned = still;
    turned.camera.yaw = glm::radians(-5.0f);
    turned.camera.pitch = glm::radians(3.0f);
    for (const renderer::GuardBand band : {renderer::GuardBand{}, kBand}) {
        const auto source = testing::renderSource(still, kW, kH, nullptr, band);
        const auto truth = testing::renderFrame(turned, kW, kH);
        const auto exact = bench::trueCorrespondence(turned, truth.depth, truth.ids, source.frame->depicts,
                                                     source.images.depth, source.images.ids);
        const auto shown = show("rotation", source, turned.camera, 0.0);
        const float sw = float(source.frame->gbuffer.width()), sh = float(source.frame->gbuffer.height());
        int inside = 0, off = 0, outside = 0, claimedOutside = 0, missedInside = 0;
        for (std::size_t i = 0; i < exact.coords.size(); ++i) {
            const glm::vec2 c = exact.coords[i], r = reportedAt(shown, i);
            // A pixel's ray within half a pixel of the edge may fall either side of it.
            if (c.x > 0.5f && c.y > 0.5f && c.x < sw - 0.5f && c.y < sh - 0.5f) {
                ++inside;
                if (!finite(r))
                    ++missedInside;
                else
                    off += !(glm::length(r - c) < 0.1f);
            } else if (c.x < -0.5f || c.y < -0.5f || c.x > sw + 0.5f || c.y > sh + 0.5f) {
                ++outside;
                claimedOutside += finite(r);
            }
        }
        const std::string label = band == renderer::GuardBand{} ? "no band" : "band";
        EXPECT_GT(inside, kW * kH * 8 / 10) << label;
        EXPECT_EQ(missedInside, 0) << label;
        EXPECT_LE(off, inside / 20) << label << ": pixels 0.1 px or more from their exact source coordinate";
        EXPECT_EQ(claimedOutside, 0) << label << ": claims where the ray leaves the source";
        // Near the image's sides a degree spans twice the pixels it does at the centre, so a
        // 5 degree turn reaches past the 16 px band only at the corners.
        if (band == renderer::GuardBand{})
            EXPECT_GT(outside, kH * 4) << "the turn must look past an unbanded source";
        else
            EXPECT_LT(outside, kW * kH / 200) << "the band covers nearly all of a 5 degree turn";
        EXPECT_EQ(testing::blackWhereTruthIsNot(shown.colour, truth.colour), 0) << label;
    }
}

// Turned right round, every ray points behind the source eye or past its image: no claim
// anywhere, and the edge colour rather than black or a mirrored image.
TEST(LateWarp, RotationClaimsNothingBehindTheSource) {
    const scene::FrameDescription still = stillHangar();
    scene::CameraState back = still.camera;
    back.yaw = glm::radians(180.0f);
    const auto source = testing::renderSource(still, kW, kH);
    const auto shown = show("rotation", source, back, 0.0);
    int claims = 0, black = 0;
    for (std::size_t i = 0; i < shown.ids.data.size(); ++i) {
        claims += finite(reportedAt(shown, i));
        const auto* p = &shown.colour.pixels[4 * i];
        black += p[0] < 8 && p[1] < 8 && p[2] < 8;
    }
    EXPECT_EQ(claims, 0);
    EXPECT_EQ(black, 0);
}

// The object under the reticle follows the turn: aimed at a still box in the source and turned
// off it for the display (and the other way round), the rotated frame's centre shows what a
// render at the display camera shows there, and the held frame does not.
TEST(LateWarp, TheIdUnderTheReticleFollowsTheRotation) {
    scene::FrameDescription withBox = stillHangar();
    scene::ObjectState box;
    box.id = scene::kIdTarget;
    box.shape = scene::Shape::Box;
    box.position = {0.0f, 4.5f, -8.0f};
    box.halfExtents = glm::vec3(0.5f);
    withBox.scene.objects.push_back(box);
    const scene::CameraState onBox = testing::aimedAt(withBox.camera, box.position);
    scene::CameraState offBox = onBox;
    offBox.yaw += glm::radians(8.0f);  // 1.1 m beside the box's centre at 8 m: on the hangar
    const std::size_t centre = static_cast<std::size_t>((kH / 2) * kW + kW / 2);
    for (const auto& [from, to] : {std::pair{onBox, offBox}, std::pair{offBox, onBox}}) {
        scene::FrameDescription source = withBox, display = withBox;
        source.camera = from;
        display.camera = to;
        const auto rendered = testing::renderSource(source, kW, kH, nullptr, kBand);
        const auto truth = testing::renderFrame(display, kW, kH);
        const auto rotated = show("rotation", rendered, to, 0.0);
        const auto held = show("hold60", rendered, to, 0.0);
        ASSERT_NE(truth.ids.data[centre], held.ids.data[centre]) << "the turn must move the box off the reticle";
        EXPECT_EQ(rotated.ids.data[centre], truth.ids.data[centre]);
        // The whole id image, not just one pixel: only silhouette pixels may differ.
        int differ = 0;
        for (std::size_t i = 0; i < truth.ids.data.size(); ++i) differ += rotated.ids.data[i] != truth.ids.data[i];
        EXPECT_LE(differ, kW * kH / 100);
    }
}

// --- Late sources in a moving sequence ---------------------------------------------------

constexpr double kRefreshHz = 120.0;
constexpr int kLagFrames = 10;  // 5 frames of a 60 Hz queue at 120 Hz: 83.3 ms
constexpr int kPeriod = 2;  // 60 Hz sources at 120 Hz

std::unique_ptr<game::BenchSequence> sequence(const std::string& name) {
    game::SequenceConfig config;
    config.aspect = double(kW) / kH;
    return game::makeSequence(name, config);
}

// The source a late method is shown at display frame k, worked out here from the definition
// (the latest 60 Hz source at or before k - 10), independently of the bench's own rule.
int lateSource(int k) {
    const int shown = k - kLagFrames;
    return static_cast<int>(std::floor(double(shown) / kPeriod)) * kPeriod;
}

double meanSquaredError(double psnrDb) { return 255.0 * 255.0 * std::pow(10.0, -psnrDb / 10.0); }

// PSNR of a late method's frames over the display frames `ks` of a sequence, as the bench
// combines them (that of the mean squared error).
std::map<std::string, double> latePsnr(const game::BenchSequence& seq, const std::vector<int>& ks) {
    std::map<std::string, double> mse;
    for (const int k : ks) {
        const double t = k / kRefreshHz;
        const scene::FrameDescription display = seq.at(t);
        const auto truth = testing::renderFrame(display, kW, kH);
        const scene::FrameDescription queued = seq.at(lateSource(k) / kRefreshHz);
        const auto plain = testing::renderSource(queued, kW, kH);
        const auto banded = testing::renderSource(queued, kW, kH, nullptr, kBand);
        mse["late-hold"] +=
            meanSquaredError(image::psnr(show("late-hold", plain, display.camera, t).colour, truth.colour));
        for (const std::string method : {"late-rotation", "late-depth"})
            mse[method] += meanSquaredError(image::psnr(show(method, banded, display.camera, t).colour, truth.colour));
    }
    std::map<std::string, double> psnr;
    for (const auto& [method, sum] : mse) psnr[method] = 10.0 * std::log10(255.0 * 255.0 / (sum / double(ks.size())));
    return psnr;
}

// 83 ms of a turning camera move the whole view several degrees: late warp by rotation takes
// most of that error away, and the warp with depth and velocities also moves the target, which
// rotation leaves where the lagged frame had it.
TEST(LateWarp, OnMovingSequencesLateWarpBeatsTheLaggedFrame) {
    const std::vector<int> ks = {37, 74, 111, 148, 185, 222};
    for (const std::string name : {"pan", "track"}) {
        const auto psnr = latePsnr(*sequence(name), ks);
        for (const auto& [method, db] : psnr) RecordProperty(name + "_" + method + "_psnr", std::to_string(db));
        EXPECT_GT(psnr.at("late-rotation"), psnr.at("late-hold") + 3.0) << name;
        EXPECT_GT(psnr.at("late-depth"), psnr.at("late-hold") + 3.0) << name;
        EXPECT_GE(psnr.at("late-depth"), psnr.at("late-rotation") - 0.1) << name;
    }
}

std::vector<std::string> splitCsv(const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    return cells;
}

// The bench itself shows a late method the source 83.3 ms before each display frame: its
// late-hold rows are the frames worked out above from the definition, its late warps beat
// them, and the summary says how late the sources are.
TEST(LateWarp, TheBenchShowsLateMethodsTheQueuedSource) {
    bench::BenchOptions options;
    options.width = kW;
    options.height = kH;
    options.refreshHz = kRefreshHz;
    options.sequences = {"pan"};
    options.methods = {"hold60", "late-hold", "late-rotation", "late-depth"};
    options.framesPerSequence = 4;
    options.repeats = 1;
    options.shadingSweep = {0};
    options.outDir = testing::testOutputDir() + "/late-warp-bench";
    renderer::DataPaths paths = testing::sourceDataPaths();
    paths.analysisDir = options.outDir + "/no-plot";  // the plot is not what is tested here
    std::ostringstream summary, progress;
    bench::runBench(options, paths, testing::glContext().info(), summary, progress);
    EXPECT_NE(summary.str().find("| pan | late-rotation | 60 Hz, 83.3 ms late |"), std::string::npos) << summary.str();

    std::ifstream csv(options.outDir + "/bench.csv");
    std::string line;
    std::getline(csv, line);
    const auto header = splitCsv(line);
    const auto column = [&](const std::string& name) {
        return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
    };
    std::map<std::string, std::vector<std::pair<int, double>>> rows;  // method -> (frame, PSNR)
    while (std::getline(csv, line)) {
        const auto cells = splitCsv(line);
        rows[cells.at(column("method"))].emplace_back(std::stoi(cells.at(column("frame"))),
                                                      std::stod(cells.at(column("psnr_db"))));
    }
    ASSERT_EQ(rows["late-hold"].size(), 4u);
    const auto pan = sequence("pan");
    double sum[4] = {};
    for (std::size_t j = 0; j < rows["late-hold"].size(); ++j) {
        const auto [k, psnr] = rows["late-hold"][j];
        const auto truth = testing::renderFrame(pan->at(k / kRefreshHz), kW, kH);
        const auto queued = testing::renderSource(pan->at(lateSource(k) / kRefreshHz), kW, kH);
        const double expected =
            image::psnr(show("late-hold", queued, pan->at(k / kRefreshHz).camera, k / kRefreshHz).colour, truth.colour);
        EXPECT_NEAR(psnr, expected, 0.01) << "frame " << k;
        const std::string methods[4] = {"hold60", "late-hold", "late-rotation", "late-depth"};
        for (int m = 0; m < 4; ++m) sum[m] += meanSquaredError(rows[methods[m]].at(j).second);
    }
    // hold60 (no queue) < late-hold in error; the late warps take most of the lag's error away.
    EXPECT_LT(sum[0], sum[1]);
    EXPECT_LT(sum[2], 0.5 * sum[1]);
    EXPECT_LT(sum[3], 0.5 * sum[1]);
}

}  // namespace
}  // namespace warplab
