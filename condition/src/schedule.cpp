#include "condition/schedule.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace warplab::condition {

const char* frameKindName(FrameKind kind) {
    switch (kind) {
        case FrameKind::Rendered: return "rendered";
        case FrameKind::Held: return "held";
        case FrameKind::Warped: return "warped";
        case FrameKind::Interpolated: return "interpolated";
    }
    return "?";
}

namespace {

// The fill's frames as a steady cadence of its own: at fill_hz, or every display frame.
Condition fillPacing(const Condition& condition, double refreshHz) {
    Condition fill;
    fill.name = condition.name;
    fill.renderHz = condition.fillKind() != Fill::Hold && condition.fillHz ? *condition.fillHz : refreshHz;
    return fill;
}

}  // namespace

ConditionSchedule::ConditionSchedule(const Condition& condition, double refreshHz, std::uint64_t pacingSeed)
    : condition_(condition),
      refreshHz_(refreshHz),
      cadence_(checked(condition, refreshHz), refreshHz, pacingSeed),
      fillCadence_(fillPacing(condition, refreshHz), refreshHz, 0) {
    fill_ = condition.fillKind();
    lagFrames_ = lagFramesAt(condition, refreshHz);
    // Hold makes no frames of its own: a steady cadence's cycle is its render period squared,
    // as the latency ranges have always scanned it.
    cycleFactor_ = fill_ == Fill::Hold ? cadence_.wholePeriod().value_or(1) : fillCadence_.cycleFrames();
}

const Condition& ConditionSchedule::checked(const Condition& condition, double refreshHz) {
    if (const auto p = problem(condition, refreshHz))
        throw std::invalid_argument("condition " + condition.name + (p->part.empty() ? " " : ": " + p->part + " ") +
                                    p->reason);
    return condition;
}

ScheduledFrame ConditionSchedule::produced(std::int64_t j) const {
    ScheduledFrame f;
    // The render on screen at j (the latest shown at or before it) and the one before it.
    const std::int64_t latest = cadence_.latestAtOrBefore(j);
    f.rendersNow = latest == j;
    auto time = [&](std::int64_t frame) { return static_cast<double>(frame) / refreshHz_; };
    // The latest frame the fill made: its own cadence, or a render that came between.
    const std::int64_t made = std::max(fillCadence_.latestAtOrBefore(j), latest);
    switch (fill_) {
        case Fill::Hold: {
            f.sourceIndex = latest;
            f.made = f.kind = f.sourceIndex == j ? FrameKind::Rendered : FrameKind::Held;
            f.cameraTime = f.sceneTime = f.worldSampleTime = time(f.sourceIndex);
            f.samplesInput = f.rendersNow;
            break;
        }
        case Fill::Warp: {
            // The latest render, warped to the instant of the latest fill frame: the camera is
            // read at each (view latency) and pixels move by their velocity (scene latency).
            f.sourceIndex = latest;
            f.made = j == f.sourceIndex ? FrameKind::Rendered
                                        : (made == f.sourceIndex ? FrameKind::Held : FrameKind::Warped);
            f.cameraTime = f.sceneTime = time(made);
            f.worldSampleTime = time(f.sourceIndex);
            f.samplesInput = made == j;
            // Between the frames the fill makes, its last one is shown again (docs/protocol.md,
            // fill_hz): held, and made again as it was (the same instant, the same sources).
            f.kind = made == j ? f.made : FrameKind::Held;
            break;
        }
        case Fill::Bireproj:
        case Fill::Blend: {
            // A frame between two renders can only be made once the later one exists, so the
            // display plays each render interval from the moment the render that ends it
            // arrives, at the fill's cadence (seed 000 section 7): one render period behind
            // when renders are even. When the next render is later than the interval is long,
            // the render that ends it stays on screen until then, however long that is.
            const Between now = between(j), before = between(j - 1);
            const std::int64_t depicted = now.depicted;
            const bool onRender = depicted == now.from || depicted == now.to;
            f.sourceIndex = depicted == now.to ? now.to : now.from;
            f.nextSourceIndex = onRender ? -1 : now.to;
            const bool newFrame = made == j && depicted != before.depicted;
            f.made = onRender ? (newFrame ? FrameKind::Rendered : FrameKind::Held) : FrameKind::Interpolated;
            f.kind = newFrame ? f.made : FrameKind::Held;
            f.sceneTime = time(depicted);
            if (fill_ == Fill::Bireproj) {
                f.cameraTime = f.sceneTime;
                f.worldSampleTime = time(onRender ? f.sourceIndex : f.nextSourceIndex);
            } else {
                // A cross-fade moves nothing: its camera and objects are those of the nearer
                // render (the one its id buffer shows: blend.frag takes B from a weight of 1/2).
                const bool later = !onRender && 2 * (depicted - f.sourceIndex) >= f.nextSourceIndex - f.sourceIndex;
                f.cameraTime = f.worldSampleTime = time(later ? f.nextSourceIndex : f.sourceIndex);
            }
            f.samplesInput = newFrame;
            break;
        }
    }
    return f;
}

ConditionSchedule::Between ConditionSchedule::between(std::int64_t j) const {
    Between b;
    b.to = cadence_.latestAtOrBefore(j);
    b.from = cadence_.latestAtOrBefore(b.to - 1);
    const std::int64_t made = std::max(fillCadence_.latestAtOrBefore(j), b.to);
    b.depicted = std::min(b.from + (made - b.to), b.to);
    return b;
}

