// Bidirectional reprojection, image-based (seed 000 sections 3-5): B-frames between two 15 Hz
// I-frames on cases whose answer is known, on the bench's sequences against ground truth
// (a conventional render at the displayed instant), and on the hard cases, where it must stay
// finite and bounded.
//
// Every test makes its own method instances: the method keeps state between frames (the
// flow fields of the current pair, the offsets of the interval's latest B-frame), and a
// fresh instance makes each test independent of the order the others ran in.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "bench/ground_truth.h"
#include "bench/sequences.h"
#include "gl/gl_test_support.h"

namespace warplab {
namespace {

constexpr int kW = 192;
constexpr int kH = 108;
constexpr double kPeriod = 1.0 / 15.0;  // between I-frames
constexpr int kPerSource = 8;  // 120 Hz display frames per I-frame, as the bench runs

using Rendered = testing::RenderedSource;

Rendered render(const scene::FrameDescription& description) { return testing::renderSource(description, kW, kH); }

std::unique_ptr<renderer::UpconversionMethod> fresh(const std::string& name) {
    testing::glContext();
    return renderer::makeMethod(name, testing::sourceDataPaths());
}

renderer::DisplayImages produce(renderer::UpconversionMethod& method, const Rendered& previous, const Rendered& next,
                                double displayTime, const scene::CameraState& camera,
                                const scene::SceneSnapshot* scene = nullptr) {
    renderer::UpconversionInput input;
    input.displayTime = displayTime;
    input.camera = camera;
    input.scene = scene;  // only scene-assisted reads it
    input.previous = previous.frame.get();
    input.next = next.frame.get();
    renderer::DisplayFrame display(kW, kH);
    method.produce(input, display);
    return renderer::readBack(display);
}

scene::FrameDescription shooterAt(double t, std::uint64_t seed = 4, double speed = 3.0) {
    const auto shooter = testing::shooterScene(kW, kH, seed, speed);
    return {shooter.restingCamera(), shooter.snapshot(t)};
}

// Reported correspondences into the previous (channels 0, 1) or the next source (2, 3).
std::vector<glm::vec2> reported(const renderer::DisplayImages& shown, int channelOffset) {
    std::vector<glm::vec2> out;
    for (std::size_t i = 0; i < shown.ids.data.size(); ++i)
        out.emplace_back(shown.correspondence.data[4 * i + channelOffset],
                         shown.correspondence.data[4 * i + channelOffset + 1]);
    return out;
}

bool anyFinite(const std::vector<glm::vec2>& v) {
    return std::any_of(v.begin(), v.end(), [](const glm::vec2& p) { return std::isfinite(p.x) && std::isfinite(p.y); });
}

// Pixels whose id differs or whose claimed correspondence moves by `tolerance` px or more
// (a claim made on one side only counts as a difference).
int differingPixels(const renderer::DisplayImages& a, const renderer::DisplayImages& b, float tolerance) {
    int n = 0;
    for (std::size_t i = 0; i < a.ids.data.size(); ++i) {
        bool differs = a.ids.data[i] != b.ids.data[i];
        for (int c = 0; c < 4; ++c) {
            const float u = a.correspondence.data[4 * i + c], v = b.correspondence.data[4 * i + c];
            differs = differs || std::isnan(u) != std::isnan(v) || std::abs(u - v) >= tolerance;
        }
        n += differs;
    }
    return n;
}

// Bit for bit, NaNs included.
bool identical(const renderer::DisplayImages& a, const renderer::DisplayImages& b) {
    return a.colour.pixels == b.colour.pixels && a.ids.data == b.ids.data &&
        a.correspondence.data.size() == b.correspondence.data.size() &&
        std::memcmp(a.correspondence.data.data(), b.correspondence.data.data(),
                    a.correspondence.data.size() * sizeof(float)) == 0;
}

glm::dvec2 centroid(const image::ImageU32& ids, std::uint32_t id, int& count) {
    glm::dvec2 sum(0.0);
    count = 0;
    for (int y = 0; y < ids.height; ++y)
        for (int x = 0; x < ids.width; ++x)
            if (ids.at(x, y) == id) sum += glm::dvec2(x + 0.5, y + 0.5), ++count;
    return count ? sum / double(count) : sum;
}

// ---------------------------------------------------------------------------------------
// 1. Nothing moves: every B-frame is the I-frame.

// The target is in the scene, at rest (both snapshots list it at the same place): flow zero
// everywhere, so every search converges at its own pixel centre and the bilinear lookups
// hit texel centres exactly.
TEST(Bireproj, StaticSceneBFramesEqualTheIFrame) {
    const scene::FrameDescription still = shooterAt(0.0);
    scene::FrameDescription later = still;
    later.scene.time = kPeriod;
    const Rendered a = render(still), b = render(later);
    ASSERT_EQ(a.images.colour.pixels, b.images.colour.pixels);  // the premise: time alone changes nothing
    auto method = fresh("bireproj");
    for (int quarter : {1, 2, 3}) {
        const auto shown = produce(*method, a, b, quarter * kPeriod / 4.0, still.camera);
        EXPECT_EQ(shown.ids.data, a.images.ids.data) << "alpha " << quarter << "/4";
        int worst = 0, misplaced = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                for (int c = 0; c < 3; ++c)
                    worst = std::max(worst, std::abs(shown.colour.at(x, y)[c] - a.images.colour.at(x, y)[c]));
                // Each pixel claims its own centre (top-down) in both I-frames.
                const float* q = shown.correspondence.at(x, y);
                const glm::vec2 centre(x + 0.5f, y + 0.5f);
                misplaced += !(glm::length(glm::vec2(q[0], q[1]) - centre) < 0.01f) ||
                    !(glm::length(glm::vec2(q[2], q[3]) - centre) < 0.01f);
            }
        EXPECT_LE(worst, 1) << "alpha " << quarter << "/4: largest channel difference from the I-frame";
        EXPECT_EQ(misplaced, 0) << "alpha " << quarter << "/4: pixels not claiming their own centre";
    }
}

// ---------------------------------------------------------------------------------------
// 2. One sphere at constant velocity parallel to the image plane of a still camera: on
// screen it moves linearly in time, so the B-frame's sphere sits on the line between the
// I-frames' spheres, and keeps their size.
//
// Where this fails with pixels missing at the sphere's leading and trailing edges, look at
// how a direction's searches are chosen between: for such a pixel the search started at the
// pixel itself lands on the static background behind the sphere in that I-frame, whose flow
// is zero, so it "converges" with an error of ~0; the dual start (eq. 16-17) finds the sphere
// with an error a little above 0, and choosing the smaller error discards it. A CPU replica
// of the shader with the scene's exact flows reproduced the method's pixel counts exactly;
// choosing instead the nearest of the searches that converged (error < epsilon 1) recovered
// the missing pixels.

TEST(Bireproj, TranslatingSphereSitsAtTheInterpolatedPosition) {
    scene::FrameDescription a = shooterAt(0.0);
    a.camera.yaw = 0.0f;  // looking down -z: a sphere moving along x keeps its view depth
    a.camera.pitch = 0.0f;
    auto& sphere = a.scene.objects.front();
    sphere.position = a.camera.eye + glm::vec3(-1.0f, -0.5f, -4.0f);
    sphere.velocity = {8.0f, 2.0f, 0.0f};  // 0.53 m, ~12 px across and 3 px down per interval
    sphere.angularVelocity = glm::vec3(0.0f);
    sphere.halfExtents = glm::vec3(0.8f);  // ~19 px radius
    scene::FrameDescription b = a;
    b.scene.time = kPeriod;
    b.scene.objects.front().position += sphere.velocity * static_cast<float>(kPeriod);
    const Rendered i0 = render(a), i1 = render(b);
    int n0 = 0, n1 = 0;
    const glm::dvec2 c0 = centroid(i0.images.ids, scene::kIdTarget, n0);
    const glm::dvec2 c1 = centroid(i1.images.ids, scene::kIdTarget, n1);
    ASSERT_GT(n0, 200);
    ASSERT_GT(glm::length(c1 - c0), 10.0);  // the premise: it moves far enough to matter
    ASSERT_LT(glm::length(c1 - c0), 30.0);

    auto method = fresh("bireproj");
    for (int quarter : {1, 2, 3}) {
        const double alpha = quarter / 4.0;
        const glm::dvec2 expected = (1.0 - alpha) * c0 + alpha * c1;
        // The premise again, from a render at that instant: perspective keeps it on the line.
        scene::FrameDescription mid = a;
        mid.scene.time = alpha * kPeriod;
        mid.scene.objects.front().position += sphere.velocity * static_cast<float>(alpha * kPeriod);
        const Rendered truthFrame = render(mid);
        int truthCount = 0;
        const glm::dvec2 truth = centroid(truthFrame.images.ids, scene::kIdTarget, truthCount);
        ASSERT_LT(glm::length(truth - expected), 0.25) << "alpha " << alpha;

        int count = 0;
        const auto shown = produce(*method, i0, i1, alpha * kPeriod, a.camera);
        const glm::dvec2 got = centroid(shown.ids, scene::kIdTarget, count);
        EXPECT_NEAR(got.x, expected.x, 0.5) << "alpha " << alpha;
        EXPECT_NEAR(got.y, expected.y, 0.5) << "alpha " << alpha;
        EXPECT_NEAR(count, 0.5 * (n0 + n1), 0.03 * 0.5 * (n0 + n1)) << "alpha " << alpha;
        // Where it falls short: sphere pixels of the render shown as something else although
        // the ground truth has their surface point visible in both I-frames.
        const auto& t = truthFrame.images;
        const auto into0 = bench::trueCorrespondence(mid, t.depth, t.ids, a, i0.images.depth, i0.images.ids);
        const auto into1 = bench::trueCorrespondence(mid, t.depth, t.ids, b, i1.images.depth, i1.images.ids);
        int missedVisibleInBoth = 0;
        for (std::size_t i = 0; i < t.ids.data.size(); ++i)
            missedVisibleInBoth += t.ids.data[i] == scene::kIdTarget && shown.ids.data[i] != scene::kIdTarget &&
                into0.visible[i] && into1.visible[i];
        std::ostringstream line;
        line << std::fixed << std::setprecision(3) << "centroid (" << got.x << ", " << got.y << ") expected ("
             << expected.x << ", " << expected.y << ") render (" << truth.x << ", " << truth.y << "); pixels " << count
             << " vs I-frames " << n0 << "/" << n1 << ", render " << truthCount << "; render's sphere pixels "
             << "visible in both I-frames but not shown: " << missedVisibleInBoth;
        RecordProperty("alpha_" + std::to_string(quarter) + "_4", line.str());
        std::cout << "[sphere alpha " << alpha << "] " << line.str() << "\n";
    }
}

// ---------------------------------------------------------------------------------------
// 3. The bench's sequences against ground truth, scored as the bench scores them.

struct Score {
    double hitLt0p5 = 0, allLt0p5 = 0, psnr = 0;
    std::vector<renderer::DisplayImages> frames;  // the interval's B-frames, in order
    // Per sample, in the order they were pooled: 0 = not visible in that source, 1 = visible
    // and claimed 0.5 px or more off (or not claimed), 2 = visible and within 0.5 px.
    std::vector<std::uint8_t> verdicts;
    // The same share over the samples whose displayed pixel shows one object (thin's bar).
    double focusHitLt0p5 = 0;
    std::size_t focusHitSamples = 0, focusRight = 0;
};

constexpr std::uint32_t kNoFocus = 0xffffffffu;

void judge(Score& score, const std::vector<glm::vec2>& claimed, const bench::Correspondence& truth,
           const image::ImageU32& truthIds, std::uint32_t focus) {
    for (std::size_t i = 0; i < claimed.size(); ++i) {
        if (!truth.visible[i]) {
            score.verdicts.push_back(0);
            continue;
        }
        const double error = glm::length(glm::dvec2(claimed[i]) - glm::dvec2(truth.coords[i]));
        score.verdicts.push_back(error < 0.5 ? 2 : 1);
        if (truthIds.data[i] == focus) ++score.focusHitSamples, score.focusRight += error < 0.5;
    }
}

// One 15 Hz interval per entry of `intervals` (I-frames at 120 Hz frames 8i and 8i + 8); in
// each, every method makes the seven 120 Hz B-frames in order, as a session would (so
// latest-frame initialisation has its earlier frames), and each is scored against a render at
// its instant: correspondence pooled over both sources as bench/src/bench.cpp pools it, PSNR
// of the mean squared error over the frames.
std::map<std::string, Score> scoreSequence(const std::string& sequenceName, const std::vector<std::string>& methods,
                                           const std::vector<int>& intervals, std::uint32_t focus = kNoFocus) {
    game::SequenceConfig config;
    config.aspect = double(kW) / kH;
    const auto sequence = game::makeSequence(sequenceName, config);
    std::map<std::string, bench::CorrespondenceAccumulator> accumulators;
    std::map<std::string, std::pair<double, int>> squaredErrors;
    std::map<std::string, Score> out;
    for (const std::string& name : methods) out[name];
    for (int interval : intervals) {
        const int first = kPerSource * interval, last = first + kPerSource;
        const Rendered a = render(sequence->at(first / 120.0)), b = render(sequence->at(last / 120.0));
        std::vector<Rendered> truths;
        std::vector<bench::Correspondence> intoPrevious, intoNext;
        for (int k = first + 1; k < last; ++k) {
            truths.push_back(render(sequence->at(k / 120.0)));
            const auto& t = truths.back();
            intoPrevious.push_back(bench::trueCorrespondence(t.frame->depicts, t.images.depth, t.images.ids,
                                                             a.frame->depicts, a.images.depth, a.images.ids));
            intoNext.push_back(bench::trueCorrespondence(t.frame->depicts, t.images.depth, t.images.ids,
                                                         b.frame->depicts, b.images.depth, b.images.ids));
        }
        for (const std::string& name : methods) {
            auto method = fresh(name);
            for (std::size_t j = 0; j < truths.size(); ++j) {
                const auto& truth = truths[j];
                auto shown = produce(*method, a, b, truth.frame->depicts.scene.time, truth.frame->depicts.camera,
                                     &truth.frame->depicts.scene);
                auto& acc = accumulators[name];
                acc.add(reported(shown, 0), intoPrevious[j]);
                judge(out[name], reported(shown, 0), intoPrevious[j], truth.images.ids, focus);
                const auto next = reported(shown, 2);
                if (method->info().needsNext && anyFinite(next)) {
                    acc.add(next, intoNext[j]);
                    judge(out[name], next, intoNext[j], truth.images.ids, focus);
                }
                const double p = image::psnr(shown.colour, truth.images.colour);
                squaredErrors[name].first += std::isinf(p) ? 0.0 : 255.0 * 255.0 / std::pow(10.0, p / 10.0);
                squaredErrors[name].second += 1;
                out[name].frames.push_back(std::move(shown));
            }
        }
    }
    for (const std::string& name : methods) {
        const auto stats = accumulators[name].stats();
        out[name].hitLt0p5 = stats.hitLt0p5;
        out[name].allLt0p5 = stats.allLt0p5;
        out[name].focusHitLt0p5 = out[name].focusHitSamples == 0
            ? std::numeric_limits<double>::quiet_NaN()
            : double(out[name].focusRight) / double(out[name].focusHitSamples);
        const double mse = squaredErrors[name].first / squaredErrors[name].second;
        out[name].psnr = mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(255.0 * 255.0 / mse);
    }
    return out;
}

std::string figures(const std::map<std::string, Score>& scores) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(2);
    for (const auto& [name, score] : scores)
        s << name << ": hit<0.5px " << 100.0 * score.hitLt0p5 << "%, all<0.5px " << 100.0 * score.allLt0p5 << "%, PSNR "
          << score.psnr << " dB"
          << (score.focusHitSamples ? ", on the focus object hit<0.5px " + std::to_string(100.0 * score.focusHitLt0p5) +
                      "% of " + std::to_string(score.focusHitSamples)
                                    : std::string())
          << "; ";
    return s.str();
}

