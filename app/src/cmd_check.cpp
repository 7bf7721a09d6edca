#include <iostream>

#include "commands.h"
#include "live/check.h"
#include "scene/limits.h"

namespace warplab::app {

int runCheck(const ParsedArgs& args) {
    live::CheckRun run;
    if (args.has("study")) {
        // The plan's copy of the participant's protocol and the rig's folder, as run --study
        // would take them.
        if (args.has("out")) throw UsageError("option --out comes from the study plan with --study (--rig NAME)");
        const StudyPick pick = pickFromPlan(args);
        run.protocolPath = pick.protocolPath;
        run.resultsDir = pick.resultsDir;
    } else {
        for (const char* option : {"participant", "rig"})
            if (args.has(option)) throw UsageError(std::string("option --") + option + " only applies with --study");
        run.protocolPath = args.string("protocol", "");
        run.resultsDir = args.string("out", run.resultsDir);
    }
    run.fullscreen = args.flag("fullscreen");
    run.display = static_cast<int>(args.integer("display", run.display, 0, 63));
    run.width = static_cast<int>(args.integer("width", run.width, scene::kMinDisplaySize, scene::kMaxImageSize));
    run.height = static_cast<int>(args.integer("height", run.height, scene::kMinDisplaySize, scene::kMaxImageSize));
    run.allowRefreshMismatch = args.flag("allow-refresh-mismatch");
    run.photonCorner = args.string("photon", "");
    bool failed = false;
    for (const live::CheckLine& line : live::checkMachine(run, dataPathsFrom(args), std::cout))
        failed = failed || line.verdict == live::Verdict::Fail;
    return failed ? 1 : 0;
}

// The command's options, beside the code that reads them; the window's as `run` takes them.
Command checkCommand() {
    const live::CheckRun defaults;
    return {
        {"check",
         "Check this machine before a participant sits down: the GL context, the display's refresh\n"
         "(reported, and measured over 2 s of swaps), vsync, the frame time of each condition of the\n"
         "protocol at the window's size against one refresh and against the shortest interval between\n"
         "new images its cadence asks for, the results folder and its lock, disk space for a session,\n"
         "the audio device. One line per check: ok, warn or FAIL and why.\n"
         "Exits 1 on any FAIL, so a lab script can gate a session on it.",
         "warplab check [--protocol P] [--out RESULTS] [--fullscreen] [--display N] [--width W --height H]\n"
         "              [--photon CORNER]\n"
         "       warplab check --study DIR --participant ID [--rig NAME] [--protocol NAME] [...]",
         {
             {"protocol", "FILE",
              "the study protocol the session will run: its refresh, conditions and size; with --study, which of "
              "the plan's protocols (its name or file)",
              "with --study: the participant's next"},
             {"out", "DIR", "the results folder the session will write into", defaults.resultsDir},
             {"study", "DIR",
              "a study plan: the participant's protocol (the plan's copy) and results folder, as run --study "
              "takes them",
              ""},
             {"participant", "ID", "with --study: the participant about to play", ""},
             {"rig", "NAME", "with --study: the rig's results folder, DIR/results/NAME, as run --rig", "DIR/results"},
             {"fullscreen", "", "fill the display, as run --fullscreen does", ""},
             {"display", "N", "which display to check", "0"},
             {"width", "PIXELS",
              "the window's width when not full screen, " + range(scene::kMinDisplaySize, scene::kMaxImageSize),
              shown(defaults.width)},
             {"height", "PIXELS", "the window's height when not full screen", shown(defaults.height)},
             {"allow-refresh-mismatch", "",
              "as run's: a refresh other than the protocol's (or none reported) warns instead of failing", ""},
             {"photon", "CORNER",
              "show the photodiode marker's test pattern in that corner (top_left, top_right, bottom_left, "
              "bottom_right): white and black for 0.25 s each, ten times",
              ""},
             dataDirOption(),
         }},
        &runCheck};
}

}  // namespace warplab::app
