#include "judgement.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iterator>
#include <limits>

namespace warplab::participants {

glm::dvec2 positionAt(const TimedLog& log, double time) {
    if (time <= log.front().first) return log.front().second;
    const auto later =
        std::lower_bound(log.begin(), log.end(), time, [](const auto& entry, double t) { return entry.first < t; });
    if (later == log.end()) return log.back().second;
    const auto& [t0, p0] = *std::prev(later);
    const auto& [t1, p1] = *later;
    return t1 > t0 ? glm::mix(p0, p1, (time - t0) / (t1 - t0)) : p1;
}

std::optional<double> fitDelay(const TimedLog& pointer, const TimedLog& hand, double step) {
    // A quarter-second baseline: long enough to see a movement, short enough that drift
    // between the hand's belief and the screen does not count.
    constexpr double kBaselineS = 0.25, kMaxDelayS = 0.4;
    double bestError = std::numeric_limits<double>::infinity(), best = 0.0, motion = 0.0;
    for (double d = 0.0; d <= kMaxDelayS + 1e-9; d += step) {
        double error = 0.0;
        int pairs = 0;
        std::size_t j = 0;
        for (std::size_t i = 1; i < pointer.size(); ++i) {
            const double ti = pointer[i].first;
            while (j + 1 < i && pointer[j + 1].first <= ti - kBaselineS) ++j;
            const double span = ti - pointer[j].first;
            if (span < kBaselineS - 1e-9 || span > 2.0 * kBaselineS) continue;
            const glm::dvec2 shown = pointer[i].second - pointer[j].second;
            const glm::dvec2 moved = positionAt(hand, ti - d) - positionAt(hand, pointer[j].first - d);
            const glm::dvec2 e = shown - moved;
            error += glm::dot(e, e);
            if (d == 0.0) motion += glm::dot(shown, shown);
            ++pairs;
        }
        if (pairs == 0) return std::nullopt;
        error /= pairs;
        if (d == 0.0) motion /= pairs;
        if (error < bestError - 1e-12) {
            bestError = error;
            best = d;
        }
    }
    // A movement the pointer's error is small against, else the judgement is noise.
    if (motion <= 4.0 * bestError || motion <= 0.0) return std::nullopt;
    return best;
}

namespace {

// The delay fit's grid for an interval: a millisecond, finer than the judgement's noise, so
// that the noise and not the grid limits how small a difference it tells.
constexpr double kIntervalDelayStepS = 0.001;
// The hand is kept from this long before an interval opens: from the interval's first images
// the fit looks back as far as its largest delay (0.4 s).
constexpr double kHandBeforeS = 0.5;

enum class Quality { None, Delay, Smoothness };
struct Asked {
    Quality quality = Quality::None;
    bool worse = false;  // it asks for the less responsive (laggier, choppier) one
};

// What a question asks, from its words, as ratingFor reads a rating statement: "Which interval
// was more responsive?", "... had less lag?", "... looked smoother?", "... was choppier?".
Asked readQuestion(const std::string& prompt) {
    std::string text = prompt;
    for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const auto has = [&](const char* word) { return text.find(word) != std::string::npos; };
    const bool less = has("less") || has("least") || has("lower") || has("shorter") || has("smaller");
    if (has("responsive")) return {Quality::Delay, less};
    if (has("lag") || has("delay") || has("latency")) return {Quality::Delay, !less};
    if (has("smooth")) return {Quality::Smoothness, less};
    if (has("chopp") || has("jerk") || has("stutter")) return {Quality::Smoothness, !less};
    return {};
}

}  // namespace

IntervalJudge::IntervalJudge(std::uint64_t seed, double delayNoiseMs, double rateNoise)
    : random_(seed), delayNoiseMs_(delayNoiseMs), rateNoise_(rateNoise) {}

void IntervalJudge::follow(const std::string& phaseText, double time, glm::dvec2 hand) {
    const auto says = [&](const char* text) { return phaseText.rfind(text, 0) == 0; };
    const int on = says("Interval 1 of 2") ? 1 : says("Interval 2 of 2") ? 2 : 0;
    if (on != open_) {
        if (open_ != 0) close();
        if (on == 1) judged_ = {};  // a new trial: the last one's judgements are done with
        if (on != 0) {
            seen_.at(static_cast<std::size_t>(on - 1)) = {};
            judged_.at(static_cast<std::size_t>(on - 1)).reset();
            openedAt_ = time;
        }
        open_ = on;
    }
    hand_.emplace_back(time, hand);
    const double keepFrom = (open_ != 0 ? openedAt_ : time) - kHandBeforeS;
    while (hand_.size() > 2 && hand_[1].first < keepFrom) hand_.pop_front();
}

void IntervalJudge::see(double time, bool newImage, std::optional<glm::dvec2> pointer) {
    if (open_ == 0) return;
    Seen& s = seen_.at(static_cast<std::size_t>(open_ - 1));
    if (s.from < 0.0)
        s.from = time;
    else
        s.changes += newImage;
    s.to = time;
    if (pointer) s.pointer.emplace_back(time, *pointer);
}

void IntervalJudge::close() {
    const auto k = static_cast<std::size_t>(open_ - 1);
    const Seen& s = seen_.at(k);
    IntervalJudgement j;
    // The delay as judgeDelay judges the display's, over this interval's images only.
    if (!hand_.empty()) j.delayS = fitDelay(s.pointer, hand_, kIntervalDelayStepS);
    // Smooth: how often the picture changed, as judgeMatch has it.
    if (s.changes > 0 && s.to > s.from) j.imagesPerS = s.changes / (s.to - s.from);
    judged_.at(k) = j;
    seen_.at(k) = {};
    open_ = 0;
}

std::optional<int> IntervalJudge::answer(const std::string& prompt) {
    const Asked asked = readQuestion(prompt);
    if (asked.quality == Quality::None || (!judged_[0] && !judged_[1])) return std::nullopt;
    // Each interval as it is felt now, the better one higher: its judgement blurred by the
    // judgement's noise (a delay in ms, an image rate on a log scale: a ratio of rates is what
    // tells them apart). Both noises and the coin are drawn whatever it saw, so that one answer's
    // draws do not depend on another's percepts.
    std::array<std::optional<double>, 2> felt;
    for (std::size_t k = 0; k < 2; ++k) {
        const double z = random_.gaussian();
        if (!judged_[k]) continue;
        const IntervalJudgement& j = *judged_[k];
        if (asked.quality == Quality::Delay && j.delayS) felt[k] = -(*j.delayS * 1000.0 + delayNoiseMs_ * z);
        if (asked.quality == Quality::Smoothness && j.imagesPerS) felt[k] = std::log(*j.imagesPerS) + rateNoise_ * z;
    }
    const double coin = random_.uniform();
    // An interval it could not judge (too little movement): it guesses.
    if (!felt[0] || !felt[1] || *felt[0] == *felt[1]) return coin < 0.5 ? 1 : 2;
    const int better = *felt[0] > *felt[1] ? 1 : 2;
    return asked.worse ? 3 - better : better;
}

}  // namespace warplab::participants