ScheduledFrame ConditionSchedule::frame(std::int64_t k) const {
    // What the fill made lagFrames_ ago comes out of the queue now; what is rendered and read
    // now is the fill's work at this frame.
    ScheduledFrame f = produced(k - lagFrames_);
    const ScheduledFrame now = lagFrames_ == 0 ? f : produced(k);
    f.index = k;
    f.displayTime = static_cast<double>(k) / refreshHz_;
    f.rendersNow = now.rendersNow;
    f.samplesInput = now.samplesInput;
    if (condition_.lateWarp != LateWarp::None) {
        // Re-projected at the last moment to the camera read for this display frame (Kim et
        // al. 2020); a depth late warp also moves the objects on to this instant.
        f.samplesInput = true;
        if (f.cameraTime != f.displayTime || (condition_.lateWarp == LateWarp::Depth && f.sceneTime != f.displayTime))
            f.kind = f.made = FrameKind::Warped;
        f.cameraTime = f.displayTime;
        if (condition_.lateWarp == LateWarp::Depth) f.sceneTime = f.displayTime;
    }
    return f;
}

template <typename Depicted>
double ConditionSchedule::firstShowing(double tau, Depicted depicted) const {
    // Display frames are at k / refresh; the first candidate is the first frame at or after tau.
    auto k = static_cast<std::int64_t>(std::ceil(tau * refreshHz_ - 1e-9));
    for (std::int64_t n = 0; n < 1000000; ++n, ++k) {
        const ScheduledFrame f = frame(k);
        if (depicted(f) >= tau - 1e-12) return f.displayTime - tau;
    }
    throw std::logic_error("ConditionSchedule: no frame ever shows the step");
}

double ConditionSchedule::viewLatency(double tau) const {
    return firstShowing(tau, [](const ScheduledFrame& f) { return f.cameraTime; });
}
double ConditionSchedule::sceneLatency(double tau) const {
    return firstShowing(tau, [](const ScheduledFrame& f) { return f.worldSampleTime; });
}

template <typename Depicted>
std::vector<ConditionSchedule::LatencySpan> ConditionSchedule::latencySpans(std::int64_t first, std::int64_t last,
                                                                            Depicted depicted) const {
    // The instants frames depict never decrease with the frame, so between two consecutive
    // distinct instants a < b a step at b is shown by the first frame depicting b, and a step
    // just after a by that same frame, b - a later.
    std::vector<double> instants;
    for (std::int64_t k = first; k <= last; ++k) {
        const double t = depicted(frame(k));
        if (instants.empty() || t > instants.back() + 1e-12) instants.push_back(t);
    }
    std::vector<LatencySpan> spans;
    for (std::size_t i = 1; i < instants.size(); ++i)
        spans.push_back({instants[i - 1], instants[i], instants[i] + firstShowing(instants[i], depicted)});
    return spans;
}

std::int64_t ConditionSchedule::settledFrame() const { return 4 * cycle() + lagFrames_; }

template <typename Depicted>
ConditionSchedule::Range ConditionSchedule::latencyRange(Depicted depicted) const {
    // Two whole cycles cover every case of a cadence that repeats within the horizon; one that
    // does not (drawn, or a rate with no short cycle) is looked at over the horizon, as
    // condition::pacingStats looks at it.
    const auto horizon = std::llround(kDrawnHorizonS * refreshHz_);
    const std::int64_t first = settledFrame();
    const std::int64_t last = first + (cadence_.cycleFrames() < horizon ? 2 * cycle() : horizon);
    Range r{1e300, -1e300};
    for (const LatencySpan& s : latencySpans(first, last, depicted)) {
        r.min = std::min(r.min, s.shownAt - s.to);
        r.max = std::max(r.max, s.shownAt - s.from);
    }
    // Steps and frames are both on the display's frame grid: the latencies are whole frames.
    auto whole = [&](double s) { return static_cast<double>(std::llround(s * refreshHz_)) / refreshHz_; };
    return {whole(r.min), whole(r.max)};
}

std::vector<ConditionSchedule::LatencySpan> ConditionSchedule::viewLatencySpans(std::int64_t first,
                                                                                std::int64_t last) const {
    return latencySpans(first, last, [](const ScheduledFrame& f) { return f.cameraTime; });
}
std::vector<ConditionSchedule::LatencySpan> ConditionSchedule::sceneLatencySpans(std::int64_t first,
                                                                                 std::int64_t last) const {
    return latencySpans(first, last, [](const ScheduledFrame& f) { return f.worldSampleTime; });
}

ConditionSchedule::Range ConditionSchedule::viewLatencyRange() const {
    return latencyRange([](const ScheduledFrame& f) { return f.cameraTime; });
}
ConditionSchedule::Range ConditionSchedule::sceneLatencyRange() const {
    return latencyRange([](const ScheduledFrame& f) { return f.worldSampleTime; });
}

ConditionSummary summarize(const Condition& condition, double refreshHz) {
    const ConditionSchedule schedule(condition, refreshHz);
    return {condition, refreshHz, schedule.lagFrames(), schedule.viewLatencyRange(), schedule.sceneLatencyRange()};
}

}  // namespace warplab::condition
