#include "app.h"

#include <cstdlib>
#include <iostream>
#include <sstream>
#include <sys/stat.h>

#include "bench/bench.h"
#include "commands.h"
#include "live/live_session.h"
#include "protocol/shooter_protocol.h"
#include "study/session_runner.h"
#include "renderer/mesh.h"
#include "scene/limits.h"

#ifndef WARPLAB_DEFAULT_DATA_DIR
#define WARPLAB_DEFAULT_DATA_DIR "."
#endif
#ifndef WARPLAB_VERSION
#define WARPLAB_VERSION "0"
#endif

namespace warplab::app {
namespace {

bool isDirectory(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

std::string overview() {
    std::string text =
        "warplab " WARPLAB_VERSION
        " -- user studies of frame-rate upconversion and latency in interactive 3D\n\n"
        "usage: warplab <command> [options]    (warplab <command> --help for its options)\n\ncommands:\n";
    for (const auto& c : commands()) {
        std::string name = "  " + c.spec.name;
        name.resize(12, ' ');
        text += name + c.spec.summary.substr(0, c.spec.summary.find('\n')) + "\n";
    }
    return text;
}

// A number as --help shows it: the shortest form, 0.5 rather than 0.500000.
template <class T>
std::string shown(T value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

std::string range(double low, double high) { return shown(low) + ".." + shown(high); }

template <class T>
std::string withQuick(const T& normal, const T& quick) {
    return shown(normal) + " (" + shown(quick) + " with --quick)";
}

std::string listed(const std::vector<int>& values) {
    std::string text;
    for (const int v : values) text += (text.empty() ? "" : ",") + std::to_string(v);
    return text;
}

}  // namespace

OptionSpec glOption(const std::string& defaultBackend) {
    return {"gl", "osmesa|egl|window",
            "OpenGL context: headless Mesa (osmesa), headless EGL (a GPU where there is one), or an SDL window",
            defaultBackend};
}

OptionSpec dataDirOption() {
    return {"data-dir", "DIR", "folder holding shaders/, assets/ and analysis/", "$WARPLAB_DATA_DIR or the source tree"};
}

renderer::GlBackend backendFrom(const ParsedArgs& args, renderer::GlBackend fallback) {
    if (!args.has("gl")) return fallback;
    try {
        return renderer::parseBackend(args.string("gl"));
    } catch (const renderer::ContextError& e) {
        throw UsageError(std::string("option --gl: ") + e.what());
    }
}

renderer::DataPaths dataPathsFrom(const ParsedArgs& args) {
    std::string root = WARPLAB_DEFAULT_DATA_DIR;
    if (const char* env = std::getenv("WARPLAB_DATA_DIR"); env != nullptr && *env != '\0') root = env;
    if (args.has("data-dir")) root = args.string("data-dir");
    renderer::DataPaths paths{root + "/shaders", root + "/assets", root + "/analysis"};
    if (!isDirectory(paths.shaderDir))
        throw renderer::AssetError("cannot find warplab's shaders: '" + paths.shaderDir +
                                   "' is not a folder (set --data-dir or WARPLAB_DATA_DIR)");
    return paths;
}

const std::vector<Command>& commands() {
    // Defaults and limits as the commands use them, so that --help cannot tell another story.
    const protocol::RenderSettings study;
    const bench::BenchOptions bench;
    const bench::BenchOptions quick = bench::quickBenchOptions();
    const study::HeadlessRun headless;
    const live::LiveRun live;
    static const std::vector<Command> list = {
        {{"info",
          "Print the vendor, renderer and version of the OpenGL context a backend gives.",
          "warplab info [--gl osmesa|egl|window]",
          {glOption("osmesa")}},
         &runInfo},
        {{"render",
          "Render one frame of the shooter scene headlessly and write it as PNG; optionally the\n"
          "depth, object-id and velocity buffers as false-colour PNGs and as raw PFM images.",
          "warplab render [--time T] [--out frame.png] [options]",
          {
              {"time", "SECONDS", "scene time of the frame, 0..1e6", "0"},
              {"yaw", "DEGREES", "camera yaw, positive turns right, -36000..36000", "0"},
              {"pitch", "DEGREES",
               "camera pitch, positive looks up, " + range(-protocol::kMaxCameraPitchDeg, protocol::kMaxCameraPitchDeg),
               "0"},
              {"aim-at-target", "", "turn the camera to the target's centre (overrides --yaw/--pitch)", ""},
              {"fov", "DEGREES",
               "vertical field of view, " + range(protocol::kMinVerticalFovDeg, protocol::kMaxVerticalFovDeg) +
                   " (as in protocols)",
               "60"},
              {"width", "PIXELS", "image width, " + range(1, scene::kMaxImageSize), "640"},
              {"height", "PIXELS", "image height, " + range(1, scene::kMaxImageSize), "360"},
              {"seed", "N", "target spawn seed", "1"},
              {"speed", "M/S", "target speed, " + range(0, protocol::kMaxBaseSpeedMPerS), "2"},
              {"out", "PATH", "colour image (PNG)", "frame.png"},
              {"depth", "PATH", "false-colour depth image (PNG)", ""},
              {"ids", "PATH", "false-colour object-id image (PNG)", ""},
              {"velocity", "PATH", "false-colour velocity image (PNG)", ""},
              {"raw", "PREFIX", "also write PREFIX-depth.pfm (window depth), PREFIX-ids.pfm, PREFIX-velocity.pfm",
               ""},
              {"show", "SECONDS", "with --gl window: keep the window open this long, 0..3600", "0"},
              {"method", "NAME", "make the frame with an upconversion method (e.g. warp-sparse8) instead", ""},
              {"source-time", "SECONDS", "with --method: when the source frame was rendered, 0..1e6", "--time"},
              {"source-yaw", "DEGREES", "with --method: the source frame's camera yaw", "--yaw"},
              {"source-pitch", "DEGREES", "with --method: the source frame's camera pitch", "--pitch"},
              {"next-time", "SECONDS", "with --method blend: the next source frame's time, 0..1e6", "source + 1/15 s"},
              {"truth", "PATH", "with --method: also write the ground truth (conventional at --time)", ""},
              {"error", "PATH", "with --method: also write |method - ground truth| x4 as a grey image", ""},
              {"guard-band", "FRACTION",
               "with --method: a warp's sources reach this much further each side, " + range(0, scene::kMaxGuardBand),
               shown(study.guardBand)},
              {"ssaa", "N",
               "supersample every conventional frame NxN (antialiasing), " + range(1, scene::kMaxSupersampling),
               shown(study.supersampling)},
              glOption("osmesa"),
              dataDirOption(),
          }},
         &runRender},
        {{"bench",
          "Speed against error: make every frame of scripted sequences with every upconversion method,\n"
          "time each pass and compare it with a conventional render at the same instant.",
          "warplab bench [--quick] [--out DIR] [options]",
          {
              {"quick", "",
               shown(quick.width) + "x" + shown(quick.height) + ", " + shown(quick.framesPerSequence) +
                   " frames per sequence, " + shown(quick.repeats) + " repeats: a few minutes at most",
               ""},
              {"out", "DIR", "where bench.csv, summary.md and speed_vs_error.png go", "bench-out"},
              {"width", "PIXELS", "frame width, " + range(scene::kMinDisplaySize, scene::kMaxImageSize),
               withQuick(bench.width, quick.width)},
              {"height", "PIXELS", "frame height, " + range(scene::kMinDisplaySize, scene::kMaxImageSize),
               withQuick(bench.height, quick.height)},
              {"sequences", "A,B", "which sequences (pan, track, translate, spheres, thin)", "all"},
              {"methods", "A,B", "which methods (see the summary for the list)", "all"},
              {"frames", "N", "sampled display frames per sequence, every 15 Hz phase covered; 0 = all",
               withQuick(bench.framesPerSequence, quick.framesPerSequence)},
              {"duration-scale", "X", "scale the sequences' length", "1"},
              {"repeats", "N", "timed runs of each pass, after an untimed one; medians are reported",
               withQuick(bench.repeats, quick.repeats)},
              {"shading-cost", "N", "extra per-fragment shading work in every conventional frame",
               shown(bench.shadingCost)},
              {"shading-sweep", "A,B", "shading costs at which the summary times a conventional frame",
               withQuick(listed(bench.shadingSweep), listed(quick.shadingSweep))},
              {"guard-band", "FRACTION",
               "sources of the warps reach this much further each side, " + range(0, scene::kMaxGuardBand),
               shown(bench.guardBand)},
              {"ssaa", "N",
               "supersample every conventional frame NxN, ground truth included, " + range(1, scene::kMaxSupersampling),
               shown(bench.supersampling)},
              {"seed", "N", "target spawn seed of the sequences", shown(bench.seed)},
              glOption("osmesa"),
              dataDirOption(),
          }},
         &runBench},
        {{"run",
          "Run a study session: in a window with the participant's mouse (the default), or\n"
          "headlessly with a simulated or recorded player. Writes the session store into the\n"
          "results folder (one file per session) as it runs, then prints its path. In the window:\n"
          "Enter starts, Esc pauses (then Enter resumes, Q ends, keeping what was recorded).",
          "warplab run --protocol P --participant ID --out RESULTS [--fullscreen] [--headless --player bot|sim[:SEED]]",
          {
              {"protocol", "FILE", "study protocol (JSON), e.g. protocol/shooter-quick.json", ""},
              {"participant", "ID", "participant id: stored as data, never used as a path", ""},
              {"out", "DIR", "results folder (must exist and be writable)", "results"},
              {"headless", "", "no window: the player is simulated or replayed", ""},
              {"player", "human|bot[:SEED]|sim[:SEED]|replay:SESSION",
               "who plays: the participant (window only), the scripted bot (reads the game's state), the "
               "simulated participant (headless: sees only the displayed frames, as the mode draws them; "
               "SEED: its motor noise, default the session seed), or a recorded session's input",
               "human in a window, bot headless"},
              {"seed", "N", "session seed: trial order and target spawns", shown(headless.seed)},
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
              {"free-play", "", "window: free play for pilots and demos, nothing recorded (keys 1-9 mode, U/D level)",
               ""},
              {"mode", "ID", "with --free-play: the mode to start in", "the protocol's first"},
              {"level", "N", "with --free-play: the difficulty (shooter: staircase level) to start at", "0"},
              {"input-script", "FILE", "window, tests: input given as if by the participant (see docs/live-sessions.md)",
               ""},
              {"gl", "osmesa|egl", "with --headless --player sim: the context the simulated participant draws in",
               "osmesa"},
              dataDirOption(),
          }},
         &runRun},
        {{"replay",
          "Re-run a session from its store without a window or rendering, check every logged\n"
          "outcome and print how many were reproduced, or the first difference (exit " +
              std::to_string(study::kReplayDiffers) + ").",
          "warplab replay SESSION [--render DIR [--frames FIRST:LAST]]",
          {
              {"render", "DIR", "also write the displayed frames of --frames as PNGs, made as the mode made them", ""},
              {"frames", "FIRST:LAST", "with --render: which display frames", "0:599"},
              {"width", "PIXELS", "with --render: image width", "the session's display"},
              {"height", "PIXELS", "with --render: image height", "the session's display"},
              glOption("osmesa"),
              dataDirOption(),
          },
          true},
         &runReplay},
        {{"export",
          "Merge every session file of a results folder (sub-folders too) into tidy CSVs for the\n"
          "analysis: sessions, shots/clicks, hit rates per participant x game x mode, matches and\n"
          "ratings (docs/export.md). Read-only; damaged files are reported and skipped.",
          "warplab export RESULTS [--out DIR] [--all-phases] [--include-incomplete] [--include-flagged]",
          {
              {"out", "DIR", "where the CSVs go (created when missing)", "export"},
              {"all-phases", "", "also practice rounds, acclimation and training (hit rates stay scored-only)", ""},
              {"include-incomplete", "", "also sessions that never finished (killed mid-way): their completed trials",
               ""},
              {"include-flagged", "", "also sessions flagged during their run (e.g. too many missed frames)", ""},
          },
          true},
         &runExport},
        {{"demo",
          "The main job on a fresh machine: a small simulated study, headless, end to end. Simulated\n"
          "participants who see only the displayed frames play shooter-demo and click-demo in every\n"
          "mode, several sessions at once; each session is replayed and checked, all are exported,\n"
          "and the analysis writes a report with figures and the participants a real study would need.",
          "warplab demo [--out DIR] [--participants N] [--protocols LIST] [--jobs N]",
          {
              {"out", "DIR", "results/, logs/, export/ and report/ go here (results/ must hold no sessions yet)",
               "demo-out"},
              {"participants", "N", "simulated participants, each plays every protocol, 2..100", "8"},
              {"player", "sim|bot", "the perceptual simulated participant, or the scripted bot that reads the game",
               "sim"},
              {"protocols", "LIST", "protocols to play, by name (in protocol/) or file, separated by commas",
               "shooter-demo,click-demo"},
              {"jobs", "N", "sessions run at once, each in its own process, 1..64", "the machine's cores"},
              glOption("osmesa"),
              dataDirOption(),
          }},
         &runDemo},
    };
    return list;
}

int run(const std::vector<std::string>& args) {
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        std::cout << overview();
        return args.empty() ? 2 : 0;
    }
    if (args[0] == "--version") {
        std::cout << "warplab " WARPLAB_VERSION "\n";
        return 0;
    }
    const Command* command = nullptr;
    for (const auto& c : commands())
        if (c.spec.name == args[0]) command = &c;
    if (command == nullptr) {
        std::cerr << "warplab: unknown command '" << args[0] << "' (see warplab --help)\n";
        return 2;
    }
    try {
        const ParsedArgs parsed = parseArgs(command->spec, {args.begin() + 1, args.end()});
        if (parsed.has("help")) {
            std::cout << helpText(command->spec);
            return 0;
        }
        return command->run(parsed);
    } catch (const UsageError& e) {
        std::cerr << "warplab: " << e.what() << " (see warplab " << command->spec.name << " --help)\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "warplab " << command->spec.name << ": " << e.what() << "\n";
        return 1;
    }
}

}  // namespace warplab::app