const std::vector<std::string> kCompared = {"bireproj", "blend", "hold15"};
const std::vector<int> kIntervals = {4, 17};  // t = 0.27..0.33 s and 1.13..1.2 s

void expectBeatsBaselines(const std::string& sequence, double hitFloor) {
    const auto scores = scoreSequence(sequence, kCompared, kIntervals);
    const std::string text = figures(scores);
    ::testing::Test::RecordProperty(sequence, text);
    std::cout << "[" << sequence << "] " << text << "\n";
    const Score& bi = scores.at("bireproj");
    EXPECT_GT(bi.hitLt0p5, hitFloor) << sequence << ": share of visible pixels within 0.5 px";
    EXPECT_GT(bi.psnr, scores.at("blend").psnr) << sequence;
    EXPECT_GT(bi.psnr, scores.at("hold15").psnr) << sequence;
}

// Floors a percentage point under what this test measured (Mesa llvmpipe, 192x108, intervals
// 4 and 17, all seven B-frames of each; hit pixels within 0.5 px, both sources pooled):
// pan 95.31 % (PSNR 25.84 dB against blend 20.14, hold15 18.02), spheres 99.71 % (38.40 dB
// against 34.69 and 30.47).
TEST(BireprojBench, PanCorrespondenceAndPsnr) { expectBeatsBaselines("pan", 0.9431); }
TEST(BireprojBench, SpheresCorrespondenceAndPsnr) { expectBeatsBaselines("spheres", 0.9871); }

