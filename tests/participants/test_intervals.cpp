// The simulated participant in two-interval discrimination trials (games/discrimination), from
// percepts made by hand: a reticle view over a textured scene, turned by the participant's own
// counts, its pictures showing where the view looks -- as each interval's condition shows it,
// late or held -- and a bouncing target; the phase text says which interval plays, and the
// question follows. No GL: the pictures are the thumbnails the eye would make of such a scene.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "participants/participant.h"
#include "participants/perception.h"
#include "scene/scene.h"

namespace warplab {
namespace {

const game::DisplaySize kDisplay{1920, 1080};
constexpr double kHz = 60.0;

// How an interval shows the view: this late after the hand turned it, a new image every
// `hold` display frames, or never one that follows the hand (a frozen view).
struct Shown {
    double delayS = 0.0;
    int hold = 1;
    bool frozen = false;
};

class TwoIntervals {
public:
    TwoIntervals() {
        knowledge_.display = kDisplay;
        knowledge_.refreshHz = kHz;
        knowledge_.radiansPerCount = 0.0022;
    }
    const participants::TaskKnowledge& knowledge() const { return knowledge_; }
    int pressesInIntervals() const { return presses_; }

    // One trial, 1.5 s intervals with a 0.5 s blank between them, then the question: the digit
    // key it answers with (1 or 2), 0 if none within 3 s.
    int trial(participants::SimulatedParticipant& participant, Shown first, Shown second,
              const std::string& question = "Which interval was more responsive?") {
        interval(participant, first, "Interval 1 of 2");
        for (int i = 0; i < 30; ++i) step(participant, blank());
        interval(participant, second, "Interval 2 of 2");
        for (int i = 0; i < 180; ++i) {
            participants::Percept p = blank();
            p.pointer = game::PointerKind::Cursor;
            p.pointerAt = {kDisplay.width * 0.5, kDisplay.height * 0.5};
            game::QuestionPrompt q;
            q.kind = protocol::QuestionKind::Choice;
            q.prompt = question;
            q.count = 1;
            q.boxLabels = {"1", "2"};
            q.boxes = {{660.0, 600.0, 200.0, 100.0}, {1060.0, 600.0, 200.0, 100.0}};
            p.question = q;
            const game::FrameInput input = step(participant, p);
            for (const int digit : {1, 2})
                if (input.keys & game::digitKey(digit)) return digit;
        }
        return 0;
    }

private:
    double focal() const { return 0.5 * kDisplay.height / std::tan(glm::radians(knowledge_.verticalFovDeg) / 2.0); }
    double now() const { return frame_ / kHz; }

    game::FrameInput step(participants::SimulatedParticipant& participant, participants::Percept percept) {
        percept.time = now();
        const game::FrameInput input = participant.act(percept);
        // The view as the counts turn it (mouse down pitches down), for the next frame.
        ++frame_;
        glm::dvec2 view = views_.back().second + glm::dvec2(input.mouseDx, -input.mouseDy) * knowledge_.radiansPerCount;
        view.y = std::clamp(view.y, -1.5, 1.5);
        views_.emplace_back(now(), view);
        return input;
    }
    participants::Percept blank() const {
        participants::Percept p;
        p.sceneShown = false;
        return p;
    }
    // The view the counts had turned to at `time`, between frames as the hand moved.
    glm::dvec2 viewAt(double time) const {
        if (time <= views_.front().first) return views_.front().second;
        for (std::size_t i = 1; i < views_.size(); ++i)
            if (views_[i].first >= time) {
                const auto& [t0, v0] = views_[i - 1];
                const auto& [t1, v1] = views_[i];
                return glm::mix(v0, v1, (time - t0) / (t1 - t0));
            }
        return views_.back().second;
    }

    void interval(participants::SimulatedParticipant& participant, Shown shown, const std::string& phase) {
        const double start = now();
        std::optional<participants::Percept> image;
        for (int i = 0; i < 90; ++i) {
            if (i % shown.hold == 0 || !image) {
                // The whole frame is as late as the condition makes it: view and target both.
                const double t = now() - shown.delayS;
                const glm::dvec2 view = shown.frozen ? views_.front().second : viewAt(t);
                image = see(view, target(t - start));
                image->phaseText = phase;
            }
            presses_ += step(participant, *image).buttons != 0;
        }
    }
    // The target bounces between -0.3 and 0.3 rad of yaw at 0.6 rad/s and bobs in pitch.
    static glm::dvec2 target(double s) {
        const double phase = std::fmod(std::max(0.0, s) * 0.6, 1.2);
        return {-0.3 + (phase < 0.6 ? phase : 1.2 - phase), 0.06 * std::sin(2.7 * s)};
    }

