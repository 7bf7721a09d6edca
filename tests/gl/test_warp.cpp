// Warp extrapolation (seed 004 sections 4.2.2-4.3.5, 5.2.4-5.2.6) on cases whose answer is
// known, and on the hard cases, where it must stay finite and bounded.
#include <algorithm>
#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "bench/ground_truth.h"
#include "bench/sequences.h"
#include "gl/gl_test_support.h"
#include "upconvert/warp.h"
#include "scene/camera.h"

namespace warplab {
namespace {

constexpr int kW = 192;
constexpr int kH = 108;
const std::vector<std::string> kWarps = {"warp-full", "warp-nofix", "warp-sparse4", "warp-sparse8", "warp-sparse16"};

scene::FrameDescription shooterAt(double t, std::uint64_t seed = 4, double speed = 3.0) {
    const auto shooter = testing::shooterScene(kW, kH, seed, speed);
    return {shooter.restingCamera(), shooter.snapshot(t)};
}

renderer::DisplayImages warp(const std::string& method, const testing::RenderedSource& source,
                             const scene::CameraState& camera, double displayTime) {
    return testing::produceFrom(method, source, camera, displayTime, kW, kH);
}

std::vector<glm::vec2> reported(const renderer::DisplayImages& shown) {
    std::vector<glm::vec2> out;
    for (std::size_t i = 0; i < shown.ids.data.size(); ++i)
        out.emplace_back(shown.correspondence.data[4 * i], shown.correspondence.data[4 * i + 1]);
    return out;
}

// dt = 0 from the source camera: the mesh lands where it started, so the warp reproduces the
// source except where a pixel centre lies within rounding of a triangle edge and takes the
// neighbouring triangle's bilinear colour (a few pixels, a few levels).
TEST(Warp, ZeroDtFromTheSourceCameraReproducesTheSource) {
    const auto source = testing::renderSource(shooterAt(1.0), kW, kH);
    for (const auto& method : kWarps) {
        const auto shown = warp(method, source, source.frame->depicts.camera, 1.0);
        const auto diff = image::compareImages(source.images.colour, shown.colour, 8);
        EXPECT_LE(diff.meanChannelDiff, 0.05) << method;
        EXPECT_LE(diff.pixelsOverThreshold, kW * kH / 1000) << method;
        EXPECT_EQ(shown.ids.data, source.images.ids.data) << method;
    }
}

// Rotation alone reveals nothing new inside the old view (no disocclusion): apart from the
// strip that enters at the edge, every displayed pixel must come from exactly the source
// pixel the scene says: within 0.1 px for 95% of them at this small size, where edges are a
// large share of the pixels; the rest sit on silhouettes, where the rasteriser picks a side. Colours then match a
// fresh render up to bilinear resampling, which softens the one-pixel panel seams: a mean
// of several levels, not zero.
TEST(Warp, CameraRotationOfAStaticSceneMatchesGroundTruthAlmostEverywhere) {
    scene::FrameDescription still = shooterAt(0.0);
    still.scene.objects.clear();
    scene::FrameDescription turned = still;
    turned.camera.yaw = glm::radians(4.0f);
    turned.camera.pitch = glm::radians(-2.0f);
    const auto source = testing::renderSource(still, kW, kH);
    const auto truth = testing::renderSource(turned, kW, kH);
    const auto exact = bench::trueCorrespondence(turned, truth.images.depth, truth.images.ids, still,
                                                 source.images.depth, source.images.ids);
    for (const auto& method : kWarps) {
        const auto shown = warp(method, source, turned.camera, 0.0);
        const auto coords = reported(shown);
        double sum = 0.0;
        int covered = 0, off = 0, offHalf = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const std::size_t i = static_cast<std::size_t>(y * kW + x);
                const glm::vec2 c = exact.coords[i];
                if (c.x < 1.0f || c.y < 1.0f || c.x > kW - 1.0f || c.y > kH - 1.0f) continue;  // entered the view
                ++covered;
                off += !(glm::length(coords[i] - c) < 0.1f);
                offHalf += !(glm::length(coords[i] - c) < 0.5f);
                int worst = 0;
                for (int k = 0; k < 3; ++k)
                    worst = std::max(worst, std::abs(shown.colour.at(x, y)[k] - truth.images.colour.at(x, y)[k]));
                sum += worst;
            }
        ASSERT_GT(covered, kW * kH * 8 / 10);
        EXPECT_LE(off, covered / 20) << method << ": pixels whose source is 0.1 px or more from the exact one";
        // A turn opens no sheet, so no silhouette may be recoloured: 99.5 % within
        // half a pixel (the old source-only sheet rule left warp-full at 97.8 % on `pan`).
        EXPECT_LE(offHalf * 1000, covered * 5)
            << method << ": " << offHalf << " of " << covered << " pixels 0.5 px or more from their exact source";
        EXPECT_LE(sum / covered, 12.0) << method;
        RecordProperty(method + "_rotation_off", off);
    }
}

glm::dvec2 centroid(const image::ImageU32& ids, std::uint32_t id, int& count) {
    glm::dvec2 sum(0.0);
    count = 0;
    for (int y = 0; y < ids.height; ++y)
        for (int x = 0; x < ids.width; ++x)
            if (ids.at(x, y) == id) sum += glm::dvec2(x + 0.5, y + 0.5), ++count;
    return count ? sum / double(count) : sum;
}

// A sphere at constant velocity, warped dt ahead, lands where a fresh render puts it. Not
// asked of warp-nofix: its rubber sheets take the sphere's id on half their width, which is
// the very artefact the fix exists for.
TEST(Warp, MovingSphereLandsWhereGroundTruthHasIt) {
    const testing::SpherePass pass =
        testing::sphereMovingAcross(shooterAt(0.0), {4.0f, 1.5f, 0.0f}, {0.0f, 4.3f, -6.0f}, 7);
    const scene::FrameDescription& a = pass.start;
    const scene::FrameDescription& b = pass.later;
    const double dt = pass.dt;
    const auto source = testing::renderSource(a, kW, kH);
    const auto truth = testing::renderSource(b, kW, kH);
    int truthCount = 0;
    const glm::dvec2 expected = centroid(truth.images.ids, scene::kIdTarget, truthCount);
    ASSERT_GT(truthCount, 100);
    for (const auto& method : kWarps) {
        if (method == "warp-nofix") continue;
        int count = 0;
        const glm::dvec2 got = centroid(warp(method, source, b.camera, dt).ids, scene::kIdTarget, count);
        EXPECT_NEAR(got.x, expected.x, 0.5) << method;
        EXPECT_NEAR(got.y, expected.y, 0.5) << method;
        EXPECT_GT(count, truthCount / 2) << method;  // the mask is the sphere, not a speck of it
    }
}

// No cracks: wherever the full mesh puts a source pixel, each sparse mesh does too. Where the
// warp folds the mesh (at moving silhouettes) the full mesh and the tessellator may split a
// folded quad along different diagonals and so cover slightly different pixels; that is not
// a crack, so pixels whose full-mesh neighbours come from sources more than 2 px apart are
// left out. A crack -- a T-junction between patches -- opens a line of pixels inside smooth
// regions. Allowed: one pixel in 100,000, for a sample point lying exactly (to float
// rounding) on an edge that the two meshes build from differently rounded vertices.
TEST(Warp, SparseMeshesCoverEverythingTheFullMeshCovers) {
    game::SequenceConfig config;
    config.aspect = double(kW) / kH;
    auto smooth = [](const std::vector<glm::vec2>& c, int x, int y) {
        const glm::vec2 here = c[static_cast<std::size_t>(y * kW + x)];
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = x + dx, ny = y + dy;
                if (nx < 0 || ny < 0 || nx >= kW || ny >= kH) continue;
                const glm::vec2 n = c[static_cast<std::size_t>(ny * kW + nx)];
                if (!(glm::length(n - here) < 2.0f)) return false;  // NaN neighbours count as folds too
            }
        return true;
    };
    int checked = 0, totalCracks = 0;
    for (const auto& name : game::sequenceNames()) {
        const auto sequence = game::makeSequence(name, config);
        for (int frame : {8, 11, 15}) {  // phases 0 (source), 3 and 7 (a whole period ahead)
            const auto source = testing::renderSource(sequence->at(8 / 120.0), kW, kH);
            const auto display = sequence->at(frame / 120.0);
            const auto full = reported(warp("warp-full", source, display.camera, display.scene.time));
            for (const std::string method : {"warp-sparse4", "warp-sparse8", "warp-sparse16"}) {
                const auto sparse = reported(warp(method, source, display.camera, display.scene.time));
                int cracks = 0;
                for (int y = 0; y < kH; ++y)
                    for (int x = 0; x < kW; ++x) {
                        const std::size_t i = static_cast<std::size_t>(y * kW + x);
                        if (!std::isfinite(full[i].x) || !smooth(full, x, y)) continue;
                        ++checked;
                        cracks += !std::isfinite(sparse[i].x);
                    }
                EXPECT_LE(cracks, 1) << method << " on " << name << " frame " << frame;
                totalCracks += cracks;
            }
        }
    }
    EXPECT_GT(checked, 5 * 3 * 3 * kW * kH / 2);
    EXPECT_LE(totalCracks, checked / 100000 + 1);
}

