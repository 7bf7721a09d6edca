// How a session's frames kept pace with its display, per condition, from its frame records: what a
// researcher reads to know whether the stimuli were the protocol's (docs/session-format.md,
// "Pacing"). The live session prints it and stores it; export writes it as pacing.csv.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "session/session_store.h"

namespace warplab::session {

struct ConditionPacing {
    std::string condition;  // "" for the frames of screens (instructions, questions, start)
    std::int64_t shown = 0;  // display frames shown
    // ... that brought a new image (not held or frozen) and reached the screen a vsync or more
    // after the refresh the schedule gave it: what the machine missed. A held frame shown late
    // left the image it repeats on screen, so the display was as the schedule meant it.
    // (Sessions stored before newImages was kept counted every frame shown late.)
    std::int64_t late = 0;
    std::int64_t skipped = 0;  // display frames stepped through and not shown (kSkippedFrameKind)
    // Present to present of the frames shown with a measured time, ms; NaN when none has one
    // (a headless session). p95: the nearest-rank 95th percentile.
    double medianMs = 0.0, p95Ms = 0.0, maxMs = 0.0;
    double budgetMs = 0.0;  // one refresh period: what every frame must fit in
    std::int64_t overBudget = 0;  // frames shown whose time exceeded the budget by more than a tenth
    // The condition's own unevenness against what was shown: the intervals between consecutive
    // new images of a run of the condition's frames, ms -- as its schedule places them (display frames
    // apart, skipped frames included: 2 and 3 refreshes for 60 fps on 144 Hz, a hitch's stall)
    // and as the display showed them (present to present, from one new image shown to the next;
    // a new image skipped is no image shown). NaN when there is no interval (or, shown, none was
    // measured: a headless session, or one stored before these were kept).
    // Frames the schedule makes a new image on, shown or skipped; none in a summary stored before
    // they were counted, which export writes as an empty cell rather than a count of 0.
    std::optional<std::int64_t> newImages = 0;
    double intendedP95Ms = 0.0, intendedMaxMs = 0.0;
    double shownP95Ms = 0.0, shownMaxMs = 0.0;
};

// Frame records added one by one (a live session's, as they are shown), summarised at any
// time; keeps one number a frame.
class PacingTally {
public:
    // `scheduledKind`: what the schedule made of the frame when its record's kind no longer says
    // (a skipped frame's); "" reads the record's kind.
    void add(const FrameRecord& frame, const std::string& scheduledKind = "");
    // Per condition in the order conditions first appear, then the screens' row when there are screens.
    std::vector<ConditionPacing> summary(double refreshHz) const;

private:
    struct Condition {
        ConditionPacing counts;
        std::vector<double> frameMs;  // of the frames shown with a measured time
        std::vector<std::int64_t> intendedFrames;  // display frames between new images
        std::vector<double> shownMs;  // ms between new images shown
        // The run of the condition's frames now going on: its last frame, the last new image in it
        // (-1: none yet), and the time shown since the last new image shown (NaN: not measured).
        std::int64_t lastFrame = -2, lastNewImage = -1;
        double shownSince = 0.0;
        bool newImageShown = false;
    };
    static void addInterval(Condition& condition, const FrameRecord& frame, bool newImage);
    std::vector<Condition> conditions_;  // in order of first appearance
    Condition screens_;
};

std::vector<ConditionPacing> summarizePacing(const std::vector<FrameRecord>& frames, double refreshHz);

// The summary for the supervisor: a heading naming the budget, then a line per condition, e.g.
//   conv120: 1163 shown (34.4 a second of 120), 12 late (1.0 %), 2888 skipped (71.3 %); frame time median
//   25.1 ms, p95 31.0, max 60.2; new images 1163, intended p95 8.3 ms, max 8.3, shown p95 33.4, max 66.7
// (the new images' part only where the condition has intervals).
std::string pacingReport(const std::vector<ConditionPacing>& pacing);

// The summary as JSON text (an array of objects, keys as the fields' snake_case names), as the
// store keeps it; and back. parsePacing returns false for text that is not such an array; a
// key a session stored before it was kept reads as 0 (counts), NaN (times) or, for new_images,
// none.
std::string pacingText(const std::vector<ConditionPacing>& pacing);
bool parsePacing(const std::string& text, std::vector<ConditionPacing>& out);

}  // namespace warplab::session
