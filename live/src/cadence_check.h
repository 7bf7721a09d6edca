// Whether a machine keeps a condition's cadence at its refresh (`warplab check`, one line per
// condition; docs/frame-pacing.md). A condition's schedule asks for new images at uneven
// intervals -- 60 fps on 144 Hz 2 and 3 refreshes apart, a jittered one sometimes a refresh
// apart -- and each new image must be made within the interval before it to reach the refresh
// the schedule gives it. The shortest of those intervals is what the machine must meet.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "condition/condition.h"
#include "live/check.h"

namespace warplab::live {

// Display frames between consecutive new images (any frame the schedule does not hold) over a
// cycle of the cadence; a drawn one (jitter, hitches) over twice kDrawnHorizonS of seed 0, as
// `warplab conditions` looks at its latencies.
struct CadenceNeed {
    std::int64_t shortestFrames = 1, longestFrames = 1;
};
CadenceNeed cadenceNeed(const condition::Condition& condition, double refreshHz);

// "cadence MODE": ok when the measured p95 time of the frames that make a new image fits the
// shortest interval, FAIL when it does not (its new images would reach the screen late).
CheckLine cadenceLine(const std::string& condition, const CadenceNeed& need, double refreshHz, double newImageP95Ms,
                      std::size_t frames);

}  // namespace warplab::live
