// How a session's frames kept pace with its display, per mode, from its frame records: what a
// researcher reads to know whether the stimuli were the protocol's (docs/session-format.md,
// "Pacing"). The live session prints it and stores it; export writes it as pacing.csv.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "session/session_store.h"

namespace warplab::session {

struct ModePacing {
    std::string mode;  // "" for the frames of screens (instructions, questions, start)
    std::int64_t shown = 0;  // display frames shown
    std::int64_t late = 0;  // ... that reached the screen a vsync or more late
    std::int64_t skipped = 0;  // display frames stepped through and not shown (kSkippedFrameKind)
    // Present to present of the frames shown with a measured time, ms; NaN when none has one
    // (a headless session). p95: the nearest-rank 95th percentile.
    double medianMs = 0.0, p95Ms = 0.0, maxMs = 0.0;
    double budgetMs = 0.0;  // one refresh period: what every frame must fit in
    std::int64_t overBudget = 0;  // frames shown whose time exceeded the budget by more than a tenth
};

// Frame records added one by one (a live session's, as they are shown), summarised at any
// time; keeps one number a frame.
class PacingTally {
public:
    void add(const FrameRecord& frame);
    // Per mode in the order modes first appear, then the screens' row when there are screens.
    std::vector<ModePacing> summary(double refreshHz) const;

private:
    struct Mode {
        ModePacing counts;
        std::vector<double> frameMs;  // of the frames shown with a measured time
    };
    std::vector<Mode> modes_;  // in order of first appearance
    Mode screens_;
};

std::vector<ModePacing> summarizePacing(const std::vector<FrameRecord>& frames, double refreshHz);

// The summary for the supervisor: a heading naming the budget, then a line per mode, e.g.
//   conv120: 1163 shown (34.4 a second of 120), 12 late (1.0 %), 2888 skipped (71.3 %); frame time median
//   25.1 ms, p95 31.0, max 60.2
std::string pacingReport(const std::vector<ModePacing>& pacing);

// The summary as JSON text (an array of objects, keys as the fields' snake_case names), as the
// store keeps it; and back. parsePacing returns false for text that is not such an array.
std::string pacingText(const std::vector<ModePacing>& pacing);
bool parsePacing(const std::string& text, std::vector<ModePacing>& out);

}  // namespace warplab::session