// Seed 000 Figure 4: thin geometry moving many times its width per frame is the search's
// known failure. Reported, not held to a floor; it must still be finite and claim more right
// correspondences than blend (which claims none), and on the bar itself more than hold15.
// (Over the whole frame hold15 is nearly as good: the camera is still, so it is exact
// wherever nothing moves.) Measured as above: bireproj 99.34 % overall, 19.3 % of the bar's
// samples, PSNR 29.98 dB; blend 0 %, 28.03 dB; hold15 99.30 %, 6.9 % of the bar's, 26.51 dB.
TEST(BireprojBench, ThinGeometryIsReported) {
    const auto scores = scoreSequence("thin", kCompared, kIntervals, scene::kIdSpinningBar);
    const std::string text = figures(scores);
    RecordProperty("thin", text);
    std::cout << "[thin] " << text << "\n";
    const Score& bi = scores.at("bireproj");
    EXPECT_TRUE(std::isfinite(bi.hitLt0p5) && std::isfinite(bi.psnr));
    EXPECT_GT(bi.hitLt0p5, scores.at("blend").hitLt0p5);
    ASSERT_GT(bi.focusHitSamples, 0u);
    EXPECT_GT(bi.focusHitLt0p5, scores.at("hold15").focusHitLt0p5);
}