// Mean absolute error over the truly disoccluded pixels (hidden in the source, not the border)
// of each method, over the frames of a sequence that have any: 9 sources 1/3 s apart, each
// warped 3, 5 and 7 display frames ahead. Every method warps the same source to the same frame.
std::map<std::string, double> disoccludedErrors(const std::vector<std::string>& methods,
                                                const std::string& sequenceName) {
    game::SequenceConfig config;
    config.aspect = double(kW) / kH;
    const auto sequence = game::makeSequence(sequenceName, config);
    std::map<std::string, double> sums;
    int frames = 0;
    for (int source = 0; source < 3 * 120; source += 40) {
        const auto src = testing::renderSource(sequence->at(source / 120.0), kW, kH);
        for (int phase : {3, 5, 7}) {
            const auto display = sequence->at((source + phase) / 120.0);
            const auto truth = testing::renderSource(display, kW, kH);
            const auto exact = bench::trueCorrespondence(display, truth.images.depth, truth.images.ids,
                                                         src.frame->depicts, src.images.depth, src.images.ids);
            const auto disoccluded = bench::unseenMasks({&exact}).occluded;  // true disocclusions, not the border
            if (std::none_of(disoccluded.begin(), disoccluded.end(), [](std::uint8_t m) { return m != 0; })) continue;
            for (const auto& method : methods)
                sums[method] += bench::maskedMeanAbsoluteError(
                    warp(method, src, display.camera, display.scene.time).colour, truth.images.colour, disoccluded);
            ++frames;
        }
    }
    EXPECT_GT(frames, 10) << sequenceName;
    for (auto& [method, sum] : sums) sum /= frames;
    return sums;
}

