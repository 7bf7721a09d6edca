// `warplab check`: the pre-flight a supervisor runs on the machine before a participant sits
// down (docs/live-sessions.md, "The supervisor's steps"). One line per check, ok / warn /
// FAIL with a short reason: the GL context, the display's refresh as the system reports it
// and as ~2 s of swaps measure it, vsync, the frame time of every condition of the protocol at
// the display's size and whether it keeps that condition's cadence, the results folder and its lock, disk space for a session, and the
// audio device. A FAIL is what would refuse the session or spoil its data: a refresh the
// protocol refuses (an unknown one included), frames slower than a refresh or than a
// condition's shortest interval between new images, no room, no folder.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "renderer/conventional.h"

namespace warplab::live {

struct CheckRun {
    std::string protocolPath;  // "" checks the machine alone: nothing a protocol decides
    std::string resultsDir = "results";
    // The window as `warplab run` would open it.
    bool fullscreen = false;
    int display = 0;
    int width = 1280, height = 720;
    // As run's: a refresh that differs from the protocol's (or is unknown) warns, not fails.
    bool allowRefreshMismatch = false;
    double refreshSeconds = 2.0;  // swaps timed for the measured refresh
    double conditionSeconds = 1.0;  // frames made per condition, after its first renders
    // The photodiode's test pattern (`--photon CORNER`, display.photon_marker's spelling; "" for
    // none): the marker in that corner white for photonOnS, black for as long, photonCycles
    // times, counted in display frames, so a meter's threshold and placement can be checked
    // against a known square wave before a session.
    std::string photonCorner;
    double photonOnS = 0.25;
    int photonCycles = 10;
};

enum class Verdict { Ok, Warn, Fail };

struct CheckLine {
    Verdict verdict = Verdict::Ok;
    std::string name;  // "refresh", "frame time conv15", ...
    std::string detail;
};

// "ok    refresh: 120 Hz, as protocol 'shooter-thesis' needs": the verdict in a column of six.
std::string formatCheckLine(const CheckLine& line);

// Runs every check, writing each line to `out` as soon as it is known (the frame times take a
// second or more each); returns them all. Throws only for what is no check's business: a
// protocol file that does not load, shaders that cannot be found.
std::vector<CheckLine> checkMachine(const CheckRun& run, const renderer::DataPaths& paths, std::ostream& out);

}  // namespace warplab::live
