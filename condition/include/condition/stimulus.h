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

// The dimension's part of `c` on a display of refreshHz: its lag in whole display frames (the
// presets' lag_ms counted in frames), its render rate, its jitter's SD (0 without jitter; the
// SD of a normal or lognormal jitter). Throws std::invalid_argument as lagFramesAt does.
double levelOf(const Condition& c, Dimension dimension, double refreshHz);
// How much worse a level is than the reference's: added lag or jitter above the reference's,
// render rate below it. What a discrimination task's psychometric function is a function of:
// positive for a test condition that is worse, and growing as it gets easier to tell apart.
double stimulusOf(Dimension dimension, double referenceLevel, double level);
// The stimulus's units, as reports write them: "display frames", "Hz", "ms".
const char* dimensionUnits(Dimension dimension);

}  // namespace warplab::condition