// Where a moving object uncovers the background (a sphere crossing a wall in `spheres`, the
// camera's parallax in `translate` and `track`), the fix fills the opened sheet from the
// background side: closer to the truth there than the naive warp's smear. Every mesh takes the
// same fix, so every sparse mesh must fill the same sheets as the full mesh: a patch
// re-densified in one direction only used to stretch one-pixel-wide slivers across the jump,
// which the fix does not take for sheets (measured then on `translate`: sparse4 31.5 and
// sparse8 29.9 against the full mesh's 27.2).
TEST(Warp, DisocclusionFixLowersTheErrorWhereTheBackgroundIsRevealed) {
    const std::vector<std::string> methods = {"warp-full", "warp-nofix", "warp-sparse4", "warp-sparse8",
                                              "warp-sparse16"};
    for (const std::string sequence : {"translate", "track", "spheres"}) {
        auto error = disoccludedErrors(methods, sequence);
        const double full = error["warp-full"], naive = error["warp-nofix"];
        EXPECT_LT(full, naive) << sequence;
        for (const std::string sparse : {"warp-sparse4", "warp-sparse8", "warp-sparse16"}) {
            EXPECT_LT(error[sparse], naive) << sparse << " on " << sequence;
            // Within 5 % of the full mesh's error: a re-densified patch is the full mesh's grid,
            // but the tessellator splits its quads along its own diagonals, and a sheet split
            // the other way recolours a slightly different pixel set (measured: from 3 % below
            // to 1.3 % above warp-full on llvmpipe).
            EXPECT_LE(error[sparse], 1.05 * full) << sparse << " on " << sequence << " against warp-full's " << full;
        }
        std::string recorded;
        for (const auto& method : methods) recorded += method + " " + std::to_string(error[method]) + "; ";
        RecordProperty(sequence + "_disoccluded_mae", recorded);
    }
}

