// A discrimination task's stimulus dimension: the part of a condition whose level an adaptive
// procedure varies against a reference condition (docs/adaptive-procedures.md). Each dimension
// is named by the condition's own JSON key, so a protocol says "lag_frames" as its conditions
// do; the condition at a level is the reference with that part set, and whether a display can
// show it is condition::problem's answer, as for any condition.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "condition/condition.h"

namespace warplab::condition {

enum class Dimension {
    LagFrames,  // "lag_frames": added latency in whole display frames
    RenderHz,  // "render_hz": conventional renders per second
    JitterSdMs,  // "frame_time_jitter.sd_ms": the SD of normal frame-time jitter, ms
};

struct DimensionSpelling {
    const char* name;
    Dimension dimension;
};
// Every dimension by its key, in this order; one list, read by parsing and messages.
const std::vector<DimensionSpelling>& dimensionSpellings();
std::optional<Dimension> dimensionNamed(const std::string& name);
const char* dimensionName(Dimension dimension);

// `reference` with the dimension's part at `level`, named "<reference>@<key>=<level>" (as
// logs and CSVs write it). A lag replaces the reference's own (lag_ms included); a jitter
// level makes the jitter normal. Throws std::invalid_argument for a level the part cannot take
// at all (a lag that is not a whole number of frames or is outside 0..kMaxLagFrames, a rate or
// SD that is not a positive or non-negative number); whether a display can show it is
// problem(varied(...), refreshHz).
Condition varied(const Condition& reference, Dimension dimension, double level);

}  // namespace warplab::condition
