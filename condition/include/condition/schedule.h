// Study modes as frame schedules on the display clock (DESIGN.md "Time, modes and
// determinism"). A mode says, for every displayed frame: is it rendered, held, warped or
// interpolated; is the mouse read for it; which instant's camera and which instant's world it
// depicts. Everything else -- the game loop, scoring, replay, the latency table in the
// README -- reads these schedules, so a mode's timing is written down once.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace warplab::condition {

enum class FrameKind : std::uint8_t { Rendered, Held, Warped, Interpolated };
const char* frameKindName(FrameKind kind);

enum class Upconversion : std::uint8_t { None, Warp, Bidirectional };
// "none", "warp", "bidirectional": as modes.csv writes it (docs/export.md).
const char* upconversionName(Upconversion upconversion);

struct ModeSpec {
    std::string id;  // as used in protocols, logs and CSVs
    std::string description;
    double renderRateHz = 60.0;  // conventional renders per second (I-frames for bireproj)
    double lagMs = 0.0;  // rendered frames wait this long in a queue before shown
    Upconversion upconversion = Upconversion::None;
    double upconvertedRateHz = 0.0;  // frames made per second by warp (every display frame) or bireproj
    std::string method;  // renderer method that makes the in-between frames
};

// Every mode's id, in the order of the one mode table (game/src/modes.cpp): the nine published
// presets first. Docs, tests, export's modes.csv and the analysis all follow that table.
std::vector<std::string> modeIds();
// Throws std::invalid_argument naming the unknown id and listing the known ones.
const ModeSpec& modeSpec(const std::string& id);
// For protocol validation (protocol/ cannot include game/, so the loader is handed this):
// "" when `id` names a mode that can run on a display of refreshHz, else the reason, e.g.
// "unknown mode 'conv45' (known: ...)" or "mode conv15 needs a display refresh that is ...".
std::string checkMode(const std::string& id, double refreshHz);

// What one displayed frame depicts. Times are seconds since the schedule started (a mode
// switch starts a new schedule); they may be negative for lag and bidirectional modes, whose
// first frames show what the queue held before the switch.
struct ScheduledFrame {
    std::int64_t index = 0;  // display frame since the schedule started
    double displayTime = 0.0;  // when it is shown
    FrameKind kind = FrameKind::Rendered;
    double cameraTime = 0.0;  // the instant whose camera (mouse) it shows
    double sceneTime = 0.0;  // the instant whose world it shows (warp: by extrapolation)
    // The latest instant at which the world was sampled for it: a change in the world's motion
    // (not just its continuation) shows from here on. Warp extrapolates the source's motion,
    // so a target that changes course shows only in the next source frame.
    double worldSampleTime = 0.0;
    bool rendersNow = false;  // a conventional frame is rendered at this display frame
    bool samplesInput = false;  // the mouse is read for this frame
    std::int64_t sourceIndex = 0;  // display frame whose conventional render it is made from
    std::int64_t nextSourceIndex = -1;  // bidirectional: the later source frame
};

class ModeSchedule {
public:
    // Throws std::invalid_argument when the display refresh is not a whole multiple of the
    // mode's rates (a 15 Hz mode on a 100 Hz display would judder unevenly).
    ModeSchedule(const ModeSpec& mode, double refreshHz);

    const ModeSpec& mode() const { return mode_; }
    double refreshHz() const { return refreshHz_; }
    ScheduledFrame frame(std::int64_t index) const;

    // Latency of a step at instant tau: time from tau to the first displayed frame whose
    // camera was read at or after tau (view), or whose world was sampled at or after tau
    // (scene: a change in the world's motion).
    double viewLatency(double tau) const;
    double sceneLatency(double tau) const;

private:
    template <typename Depicted>
    double firstShowing(double tau, Depicted depicted) const;
    ModeSpec mode_;
    double refreshHz_;
    std::int64_t renderPeriod_;  // display frames between conventional renders
    std::int64_t lagFrames_;  // display frames a rendered frame waits (lag modes)
    std::int64_t bPeriod_;  // display frames per bidirectional B-frame
};

}  // namespace warplab::condition
