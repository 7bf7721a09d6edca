#include "judgement.h"

#include <algorithm>
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

}  // namespace warplab::participants
