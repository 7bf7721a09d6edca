#include "condition/pacing.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <vector>

#include "physics/splitmix.h"

namespace warplab::condition {
namespace {

// A render instant that is a whole display frame to the last bits (5 renders of 60 Hz are 12
// frames of 144 Hz, 12.000000000000002 in doubles) is shown at that frame, not the next.
constexpr double kOnFrame = 1e-7;

std::int64_t frameAtOrAfter(double frames) { return static_cast<std::int64_t>(std::ceil(frames - kOnFrame)); }

// Normal draws farther than this many SDs from the mean are drawn again (symmetric, so the
// mean stays 1 / render_hz; the SD drops by 1.3 %); log-normal draws farther above it, so one
// draw cannot stall a session (at an SD of 0.72 times the mean, 12 ms at 60 fps, one draw in
// 6000 is cut: the mean drops 0.2 % and the SD 1.5 %).
constexpr double kNormalCutSd = 3.0;
constexpr double kLognormalCutSd = 10.0;

double meanIntervalS(const Condition& c) { return 1.0 / c.renderHz; }

}  // namespace

double longestRenderIntervalS(const Condition& c) {
    double longest = c.frameTimes ? c.frameTimes->longestPlayedMs() / 1000.0 : meanIntervalS(c);
    switch (c.jitter.shape) {
        case JitterShape::None: break;
        case JitterShape::Normal: longest += kNormalCutSd * c.jitter.sdMs / 1000.0; break;
        case JitterShape::Lognormal: longest += kLognormalCutSd * c.jitter.sdMs / 1000.0; break;
        case JitterShape::Uniform: longest += c.jitter.rangeMs / 2000.0; break;
    }
    // Hitches falling in one interval merge into one stall (Drawn::next).
    return longest + c.hitches.ms / 1000.0;
}

// The cadence from frame 0 on, drawn as far as anyone has asked. Copies of a schedule share it;
// the mutex makes a shared schedule safe to read from two threads.
struct RenderCadence::Drawn {
    Condition condition;
    double refreshHz;
    std::uint64_t jitterState, hitchState;
    std::mutex mutex;
    std::vector<std::int64_t> frames{0};  // the display frame that first shows each render
    double time = 0.0;  // of the latest render drawn, seconds
    double nextHitchS = 0.0;
    std::size_t traceFrame = 0;  // the next of a trace's frames to play
    double traceScale = 1.0;

    Drawn(const Condition& c, double refresh, std::uint64_t seed)
        : condition(c),
          refreshHz(refresh),
          jitterState(seed ^ 0x6A17735EED5EEDULL),
          hitchState(seed ^ 0x417C4E55EED5EEDULL) {
        nextHitchS = condition.hitches.everyS > 0.0 ? condition.hitches.everyS : exponential();
        if (condition.frameTimes) {
            traceFrame = condition.frameTimes->firstFrame();
            traceScale = condition.frameTimes->scale();
        }
    }

    double uniform(std::uint64_t& state) {  // (0, 1): never 0, so log() stays finite
        return (static_cast<double>(physics::splitmix64(state) >> 11) + 0.5) * 0x1.0p-53;
    }
    double gaussian() {  // Box-Muller
        constexpr double kTwoPi = 6.28318530717958647692;
        const double u = uniform(jitterState);
        return std::sqrt(-2.0 * std::log(u)) * std::cos(kTwoPi * uniform(jitterState));
    }
    double exponential() {
        return condition.hitches.ratePerS > 0.0 ? -std::log(uniform(hitchState)) / condition.hitches.ratePerS : 1e300;
    }

    double interval() {
        if (const FrameTrace* trace = condition.frameTimes.get()) {
            // Looped: the frame after the last is the first.
            const double ms = trace->recordedMs[traceFrame] * traceScale;
            traceFrame = (traceFrame + 1) % trace->recordedMs.size();
            return ms / 1000.0;
        }
        const double mean = meanIntervalS(condition), sd = condition.jitter.sdMs / 1000.0;
        switch (condition.jitter.shape) {
            case JitterShape::None: return mean;
            case JitterShape::Normal:
                for (;;) {
                    const double z = gaussian();
                    if (std::abs(z) <= kNormalCutSd) return mean + sd * z;
                }
            case JitterShape::Lognormal: {
                // The log-normal whose mean and SD are those asked.
                const double s2 = std::log1p((sd * sd) / (mean * mean));
                const double mu = std::log(mean) - s2 / 2.0;
                for (;;) {
                    const double d = std::exp(mu + std::sqrt(s2) * gaussian());
                    if (d <= mean + kLognormalCutSd * sd) return d;
                }
            }
            case JitterShape::Uniform: return mean + (uniform(jitterState) - 0.5) * condition.jitter.rangeMs / 1000.0;
        }
        return mean;
    }

