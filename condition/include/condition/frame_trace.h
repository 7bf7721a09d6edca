// Frame times recorded from a real game, played as a condition's render intervals
// (docs/frame-pacing.md, "Traces"): MangoHud's CSV log, PresentMon's CSV (its older
// msBetweenPresents and newer MsBetweenPresents / FrameTime spellings; CapFrameX writes the
// same columns) and a plain list of one frame time in milliseconds per line. A trace is played
// from a stated offset, looped, and optionally rescaled to a stated mean rate; the protocol
// copy a session stores keeps the frame times themselves, so the session replays without the file.
#pragma once

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace warplab::condition {

// The most frames a trace may hold: a session keeps the trace in its protocol copy, which a
// protocol's size limit bounds (20000 frames is 5.5 minutes at 60 fps, 2.3 at 144).
inline constexpr std::size_t kMaxTraceFrames = 20000;
// The longest frame time a trace may hold, ms: longer is a capture's pause, not a frame.
inline constexpr double kMaxTraceFrameMs = 10000.0;

// The formats, as the protocol's frame_times.format names them.
inline constexpr const char* kTraceFormats[] = {"mangohud", "presentmon", "list"};

struct FrameTrace {
    std::vector<double> recordedMs;  // each frame's time as recorded, in order
    std::string file;  // the file as the protocol names it; "" for frame times written inline
    std::string sha256;  // of the file's bytes, hex; "" inline
    std::string format;  // one of kTraceFormats; "" inline
    double offsetS = 0.0;  // where playing starts, seconds into the (rescaled) trace
    std::optional<double> meanHz;  // rescaled so that its mean rate is this; unset: as recorded

    // What each recorded time is multiplied by when played.
    double scale() const;
    // Frames per second as played: meanHz, or the recording's own.
    double playedHz() const;
    double longestPlayedMs() const;
    // The frame played first: the one in progress offsetS into the trace (looped).
    std::size_t firstFrame() const;
    bool operator==(const FrameTrace& o) const {
        return recordedMs == o.recordedMs && file == o.file && sha256 == o.sha256 && format == o.format &&
            offsetS == o.offsetS && meanHz == o.meanHz;
    }
};

// A trace file that cannot be played: the 1-based line at fault (0: the file as a whole) and
// why, in words that say what is allowed.
class TraceError : public std::runtime_error {
public:
    TraceError(std::size_t line, const std::string& reason) : std::runtime_error(reason), line_(line) {}
    std::size_t line() const { return line_; }

private:
    std::size_t line_;
};

// The format of a trace file's text, from its first lines: "mangohud", "presentmon", "list";
// throws TraceError when it is none of them.
std::string detectTraceFormat(const std::string& text);
// The frame times of a trace file in `format`; throws TraceError for an empty file, missing
// columns, a value that is not a number, and a frame time that is zero, negative or over
// kMaxTraceFrameMs. PresentMon's first row of a swap chain has no present before it, and its
// msBetweenPresents of 0 is passed over.
std::vector<double> parseTrace(const std::string& text, const std::string& format);

}  // namespace warplab::condition