// ---------------------------------------------------------------------------------------
// 4. Hard cases: every id shown is one the frames have, every correspondence is NaN (no
// claim) or finite and within a few image sizes of the image, and nothing throws.

void expectSane(const std::string& label, const scene::FrameDescription& from, const scene::FrameDescription& to) {
    const Rendered a = render(from), b = render(to);
    std::set<std::uint32_t> valid = {scene::kIdNone, scene::kIdHangar};
    for (const auto& o : from.scene.objects) valid.insert(o.id);
    for (const auto& o : to.scene.objects) valid.insert(o.id);
    for (const std::string name : {"bireproj", "bireproj-m1", "bireproj-noinit"}) {
        auto method = fresh(name);
        for (int quarter : {1, 2, 3}) {
            const double t = from.scene.time + quarter / 4.0 * (to.scene.time - from.scene.time);
            renderer::DisplayImages shown;
            ASSERT_NO_THROW(shown = produce(*method, a, b, t, to.camera)) << label << " " << name;
            const std::string where = label + " " + name + " alpha " + std::to_string(quarter) + "/4";
            int badIds = 0, badCoords = 0, opaque = 0;
            for (std::size_t i = 0; i < shown.ids.data.size(); ++i) {
                badIds += valid.count(shown.ids.data[i]) == 0;
                opaque += shown.colour.pixels[4 * i + 3] == 255;
                for (int s = 0; s < 2; ++s) {
                    const float x = shown.correspondence.data[4 * i + 2 * s];
                    const float y = shown.correspondence.data[4 * i + 2 * s + 1];
                    if (std::isnan(x) && std::isnan(y)) continue;
                    badCoords += !(std::isfinite(x) && std::isfinite(y) && x > -2.0f * kW && x < 3.0f * kW &&
                                   y > -2.0f * kH && y < 3.0f * kH);
                }
            }
            EXPECT_EQ(badIds, 0) << where;
            EXPECT_EQ(badCoords, 0) << where;
            EXPECT_EQ(opaque, kW * kH) << where;
        }
    }
}

