#include "cadence_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "condition/schedule.h"

namespace warplab::live {

CadenceNeed cadenceNeed(const condition::Condition& condition, double refreshHz) {
    const condition::ConditionSchedule schedule(condition, refreshHz, 0);
    const std::int64_t cycle = schedule.cadence().cycleFrames();
    // Past what a lag or bidirectional queue held before the schedule began; a second at least,
    // so that a fill slower than the refresh shows its own cycle too.
    const std::int64_t first = schedule.lagFrames() + cycle;
    const std::int64_t last = first + std::max<std::int64_t>(2 * cycle, std::llround(refreshHz));
    CadenceNeed need{std::numeric_limits<std::int64_t>::max(), 0};
    std::int64_t previous = -1;
    for (std::int64_t k = first; k <= last; ++k) {
        if (schedule.frame(k).kind == condition::FrameKind::Held) continue;
        if (previous >= 0) {
            need.shortestFrames = std::min(need.shortestFrames, k - previous);
            need.longestFrames = std::max(need.longestFrames, k - previous);
        }
        previous = k;
    }
    if (need.longestFrames == 0) need = {last - first, last - first};  // one new image in all that: as slow as it gets
    return need;
}

CheckLine cadenceLine(const std::string& condition, const CadenceNeed& need, double refreshHz, double newImageP95Ms,
                      std::size_t frames) {
    const double shortestMs = 1000.0 * static_cast<double>(need.shortestFrames) / refreshHz;
    const bool keeps = newImageP95Ms <= shortestMs;
    auto refreshes = [](std::int64_t n) { return std::to_string(n) + (n == 1 ? " refresh" : " refreshes"); };
    char numbers[96];
    std::snprintf(numbers, sizeof numbers, "p95 %.1f ms over %zu frames, %s the %.2f ms", newImageP95Ms, frames,
                  keeps ? "within" : "longer than", shortestMs);
    std::string detail = std::string("its frames that make a new image take ") + numbers +
        " its schedule leaves the shortest of its intervals between new images (" + refreshes(need.shortestFrames) +
        " at " + std::to_string(std::lround(refreshHz)) + " Hz; they run " + std::to_string(need.shortestFrames) +
        " to " + std::to_string(need.longestFrames) + ")";
    if (!keeps) detail += ": its new images would reach the screen after the refreshes the schedule gives them";
    return {keeps ? Verdict::Ok : Verdict::Fail, "cadence " + condition, detail};
}

}  // namespace warplab::live
