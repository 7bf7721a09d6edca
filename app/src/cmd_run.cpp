#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <random>

#include "commands.h"
#include "table/csv.h"
#include "live/live_session.h"
#include "present/replay_render.h"
#include "runner/session_runner.h"
#include "participants/eye.h"
#include "plan/status.h"
#include "plan/study_plan.h"
#include "protocol/study_protocol.h"
#include "scene/limits.h"
#include "session/results_lock.h"
#include "runner/session_size.h"

namespace warplab::app {

StudyPick pickFromPlan(const ParsedArgs& args) {
    StudyPick pick;
    pick.dir = args.string("study");
    if (args.has("rig")) {
        pick.rig = args.string("rig");
        if (const std::string problem = plan::rigNameProblem(pick.rig); !problem.empty())
            throw UsageError("option --rig " + problem);
    }
    if (!args.has("participant")) throw UsageError("option --participant is required");
    const std::string id = args.string("participant");
    pick.plan = plan::readPlan(pick.dir);
    const std::string planFile = (std::filesystem::path(pick.dir) / "study.json").string();
    const plan::ParticipantPlan* participant = plan::findParticipant(pick.plan, id);
    if (!participant) {
        std::vector<std::string> ids;
        for (const auto& p : pick.plan.participants) ids.push_back(p.id);
        throw plan::PlanError("study plan '" + planFile + "' has no participant " + quotedForMessage(id) +
                              " (it plans " + firstFew(ids) + "); warplab study add adds participants");
    }
    pick.participant = static_cast<std::size_t>(participant - pick.plan.participants.data());
    plan::ParticipantStatus status;
    for (auto& s : plan::studyStatus(pick.dir, pick.plan))
        if (s.id == participant->id) status = std::move(s);
    int position = plan::nextProtocol(status);
    if (args.has("protocol")) {
        const std::string wanted = args.string("protocol");
        position = -1;
        for (std::size_t i = 0; i < status.protocols.size(); ++i) {
            const plan::ProtocolEntry& e =
                pick.plan.protocols[static_cast<std::size_t>(status.protocols[i].protocolIndex)];
            if (e.name == wanted || e.file == wanted || std::filesystem::path(e.file).filename() == wanted)
                position = static_cast<int>(i);
        }
        if (position < 0) throw plan::PlanError("study plan '" + planFile + "' has no protocol '" + wanted + "'");
    } else if (position < 0) {
        throw plan::PlanError("participant " + participant->id + " of study plan '" + planFile +
                              "' has done every protocol; to run one again, name it with --protocol and add --again");
    }
    pick.chosen = status.protocols[static_cast<std::size_t>(position)];
    const plan::ProtocolEntry& entry = pick.plan.protocols[static_cast<std::size_t>(pick.chosen.protocolIndex)];
    // Rigs lock only their own folders: one participant on two rigs at once is caught here.
    if (pick.chosen.running)
        throw plan::PlanError("participant " + participant->id + " of study plan '" + planFile + "' is playing " +
                              entry.name + " now (" + session::holderText(*pick.chosen.running) + ", " +
                              plan::rigText(pick.chosen.runningRig) + "); wait for it to end");
    pick.protocolPath = (std::filesystem::path(pick.dir) / entry.file).string();
    pick.protocolText = plan::participantProtocolJson(pick.dir, pick.plan, *participant, pick.chosen.protocolIndex);
    pick.resultsDir = plan::resultsFolder(pick.dir, pick.rig);
    if (!pick.rig.empty()) {
        // A rig's folder is made on its first use; the plan's results folder must be there.
        std::error_code error;
        if (std::filesystem::is_directory(plan::resultsFolder(pick.dir), error))
            std::filesystem::create_directory(pick.resultsDir, error);
    }
    return pick;
}

namespace {

// What every run names, windowed or headless.
// A participant id is data that export, R and spreadsheets must read back: something, in
// well-formed UTF-8, without control characters, of a sane length.
void checkParticipant(const std::string& id) {
    const std::string what = "option --participant ";
    if (id.find_first_not_of(" \t") == std::string::npos) throw UsageError(what + "must not be empty or blank");
    if (id.size() > 128) throw UsageError(what + "must be at most 128 bytes, got " + std::to_string(id.size()));
    if (!table::isValidUtf8(id)) throw UsageError(what + "must be UTF-8 text, got " + quotedForMessage(id));
    for (const char c : id)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            throw UsageError(what + "must not hold control characters, got " + quotedForMessage(id));
}

// run --study DIR --participant ID [--protocol NAME] [--again]: the protocol (with the
// participant's condition order), seed and results folder come from the plan; the protocol is
// the participant's next one not yet done unless --protocol names one of the plan's. Returns
// the participant's mouse settings, for a window.
template <typename Run>
plan::ParticipantSettings readStudyOptions(const ParsedArgs& args, Run& run) {
    for (const char* option : {"seed", "out"})
        if (args.has(option))
            throw UsageError(std::string("option --") + option + " comes from the study plan with --study");
    if (args.has("participant")) checkParticipant(args.string("participant"));  // no plan holds an id this refuses
    const StudyPick pick = pickFromPlan(args);
    const plan::ParticipantPlan& participant = pick.plan.participants[pick.participant];
    const plan::ProtocolStatus& chosen = pick.chosen;
    const plan::ProtocolEntry& entry = pick.plan.protocols[static_cast<std::size_t>(chosen.protocolIndex)];
    const std::string results = plan::resultsFolder(pick.dir) + (pick.rig.empty() ? "" : " (every rig's)");
    run.participant = participant.id;
    if (args.has("resume")) {
        if (!args.string("resume").empty())
            throw UsageError("option --resume takes no SESSION with --study: the plan's results say which one");
        if (chosen.resumable.empty())
            throw plan::PlanError("participant " + participant.id + " has no incomplete session of " + entry.name +
                                  " to resume in " + results + " (" + plan::stateName(chosen.state) + ")");
        run.resumeFrom = chosen.resumable;
    }
    if ((chosen.state == plan::SessionState::Done || chosen.state == plan::SessionState::Flagged) &&
        !args.flag("again"))
        throw plan::PlanError("participant " + participant.id + " already has a complete session of " + entry.name +
                              " (" + chosen.detail + " in " + plan::resultsFolder(pick.dir) +
                              "); add --again to record another");
    run.protocolPath = pick.protocolPath;
    run.protocolText = pick.protocolText;
    run.planId = pick.plan.id;
    run.resultsDir = pick.resultsDir;
    run.seed = participant.seed;
    return participant.settings;
}

// The results folder's lock, held for the whole session (docs/live-sessions.md): a second run
// into the folder is refused here, before it opens a window or creates a file.
template <typename Run>
session::ResultsFolderLock lockResults(const ParsedArgs& args, const Run& run) {
    // A resumed session's participant and protocol are the interrupted one's.
    std::string participant = run.participant, protocol;
    if (!run.resumeFrom.empty()) {
        const session::SessionHeader was = session::readSessionHeader(run.resumeFrom);
        participant = was.participant;
        protocol = runner::loadRunStudy(run.resumeFrom, was.protocolJson)->name();
    } else {
        protocol = runner::loadRunStudy(run.protocolPath, run.protocolText)->name();
    }
    try {
        return session::ResultsFolderLock(run.resultsDir, participant, protocol);
    } catch (const session::ResultsFolderBusy& e) {
        throw std::runtime_error(e.what() +
                                 std::string(args.has("study")
                                                 ? "; wait for it to end, or run on another rig (--rig NAME)."
                                                 : "; wait for it to end, or use another --out."));
    }
}

// Room on disk for a session, checked with its folder before the window opens or the first
// headless frame: a disk that fills mid-session ends a live one at a commit, with the
// participant seated, and leaves a headless one's file damaged.
template <typename Run>
void requireRoom(const ParsedArgs& args, const Run& run, const game::DisplaySize& display) {
    const auto study = run.resumeFrom.empty()
        ? runner::loadRunStudy(run.protocolPath, run.protocolText)
        : runner::loadRunStudy(run.resumeFrom, session::readSessionHeader(run.resumeFrom).protocolJson);
    try {
        runner::requireDiskSpace(run.resultsDir, runner::estimateSessionSize(*study, display), study->name());
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(
            e.what() +
            std::string(args.has("study") ? "; free some space there." : "; free some space, or use another --out."));
    }
}

// `run`'s exit status for a session the supervisor ended before its end (README "Exit codes"):
// replay's "incomplete", since that is what replay says of its file; 0 is kept for a session
// that played to its end, so that a script does not go on to the next step as if it had.
constexpr int kRunEndedEarly = runner::kReplayIncomplete;

constexpr long long kMaxSeed = 1LL << 62;

// A session seed of the operating system's randomness, 0..kMaxSeed: without --seed (and without
// a plan) each participant gets their own trial order and target spawns.
std::uint64_t drawSeed() {
    std::random_device device;
    const std::uint64_t bits = (static_cast<std::uint64_t>(device()) << 32) ^ device();
    return bits & static_cast<std::uint64_t>(kMaxSeed - 1);
}

template <typename Run>
void readSessionOptions(const ParsedArgs& args, const char* defaultPlayer, Run& run, bool recorded = true) {
    run.player = args.string("player", defaultPlayer);
    try {
        runner::checkPlayer(run.player);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    // A recorded session to play is read now, so that a wrong one is all the run says (the
    // drawn seed's line and the window come after).
    if (const std::string source = runner::replaySource(run.player); !source.empty())
        session::readSessionHeader(source);
    // A resumed session goes on on the display it was played on (the click game's cursor
    // lives in its pixels).
    if (args.has("resume"))
        for (const char* option : {"width", "height"})
            if (args.has(option))
                throw UsageError(std::string("option --") + option + " comes from the session with --resume");
    if (args.has("study")) return;  // the rest from the plan: readStudyOptions
    if (args.flag("again")) throw UsageError("option --again only applies with --study");
    if (args.has("rig"))
        throw UsageError("option --rig only applies with --study; without a plan, --out names the folder");
    if (args.has("resume")) {
        // The interrupted session says what it ran; its folder takes the new session.
        for (const char* option : {"protocol", "participant", "seed"})
            if (args.has(option))
                throw UsageError(std::string("option --") + option + " comes from the session with --resume");
        run.resumeFrom = args.string("resume");
        if (run.resumeFrom.empty())
            throw UsageError("option --resume needs the SESSION to resume (or --study DIR --participant ID)");
        const std::string folder = std::filesystem::path(run.resumeFrom).parent_path().string();
        run.resultsDir = args.string("out", folder.empty() ? "." : folder);
        return;
    }
    run.protocolPath = args.string("protocol");
    if (run.protocolPath.empty()) throw UsageError("option --protocol is required");
    if (recorded && !args.has("participant")) throw UsageError("option --participant is required");
    run.participant = args.string("participant");
    if (recorded) checkParticipant(run.participant);
    run.resultsDir = args.string("out", "results");
    run.seed = args.has("seed") ? static_cast<std::uint64_t>(args.integer("seed", 0, 0, kMaxSeed)) : drawSeed();
}

// Said once the run holds its folder, so that a session run without --seed can be repeated.
void tellDrawnSeed(const ParsedArgs& args, std::uint64_t seed) {
    if (!args.has("seed") && !args.has("study") && !args.has("resume"))
        std::cerr << "seed " << seed << " drawn at random; --seed " << seed << " repeats this session\n";
}

int runWindowed(const ParsedArgs& args) {
    live::LiveRun run;
    readSessionOptions(args, "human", run, !args.flag("free-play"));
    if (args.has("gl")) throw UsageError("option --gl only applies with --headless --player sim");
    if (runner::isSimulatedParticipant(run.player))
        throw UsageError("--player " + run.player + " (the simulated participant) runs headless only: add --headless");
    run.width = static_cast<int>(args.integer("width", run.width, scene::kMinDisplaySize, scene::kMaxImageSize));
    run.height = static_cast<int>(args.integer("height", run.height, scene::kMinDisplaySize, scene::kMaxImageSize));
    run.fullscreen = args.flag("fullscreen");
    run.display = static_cast<int>(args.integer("display", 0, 0, 63));
    run.cmPer360 = args.number("cm-per-360", 0.0);
    run.mouseDpi = args.number("mouse-dpi", 800.0);
    if (run.cmPer360 < 0.0 || !(run.mouseDpi > 0.0))
        throw UsageError("options --cm-per-360 and --mouse-dpi need positive numbers");
    run.invertY = args.flag("invert-y");
    if (args.has("study")) {
        if (args.flag("free-play")) throw UsageError("option --free-play records nothing: leave out --study");
        // The participant's settings from the plan, unless given here.
        const plan::ParticipantSettings settings = readStudyOptions(args, run);
        if (!args.has("cm-per-360") && settings.cmPer360) run.cmPer360 = *settings.cmPer360;
        if (!args.has("mouse-dpi")) run.mouseDpi = settings.mouseDpi;
        if (!args.has("invert-y")) run.invertY = settings.invertY;
    }
    run.allowRefreshMismatch = args.flag("allow-refresh-mismatch");
    run.inputScript = args.string("input-script", "");
    run.everyFrame = args.flag("every-frame");
    if (args.has("slow-frames")) {
        const std::string slow = args.string("slow-frames", "");
        const std::size_t colon = slow.find(':');
        const std::string why = "option --slow-frames needs MS:EVERY, e.g. 40:10 (40 ms more on every 10th frame)";
        if (colon == std::string::npos) throw UsageError(why);
        run.slowMs = static_cast<double>(wholeInteger(slow.substr(0, colon), why));
        run.slowEvery = static_cast<int>(wholeInteger(slow.substr(colon + 1), why));
        if (run.slowMs < 0 || run.slowMs > 10000 || run.slowEvery < 1) throw UsageError(why);
    }
    if (args.has("photon-marker")) {
        run.photonMarker = args.string("photon-marker", "");
        std::string spellings;
        bool known = false;
        for (const auto& entry : protocol::EnumNames<protocol::PhotonMarker>::list) {
            known = known || run.photonMarker == entry.name;
            spellings += std::string(spellings.empty() ? "" : ", ") + entry.name;
        }
        if (!known)
            throw UsageError("option --photon-marker needs one of " + spellings + ", got '" + run.photonMarker + "'");
    }
    run.screenshotDir = args.string("screenshots", "");
    run.screenshotStartScreen = !run.screenshotDir.empty();
    const std::string frames = args.string("screenshot-frames", "");
    std::size_t at = 0;
    while (at < frames.size()) {
        const std::size_t comma = std::min(frames.find(',', at), frames.size());
        run.screenshotFrames.push_back(wholeInteger(
            frames.substr(at, comma - at), "option --screenshot-frames needs frame numbers separated by commas"));
        at = comma + 1;
    }
    if (args.flag("free-play")) {
        if (args.has("condition") && args.has("mode"))
            throw UsageError("options --condition and --mode are one option (--mode is its older name): give one");
        run.freePlayCondition = args.string("condition", args.string("mode", ""));
        run.freePlayLevel = static_cast<int>(args.integer("level", 0, 0, 120));
        live::runFreePlay(run, dataPathsFrom(args), std::cerr);
        return 0;
    }
    const auto lock = lockResults(args, run);
    requireRoom(args, run, {run.width, run.height});
    tellDrawnSeed(args, run.seed);
    const live::LiveEnd end = live::runLive(run, dataPathsFrom(args), std::cerr);
    if (!end.session.empty()) std::cout << end.session << "\n";
    return end.endedBySupervisor ? kRunEndedEarly : 0;
}

}  // namespace

// Options that only a window reads: under --headless they would be silently ignored (a
// mistyped --cm-per-360 unnoticed, an --input-script that drives nothing).
const char* const kWindowOnlyOptions[] = {
    "fullscreen",   "display",           "cm-per-360",  "mouse-dpi",    "invert-y", "allow-refresh-mismatch",
    "screenshots",  "screenshot-frames", "free-play",   "condition",    "mode",     "level",
    "input-script", "every-frame",       "slow-frames", "photon-marker"};

int runRun(const ParsedArgs& args) {
    if (!args.flag("headless")) return runWindowed(args);
    for (const char* option : kWindowOnlyOptions)
        if (args.has(option))
            throw UsageError(std::string("option --") + option + " only applies in the window; leave out --headless");
    if (args.string("player", "bot") == "human")
        throw UsageError("a human player needs the window; leave out --headless");
    runner::HeadlessRun run;
    readSessionOptions(args, "bot", run);
    if (args.has("study")) readStudyOptions(args, run);
    run.displayWidth =
        static_cast<int>(args.integer("width", run.displayWidth, scene::kMinDisplaySize, scene::kMaxImageSize));
    run.displayHeight =
        static_cast<int>(args.integer("height", run.displayHeight, scene::kMinDisplaySize, scene::kMaxImageSize));
    if (runner::isSimulatedParticipant(run.player)) {
        // It draws what it sees: the shaders, and a headless context.
        const auto backend = backendFrom(args, renderer::GlBackend::OSMesa);
        if (backend == renderer::GlBackend::Window)
            throw UsageError("option --gl: the simulated participant draws headless (osmesa or egl)");
        const renderer::DataPaths paths = dataPathsFrom(args);
        run.seeingPlayer = participants::perceptualPlayerMaker(paths, backend, populationFrom(args, paths));
    } else if (args.has("gl")) {
        throw UsageError("option --gl only applies with --headless --player sim");
    } else if (args.has("population")) {
        throw UsageError("option --population only applies with --headless --player sim");
    } else if (args.has("data-dir")) {
        // Nothing here draws, but a script that hands every command its --data-dir should hear
        // of a wrong one rather than have it pass unread.
        dataPathsFrom(args);
    }
    const auto lock = lockResults(args, run);
    requireRoom(args, run, {run.displayWidth, run.displayHeight});
    tellDrawnSeed(args, run.seed);
    const std::string path = runner::runHeadless(run, std::cerr);
    std::cout << path << "\n";
    return 0;
}

int runReplay(const ParsedArgs& args) {
    if (args.positional().size() != 1) throw UsageError("give exactly one SESSION file");
    if (!args.has("render"))
        for (const char* option : {"frames", "width", "height", "gl", "data-dir"})
            if (args.has(option)) throw UsageError(std::string("option --") + option + " only applies with --render");
    const std::string& path = args.positional().front();
    if (args.has("render")) {
        present::ReplayRender request;
        request.sessionPath = path;
        request.outDir = args.string("render");
        const std::string range = args.string("frames", "0:599");
        const auto colon = range.find(':');
        const std::string what = "option --frames needs FIRST:LAST frame numbers";
        if (colon == std::string::npos) throw UsageError(what + ", got '" + range + "'");
        request.firstFrame = wholeInteger(range.substr(0, colon), what);
        request.lastFrame = wholeInteger(range.substr(colon + 1), what);
        if (request.firstFrame < 0 || request.lastFrame < request.firstFrame)
            throw UsageError("option --frames needs 0 <= FIRST <= LAST, got '" + range + "'");
        // Unset (0) means the session's display; a size given must be one an image can have.
        request.width = args.has("width")
            ? static_cast<int>(args.integer("width", 0, scene::kMinDisplaySize, scene::kMaxImageSize))
            : 0;
        request.height = args.has("height")
            ? static_cast<int>(args.integer("height", 0, scene::kMinDisplaySize, scene::kMaxImageSize))
            : 0;
        const present::ReplayRenderResult rendered = present::renderReplay(
            request, dataPathsFrom(args), backendFrom(args, renderer::GlBackend::OSMesa), std::cout, std::cerr);
        if (rendered.disagreed > 0) {
            std::cout << "replay --render: the pointer cross-check failed on " << rendered.disagreed
                      << " comparisons\n";
            return runner::kReplayFailed;
        }
    }
    runner::ReplayResult r;
    try {
        r = runner::replaySession(path);
    } catch (const session::SessionError& e) {
        std::cerr << "warplab replay: " << e.what() << "\n";
        return runner::kReplayDamaged;
    }
    if (!r.note.empty()) std::cout << path << ": " << r.note << "\n";
    if (!r.difference.empty()) {
        std::cout << "replay differs at " << r.difference << "\n"
                  << r.reproduced << "/" << r.outcomes << " outcomes reproduced before it\n";
        return runner::replayExitCode(r);
    }
    // Frames as well as seconds: a session under a second long (one ended early) said "0 s".
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, r.displaySeconds < 10 ? "%.2f" : "%.0f", r.displaySeconds);
    std::cout << r.reproduced << "/" << r.outcomes << " outcomes reproduced (" << r.events << " events, " << r.frames
              << " frames, " << seconds << " s of display time replayed in " << r.seconds
              << " s: " << static_cast<long long>(r.seconds > 0 ? r.displaySeconds / r.seconds : 0) << "x real time)\n";
    return runner::replayExitCode(r);
}

// The command's options, beside the code that reads them (defaults and limits as it uses
// them, so that --help cannot tell another story).
Command runCommand() {
    const runner::HeadlessRun headless;
    const live::LiveRun live;
    return {
        {"run",
         "Run a study session: in a window with the participant's mouse (the default), or\n"
         "headlessly with a simulated or recorded player. Writes the session store into the\n"
         "results folder (one file per session) as it runs, then prints its path. In the window:\n"
         "Enter starts, Esc pauses (then Enter resumes, Q ends early, keeping what was recorded:\n"
         "exit status 3, as replay's for an incomplete session; --resume carries it on).",
         "warplab run --protocol P --participant ID --out RESULTS [--fullscreen] [--headless --player bot|sim[:SEED]]\n"
         "       warplab run --study DIR --participant ID [--rig NAME] [--resume] [...]\n"
         "       warplab run --resume SESSION [...]",
         {
             {"protocol", "FILE",
              "study protocol (JSON), e.g. protocol/shooter-quick.json; with --study, which of the plan's protocols "
              "(its name or file)",
              "with --study: the participant's next"},
             {"study", "DIR",
              "a study plan (warplab study init): protocol, seed, condition order, mouse settings and results folder "
              "(DIR/results) come from it",
              ""},
             {"again", "", "with --study: record another session of a protocol the participant has completed", ""},
             {"rig", "NAME",
              "with --study: this rig's (booth's, machine's) own results folder, DIR/results/NAME, so that rigs run "
              "the plan at once (docs/study-plan.md, \"Several rigs\")",
              "DIR/results"},
             {"resume", "[SESSION]",
              "carry on an interrupted session: its recorded input is played again and checked up to its last "
              "completed trial or match, and a new session goes on from there (protocol, seed, participant from "
              "it); with --study, the participant's incomplete session of the protocol",
              ""},
             {"participant", "ID", "participant id: stored as data, never used as a path", ""},
             {"out", "DIR", "results folder (must exist and be writable)",
              "results; with --resume the session's folder"},
             {"headless", "", "no window: the player is simulated or replayed", ""},
             {"player", "human|bot[:SEED]|sim[:SEED]|replay:SESSION",
              "who plays: the participant (window only), the scripted bot (reads the game's state), the "
              "simulated participant (headless: sees only the displayed frames, as the condition draws them; "
              "SEED: its motor noise, default the session seed), or a recorded session's input",
              "human in a window, bot headless"},
             {"seed", "N", "session seed, 0..2^62: trial order and target spawns", "drawn at random, and printed"},
             {"width", "PIXELS",
              "headless: display width the session stands for; window: its width, " +
                  range(scene::kMinDisplaySize, scene::kMaxImageSize),
              shown(headless.displayWidth) + " / " + shown(live.width)},
             {"height", "PIXELS", "display height", shown(headless.displayHeight) + " / " + shown(live.height)},
             {"fullscreen", "", "window: fill the display (borderless, at its own mode)", ""},
             {"display", "N", "window: which display to open on", "0"},
             {"cm-per-360", "CM", "window, shooter: mouse travel for a full turn (the participant's sensitivity)",
              "the protocol's"},
             {"mouse-dpi", "DPI", "with --cm-per-360: the mouse's counts per inch", "800"},
             {"invert-y", "", "window: moving the mouse forward looks down", ""},
             {"allow-refresh-mismatch", "", "window: run although the display's refresh differs from the protocol's",
              ""},
             {"screenshots", "DIR", "window: also write the start and end screens and the --screenshot-frames as PNG",
              ""},
             {"screenshot-frames", "A,B,...", "with --screenshots: which session frames", ""},
             {"free-play", "",
              "window: free play for pilots and demos, nothing recorded (keys 1-9 condition, U/D level)", ""},
             {"condition", "ID", "with --free-play: the condition to start in", "the protocol's first"},
             {"mode", "ID", "the older name of --condition", ""},
             {"level", "N", "with --free-play: the difficulty (shooter: staircase level) to start at", "0"},
             {"input-script", "FILE", "window, tests: input given as if by the participant (see docs/live-sessions.md)",
              ""},
             {"every-frame", "", "window, tests: show every display frame however late (slow motion on a slow machine)",
              "late frames' display frames are skipped"},
             {"photon-marker", "CORNER",
              "window: a square for a photodiode in that corner (top_left, top_right, bottom_left, bottom_right; off "
              "for none), white on the first frame that shows a press (docs/live-sessions.md)",
              "the protocol's display.photon_marker"},
             {"slow-frames", "MS:EVERY", "window, tests: make every EVERY-th frame MS ms slower, as a slow machine",
              ""},
             {"gl", "osmesa|egl", "with --headless --player sim: the context the simulated participant draws in",
              "osmesa"},
             populationOption(),
             dataDirOption(),
         }},
        &runRun};
}

// The command's options, beside the code that reads them.
Command replayCommand() {
    return {{"replay",
             "Re-run a session from its store without a window or rendering, check every logged\n"
             "outcome and print how many were reproduced, or the first difference (exit " +
                 std::to_string(runner::kReplayDiffers) + ").",
             "warplab replay SESSION [--render DIR [--frames FIRST:LAST]]",
             {
                 {"render", "DIR",
                  "also write the displayed frames of --frames as PNGs, made as the condition made them", ""},
                 {"frames", "FIRST:LAST", "with --render: which display frames", "0:599"},
                 {"width", "PIXELS", "with --render: image width", "the session's display"},
                 {"height", "PIXELS", "with --render: image height", "the session's display"},
                 glOption("osmesa"),
                 dataDirOption(),
             },
             true},
            &runReplay};
}

}  // namespace warplab::app
