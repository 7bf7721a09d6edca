// Warp extrapolation by forward splatting ("warp-splat", compute): the mesh warps' equations
// with an atomic depth test instead of a rasterised mesh. Checked against its source, against
// warp-full, and against the scene's exact correspondences.
#include <algorithm>
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "bench/ground_truth.h"
#include "gl/gl_test_support.h"
#include "upconvert/warp.h"
#include "upconvert/warp_splat.h"
#include "scene/camera.h"

namespace warplab {
namespace {

const std::string kMethod = "warp-splat";

scene::FrameDescription shooterAt(int w, int h, double t, std::uint64_t seed = 4, double speed = 3.0) {
    const auto shooter = testing::shooterScene(w, h, seed, speed);
    return {shooter.restingCamera(), shooter.snapshot(t)};
}

renderer::UpconversionInput from(const testing::RenderedSource& source, const scene::CameraState& camera,
                                 double displayTime) {
    renderer::UpconversionInput input;
    input.displayTime = displayTime;
    input.camera = camera;
    input.previous = source.frame.get();
    return input;
}

glm::vec2 reportedAt(const renderer::DisplayImages& shown, std::size_t i) {
    return {shown.correspondence.data[4 * i], shown.correspondence.data[4 * i + 1]};
}

bool claimed(const renderer::DisplayImages& shown, std::size_t i) {
    const glm::vec2 c = reportedAt(shown, i);
    return std::isfinite(c.x) && std::isfinite(c.y);
}

// A splat whose holes stay holes: no background search, so a pixel nothing was splatted onto
// keeps a NaN correspondence (it takes the border fill's colour) and can be counted.
renderer::DisplayImages splatWithoutHoleFill(const renderer::UpconversionInput& input, int w, int h) {
    static std::unique_ptr<renderer::UpconversionMethod> method = [] {
        testing::glContext();
        renderer::WarpSplatSettings settings;
        settings.holeReach = 0.0f;
        return renderer::makeWarpSplat(testing::sourceDataPaths(), kMethod, settings);
    }();
    renderer::DisplayFrame frame(w, h);
    method->produce(input, frame);
    return renderer::readBack(frame);
}

// dt = 0 from the source camera: every source pixel centre lands on its own display pixel
// centre (to rounding), so the source comes back bit for bit -- colours, ids -- and every pixel
// claims its own centre. At the sizes of the mesh warps' identity test, where warp-full keeps
// 60 dB only (a rasteriser's rounding of the mesh).
TEST(WarpSplat, IdentityWarpReproducesItsSourceExactly) {
    for (const int w : {320, 640}) {
        const int h = w * 9 / 16;
        const auto at = shooterAt(w, h, 0.3, 1, 2.0);
        const auto source = testing::renderSource(at, w, h);
        const auto shown = testing::produceFrom(kMethod, source, at.camera, at.scene.time, w, h);
        EXPECT_EQ(shown.colour.pixels, source.images.colour.pixels) << w << "x" << h;
        EXPECT_EQ(shown.ids.data, source.images.ids.data) << w << "x" << h;
        int off = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const glm::vec2 c = reportedAt(shown, static_cast<std::size_t>(y * w + x));
                off += !(glm::length(c - glm::vec2(x + 0.5f, y + 0.5f)) < 1e-3f);
            }
        EXPECT_EQ(off, 0) << w << "x" << h << ": pixels not claiming their own centre";
    }
}

// A guard band is rendered beyond the displayed view at the same pitch: the identity warp of a
// banded source shows the band's inside, as the holds do.
TEST(WarpSplat, IdentityWarpOfABandedSourceShowsItsInside) {
    constexpr int w = 320, h = 180;
    const auto at = shooterAt(w, h, 0.3, 1, 2.0);
    const renderer::GuardBand band = renderer::guardBandFor(w, h, 0.1);
    const auto source = testing::renderSource(at, w, h, nullptr, band);
    const auto shown = testing::produceFrom(kMethod, source, at.camera, at.scene.time, w, h);
    const auto held = testing::produceFrom("hold120", source, at.camera, at.scene.time, w, h);
    EXPECT_EQ(shown.colour.pixels, held.colour.pixels);
    EXPECT_EQ(shown.ids.data, held.ids.data);
}

// A pure camera rotation: the splat interpolates the same warped grid as warp-full's mesh,
// split along the same diagonals, so both report the same source coordinate -- within 0.1 px
// on 99 % of the pixels both claim (the rest sit on silhouettes, where the rasteriser's tie
// rules and the splat's depth ties pick different sides) -- and claim the same pixels.
TEST(WarpSplat, CameraRotationMatchesWarpFullsCorrespondences) {
    constexpr int w = 320, h = 180;
    scene::FrameDescription still = shooterAt(w, h, 0.0);
    still.scene.objects.clear();
    scene::FrameDescription turned = still;
    turned.camera.yaw += glm::radians(4.0f);
    turned.camera.pitch += glm::radians(-2.0f);
    const auto source = testing::renderSource(still, w, h);
    const auto full = testing::produceFrom("warp-full", source, turned.camera, 0.0, w, h);
    const auto splat = testing::produceFrom(kMethod, source, turned.camera, 0.0, w, h);
    int both = 0, onlyFull = 0, onlySplat = 0, off = 0;
    for (std::size_t i = 0; i < full.ids.data.size(); ++i) {
        const bool f = claimed(full, i), s = claimed(splat, i);
        onlyFull += f && !s;
        onlySplat += s && !f;
        if (!(f && s)) continue;
        ++both;
        off += !(glm::length(reportedAt(full, i) - reportedAt(splat, i)) < 0.1f);
    }
    ASSERT_GT(both, w * h * 8 / 10);
    EXPECT_LE(off * 100, both) << off << " of " << both << " pixels 0.1 px or more from warp-full's source";
    EXPECT_LE((onlyFull + onlySplat) * 100, both)
        << onlyFull << " claimed by warp-full only, " << onlySplat << " by the splat only";
    RecordProperty("rotation_off_0p1", off);
}

// Whether the source shows no depth jump around source point `at` (top-down pixels): its 3 x 3
// pixels' distances from the eye within the disocclusion fix's sheet ratio of each other. Where
// they are not, the fix's rule may call the triangles across the jump a sheet once the warp
// opens it (a recessed seam between panels, a face seen edge-on that a step turns to the view):
// those pixels are disocclusions, the resolve's to fill, not cracks.
bool smoothInSource(const renderer::GBufferImages& source, const scene::CameraState& camera, glm::vec2 at) {
    const int cx = static_cast<int>(std::floor(at.x)), cy = static_cast<int>(std::floor(at.y));
    if (cx < 1 || cy < 1 || cx + 1 >= source.depth.width || cy + 1 >= source.depth.height) return false;
    const double n = camera.nearPlane, f = camera.farPlane;
    double lo = 1e30, hi = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const double ndc = 2.0 * source.depth.at(cx + dx, cy + dy)[0] - 1.0;
            const double d = 2.0 * n * f / (f + n - ndc * (f - n));
            lo = std::min(lo, d);
            hi = std::max(hi, d);
        }
    return hi <= renderer::WarpSettings{}.sheetDepthRatio * lo;
}

