// The baseline upconversion methods and the bench's measures on cases whose answer is known.
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "bench/bench.h"
#include "bench/ground_truth.h"
#include "gl/gl_test_support.h"
#include "renderer/upconvert.h"

namespace warplab {
namespace {

constexpr int kW = 128;
constexpr int kH = 72;

using Rendered = testing::RenderedSource;

Rendered render(const scene::FrameDescription& description) { return testing::renderSource(description, kW, kH); }

renderer::DisplayImages produce(const std::string& method, const renderer::UpconversionInput& input) {
    return testing::produceFrame(method, input, kW, kH);
}

scene::FrameDescription shooterAt(double t) {
    const auto shooter = testing::shooterScene(kW, kH, 4, 6.0);
    return {shooter.restingCamera(), shooter.snapshot(t)};
}

TEST(Methods, Hold120EqualsGroundTruthExactly) {
    const double t = 0.5;
    const Rendered source = render(shooterAt(t));
    const Rendered truth = render(shooterAt(t));
    renderer::UpconversionInput input;
    input.displayTime = t;
    input.camera = shooterAt(t).camera;
    input.previous = source.frame.get();
    const auto shown = produce("hold120", input);
    EXPECT_EQ(shown.colour.pixels, truth.images.colour.pixels);
    EXPECT_EQ(shown.ids.data, truth.images.ids.data);
    EXPECT_TRUE(std::isinf(image::psnr(shown.colour, truth.images.colour)));
    EXPECT_EQ(image::ssimLuminance(shown.colour, truth.images.colour), 1.0);
}

// What a reader of displayed pixels (the simulated participant's eye) may read instead of the
// copy hold makes: the same colour and ids, bit for bit; a banded source is refused.
TEST(Methods, ReadShownIsWhatHoldShows) {
    const Rendered source = render(shooterAt(0.25));
    renderer::UpconversionInput input;
    input.displayTime = 0.25;
    input.camera = shooterAt(0.25).camera;
    input.previous = source.frame.get();
    const auto held = produce("hold120", input);
    const auto read = renderer::readShown(*source.frame);
    EXPECT_EQ(read.colour.pixels, held.colour.pixels);
    EXPECT_EQ(read.ids.data, held.ids.data);
    const Rendered banded = testing::renderSource(shooterAt(0.25), kW, kH, nullptr, {4, 2});
    EXPECT_THROW(renderer::readShown(*banded.frame), std::invalid_argument);
}

TEST(Methods, HoldOfAMovingTargetDiffersFromGroundTruth) {
    const Rendered source = render(shooterAt(0.0));
    const Rendered truth = render(shooterAt(7.0 / 120.0));
    renderer::UpconversionInput input;
    input.displayTime = 7.0 / 120.0;
    input.camera = truth.frame->depicts.camera;
    input.previous = source.frame.get();
    const auto shown = produce("hold15", input);
    EXPECT_EQ(shown.colour.pixels, source.images.colour.pixels);  // held, not re-rendered
    EXPECT_LT(image::psnr(shown.colour, truth.images.colour), 60.0);
}

// A static scene and a still camera: every held pixel is exactly where the scene says it is.
TEST(Methods, HoldOfAStaticSceneHasZeroCorrespondenceError) {
    scene::FrameDescription still = shooterAt(0.0);
    still.scene.objects.clear();
    scene::FrameDescription later = still;
    later.scene.time = 0.05;
    const Rendered source = render(still);
    const Rendered truth = render(later);
    renderer::UpconversionInput input;
    input.displayTime = later.scene.time;
    input.camera = later.camera;
    input.previous = source.frame.get();
    const auto shown = produce("hold15", input);
    std::vector<glm::vec2> reported;
    for (std::size_t i = 0; i < shown.ids.data.size(); ++i)
        reported.emplace_back(shown.correspondence.data[4 * i], shown.correspondence.data[4 * i + 1]);
    const auto exact = bench::trueCorrespondence(later, truth.images.depth, truth.images.ids, still,
                                                 source.images.depth, source.images.ids);
    bench::CorrespondenceAccumulator accumulator;
    accumulator.add(reported, exact);
    const auto stats = accumulator.stats();
    EXPECT_EQ(stats.allLt0p1, 1.0);
    EXPECT_EQ(stats.hitLt0p1, 1.0);
    EXPECT_EQ(stats.samples, static_cast<std::size_t>(kW * kH));
}

TEST(Methods, HoldOfATurningCameraHasCorrespondenceErrorOfTheTurn) {
    scene::FrameDescription still = shooterAt(0.0);
    still.scene.objects.clear();
    scene::FrameDescription turned = still;
    turned.camera.yaw = glm::radians(2.0f);  // ~2.7 px at this size and field of view
    const Rendered source = render(still);
    const Rendered truth = render(turned);
    renderer::UpconversionInput input;
    input.camera = turned.camera;
    input.previous = source.frame.get();
    const auto shown = produce("hold15", input);
    std::vector<glm::vec2> reported;
    for (std::size_t i = 0; i < shown.ids.data.size(); ++i)
        reported.emplace_back(shown.correspondence.data[4 * i], shown.correspondence.data[4 * i + 1]);
    bench::CorrespondenceAccumulator accumulator;
    accumulator.add(reported,
                    bench::trueCorrespondence(turned, truth.images.depth, truth.images.ids, still, source.images.depth,
                                              source.images.ids));
    EXPECT_EQ(accumulator.stats().allLt1, 0.0);
}

TEST(Methods, BlendMixesItsNeighboursByTime) {
    const Rendered a = render(shooterAt(0.0));
    const Rendered b = render(shooterAt(8.0 / 120.0));
    renderer::UpconversionInput input;
    input.camera = a.frame->depicts.camera;
    input.previous = a.frame.get();
    input.next = b.frame.get();
    input.displayTime = 0.0;
    EXPECT_EQ(produce("blend", input).colour.pixels, a.images.colour.pixels);
    input.displayTime = 8.0 / 120.0;
    EXPECT_EQ(produce("blend", input).colour.pixels, b.images.colour.pixels);
    input.displayTime = 4.0 / 120.0;
    const auto half = produce("blend", input).colour;
    int off = 0;
    for (std::size_t i = 0; i < half.pixels.size(); ++i) {
        const double expected = 0.5 * (a.images.colour.pixels[i] + b.images.colour.pixels[i]);
        off += std::abs(half.pixels[i] - expected) > 1.0;  // 8-bit rounding of the mix
    }
    EXPECT_EQ(off, 0);
}

TEST(Methods, UnknownMethodIsNamed) {
    try {
        renderer::makeMethod("warp-magic", testing::sourceDataPaths());
        FAIL() << "no exception";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("warp-magic"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("hold15"), std::string::npos);
    }
}

// The bench's CSV, the summary and the conditions name a method by its registry name; a method
// that called itself anything else would be measured under one name and reported under another.
TEST(Methods, EveryMethodCallsItselfByItsRegistryName) {
    testing::glContext();
    for (const std::string& name : renderer::methodNames())
        EXPECT_EQ(renderer::makeMethod(name, testing::sourceDataPaths())->info().name, name);
}

TEST(BenchSampling, EveryPhaseOfTheSourceCycleIsSampled) {
    const auto frames = bench::sampleFrames(360, 16, 8);
    ASSERT_EQ(frames.size(), 16u);
    std::vector<int> perPhase(8, 0);
    for (int k : frames) ++perPhase[static_cast<std::size_t>(k % 8)];
    for (int n : perPhase) EXPECT_EQ(n, 2);
    EXPECT_TRUE(std::is_sorted(frames.begin(), frames.end()));
    EXPECT_GT(frames.back(), 180);  // spread over the sequence, not bunched at its start
    EXPECT_EQ(bench::sampleFrames(10, 0, 8).size(), 10u);
}

}  // namespace
}  // namespace warplab
