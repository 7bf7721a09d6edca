// What the condition tests read off a schedule: the display frames that show a new render.
#pragma once

#include <cstdint>
#include <vector>

#include "condition/schedule.h"

namespace warplab::condition {

// The display frames that show a new render, in [0, frames].
inline std::vector<std::int64_t> renderFrames(const ConditionSchedule& s, std::int64_t frames) {
    std::vector<std::int64_t> out;
    for (std::int64_t k = 0; k <= frames; ++k)
        if (s.frame(k).rendersNow) out.push_back(k);
    return out;
}

}  // namespace warplab::condition