// No crack: a display pixel whose true surface point is visible in the source, inside a
// continuous surface (its 3 x 3 neighbourhood shows the same object, visible there too, from
// source points at most 3 px apart, around which the source has no depth jump), must be
// splatted onto. Under a 3 degree turn and under 1.5 m steps (sideways, forward, back) at
// 640 x 360, where near surfaces stretch several display pixels per source pixel. Counted with
// the hole fill off, so that an unwritten pixel shows.
TEST(WarpSplat, NoCrackInsideAContinuousSurface) {
    constexpr int w = 640, h = 360;
    scene::FrameDescription still = shooterAt(w, h, 0.0);
    still.scene.objects.clear();
    struct Case {
        const char* name;
        float yawDeg;
        glm::vec3 step;
    };
    const glm::vec3 forward = scene::forwardDirection(still.camera.yaw, still.camera.pitch);
    const glm::vec3 side = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
    for (const Case& c : {Case{"3 degree turn", 3.0f, glm::vec3(0.0f)}, Case{"1.5 m sideways", 0.0f, 1.5f * side},
                          Case{"1.5 m forward", 0.0f, 1.5f * forward}, Case{"1.5 m back", 0.0f, -1.5f * forward}}) {
        scene::FrameDescription moved = still;
        moved.camera.yaw += glm::radians(c.yawDeg);
        moved.camera.eye += c.step;
        const auto source = testing::renderSource(still, w, h);
        const auto truth = testing::renderSource(moved, w, h);
        const auto exact = bench::trueCorrespondence(moved, truth.images.depth, truth.images.ids, still,
                                                     source.images.depth, source.images.ids);
        const auto shown = splatWithoutHoleFill(from(source, moved.camera, 0.0), w, h);
        int inside = 0, cracks = 0;
        for (int y = 1; y + 1 < h; ++y)
            for (int x = 1; x + 1 < w; ++x) {
                const std::size_t i = static_cast<std::size_t>(y * w + x);
                bool continuous = exact.visible[i] != 0;
                for (int dy = -1; dy <= 1 && continuous; ++dy)
                    for (int dx = -1; dx <= 1 && continuous; ++dx) {
                        const std::size_t j = static_cast<std::size_t>((y + dy) * w + x + dx);
                        continuous = exact.visible[j] != 0 && truth.images.ids.data[j] == truth.images.ids.data[i] &&
                            glm::length(exact.coords[j] - exact.coords[i]) < 3.0f;
                    }
                if (!continuous || !smoothInSource(source.images, still.camera, exact.coords[i])) continue;
                ++inside;
                cracks += !claimed(shown, i);
            }
        ASSERT_GT(inside, w * h / 2) << c.name;
        EXPECT_EQ(cracks, 0) << c.name << ": pixels left unwritten inside a continuous surface";
    }
}

