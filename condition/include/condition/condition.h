// What a study condition is, as data (DESIGN.md "Time, modes and determinism"): composed from
// parts -- how often frames are rendered, how long they wait in a queue, what makes the display
// frames between renders, and whether the frame on screen is re-projected to the display
// instant's camera at the last moment (late warp, Kim et al. 2020). A protocol names the nine
// published conditions by their preset ids and defines any other in its "conditions" object;
// both are this one struct, and condition/schedule.h turns one into its frame schedule.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "condition/frame_trace.h"

namespace warplab::condition {

// What makes the display frames between two conventional renders.
enum class Fill : std::uint8_t {
    Hold,  // the last render stays on screen
    Warp,  // the latest render warped to each fill frame's camera, its pixels moved by their velocities
    Bireproj,  // bidirectional reprojection between the renders before and after (one render period late)
    Blend,  // a cross-fade of the renders before and after (one render period late)
};

// Re-projecting the frame the queue puts on screen to the camera of the instant it is shown.
enum class LateWarp : std::uint8_t {
    None,
    Rotation,  // depth-free camera-rotation reprojection; the world stays as rendered
    Depth,  // the warp, with depth and the objects' velocities, to the display instant
};

// The spellings of the protocol's "fill" and the renderer method each one names: "hold", the
// warp methods by name, "bireproj", "blend". One list, read by parsing, messages and export.
struct FillSpelling {
    const char* name;
    Fill fill;
};
const std::vector<FillSpelling>& fillSpellings();
// nullopt for a name no fill has.
std::optional<Fill> fillNamed(const std::string& name);
// "none", "rotation", "depth".
const char* lateWarpName(LateWarp lateWarp);
std::optional<LateWarp> lateWarpNamed(const std::string& name);
const std::vector<LateWarp>& lateWarps();

// The renderer method a depth late warp of a held frame uses: the warp of warp15to120.
inline constexpr const char* kDepthLateWarpMethod = "warp-sparse8";
// The renderer method of a rotation late warp.
inline constexpr const char* kRotationLateWarpMethod = "rotation";

// The most added latency a composed condition may give in display frames (lag_frames): 4 s at
// 120 Hz, a stray digit's worth past any study of latency.
inline constexpr int kMaxLagFrames = 480;
// The longest look back a condition may have, in display frames: its lag plus two render
// periods (a held render, and bidirectional reprojection's wait for the next). Games keep this
// much of their history (game/frame_history.h). Room for the longest lag either field allows
// (lag_frames 480; lag_ms 1000 at the 1000 Hz ceiling) and render periods of hundreds of frames.
inline constexpr std::int64_t kMaxLookBackFrames = 2048;

// Frame-time jitter (docs/frame-pacing.md): each render interval drawn around 1 / render_hz from
// the schedule's seeded stream, so a seed means the same cadence and replay is exact.
enum class JitterShape : std::uint8_t {
    None,
    Normal,  // sd_ms; draws beyond 3 SD of the mean are drawn again, so no interval is negative
    Lognormal,  // sd_ms; the mean interval is 1 / render_hz
    Uniform,  // range_ms: the mean interval +- range_ms / 2
};
const char* jitterShapeName(JitterShape shape);
std::optional<JitterShape> jitterShapeNamed(const std::string& name);
const std::vector<JitterShape>& jitterShapes();

struct Jitter {
    JitterShape shape = JitterShape::None;
    double sdMs = 0.0;  // normal, lognormal
    double rangeMs = 0.0;  // uniform
    bool operator==(const Jitter& o) const { return shape == o.shape && sdMs == o.sdMs && rangeMs == o.rangeMs; }
};

// Stalls added to the render cadence: the render due when a hitch falls stalls `ms` longer.
// Periodic (every everyS seconds, the first at everyS) or random (a Poisson process of
// ratePerS, from the schedule's seeded stream); ms 0: none.
struct Hitches {
    double ms = 0.0;
    double everyS = 0.0;
    double ratePerS = 0.0;
    bool operator==(const Hitches& o) const { return ms == o.ms && everyS == o.everyS && ratePerS == o.ratePerS; }
};

struct Condition {
    std::string name;  // as protocols, logs and CSVs write it
    std::string description;
    double renderHz = 60.0;  // conventional renders per second (bidirectional reprojection's I-frames)
    // Added latency: rendered frames wait this long in a queue before shown. A composed
    // condition gives whole display frames (lag_frames) or milliseconds (lag_ms), which must be
    // whole frames at the display's refresh; the presets give milliseconds.
    std::optional<int> lagFrames;
    double lagMs = 0.0;
    std::string fill = "hold";  // a FillSpelling's name
    std::optional<double> fillHz;  // frames the fill makes per second; unset: every display frame
    LateWarp lateWarp = LateWarp::None;
    Jitter jitter;  // frame_time_jitter
    Hitches hitches;
    // A real game's frame times (frame_times), played as the render intervals; renderHz is then
    // the rate they play at. Shared: a trace is read once, and copies of a condition are many.
    std::shared_ptr<const FrameTrace> frameTimes;

