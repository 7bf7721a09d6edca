// `warplab demo [--out DIR]`: the main job on a fresh machine -- a small simulated study run
// headlessly end to end: simulated participants who see only the displayed frames play the
// quick shooter and click-game protocols, every session is replayed and checked, exported,
// and analysed into a report with figures and a sample-size plan for a real study.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "app/commands.h"
#include "app/export/export.h"
#include "app/session_runner.h"
#include "renderer/mesh.h"

namespace warplab::app {
namespace {

namespace fs = std::filesystem;

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A results folder that already holds sessions would mix two demos into one analysis.
bool holdsSessions(const fs::path& dir) {
    std::error_code error;
    if (!fs::is_directory(dir, error)) return false;
    for (const auto& entry : fs::recursive_directory_iterator(dir, error))
        if (entry.path().extension() == ".warplab-session") return true;
    return false;
}

}  // namespace

int runDemo(const ParsedArgs& args) {
    const std::string out = args.path("out", "demo-out");
    // Two at least: the analysis pairs modes within participants across them.
    const int participants = static_cast<int>(args.integer("participants", 8, 2, 100));
    const std::string player = args.string("player", "sim");
    if (player != "sim" && player != "bot")
        throw UsageError("option --player of 'warplab demo' needs sim or bot, got '" + player + "'");
    const renderer::DataPaths paths = dataPathsFrom(args);
    const auto backend = backendFrom(args, renderer::GlBackend::OSMesa);
    if (backend == renderer::GlBackend::Window)
        throw UsageError("option --gl: the demo runs headless (osmesa or egl)");
    const fs::path root = fs::path(paths.shaderDir).parent_path();
    const std::vector<std::string> protocols{"shooter-quick", "click-quick"};
    for (const auto& name : protocols)
        if (!fs::is_regular_file(root / "protocol" / (name + ".json")))
            throw renderer::AssetError("cannot find the demo's protocol '" + (root / "protocol" / (name + ".json")).string() +
                                       "' (set --data-dir or WARPLAB_DATA_DIR)");
    const fs::path results = fs::path(out) / "results";
    if (holdsSessions(results))
        throw UsageError("'" + results.string() +
                         "' already holds sessions; a demo analyses only its own, so choose another --out");
    fs::create_directories(results);

    const auto started = std::chrono::steady_clock::now();
    std::cerr << "demo: " << participants << " simulated participants (" << player << ") x "
              << protocols.size() << " protocols into " << results.string() << "\n";
    int sessions = 0, reproduced = 0;
    for (int i = 1; i <= participants; ++i) {
        for (const auto& name : protocols) {
            HeadlessRun run;
            run.protocolPath = (root / "protocol" / (name + ".json")).string();
            run.participant = player + "-" + std::to_string(i);
            run.resultsDir = results.string();
            run.player = player + ":" + std::to_string(i);
            run.seed = static_cast<std::uint64_t>(i);
            run.dataPaths = paths;
            run.glBackend = backend;
            std::ostringstream quiet;  // the session's own progress lines; shown only on failure
            const auto t0 = std::chrono::steady_clock::now();
            std::string session;
            try {
                session = runHeadless(run, quiet);
            } catch (...) {
                std::cerr << quiet.str();
                throw;
            }
            // Every outcome must replay from the log alone, as a reviewer would check it.
            const ReplayResult replay = replaySession(session);
            ++sessions;
            if (replayExitCode(replay) == kReplayReproduced) ++reproduced;
            else
                std::cerr << "demo: " << session << " did not replay: "
                          << (replay.difference.empty() ? replay.note : replay.difference) << "\n";
            std::cerr << "demo: participant " << i << "/" << participants << ", " << name << ": "
                      << replay.outcomes << " outcomes, " << std::fixed << std::setprecision(0)
                      << secondsSince(t0) << " s; " << secondsSince(started) << " s elapsed\n"
                      << std::defaultfloat;
        }
    }
    if (reproduced != sessions) {
        std::cerr << "demo: " << sessions - reproduced << " of " << sessions << " sessions did not replay\n";
        return 1;
    }

    const std::string exportDir = (fs::path(out) / "export").string();
    ExportOptions options;
    exportResults(results.string(), exportDir, options, std::cerr);
    const std::string reportDir = (fs::path(out) / "report").string();
    const std::string command = shellQuoted(paths.analysisDir + "/analyze") + " " + shellQuoted(exportDir) +
                                " --out " + shellQuoted(reportDir) + " 1>&2";
    std::cerr << "demo: analysing " << exportDir << "\n";
    const int status = std::system(command.c_str());
    if (status != 0) {
        std::cerr << "demo: the analysis failed (" << paths.analysisDir
                  << "/analyze exited non-zero); the sessions and CSVs are kept in " << out << "\n";
        return 1;
    }
    std::cout << "demo: " << sessions << " sessions in " << results.string() << ", every outcome replayed\n"
              << "demo: CSVs in " << exportDir << "\n"
              << "demo: the report in " << reportDir << "/report.md, with its figures\n";
    std::cerr << "demo: done in " << std::fixed << std::setprecision(0) << secondsSince(started) << " s\n";
    return 0;
}

}  // namespace warplab::app