// The sparse meshes once found each patch's flags by gl_PrimitiveID, which llvmpipe
// restarts every 1024 patches of a draw, so every later patch took another's flags and a moving
// silhouette there could stay two triangles stretched across the background. At 640x360 sparse4
// draws 14,651 patches and sparse8 3,726; on this frame (the target crossing the hallway, the
// camera following it) they lost 0.49 and 0.09 dB against warp-full. Every discontinuity is
// re-densified, so a sparse mesh must now warp as well as the full mesh: within 0.05 dB. The
// meshes differ only in how a quad is split into triangles (measured since: 0.007 to 0.03 dB
// better than warp-full). Not at 960x540 and above on llvmpipe: see the note in
// warp_sparse.tesc about sparse16.
TEST(Warp, SparseMeshesWarpLargeFramesAsWellAsTheFullMesh) {
    constexpr int w = 640, h = 360;
    const auto shooter = testing::shooterScene(w, h, 1, 6.0);
    auto at = [&](double t) {
        scene::FrameDescription frame{shooter.restingCamera(), shooter.snapshot(t)};
        frame.camera = testing::aimedAt(frame.camera, frame.scene.objects.front().position);
        return frame;
    };
    const auto source = testing::renderSource(at(1.0), w, h);
    const scene::FrameDescription display = at(1.0 + 7.0 / 120.0);
    const auto truth = testing::renderFrame(display, w, h);
    renderer::UpconversionInput input;
    input.displayTime = display.scene.time;
    input.camera = display.camera;
    input.previous = source.frame.get();
    const double full = image::psnr(testing::produceFrame("warp-full", input, w, h).colour, truth.colour);
    for (const std::string method : {"warp-sparse4", "warp-sparse8", "warp-sparse16"}) {
        const double db = image::psnr(testing::produceFrame(method, input, w, h).colour, truth.colour);
        EXPECT_GE(db, full - 0.05) << method << " against warp-full's " << full << " dB";
        RecordProperty(method + "_large_frame_psnr", std::to_string(db) + " (warp-full " + std::to_string(full) + ")");
    }
}

// A few pixels may still be black where the truth is not: a dark source pixel sampled where a
// bright one belongs. Measured: at most 3 of 20736 (the sky case) with the border fill.
constexpr double kBlackShare = 0.001;