    Fill fillKind() const;  // of `fill`, which parsing has checked
    // Whether render intervals are all 1 / render_hz: no jitter, no hitches, no trace.
    bool steadyPacing() const { return jitter.shape == JitterShape::None && hitches.ms == 0.0 && !frameTimes; }
    // Whether the world a frame shows is the source's moved on by velocities (warp fill, depth
    // late warp), as opposed to the world as sampled or blended.
    bool movesWorld() const { return fillKind() == Fill::Warp || lateWarp == LateWarp::Depth; }
    // The renderer method that makes its warped frames ("" when it makes none) and its
    // interpolated ones; the method its sources are rendered for (guard band, flow).
    std::string warpMethod() const;
    std::string interpolationMethod() const;
    std::string sourceMethod() const;
    // The parts, not the name or description: a definition that repeats a preset's parts may
    // use its name.
    bool sameParts(const Condition& other) const;
};

// The nine published presets, in their documented order.
const std::vector<Condition>& presets();
const Condition* findPreset(const std::string& name);
// Throws std::invalid_argument naming the unknown preset and listing the known ones.
const Condition& preset(const std::string& name);
std::vector<std::string> presetNames();

// What is wrong with a condition on a display of refreshHz: the part at fault (its JSON key:
// "render_hz", "lag_frames", "lag_ms", "fill", "fill_hz", "late_warp", or a key within
// "frame_time_jitter" and "hitches", as "hitches.ms") and why, in words that
// name the allowed values. nullopt when it can run.
struct Problem {
    std::string part;
    std::string reason;
};
std::optional<Problem> problem(const Condition& condition, double refreshHz);

// Display frames a rendered frame waits at refreshHz; throws std::invalid_argument as
// problem() would say.
std::int64_t lagFramesAt(const Condition& condition, double refreshHz);

// The conditions a protocol can name: the presets, then the ones it defines.
class ConditionTable {
public:
    ConditionTable() = default;
    explicit ConditionTable(std::vector<Condition> defined) : defined_(std::move(defined)) {}
    const std::vector<Condition>& defined() const { return defined_; }
    const Condition* find(const std::string& name) const;
    // Throws std::invalid_argument naming the unknown condition and listing the known ones.
    const Condition& at(const std::string& name) const;
    std::vector<std::string> names() const;  // presets first
    // "" when `name` is known and can run at refreshHz, else the reason in one sentence.
    std::string check(const std::string& name, double refreshHz) const;
    bool operator==(const ConditionTable& o) const;
    bool operator!=(const ConditionTable& o) const { return !(*this == o); }

private:
    std::vector<Condition> defined_;
};

// A rate or a duration for a message: "60", "59.94", "58.333", never "60.000000".
std::string number(double value);

// total / part when it is a whole number n >= 1 and n parts make total to the last bits of a
// double (29.97 Hz fits 59.94 Hz twice), else nullopt: 59.999999999 Hz is not 60 Hz, and a
// display would run it as 60 Hz. How a render, fill or physics rate is checked against a refresh.
std::optional<std::int64_t> wholeRatio(double total, double part);

}  // namespace warplab::condition
