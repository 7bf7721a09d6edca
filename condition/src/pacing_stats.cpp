#include "condition/pacing_stats.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace warplab::condition {
namespace {

// The q-quantile (0 < q <= 1) of a step's latency over `spans`. A step in (from, to] waits
// shownAt - tau, uniform over [shownAt - to, shownAt - from) with weight to - from, so the
// density at x is the number of spans whose interval holds x: sweep their ends, adding area.
double latencyQuantile(const std::vector<ConditionSchedule::LatencySpan>& spans, double q) {
    std::vector<std::pair<double, int>> ends;  // latency, +1 where a span's interval opens, -1 where it closes
    double total = 0.0;
    for (const auto& s : spans) {
        ends.emplace_back(s.shownAt - s.to, +1);
        ends.emplace_back(s.shownAt - s.from, -1);
        total += s.to - s.from;
    }
    std::sort(ends.begin(), ends.end());
    const double target = q * total;
    double area = 0.0;
    int open = 0;
    for (std::size_t i = 0; i + 1 < ends.size(); ++i) {
        open += ends[i].second;
        const double width = ends[i + 1].first - ends[i].first;
        if (open > 0 && area + open * width >= target) return ends[i].first + (target - area) / open;
        area += open * width;
    }
    return ends.empty() ? std::numeric_limits<double>::quiet_NaN() : ends.back().first;
}

LatencyDistribution distributionOf(const std::vector<ConditionSchedule::LatencySpan>& spans) {
    LatencyDistribution d{std::numeric_limits<double>::infinity(), 0.0, 0.0, -std::numeric_limits<double>::infinity()};
    for (const auto& s : spans) {
        d.min = std::min(d.min, s.shownAt - s.to);
        // A supremum, as ConditionSchedule::Range's max: a step just after `from` waits this long.
        d.max = std::max(d.max, s.shownAt - s.from);
    }
    d.median = latencyQuantile(spans, 0.5);
    d.p95 = latencyQuantile(spans, 0.95);
    return d;
}

}  // namespace

double percentile(std::vector<double> values, double p) {
    if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(values.begin(), values.end());
    // The rank is rounded up from p % of n; a hair of slack keeps 95 % of 20 at rank 19, not 20.
    const double rank = std::ceil(p / 100.0 * static_cast<double>(values.size()) - 1e-9);
    const auto at = static_cast<std::size_t>(std::clamp(rank, 1.0, static_cast<double>(values.size())));
    return values[at - 1];
}

FrameTimeSummary summarizeFrameTimes(const FrameTimes& times, std::int64_t newImages, double horizonS) {
    FrameTimeSummary s;
    const std::vector<double>& t = times.frameTimeS;
    s.meanFps = static_cast<double>(newImages) / horizonS;
    s.medianS = percentile(t, 50.0);
    s.p95S = percentile(t, 95.0);
    s.p99S = percentile(t, 99.0);
    s.maxS = t.empty() ? std::numeric_limits<double>::quiet_NaN() : *std::max_element(t.begin(), t.end());
    s.low1Fps = 1.0 / s.p99S;
    s.low5Fps = 1.0 / s.p95S;
    // A hair of slack: frame times are whole refreshes, and two of one are not a stutter of it.
    s.stutters = std::count_if(t.begin(), t.end(), [&](double x) { return x > 2.0 * s.medianS + 1e-9; });
    return s;
}

PacingStats pacingStats(const ConditionSchedule& schedule) {
    PacingStats stats;
    const double refreshHz = schedule.refreshHz();
    const std::int64_t first = schedule.settledFrame();
    const std::int64_t frames = std::llround(stats.horizonS * refreshHz);
    stats.firstFrame = first;
    // A new image is any frame that is not the one before it shown again (Held).
    std::int64_t newImages = 0;
    double previous = std::numeric_limits<double>::quiet_NaN();
    for (std::int64_t k = first; k < first + frames; ++k) {
        const ScheduledFrame f = schedule.frame(k);
        if (f.kind == FrameKind::Held) continue;
        ++newImages;
        if (!std::isnan(previous)) {
            stats.frames.shownAtS.push_back(f.displayTime);
            stats.frames.frameTimeS.push_back(f.displayTime - previous);
        }
        previous = f.displayTime;
    }
    stats.frameTimes = summarizeFrameTimes(stats.frames, newImages, stats.horizonS);
    stats.viewSpans = schedule.viewLatencySpans(first, first + frames);
    stats.sceneSpans = schedule.sceneLatencySpans(first, first + frames);
    stats.viewS = distributionOf(stats.viewSpans);
    stats.sceneS = distributionOf(stats.sceneSpans);
    return stats;
}

}  // namespace warplab::condition