// Hard cases: the output stays finite, and what it covers stays near the exact
// correspondence -- no spikes or sheets across the screen.
void expectBounded(const std::string& label, const scene::FrameDescription& from, const scene::FrameDescription& to,
                   double maxWrongShare) {
    const auto source = testing::renderSource(from, kW, kH);
    const auto truth = testing::renderSource(to, kW, kH);
    const auto exact = bench::trueCorrespondence(to, truth.images.depth, truth.images.ids, from, source.images.depth,
                                                 source.images.ids);
    for (const auto& method : kWarps) {
        const auto shown = warp(method, source, to.camera, to.scene.time - from.scene.time + from.scene.time);
        const auto coords = reported(shown);
        int covered = 0, wrong = 0;
        for (std::size_t i = 0; i < coords.size(); ++i) {
            ASSERT_FALSE(std::isinf(coords[i].x) || std::isinf(coords[i].y)) << label << " " << method;
            if (std::isnan(coords[i].x)) continue;
            ASSERT_TRUE(std::isfinite(coords[i].y)) << label << " " << method;
            ++covered;
            const glm::vec2 e = exact.coords[i];
            wrong += !(glm::length(coords[i] - e) < 2.0f);
        }
        EXPECT_LE(wrong, maxWrongShare * std::max(covered, 1))
            << label << " " << method << ": " << wrong << " of " << covered << " covered pixels off by 2+ px";
        // A warp that draws nothing is finite and never wrong: it must also cover what the
        // source saw. Pixels whose surface is visible inside the source (exact correspondence) are
        // the ones the mesh can reach; at least 97% of them must be covered -- the rest are
        // silhouette pixels where a fold or the disocclusion fix hands the pixel elsewhere.
        int reachable = 0, reached = 0;
        for (std::size_t i = 0; i < coords.size(); ++i) {
            const glm::vec2 e = exact.coords[i];
            if (!(e.x >= 1.0f && e.y >= 1.0f && e.x <= kW - 1.0f && e.y <= kH - 1.0f)) continue;  // not in the source
            ++reachable;
            reached += std::isfinite(coords[i].x);
        }
        ASSERT_GT(reachable, 0) << label;  // else the coverage check below would be vacuous
        EXPECT_GE(reached, 0.97 * reachable) << label << " " << method << ": " << reached << " of " << reachable
                                             << " pixels visible in the source are covered";
        // ...and nothing is left black, including what turned into view: the clear
        // colour is black, the scene has hardly any black, so count black where the truth is not dark.
        const int black = testing::blackWhereTruthIsNot(shown.colour, truth.images.colour);
        EXPECT_LE(black, kBlackShare * double(coords.size()))
            << label << " " << method << ": " << black << " black pixels";
    }
}

// A sparse mesh subdivides a patch only where this warp moves its pixels apart across a jump:
// for the identity warp and a camera turn nothing does, so every patch stays two triangles
// (subdividing every depth jump made sparse8 draw 524k triangles at 1080p, 0.31 of the full
// mesh's pass); behind a moving sphere the patches it uncovers must subdivide.
TEST(Warp, SparseMeshesSubdivideOnlyWhereTheWarpOpensAJump) {
    constexpr int w = 320, h = 180;
    auto shooter = testing::shooterScene(w, h, 1, 6.0);
    const scene::FrameDescription at{shooter.restingCamera(), shooter.snapshot(0.3)};
    const auto source = testing::renderSource(at, w, h);
    for (const int n : {4, 8, 16}) {
        auto method = renderer::makeMethod("warp-sparse" + std::to_string(n), testing::sourceDataPaths());
        renderer::DisplayFrame display(w, h);
        const double patches = double((w + 1 + n - 1) / n) * double((h + 1 + n - 1) / n);
        renderer::UpconversionInput input;
        input.previous = source.frame.get();
        input.displayTime = at.scene.time;
        input.camera = at.camera;
        method->produce(input, display);
        EXPECT_EQ(method->lastTriangleCount(), 2 * patches) << "identity, sparse" << n;
        input.camera.yaw += 0.05f;  // a 3 degree turn moves every depth alike
        method->produce(input, display);
        EXPECT_EQ(method->lastTriangleCount(), 2 * patches) << "turn, sparse" << n;
        input.camera = at.camera;
        input.displayTime = at.scene.time + 7.0 / 120.0;  // the target moves 0.35 m across the wall
        method->produce(input, display);
        // Its silhouette's patches now subdivide to single pixels: n * n * 2 triangles each.
        EXPECT_GT(method->lastTriangleCount(), 2 * patches + 4.0 * n * n) << "moving target, sparse" << n;
    }
}