    // Draws the next render; a render ready within the same refresh as the one after it is
    // never shown (the newest ready render is what a refresh shows), and nothing any frame
    // depicts depends on it.
    void next() {
        double t = time + interval();
        if (condition.hitches.ms > 0.0 && nextHitchS <= t) {
            // The render due when the hitch falls is late by its length; hitches that fall
            // during that stall merge with it.
            t += condition.hitches.ms / 1000.0;
            while (nextHitchS <= t)
                nextHitchS += condition.hitches.everyS > 0.0 ? condition.hitches.everyS : exponential();
        }
        time = t;
        const std::int64_t frame = frameAtOrAfter(t * refreshHz);
        if (frame > frames.back()) frames.push_back(frame);
    }

    // The index of the first render shown after frame j (j >= 0), drawing as far as needed.
    std::size_t firstAfter(std::int64_t j) {
        while (frames.back() <= j) next();
        return static_cast<std::size_t>(std::upper_bound(frames.begin(), frames.end(), j) - frames.begin());
    }
};

RenderCadence::RenderCadence(const Condition& c, double refreshHz, std::uint64_t seed)
    : framesPerRender_(refreshHz / c.renderHz) {
    if (!c.steadyPacing()) {
        drawn_ = std::make_shared<Drawn>(c, refreshHz, seed);
        cycleFrames_ = std::max<std::int64_t>(1, std::llround(kDrawnHorizonS * refreshHz));
        return;
    }
    wholePeriod_ = wholeRatio(refreshHz, c.renderHz);
    if (wholePeriod_) {
        cycleFrames_ = *wholePeriod_;
        return;
    }
    // The fewest renders that make whole display frames (5 of 60 Hz are 12 of 144 Hz); a rate
    // with no short cycle is looked at over the drawn horizon.
    cycleFrames_ = std::max<std::int64_t>(1, std::llround(kDrawnHorizonS * refreshHz));
    for (std::int64_t n = 1; n <= 10000; ++n) {
        const double frames = static_cast<double>(n) * framesPerRender_;
        if (std::abs(frames - std::round(frames)) < kOnFrame) {
            cycleFrames_ = std::llround(frames);
            break;
        }
    }
}

std::int64_t RenderCadence::steadyFrame(std::int64_t i) const {
    if (wholePeriod_) return i * *wholePeriod_;
    return frameAtOrAfter(static_cast<double>(i) * framesPerRender_);
}

std::int64_t RenderCadence::steadyIndex(std::int64_t j) const {
    if (wholePeriod_) {
        const std::int64_t p = *wholePeriod_;
        return (j - (((j % p) + p) % p)) / p;  // floor division, right for negative frames too
    }
    // steadyFrame(i) <= j exactly when i * framesPerRender - kOnFrame <= j.
    return static_cast<std::int64_t>(std::floor((static_cast<double>(j) + kOnFrame) / framesPerRender_));
}

std::int64_t RenderCadence::latestAtOrBefore(std::int64_t j) const {
    if (drawn_ && j >= 0) {
        const std::lock_guard<std::mutex> lock(drawn_->mutex);
        return drawn_->frames[drawn_->firstAfter(j) - 1];
    }
    return steadyFrame(steadyIndex(j));
}

std::int64_t RenderCadence::firstAfter(std::int64_t j) const {
    if (drawn_ && j >= 0) {
        const std::lock_guard<std::mutex> lock(drawn_->mutex);
        return drawn_->frames[drawn_->firstAfter(j)];
    }
    return steadyFrame(steadyIndex(j) + 1);  // at most 0, where the drawn cadence starts
}

}  // namespace warplab::condition