TEST(BireprojHardCases, CameraTurned90DegreesBetweenIFrames) {
    const scene::FrameDescription a = shooterAt(0.0);
    scene::FrameDescription b = shooterAt(kPeriod);
    b.camera.yaw = a.camera.yaw + glm::radians(90.0f);  // most flow points off screen
    expectSane("90 degrees", a, b);
}

TEST(BireprojHardCases, MostlySky) {
    scene::FrameDescription a = shooterAt(0.0);
    a.camera.eye.z = -54.0f;  // past the last rib, 6 m from the open far end
    a.camera.yaw = 0.0f;
    a.camera.pitch = 0.0f;
    scene::FrameDescription b = shooterAt(kPeriod);
    b.camera = a.camera;
    b.camera.yaw = glm::radians(4.0f);
    b.camera.pitch = glm::radians(3.0f);
    const auto ids = render(a).images.ids.data;
    ASSERT_GT(std::count(ids.begin(), ids.end(), scene::kIdNone), kW * kH / 2);  // the premise
    expectSane("sky", a, b);

    // A turning camera over the sky is a smooth flow the search solves: measured 99.53 % of
    // visible samples within 0.5 px.
    const auto scores = [&] {
        const Rendered i0 = render(a), i1 = render(b);
        auto method = fresh("bireproj");
        bench::CorrespondenceAccumulator acc;
        for (int quarter : {1, 2, 3}) {
            scene::FrameDescription mid = b;
            mid.scene = shooterAt(quarter * kPeriod / 4.0).scene;
            mid.camera.yaw = glm::radians(4.0f) * quarter / 4.0f;
            mid.camera.pitch = glm::radians(3.0f) * quarter / 4.0f;
            const Rendered truth = render(mid);
            const auto shown = produce(*method, i0, i1, mid.scene.time, mid.camera);
            acc.add(reported(shown, 0),
                    bench::trueCorrespondence(mid, truth.images.depth, truth.images.ids, a, i0.images.depth,
                                              i0.images.ids));
            acc.add(reported(shown, 2),
                    bench::trueCorrespondence(mid, truth.images.depth, truth.images.ids, b, i1.images.depth,
                                              i1.images.ids));
        }
        return acc.stats();
    }();
    std::cout << "[sky] hit<0.5px " << 100.0 * scores.hitLt0p5 << "%\n";
    RecordProperty("sky_hit_lt_0p5", std::to_string(scores.hitLt0p5));
    EXPECT_GT(scores.hitLt0p5, 0.985);
}