// Subdivided nearly everywhere, a sparse mesh warps as well as the full mesh, whatever llvmpipe's
// tessellator can number at once: Mesa 22.3 numbers the tessellated vertices of a run of
// patches with 16 bits, and 227 dense 16 x 16 patches (809 of 8 x 8) already pass 65535. Drawn
// in one call, the runs past that joined the wrong vertices: measured against the truth, 18.5 dB
// for sparse16 and 21.8 for sparse8 here, against warp-full's 27.1. Every relative depth change
// counting as a jump, and the camera moving 2.5 m forward, spread nearly every patch's
// neighbours apart.
TEST(Warp, ASparseMeshSubdividedEverywhereWarpsAsWellAsTheFullMesh) {
    constexpr int w = 640, h = 360;
    auto shooter = testing::shooterScene(w, h, 1, 6.0);
    const scene::FrameDescription at{shooter.restingCamera(), shooter.snapshot(0.3)};
    const auto source = testing::renderSource(at, w, h);
    scene::FrameDescription display{at.camera, shooter.snapshot(0.3 + 7.0 / 120.0)};
    display.camera.eye += 2.5f * scene::forwardDirection(at.camera.yaw, at.camera.pitch);
    display.camera.yaw += 0.03f;
    const auto truth = testing::renderFrame(display, w, h);
    renderer::UpconversionInput input;
    input.previous = source.frame.get();
    input.displayTime = display.scene.time;
    input.camera = display.camera;
    renderer::WarpSettings everywhere;
    everywhere.depthJump = 0.0f;
    everywhere.velocityJump = 0.0f;
    const double full = image::psnr(testing::produceFrame("warp-full", input, w, h).colour, truth.colour);
    for (const int n : {8, 16}) {
        everywhere.patchSize = n;
        auto sparse = renderer::makeWarp(testing::sourceDataPaths(), "warp-sparse" + std::to_string(n), everywhere);
        renderer::DisplayFrame frame(w, h);
        sparse->produce(input, frame);
        // Nearly every patch dense (2 n^2 triangles): the draw is far past 65535 vertices.
        const double patches = double((w + 1 + n - 1) / n) * double((h + 1 + n - 1) / n);
        EXPECT_GT(sparse->lastTriangleCount(), 0.9 * patches * 2.0 * n * n) << "sparse" << n;
        const double db = image::psnr(renderer::readBack(frame).colour, truth.colour);
        EXPECT_GE(db, full - 0.1) << "sparse" << n << " against warp-full's " << full << " dB";
    }
}

TEST(WarpHardCases, SkyAndFarPlane) {
    scene::FrameDescription a = shooterAt(0.0);
    a.camera.yaw = 0.0f;  // the open far door fills the centre
    scene::FrameDescription b = a;
    b.camera.yaw = glm::radians(3.0f);
    b.camera.pitch = glm::radians(2.0f);
    expectBounded("sky", a, b, 0.03);
}

TEST(WarpHardCases, GeometryAtTheNearPlane) {
    scene::FrameDescription a = shooterAt(0.0);
    a.camera.eye = {7.4f, 4.0f, -1.0f};  // a pipe and a panel a few centimetres away
    a.camera.yaw = glm::radians(75.0f);
    scene::FrameDescription b = a;
    b.camera.yaw = glm::radians(78.0f);
    expectBounded("near plane", a, b, 0.05);
}

TEST(WarpHardCases, GrazingSurfaces) {
    scene::FrameDescription a = shooterAt(0.0);
    a.camera.eye.y = 0.7f;  // just above the deck, looking along it
    a.camera.pitch = glm::radians(-3.0f);
    scene::FrameDescription b = a;
    b.camera.yaw = glm::radians(2.0f);
    expectBounded("grazing", a, b, 0.06);
}

TEST(WarpHardCases, CameraTurned90DegreesBetweenSourceAndDisplay) {
    scene::FrameDescription a = shooterAt(0.0);
    scene::FrameDescription b = a;
    b.camera.yaw = glm::radians(90.0f);
    expectBounded("90 degrees", a, b, 0.02);
}

TEST(WarpHardCases, DtOfAWholeSourcePeriod) {
    expectBounded("dt 1/15 s", shooterAt(0.0, 9, 6.0), shooterAt(1.0 / 15.0, 9, 6.0), 0.03);
}

TEST(WarpHardCases, VelocityPointingOffScreen) {
    scene::FrameDescription a = shooterAt(0.0);
    a.scene.objects.front().position = {6.5f, 4.5f, -7.0f};
    a.scene.objects.front().velocity = {60.0f, 0.0f, 40.0f};  // out of the view and behind the eye
    scene::FrameDescription b = a;
    b.scene.time = 1.0 / 15.0;
    b.scene.objects.front().position += a.scene.objects.front().velocity * (1.0f / 15.0f);
    expectBounded("off screen", a, b, 0.03);
}