    // What the eye would make of the scene seen from `view`: the target where the view puts it,
    // and the scene's pictures, a texture fixed in the world (sharp: 15 px cells; blurred: 4 x 4
    // of those). Separable in yaw and pitch, so that a picture costs a few hundred sines.
    participants::Percept see(glm::dvec2 view, glm::dvec2 targetAt) const {
        participants::Percept p;
        p.pointer = game::PointerKind::Reticle;
        p.pointerAt = {kDisplay.width * 0.5, kDisplay.height * 0.5};
        const double f = focal();
        if (std::abs(targetAt.x - view.x) < 0.9 && std::abs(targetAt.y - view.y) < 0.5) {
            const glm::dvec2 at(p.pointerAt.x + f * std::tan(targetAt.x - view.x),
                                p.pointerAt.y - f * std::tan(targetAt.y - view.y));
            p.objects.push_back({scene::kIdTarget, at, 25.0, {0.9, 0.25, 0.15}, 40});
        }
        constexpr int kW = 128, kH = 72;
        const double cell = kDisplay.width / static_cast<double>(kW);
        std::vector<double> a(kW), b(kW), c(kH), d(kH);
        for (int x = 0; x < kW; ++x) {
            const double yaw = view.x + std::atan(((x + 0.5) * cell - p.pointerAt.x) / f);
            a[x] = 0.12 * std::sin(9.0 * yaw + 1.0) + 0.08 * std::sin(23.0 * yaw + 0.5);
            b[x] = 0.1 * std::sin(5.0 * yaw + 0.3);
        }
        for (int y = 0; y < kH; ++y) {
            const double pitch = view.y - std::atan(((y + 0.5) * cell - p.pointerAt.y) / f);
            c[y] = 0.12 * std::sin(11.0 * pitch + 2.0) + 0.08 * std::sin(29.0 * pitch);
            d[y] = std::cos(13.0 * pitch);
        }
        p.detail = {kW, kH, std::vector<float>(static_cast<std::size_t>(kW) * kH), glm::dvec2(cell)};
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                p.detail.luma[static_cast<std::size_t>(y) * kW + x] =
                    static_cast<float>(0.5 + a[x] + c[y] + b[x] * d[y]);
        p.picture = {kW / 4, kH / 4, std::vector<float>(static_cast<std::size_t>(kW / 4) * (kH / 4), 0.0f),
                     glm::dvec2(4.0 * cell)};
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                p.picture.luma[static_cast<std::size_t>(y / 4) * (kW / 4) + x / 4] += p.detail.at(x, y) / 16.0f;
        return p;
    }

    participants::TaskKnowledge knowledge_;
    std::int64_t frame_ = 0;
    int presses_ = 0;
    std::vector<std::pair<double, glm::dvec2>> views_ = {{0.0, glm::dvec2(0.0)}};
};

// It names the interval whose picture followed its hand sooner, whichever came first, and,
// asked the other way round, the later one -- one participant through several trials, so each
// trial's judgement is its own. It tracks the target and never shoots it (nothing is shot in
// an interval: a shot target would be let go for a while, and the hand with it).
TEST(SimulatedParticipantIntervals, ItNamesTheIntervalWhosePictureFollowedItsHandSooner) {
    for (const std::uint64_t seed : {1, 2, 3, 4, 5}) {
        TwoIntervals world;
        participants::SimulatedParticipant participant(world.knowledge(), {}, seed);
        EXPECT_EQ(world.trial(participant, {0.0}, {0.1}), 1) << "seed " << seed;
        EXPECT_EQ(world.trial(participant, {0.1}, {0.0}), 2) << "seed " << seed;
        EXPECT_EQ(world.trial(participant, {0.0}, {0.1}, "Which interval had more lag?"), 2) << "seed " << seed;
        EXPECT_EQ(world.pressesInIntervals(), 0) << "seed " << seed;
    }
}

// Its judgement is noisy, as its parameter says. A hand without motor noise moves alike for
// every seed, so each seed's participant sees the same pictures and its fit judges them alike
// (0 and 7 ms): with 10 ms between the intervals, two-thirds of the noise's standard deviation,
// the seeds' answers differ by the judgement's noise alone (13 of 20 name the first), and
// without that noise all name the first.
TEST(SimulatedParticipantIntervals, ATinyDifferenceGetsAnswersThatDifferByTheJudgementsNoise) {
    for (const double noiseMs : {participants::ParticipantParams{}.delayJudgementNoiseMs, 0.0}) {
        int first = 0, answered = 0;
        for (std::uint64_t seed = 1; seed <= 20; ++seed) {
            participants::ParticipantParams params;
            params.motorNoise = 0.0;
            params.motorNoiseFloorCountsPerS = 0.0;
            params.delayJudgementNoiseMs = noiseMs;
            TwoIntervals world;
            participants::SimulatedParticipant participant(world.knowledge(), params, seed);
            const int answer = world.trial(participant, {0.0}, {0.010});
            answered += answer != 0;
            first += answer == 1;
        }
        EXPECT_EQ(answered, 20);
        if (noiseMs > 0.0) {
            EXPECT_GT(first, 0);
            EXPECT_LT(first, 20);
        } else {
            EXPECT_EQ(first, 20);
        }
    }
}

// Asked which was the smoother, it names the interval whose picture changed every frame over
// the one that changed every 8th, whichever came first.
TEST(SimulatedParticipantIntervals, ItNamesTheIntervalWhosePictureChangedMoreOftenAsTheSmoother) {
    for (const std::uint64_t seed : {1, 2, 3}) {
        TwoIntervals world;
        participants::SimulatedParticipant participant(world.knowledge(), {}, seed);
        const std::string smoother = "Which interval looked smoother?";
        EXPECT_EQ(world.trial(participant, {0.0, 1}, {0.0, 8}, smoother), 1) << "seed " << seed;
        EXPECT_EQ(world.trial(participant, {0.0, 8}, {0.0, 1}, smoother), 2) << "seed " << seed;
    }
}

// A trial it cannot judge -- a frozen view shows no delay -- leaves it guessing, not answering
// from the trial before (which all seeds judge alike).
TEST(SimulatedParticipantIntervals, ATrialItCannotJudgeLeavesItGuessingNotRecallingTheLastOne) {
    int first = 0, answered = 0;
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        TwoIntervals world;
        participants::SimulatedParticipant participant(world.knowledge(), {}, seed);
        ASSERT_EQ(world.trial(participant, {0.0}, {0.1}), 1) << "seed " << seed;
        const int answer = world.trial(participant, {0.0, 1, true}, {0.0, 1, true});
        answered += answer != 0;
        first += answer == 1;
    }
    EXPECT_EQ(answered, 20);
    EXPECT_GT(first, 0);
    EXPECT_LT(first, 20);
}

}  // namespace
}  // namespace warplab