// A sphere moving across the hangar uncovers background it hid in the source. The splat
// leaves those pixels empty and the resolve fills them from the background side: never the
// sphere's id.
TEST(WarpSplat, RevealedBackgroundIsFilledFromTheBackground) {
    constexpr int w = 320, h = 180;
    const testing::SpherePass pass =
        testing::sphereMovingAcross(shooterAt(w, h, 0.0), {4.0f, 1.5f, 0.0f}, {0.0f, 4.3f, -6.0f}, 7);
    const scene::FrameDescription& a = pass.start;
    const scene::FrameDescription& b = pass.later;
    const double dt = pass.dt;
    const auto source = testing::renderSource(a, w, h);
    const auto truth = testing::renderSource(b, w, h);
    const auto exact =
        bench::trueCorrespondence(b, truth.images.depth, truth.images.ids, a, source.images.depth, source.images.ids);
    const auto revealed = bench::unseenMasks({&exact}).occluded;
    const int count = static_cast<int>(std::count(revealed.begin(), revealed.end(), std::uint8_t{1}));
    ASSERT_GT(count, 50);
    const auto splat = testing::produceFrom(kMethod, source, b.camera, dt, w, h);
    int fromSphere = 0;
    for (std::size_t i = 0; i < revealed.size(); ++i)
        fromSphere += revealed[i] && splat.ids.data[i] == scene::kIdTarget;
    EXPECT_EQ(fromSphere, 0) << "of " << count << " revealed pixels";
    const auto full = testing::produceFrom("warp-full", source, b.camera, dt, w, h);
    // How close the fill comes to the truth: measured 24.3 against warp-full's 17.1 (the bench's
    // disocc MAE says the same over its sequences); held within 1.5x of the mesh warp's here.
    const double splatError = bench::maskedMeanAbsoluteError(splat.colour, truth.images.colour, revealed);
    const double fullError = bench::maskedMeanAbsoluteError(full.colour, truth.images.colour, revealed);
    RecordProperty("revealed_mae", std::to_string(splatError) + " (warp-full " + std::to_string(fullError) + ")");
    EXPECT_GT(fullError, 1.0);  // the mesh warp's fill is not exact either: the case is a real disocclusion
    EXPECT_LT(splatError, 1.5 * fullError) << splatError << " against warp-full's " << fullError;
}

// The sphere moves onto background that stays: two source surfaces land on the same display
// pixels and the nearer, the sphere, must win there (its interior, away from the silhouette,
// where a fresh render shows it too), whatever order the invocations ran in. Made twice, the
// frame is the same bit for bit.
TEST(WarpSplat, OverlappingSourcesResolveToTheNearerTheSameEveryRun) {
    constexpr int w = 320, h = 180;
    const testing::SpherePass pass =
        testing::sphereMovingAcross(shooterAt(w, h, 0.0), {5.0f, 0.0f, 0.0f}, {0.0f, 4.0f, -6.0f}, 6);
    const scene::FrameDescription& a = pass.start;
    const scene::FrameDescription& b = pass.later;
    const double dt = pass.dt;
    const auto source = testing::renderSource(a, w, h);
    const auto truth = testing::renderSource(b, w, h);
    const auto first = testing::produceFrom(kMethod, source, b.camera, dt, w, h);
    const auto second = testing::produceFrom(kMethod, source, b.camera, dt, w, h);
    EXPECT_EQ(first.colour.pixels, second.colour.pixels);
    EXPECT_EQ(first.ids.data, second.ids.data);
    EXPECT_EQ(0,
              std::memcmp(first.correspondence.data.data(), second.correspondence.data.data(),
                          first.correspondence.data.size() * sizeof(float)));
    // Where the sphere now covers what the source showed as background, away from its rim.
    int overlapped = 0, lost = 0;
    for (int y = 2; y + 2 < h; ++y)
        for (int x = 2; x + 2 < w; ++x) {
            bool interior = true;
            for (int dy = -2; dy <= 2 && interior; ++dy)
                for (int dx = -2; dx <= 2 && interior; ++dx)
                    interior = truth.images.ids.at(x + dx, y + dy) == scene::kIdTarget;
            if (!interior || source.images.ids.at(x, y) == scene::kIdTarget) continue;
            ++overlapped;
            lost += first.ids.at(x, y) != scene::kIdTarget;
        }
    ASSERT_GT(overlapped, 20);
    EXPECT_EQ(lost, 0) << "of " << overlapped << " pixels the sphere moved onto";
}

// Below OpenGL 4.3 the method says why and what a study shows instead; here, with compute,
// it has nothing to say.
TEST(WarpSplat, SaysWhatItNeedsAndWhatReplacesIt) {
    testing::glContext();
    EXPECT_EQ(renderer::methodUnavailable(kMethod), "");
    EXPECT_EQ(renderer::methodFallback(kMethod), "warp-sparse8");
    EXPECT_EQ(renderer::methodFallback("warp-full"), "");
}

}  // namespace
}  // namespace warplab