// The target crosses half the screen between I-frames while spinning fast: its flow changes
// by far more than a pixel per pixel, which the fixed-point search is not made for (it
// converges only where alpha times the flow's gradient stays below 1).
TEST(BireprojHardCases, MotionTooFastForTheSearch) {
    scene::FrameDescription a = shooterAt(0.0);
    auto& target = a.scene.objects.front();
    target.position = a.camera.eye + glm::vec3(-3.0f, 0.5f, -6.0f);
    target.velocity = {90.0f, -15.0f, 0.0f};
    target.angularVelocity = {0.0f, 40.0f, 25.0f};
    target.halfExtents = glm::vec3(0.8f);
    scene::FrameDescription b = a;
    b.scene.time = kPeriod;
    b.scene.objects.front().position += target.velocity * static_cast<float>(kPeriod);
    b.scene.objects.front().orientation = glm::normalize(
        glm::angleAxis(glm::length(target.angularVelocity) * float(kPeriod), glm::normalize(target.angularVelocity)) *
        target.orientation);
    expectSane("too fast", a, b);
}

// The shooter's target respawns between I-frames: the same id, somewhere else entirely.
TEST(BireprojHardCases, TargetJumpsBetweenIFrames) {
    scene::FrameDescription a = shooterAt(0.0);
    a.scene.objects.front().position = a.camera.eye + glm::vec3(-4.0f, 2.0f, -7.0f);
    scene::FrameDescription b = a;
    b.scene.time = kPeriod;
    b.scene.objects.front().position = a.camera.eye + glm::vec3(4.0f, -2.5f, -7.0f);
    expectSane("respawn", a, b);
}

// ---------------------------------------------------------------------------------------
// 5. Determinism, with the state latest-frame initialisation keeps.

