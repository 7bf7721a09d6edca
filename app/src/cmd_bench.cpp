#include <iostream>

#include "bench/bench.h"
#include "bench/sequences.h"
#include "commands.h"
#include "renderer/upconvert.h"
#include "scene/limits.h"

namespace warplab::app {
namespace {

template <class T>
std::string withQuick(const T& normal, const T& quick) {
    return shown(normal) + " (" + shown(quick) + " with --quick)";
}

// A comma-separated option value; an empty item ("", "a,,b", "a,") would silently mean "all",
// "none" or a slip of the keyboard, so it is a wrong command line naming the option.
std::vector<std::string> splitList(const ParsedArgs& args, const std::string& option, const std::string& items) {
    return commaSeparated(args.string(option),
                          "option --" + option + " of 'warplab bench' needs a list of " + items +
                              " separated by commas, got '" + args.string(option) + "'");
}

}  // namespace

int runBench(const ParsedArgs& args) {
    bench::BenchOptions options = args.flag("quick") ? bench::quickBenchOptions() : bench::BenchOptions{};
    options.width =
        static_cast<int>(args.integer("width", options.width, scene::kMinDisplaySize, scene::kMaxImageSize));
    options.height =
        static_cast<int>(args.integer("height", options.height, scene::kMinDisplaySize, scene::kMaxImageSize));
    options.framesPerSequence = static_cast<int>(args.integer("frames", options.framesPerSequence, 0, 1000000));
    options.repeats = static_cast<int>(args.integer("repeats", options.repeats, 1, 1000));
    options.shadingCost = static_cast<int>(args.integer("shading-cost", 0, 0, 1 << 20));
    options.guardBand = args.number("guard-band", options.guardBand, 0.0, scene::kMaxGuardBand);
    options.supersampling = static_cast<int>(args.integer("ssaa", options.supersampling, 1, scene::kMaxSupersampling));
    options.durationScale = args.number("duration-scale", 1.0);
    if (!(options.durationScale > 0.0 && options.durationScale <= 100.0))
        throw UsageError("option --duration-scale must be in (0, 100]");
    options.seed = static_cast<std::uint64_t>(args.integer("seed", static_cast<long long>(options.seed), 0, 1LL << 62));
    if (args.has("sequences")) options.sequences = splitList(args, "sequences", "sequence names");
    if (args.has("methods")) options.methods = splitList(args, "methods", "method names");
    // Unknown names are a wrong command line (exit 2), found before a context is made.
    try {
        for (const auto& name : options.sequences) game::makeSequence(name, {});
        for (const auto& name : options.methods) renderer::requireMethod(name);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    if (args.has("shading-sweep")) {
        options.shadingSweep.clear();
        for (const auto& item : splitList(args, "shading-sweep", "shading costs")) {
            const std::string what = "option --shading-sweep needs integers from 0 to 1000000";
            const long long cost = wholeInteger(item, what);
            if (cost < 0 || cost > 1000000) throw UsageError(what + ", got '" + item + "'");
            options.shadingSweep.push_back(static_cast<int>(cost));
        }
    }
    options.outDir = outputFolder(args, "out", "bench-out");  // before the context, so a refusal is all it says

    const renderer::DataPaths paths = dataPathsFrom(args);
    renderer::ContextOptions context;
    context.backend = backendFrom(args, renderer::GlBackend::OSMesa);
    context.visible = false;
    const auto gl = renderer::createContext(context);
    std::cerr << "bench: " << options.width << "x" << options.height << " on " << gl->info().renderer << "\n";
    bench::runBench(options, paths, gl->info(), std::cout, std::cerr);
    std::cout << "\nwrote " << options.outDir << "/bench.csv, summary.md, speed_vs_error.png, budget_vs_error.png\n";
    return 0;
}

// The command's options, beside the code that reads them (defaults and limits as it uses
// them, so that --help cannot tell another story).
Command benchCommand() {
    const bench::BenchOptions bench;
    const bench::BenchOptions quick = bench::quickBenchOptions();
    return {
        {"bench",
         "Speed against error: make every frame of scripted sequences with every upconversion method,\n"
         "time each pass and compare it with a conventional render at the same instant.",
         "warplab bench [--quick] [--out DIR] [options]",
         {
             {"quick", "",
              shown(quick.width) + "x" + shown(quick.height) + ", " + shown(quick.framesPerSequence) +
                  " frames per sequence, " + shown(quick.repeats) + " repeats: a few minutes at most",
              ""},
             {"out", "DIR", "where bench.csv, summary.md, speed_vs_error.png and budget_vs_error.png go", "bench-out"},
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
        &runBench};
}

}  // namespace warplab::app