// A pure 3 degree turn of the static scene (the case of `warplab render
// --method warp-full --source-yaw 0 --yaw 3`) at the bench's quick size. What turned into view
// was off-screen in the source; it must be filled from the nearest source edge, never black.
TEST(Warp, CameraTurnLeavesNoPixelBlack) {
    constexpr int w = 320, h = 180;
    auto frame = testing::shooterScene(w, h, 1, 2.0);
    scene::FrameDescription still{frame.restingCamera(), frame.snapshot(0.0)};
    still.scene.objects.clear();
    still.camera.yaw = 0.0f;
    still.camera.pitch = 0.0f;
    scene::FrameDescription turned = still;
    turned.camera.yaw = glm::radians(3.0f);
    const auto source = testing::renderSource(still, w, h);
    const auto truth = testing::renderSource(turned, w, h);
    ASSERT_LE(testing::blackWhereTruthIsNot(source.images.colour, truth.images.colour), w * h / 1000);
    for (const std::string method : {"warp-full", "warp-nofix", "warp-sparse8", "warp-sparse16"}) {
        renderer::UpconversionInput input;
        input.displayTime = 0.0;
        input.camera = turned.camera;
        input.previous = source.frame.get();
        const auto shown = testing::produceFrame(method, input, w, h);
        int meshCovered = 0;
        for (std::size_t i = 0; i < shown.ids.data.size(); ++i)
            meshCovered += std::isfinite(shown.correspondence.data[4 * i]);
        // The strip that turned into view (about 3/60 of the width) is the fill's, not the mesh's.
        EXPECT_LT(meshCovered, w * h * 97 / 100) << method << ": the turn should bring uncovered pixels into view";
        EXPECT_EQ(testing::blackWhereTruthIsNot(shown.colour, truth.images.colour), 0) << method;
        const double db = image::psnr(shown.colour, truth.images.colour);
        // Floor: measured 26.1 dB (warp-full, warp-sparse16) to 26.7 dB (warp-nofix) on llvmpipe;
        // with the band left black it was about 20 dB. 25 dB leaves a margin for another rasteriser's
        // aliasing of the panel seams (the interior error is mostly aliasing: docs/bench.md, "Warp quality, part 4").
        EXPECT_GE(db, 25.0) << method;
        RecordProperty(method + "_turn_psnr", std::to_string(db));
    }
}

// A warp with nothing to do (dt = 0, the source's own camera) must give back its source. The
// disocclusion fix used to decide sheets from the source alone and recoloured every
// silhouette's rim even here: 69 / 51.7 / 44.5 dB at 320 / 640 / 960 wide. It now fixes only
// sheets that open in the target view. 60 dB leaves room for a rasteriser's rounding of the
// mesh (measured: exact at 320, 98 and 92 dB at 640 and 960 for warp-full on llvmpipe).
TEST(Warp, IdentityWarpReproducesItsSource) {
    for (const int w : {320, 640, 960}) {
        const int h = w * 9 / 16;
        auto frame = testing::shooterScene(w, h, 1, 2.0);
        const scene::FrameDescription at{frame.restingCamera(), frame.snapshot(0.3)};
        const auto source = testing::renderSource(at, w, h);
        for (const std::string method : {"warp-full", "warp-sparse4", "warp-sparse8", "warp-sparse16"}) {
            renderer::UpconversionInput input;
            input.displayTime = at.scene.time;
            input.camera = at.camera;
            input.previous = source.frame.get();
            const auto shown = testing::produceFrame(method, input, w, h);
            const double db = image::psnr(shown.colour, source.images.colour);
            EXPECT_GE(db, 60.0) << method << " at " << w << "x" << h;
            RecordProperty(method + "_identity_psnr_" + std::to_string(w), std::to_string(db));
        }
    }
}

}  // namespace
}  // namespace warplab
