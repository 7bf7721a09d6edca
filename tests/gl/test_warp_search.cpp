// Extrapolation by iterative search ("warp-search": warp's motion solved per displayed pixel
// with seed 000's fixed-point search) on cases whose answer is known, and on the hard cases,
// where it must stay finite and show only ids the source has.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "bench/ground_truth.h"
#include "gl/gl_test_support.h"

namespace warplab {
namespace {

constexpr int kW = 192;
constexpr int kH = 108;
const std::string kMethod = "warp-search";

scene::FrameDescription shooterAt(double t, std::uint64_t seed = 4, double speed = 3.0) {
    const auto shooter = testing::shooterScene(kW, kH, seed, speed);
    return {shooter.restingCamera(), shooter.snapshot(t)};
}

renderer::DisplayImages extrapolate(const testing::RenderedSource& source, const scene::CameraState& camera,
                                    double displayTime) {
    renderer::UpconversionInput input;
    input.displayTime = displayTime;
    input.camera = camera;
    input.previous = source.frame.get();
    return testing::produceFrame(kMethod, input, kW, kH);
}

std::vector<glm::vec2> reported(const renderer::DisplayImages& shown) {
    std::vector<glm::vec2> out;
    for (std::size_t i = 0; i < shown.ids.data.size(); ++i)
        out.emplace_back(shown.correspondence.data[4 * i], shown.correspondence.data[4 * i + 1]);
    return out;
}

bench::CorrespondenceStats scored(const renderer::DisplayImages& shown, const bench::Correspondence& exact) {
    bench::CorrespondenceAccumulator accumulator;
    accumulator.add(reported(shown), exact);
    return accumulator.stats();
}

// dt = 0 from the source camera: every flow is zero (to rounding), the search stays on the
// pixel centre, so the source comes back: the same ids, colours within one level (a sample
// a rounding away from the centre), and a correspondence everywhere.
TEST(WarpSearch, ZeroDtFromTheSourceCameraReproducesTheSource) {
    const auto source = testing::renderSource(shooterAt(1.0), kW, kH);
    const auto shown = extrapolate(source, source.frame->depicts.camera, 1.0);
    EXPECT_EQ(shown.ids.data, source.images.ids.data);
    const auto diff = image::compareImages(source.images.colour, shown.colour, 1);
    EXPECT_LE(diff.maxChannelDiff, 1);
    int claimed = 0;
    for (const auto& c : reported(shown)) claimed += std::isfinite(c.x) && std::isfinite(c.y);
    EXPECT_EQ(claimed, kW * kH);
}

// Rotation alone reveals nothing new inside the old view, and the flow of a rotation is
// smooth and exact at every continuous source coordinate (the nearest pixel's depth does not
// matter to a rotation), so the search solves it wherever the point is visible. Measured:
// 100.00 % of the 18629 hit samples within 0.1 px (warp-full, rasterising its mesh: 96.1 %
// within 0.1 px, 97.7 % within 0.5 px); mean worst-channel colour difference 8.5 (warp-full
// 8.7), the bilinear resampling both share.
TEST(WarpSearch, CameraRotationOfAStaticSceneMatchesGroundTruthAlmostEverywhere) {
    scene::FrameDescription still = shooterAt(0.0);
    still.scene.objects.clear();
    scene::FrameDescription turned = still;
    turned.camera.yaw = glm::radians(4.0f);
    turned.camera.pitch = glm::radians(-2.0f);
    const auto source = testing::renderSource(still, kW, kH);
    const auto truth = testing::renderSource(turned, kW, kH);
    const auto exact = bench::trueCorrespondence(turned, truth.images.depth, truth.images.ids, still,
                                                 source.images.depth, source.images.ids);
    const auto shown = extrapolate(source, turned.camera, 0.0);
    const auto stats = scored(shown, exact);
    double sum = 0.0;
    int covered = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const glm::vec2 c = exact.coords[static_cast<std::size_t>(y * kW + x)];
            if (c.x < 1.0f || c.y < 1.0f || c.x > kW - 1.0f || c.y > kH - 1.0f) continue;  // entered the view
            ++covered;
            int worst = 0;
            for (int k = 0; k < 3; ++k)
                worst = std::max(worst, std::abs(shown.colour.at(x, y)[k] - truth.images.colour.at(x, y)[k]));
            sum += worst;
        }
    ASSERT_GT(stats.hitSamples, static_cast<std::size_t>(kW * kH * 8 / 10));
    EXPECT_GE(stats.hitLt0p5, 0.999);
    EXPECT_GE(stats.hitLt0p1, 0.99);
    EXPECT_LE(sum / covered, 10.0);
    RecordProperty("rotation_hit_lt0p5", std::to_string(stats.hitLt0p5));
}

glm::dvec2 centroid(const image::ImageU32& ids, std::uint32_t id, int& count) {
    glm::dvec2 sum(0.0);
    count = 0;
    for (int y = 0; y < ids.height; ++y)
        for (int x = 0; x < ids.width; ++x)
            if (ids.at(x, y) == id) sum += glm::dvec2(x + 0.5, y + 0.5), ++count;
    return count ? sum / double(count) : sum;
}

// A sphere at constant velocity, extrapolated dt ahead, lands where a fresh render puts it
// (the id mask moves by whole pixels -- ids are the nearest source pixel's -- so the centroid
// may be off by up to half a pixel; measured 0.37 px in x, 0.32 in y, 280 pixels against
// 276). Its leading edge is found by the neighbourhood start (without it: 1.6 px behind, 204
// pixels). Where it uncovers the hangar the search converges nowhere: no correspondence is
// claimed there and the background fills it (measured: 73 of the 74 such pixels).
TEST(WarpSearch, MovingSphereLandsWhereGroundTruthHasIt) {
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
    const auto shown = extrapolate(source, b.camera, dt);
    int count = 0;
    const glm::dvec2 got = centroid(shown.ids, scene::kIdTarget, count);
    EXPECT_NEAR(got.x, expected.x, 0.5);
    EXPECT_NEAR(got.y, expected.y, 0.5);
    EXPECT_GT(count, truthCount * 9 / 10);
    EXPECT_LT(count, truthCount * 11 / 10);

    int revealed = 0, filled = 0, unclaimed = 0;
    for (std::size_t i = 0; i < shown.ids.data.size(); ++i) {
        if (source.images.ids.data[i] != scene::kIdTarget || truth.images.ids.data[i] != scene::kIdHangar) continue;
        ++revealed;
        filled += shown.ids.data[i] == scene::kIdHangar;
        unclaimed += std::isnan(shown.correspondence.data[4 * i]);
    }
    ASSERT_GT(revealed, 20);
    EXPECT_GE(filled, revealed * 9 / 10);
    EXPECT_GE(unclaimed, revealed * 9 / 10);
}

// Hard cases: every id shown is one the source has, every correspondence is NaN (no claim)
// or finite and inside the source image, and nothing throws. Of the correspondences claimed,
// hardly any may be 2 px or more from the exact one (measured below each case).
void expectSane(const std::string& label, const scene::FrameDescription& from, const scene::FrameDescription& to,
                double maxWrongShare) {
    const auto source = testing::renderSource(from, kW, kH);
    const auto truth = testing::renderSource(to, kW, kH);
    const auto exact = bench::trueCorrespondence(to, truth.images.depth, truth.images.ids, from, source.images.depth,
                                                 source.images.ids);
    const std::set<std::uint32_t> valid(source.images.ids.data.begin(), source.images.ids.data.end());
    renderer::DisplayImages shown;
    ASSERT_NO_THROW(shown = extrapolate(source, to.camera, to.scene.time)) << label;
    const auto coords = reported(shown);
    int badIds = 0, badCoords = 0, covered = 0, wrong = 0;
    for (std::size_t i = 0; i < coords.size(); ++i) {
        badIds += valid.count(shown.ids.data[i]) == 0;
        const glm::vec2 c = coords[i];
        const float z = shown.correspondence.data[4 * i + 2], w = shown.correspondence.data[4 * i + 3];
        badCoords += !(std::isnan(z) && std::isnan(w));  // never a claim into a next frame
        if (std::isnan(c.x) && std::isnan(c.y)) continue;
        badCoords +=
            !(std::isfinite(c.x) && std::isfinite(c.y) && c.x >= 0.0f && c.x <= kW && c.y >= 0.0f && c.y <= kH);
        ++covered;
        wrong += !(glm::length(c - exact.coords[i]) < 2.0f);
    }
    EXPECT_EQ(badIds, 0) << label;
    EXPECT_EQ(badCoords, 0) << label;
    std::string key = label + "_claimed_off_by_2px";
    std::replace_if(
        key.begin(), key.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
    ::testing::Test::RecordProperty(key, std::to_string(covered) + " " + std::to_string(wrong));
    EXPECT_LE(wrong, maxWrongShare * std::max(covered, 1)) << label << ": " << wrong << " of " << covered;
}

TEST(WarpSearchHardCases, CameraTurned90DegreesBetweenSourceAndDisplay) {
    scene::FrameDescription a = shooterAt(0.0);
    scene::FrameDescription b = a;
    b.camera.yaw = glm::radians(90.0f);
    // Measured: none claimed. 536 pixels of the edge strip still show what the source did, but
    // no search converges there (the flow, nearly a screen width, changes fast across the
    // strip under the perspective); they are filled, unclaimed.
    expectSane("90 degrees", a, b, 0.001);
}

TEST(WarpSearchHardCases, SkyAndFarPlane) {
    scene::FrameDescription a = shooterAt(0.0);
    a.camera.yaw = 0.0f;  // the open far door fills the centre
    scene::FrameDescription b = a;
    b.camera.yaw = glm::radians(3.0f);
    b.camera.pitch = glm::radians(2.0f);
    expectSane("sky", a, b, 0.001);  // measured: 0 of the 18941 claimed off by 2+ px
}

TEST(WarpSearchHardCases, DtOfAWholeSourcePeriod) {
    // Measured: 11 of the 20691 claimed off by 2+ px, on the leading edge of the target (moved
    // 5 px, beyond the neighbourhood ring's reach at this size) and its silhouette.
    expectSane("dt 1/15 s", shooterAt(0.0, 9, 6.0), shooterAt(1.0 / 15.0, 9, 6.0), 0.002);
}

TEST(WarpSearchHardCases, VelocityPointingOffScreen) {
    scene::FrameDescription a = shooterAt(0.0);
    a.scene.objects.front().position = {6.5f, 4.5f, -7.0f};
    a.scene.objects.front().velocity = {60.0f, 0.0f, 40.0f};  // out of the view and behind the eye
    scene::FrameDescription b = a;
    b.scene.time = 1.0 / 15.0;
    b.scene.objects.front().position += a.scene.objects.front().velocity * (1.0f / 15.0f);
    expectSane("off screen", a, b, 0.001);  // measured: 0 of the 20644 claimed off by 2+ px
}

}  // namespace
}  // namespace warplab