TEST(BireprojDeterminism, RepeatsAndOrderGiveTheSameFrames) {
    game::SequenceConfig config;
    config.aspect = double(kW) / kH;
    const auto sequence = game::makeSequence("track", config);
    const int first = kPerSource * 17;
    const Rendered a = render(sequence->at(first / 120.0)), b = render(sequence->at((first + 8) / 120.0));
    auto at = [&](int eighths) { return sequence->at((first + eighths) / 120.0); };
    auto make = [&](renderer::UpconversionMethod& m, int eighths) {
        const auto d = at(eighths);
        return produce(m, a, b, d.scene.time, d.camera);
    };

    auto once = fresh("bireproj");
    const auto half = make(*once, 4);
    EXPECT_TRUE(identical(half, make(*once, 4))) << "the same B-frame twice";

    auto inOrder = fresh("bireproj");
    make(*inOrder, 2);
    make(*inOrder, 4);
    const auto threeQuarters = make(*inOrder, 6);
    EXPECT_TRUE(identical(threeQuarters, make(*inOrder, 6))) << "3/4 after 1/4, 2/4, 3/4";

    // Another instance walking the same frames makes the same pixels.
    auto again = fresh("bireproj");
    make(*again, 2);
    make(*again, 4);
    EXPECT_TRUE(identical(threeQuarters, make(*again, 6))) << "a second instance";
}

// ---------------------------------------------------------------------------------------
// 6. Latest-frame initialisation (eq. 18-19) is used, and what it does is small: over the
// same frames, made in order, its share of visible samples within 0.5 px stays within 0.05
// percentage points of the same method without it. Measured at 192x108: track 95.9457 %
// against 95.9459 % (2 samples made right, 3 made wrong of 580,608), spheres 99.7097 %
// against 99.7194 % (70 right, 126 wrong) -- slightly worse: its neighbourhood start takes the
// nearest surface around p, which at a silhouette can converge onto the foreground a fraction
// of a pixel from where the truth has the edge. docs/bench.md reports it.
TEST(BireprojLatestInit, StartingFromTheEarlierBFrameIsUsedAndChangesLittle) {
    for (const std::string sequence : {"track", "spheres"}) {
        const auto scores = scoreSequence(sequence, {"bireproj", "bireproj-nolatest"}, kIntervals);
        const std::string text = figures(scores);
        RecordProperty(sequence, text);
        std::cout << "[latest " << sequence << "] " << text << "\n";
        const Score& latest = scores.at("bireproj");
        const Score& without = scores.at("bireproj-nolatest");
        ASSERT_EQ(latest.verdicts.size(), without.verdicts.size());
        int gained = 0, lost = 0;
        for (std::size_t i = 0; i < latest.verdicts.size(); ++i) {
            gained += latest.verdicts[i] == 2 && without.verdicts[i] == 1;
            lost += latest.verdicts[i] == 1 && without.verdicts[i] == 2;
        }
        std::cout << "[latest " << sequence << "] samples made right by it " << gained << ", made wrong " << lost
                  << " of " << latest.verdicts.size() << "\n";
        EXPECT_NEAR(latest.hitLt0p5, without.hitLt0p5, 0.0005) << sequence;
        // Used at all: after the first B-frame of an interval, some pixel differs from the
        // search without it. (The first B-frame of each interval has nothing to start from.)
        int differing = 0;
        for (std::size_t j = 0; j < latest.frames.size(); ++j) {
            const int pixels = differingPixels(latest.frames[j], without.frames[j], 1e-3f);
            if (j % (kPerSource - 1) == 0) {
                EXPECT_EQ(pixels, 0) << sequence << " frame " << j << ", the first of its interval";
                continue;
            }
            differing += pixels > 0;
        }
        EXPECT_GT(differing, 0) << sequence;
    }
}

