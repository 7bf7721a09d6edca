// A study session in a real window (seed 004 section 5.2 and Appendix B;
// seed 000 section 8): the participant's mouse in relative mode, one frame per vsync (or per
// timer tick where vsync or the refresh rate cannot be had), the frames made as the condition makes
// them with the HUD over them, feedback sounds, and the supervisor's start, pause, abort and
// end screens. The session is written as it runs, like a headless one, and replays the same.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "renderer/context.h"
#include "renderer/conventional.h"

namespace warplab::live {

struct LiveRun {
    std::string protocolPath;
    std::string protocolText, planId;  // a study plan's run: as runner::HeadlessRun's
    std::string participant;
    std::string resultsDir;
    std::string player = "human";  // "human", "bot[:SEED]" or "replay:SESSION"
    std::uint64_t seed = 1;
    // An interrupted session to carry on (runner/resume.h): its protocol, seed, participant,
    // plan and display size replace the run's own.
    std::string resumeFrom;
    bool fullscreen = false;
    int display = 0;
    int width = 1280, height = 720;  // windowed size; fullscreen takes the display's
    // The participant's mouse: a full turn (shooter) takes cmPer360 cm of mouse travel at
    // mouseDpi counts per inch; 0 keeps the protocol's own sensitivity. Logged in the header.
    double cmPer360 = 0.0;
    double mouseDpi = 800.0;
    bool invertY = false;
    // A known display refresh that differs from the protocol's refuses the session unless
    // this is set (then it warns).
    bool allowRefreshMismatch = false;
    // Tests: a script of input the window receives as if from the participant, one action a
    // line: "WHEN ACTION", WHEN a session frame number, "start" (the start screen) or "end"
    // (the end screen); ACTION "key enter|esc|pageup|pagedown|[|]|0-9|a-z", "move DX DY"
    // (mouse counts) or "click" (a left press). Lines starting with # are comments.
    std::string inputScript;
    // Every display frame is shown, however late: the session runs in slow motion on a machine
    // too slow for its protocol. For input scripts and screenshots that name session frames
    // (tests, documentation); a study leaves it off, so that time follows the display.
    bool everyFrame = false;
    // Tests of the display clock: every slowEvery-th displayed frame takes slowMs longer to
    // make (a sleep where the frame is made), as a slow machine's would; 0 for none.
    double slowMs = 0.0;
    int slowEvery = 0;
    // Test and documentation aid: write the window's frame as PNG at these session frames.
    std::string screenshotDir;
    std::vector<std::int64_t> screenshotFrames;
    bool screenshotStartScreen = false;
    // The photodiode marker: "" for the protocol's display.photon_marker, else one of its
    // spellings ("off", "top_left" ...), which replaces it.
    std::string photonMarker;
    // Free play (runFreePlay): the condition and difficulty it starts in ("" = the protocol's first).
    std::string freePlayCondition;
    int freePlayLevel = 0;
};

// How a live session ended: its file ("" if the supervisor left at the start screen), and
// whether the supervisor ended it before its end (Esc then Q, the window's close then Q, Esc
// on the start screen), which `run` tells a script by its exit status.
struct LiveEnd {
    std::string session;
    bool endedBySupervisor = false;
};

// Runs the session. Throws for bad input (protocol, results folder, refresh mismatch) before
// anything is written.
LiveEnd runLive(const LiveRun& run, const renderer::DataPaths& paths, std::ostream& progress);

// Free play for pilots and demonstrations: the protocol's game, endless and unrecorded; keys
// 1-9 switch live to the nine presets (condition::presets()), ] and [ (PageDown and PageUp)
// step to the next and previous of all of them and of the protocol's own conditions (around the list, over those the display
// cannot run), U and D change the difficulty, the status line shows the condition and the frame
// times; Esc pauses, Q ends. Returns when it ends.
void runFreePlay(const LiveRun& run, const renderer::DataPaths& paths, std::ostream& progress);

}  // namespace warplab::live
