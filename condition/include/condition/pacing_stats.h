// Frame pacing and latency as distributions, the numbers labs report for frame pacing (Liu et
// al., CHI 2023: the 95 % floor, not the mean, predicts experience): frame times of the new
// images a schedule shows, their percentiles and lows, stutters, and the view and scene latency
// of a step falling uniformly in time. `warplab conditions` and export's conditions.csv list
// them; docs/frame-pacing.md says how each is defined.
#pragma once

#include <cstdint>
#include <vector>

#include "condition/pacing.h"
#include "condition/schedule.h"

namespace warplab::condition {

// How much display clock the statistics look at: the horizon a drawn cadence's latency ranges
// are taken over, so that the least and greatest latencies here are those ranges.
inline constexpr double kPacingStatsHorizonS = kDrawnHorizonS;

// The p-th percentile (0 < p <= 100) by nearest rank: the smallest value that at least p % of
// the values are at or below, so it is always one of them. NaN when there are none.
double percentile(std::vector<double> values, double p);

// The frame times of a run of new images: each is the display time from the new image before it.
struct FrameTimes {
    std::vector<double> shownAtS;  // when each new image after the first is shown
    std::vector<double> frameTimeS;  // since the new image before it
};

struct FrameTimeSummary {
    double meanFps = 0.0;  // new images per second of the horizon
    // The frame rate of the 99th and 95th percentile frame time: MangoHud's "1% low" and "5%
    // low" (src/fps_metrics.h: sorted frame times, the one at that rank) and CapFrameX's P1 and
    // P5, not the mean of the slowest 1 % (CapFrameX's "1% low average").
    double low1Fps = 0.0, low5Fps = 0.0;
    double medianS = 0.0, p95S = 0.0, p99S = 0.0, maxS = 0.0;
    // Frame times over twice the median: a stall the eye sees as a hitch, not jitter.
    std::int64_t stutters = 0;
};
// Of the frame times of `horizonS` seconds of display clock that showed `newImages` new images.
FrameTimeSummary summarizeFrameTimes(const FrameTimes& times, std::int64_t newImages, double horizonS);

// A latency of a step that falls uniformly in time, seconds. min and max are the schedule's
// latency range; between two consecutive distinct instants the frames depict, a step's latency
// falls linearly, so the distribution is a mix of uniform ones and its quantiles are exact.
struct LatencyDistribution {
    double min = 0.0, median = 0.0, p95 = 0.0, max = 0.0;
};

struct PacingStats {
    std::int64_t firstFrame = 0;  // the horizon's first display frame: the schedule's settledFrame()
    double horizonS = kPacingStatsHorizonS;
    FrameTimes frames;  // of the new images shown over the horizon
    FrameTimeSummary frameTimes;
    LatencyDistribution viewS, sceneS;  // of steps falling over the horizon
    // The spans those distributions are exact mixes of (export's latency.csv, the report's
    // latency histograms).
    std::vector<ConditionSchedule::LatencySpan> viewSpans, sceneSpans;
};
// Of kPacingStatsHorizonS of `schedule` from its settledFrame().
PacingStats pacingStats(const ConditionSchedule& schedule);

}  // namespace warplab::condition