// The later I-frame's backward flow drawn in its own render (a fourth render target, as the
// study condition and the bench make their I-frames) gives exactly the B-frames the method makes
// when it has to draw that flow itself.
TEST(BireprojFlow, TheIFramesOwnFlowGivesTheSameBFrames) {
    game::SequenceConfig config;
    config.aspect = double(kW) / kH;
    for (const std::string name : {"spheres", "pan"}) {
        const auto sequence = game::makeSequence(name, config);
        const auto before = sequence->at(4 * kPeriod), after = sequence->at(5 * kPeriod);
        const Rendered a = render(before), plain = render(after);
        const Rendered withFlow = testing::renderSource(after, kW, kH, &before);
        EXPECT_EQ(withFlow.images.colour.pixels, plain.images.colour.pixels)
            << name << ": the flow target changes nothing else";
        auto drawsItsOwn = fresh("bireproj"), takesTheSources = fresh("bireproj");
        for (int eighth = 1; eighth < 8; ++eighth) {
            const auto d = sequence->at((4 + eighth / 8.0) * kPeriod);
            const auto own = produce(*drawsItsOwn, a, plain, d.scene.time, d.camera);
            const auto sources = produce(*takesTheSources, a, withFlow, d.scene.time, d.camera);
            EXPECT_TRUE(identical(own, sources)) << name << " B-frame " << eighth << "/8";
        }
    }
}

// ---------------------------------------------------------------------------------------
// 7. Scene-assisted reprojection (section 4): the reference the search is measured against.

TEST(SceneAssisted, CorrespondencesAreExactAndBeatTheSearch) {
    for (const std::string sequence : {"spheres", "thin"}) {
        const auto scores = scoreSequence(sequence, {"scene-assisted", "bireproj"}, {4});
        const Score& exact = scores.at("scene-assisted");
        std::cout << "[scene-assisted " << sequence << "] " << figures(scores) << "\n";
        // Measured: 100 % on both (the claims are the scene's own projections).
        EXPECT_GT(exact.hitLt0p5, 0.999) << sequence;
        EXPECT_GT(exact.psnr, scores.at("bireproj").psnr) << sequence;
    }
}

// ---------------------------------------------------------------------------------------
// 8. Motion blur from B-frames (section 9).

renderer::DisplayImages blurred(const Rendered& a, const Rendered& b) {
    auto method = fresh("bireproj-blur");
    EXPECT_EQ(method->info().exposureSamples, 10);
    return produce(*method, a, b, 0.5 * (a.frame->depicts.scene.time + b.frame->depicts.scene.time),
                   a.frame->depicts.camera);
}

TEST(BireprojBlur, AStillSceneIsNotBlurred) {
    const scene::FrameDescription still = shooterAt(0.0, 4, 0.0);
    scene::FrameDescription later = still;
    later.scene.time = kPeriod;
    const Rendered a = render(still), b = render(later);
    const auto shown = blurred(a, b);
    int worst = 0;
    for (std::size_t i = 0; i < shown.colour.pixels.size(); ++i)
        worst = std::max(worst, std::abs(int(shown.colour.pixels[i]) - int(a.images.colour.pixels[i])));
    EXPECT_LE(worst, 1);
    EXPECT_EQ(shown.ids.data, a.images.ids.data);
}

// The mean of ten B-frames against brute force, the mean of ten conventional renders at the
// same instants, on the bouncing spheres.
TEST(BireprojBlur, MatchesBruteForceOverTheInterval) {
    game::SequenceConfig config;
    config.aspect = double(kW) / kH;
    const auto sequence = game::makeSequence("spheres", config);
    const double t0 = 4 * kPeriod, t1 = 5 * kPeriod;
    const Rendered a = render(sequence->at(t0)), b = render(sequence->at(t1));
    std::vector<double> sum(a.images.colour.pixels.size(), 0.0);
    for (int k = 0; k < 10; ++k) {
        const Rendered r = render(sequence->at(t0 + (t1 - t0) * (k + 0.5) / 10.0));
        for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += r.images.colour.pixels[i];
    }
    image::ImageRGBA8 brute = a.images.colour;
    for (std::size_t i = 0; i < sum.size(); ++i)
        brute.pixels[i] = static_cast<std::uint8_t>(std::lround(sum[i] / 10.0));
    const double blurPsnr = image::psnr(blurred(a, b).colour, brute);
    const double holdPsnr = image::psnr(a.images.colour, brute);  // no blur at all
    std::cout << "[blur spheres] PSNR against brute force " << blurPsnr << " dB, the I-frame alone " << holdPsnr
              << " dB\n";
    EXPECT_GT(blurPsnr, 40.0);
    EXPECT_GT(blurPsnr, holdPsnr + 5.0);
}

}  // namespace
}  // namespace warplab
