// `warplab demo [--out DIR]`: the main job on a fresh machine -- a small simulated study run
// headlessly end to end: simulated participants who see only the displayed frames play the
// demo protocols, every session is replayed and checked, exported, and analysed into a report
// with figures and a sample-size plan for a real study.
//
// Sessions run in child processes, as many at once as --jobs says (the machine's cores by
// default): a simulated participant's eye renders every displayed frame, and llvmpipe keeps
// only about one and a half of two cores busy with such small frames. Each child is forked
// before this process has made any GL context or thread, runs one session exactly as
// `warplab run --headless` does, and writes its progress to DIR/logs/; the sessions do not
// depend on one another or on the order they finish in.
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#include "commands.h"
#include "export/export.h"
#include "session/results_lock.h"
#include "runner/session_runner.h"
#include "participants/eye.h"
#include "game/registry.h"
#include "renderer/mesh.h"

namespace warplab::app {
namespace {

namespace fs = std::filesystem;

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A session already anywhere under the demo's folder ("" for none): in its results/ it would
// mix two demos into one analysis, and anywhere else it is someone's data a demo should not
// write beside (docs: `--out` already holding sessions is a wrong command line).
std::string sessionUnder(const fs::path& dir) {
    std::error_code error;
    if (!fs::is_directory(dir, error)) return "";
    for (auto it = fs::recursive_directory_iterator(dir, fs::directory_options::skip_permission_denied, error);
         !error && it != fs::recursive_directory_iterator(); it.increment(error))
        if (it->path().extension() == ".warplab-session") return it->path().string();
    return "";
}

// --protocols: names of the protocols shipped in protocol/, or paths to protocol files.
std::vector<fs::path> protocolPaths(const std::string& list, const fs::path& root) {
    std::vector<fs::path> paths;
    for (const std::string& item :
         commaSeparated(list, "option --protocols needs protocol names or files separated by commas")) {
        const bool named = item.find('/') == std::string::npos && fs::path(item).extension() != ".json";
        const fs::path path = named ? root / "protocol" / (item + ".json") : fs::path(item);
        if (!fs::is_regular_file(path))
            throw renderer::AssetError("cannot find the demo's protocol '" + path.string() + "'" +
                                       (named ? " (set --data-dir or WARPLAB_DATA_DIR)" : ""));
        game::loadStudy(path.string());  // a malformed protocol is refused now, naming its field
        paths.push_back(path);
    }
    return paths;
}

struct Job {
    int participant = 0;
    fs::path protocol;
    fs::path log;  // the session's progress; its last line names the session file
    std::chrono::steady_clock::time_point started;
};

constexpr const char* kSessionLine = "demo-session\t";

// In the forked child: one session, as `warplab run --headless` runs it; never returns.
[[noreturn]] void runChild(const runner::HeadlessRun& run, const fs::path& logPath) {
    int code = 1;
    {
        std::ofstream log(logPath);
        try {
            const std::string session = runner::runHeadless(run, log);
            log << kSessionLine << session << "\n";
            code = log ? 0 : 1;
        } catch (const std::exception& e) {
            log << "error: " << e.what() << "\n";
        }
    }
    std::_Exit(code);  // no atexit handlers or static destructors of the parent's copy
}

std::string readFile(const fs::path& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// The session file a finished child's log names, or "".
std::string sessionOf(const std::string& log) {
    const std::size_t at = log.rfind(kSessionLine);
    if (at == std::string::npos) return "";
    const std::size_t start = at + std::string(kSessionLine).size();
    return log.substr(start, log.find('\n', start) - start);
}

// The demo's command line, read and checked before anything is written.
struct DemoSetup {
    std::string out;
    int participants = 0;
    std::string player;
    int jobs = 1;
    renderer::DataPaths paths;
    renderer::GlBackend backend = renderer::GlBackend::OSMesa;
    participants::Population population;
    std::vector<fs::path> protocols;
    fs::path results, logs;
};

DemoSetup readDemoSetup(const ParsedArgs& args) {
    DemoSetup d;
    const std::string out = args.path("out", "demo-out");
    d.out = out;
    if (const std::string found = sessionUnder(out); !found.empty())
        throw UsageError("option --out: '" + out + "' already holds sessions (" + found +
                         "); a demo analyses only its own, so choose another --out");
    // Two at least: the analysis pairs conditions within participants across them.
    d.participants = static_cast<int>(args.integer("participants", 8, 2, 100));
    const std::string player = args.string("player", "sim");
    d.player = player;
    if (player != "sim" && player != "bot")
        throw UsageError("option --player of 'warplab demo' needs sim or bot, got '" + player + "'");
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    d.jobs = static_cast<int>(args.integer("jobs", std::min(cores, 64), 1, 64));
    d.paths = dataPathsFrom(args);
    d.backend = backendFrom(args, renderer::GlBackend::OSMesa);
    if (d.backend == renderer::GlBackend::Window)
        throw UsageError("option --gl: the demo runs headless (osmesa or egl)");
    const fs::path root = fs::path(d.paths.shaderDir).parent_path();
    if (player == "bot" && args.has("population"))
        throw UsageError("option --population only applies with --player sim (the bot reads the game)");
    // Read (and a bad file refused) now, not in a child; the bot has no population to read.
    d.population = player == "sim" ? populationFrom(args, d.paths) : participants::uniformPopulation();
    d.protocols = protocolPaths(args.string("protocols", "shooter-demo,click-demo"), root);
    d.results = outputFolder(args, "out", out) + "/results";
    d.logs = fs::path(out) / "logs";
    return d;
}

// Where the sessions stand.
struct DemoProgress {
    std::size_t finished = 0, reproduced = 0;
    std::string failure;  // the first session that could not be run or replayed
};

// Forks the child that runs `job`'s session; returns its process id.
pid_t startSession(const DemoSetup& d, const Job& job) {
    runner::HeadlessRun run;
    run.protocolPath = job.protocol.string();
    run.participant = d.player + "-" + std::to_string(job.participant);
    run.resultsDir = d.results.string();
    run.player = d.player + ":" + std::to_string(job.participant);
    run.seed = static_cast<std::uint64_t>(job.participant);
    run.seeingPlayer = participants::perceptualPlayerMaker(d.paths, d.backend, d.population);
    std::cout.flush();
    std::cerr.flush();
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("demo: cannot start a session process (fork failed)");
    if (pid == 0) runChild(run, job.log);
    return pid;
}

// A child has ended with `status`: its session replayed, or the first failure noted.
void sessionEnded(const DemoSetup& d, const Job& job, int status, std::size_t total,
                  std::chrono::steady_clock::time_point started, DemoProgress& progress) {
    ++progress.finished;
    const std::string log = readFile(job.log);
    const std::string session = sessionOf(log);
    const std::string name = d.player + "-" + std::to_string(job.participant) + ", " + job.protocol.stem().string();
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || session.empty()) {
        std::cerr << log;
        if (progress.failure.empty())
            progress.failure = "the session of " + name + " failed (" +
                (WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status))
                                     : "exit status " + std::to_string(WEXITSTATUS(status))) +
                "); its log is " + job.log.string();
        return;
    }
    // Every outcome must replay from the log alone, as a reviewer would check it.
    const runner::ReplayResult replay = runner::replaySession(session);
    if (runner::replayExitCode(replay) == runner::kReplayReproduced) {
        ++progress.reproduced;
    } else if (progress.failure.empty()) {
        progress.failure =
            session + " did not replay: " + (replay.difference.empty() ? replay.note : replay.difference);
    }
    std::cerr << "demo: [" << progress.finished << "/" << total << "] " << name << ": " << replay.reproduced << "/"
              << replay.outcomes << " outcomes replayed, " << std::fixed << std::setprecision(0)
              << secondsSince(job.started) << " s; " << secondsSince(started) << " s elapsed\n"
              << std::defaultfloat;
}

// Every session in `waiting`, --jobs at a time, each replayed as it ends; none started after
// the first failure.
DemoProgress runSessions(const DemoSetup& d, std::deque<Job> waiting, std::chrono::steady_clock::time_point started) {
    const std::size_t total = waiting.size();
    std::map<pid_t, Job> running;
    DemoProgress progress;
    while (!running.empty() || (!waiting.empty() && progress.failure.empty())) {
        while (progress.failure.empty() && !waiting.empty() && static_cast<int>(running.size()) < d.jobs) {
            Job job = waiting.front();
            waiting.pop_front();
            const pid_t pid = startSession(d, job);
            job.started = std::chrono::steady_clock::now();
            running.emplace(pid, job);
        }
        int status = 0;
        const pid_t pid = waitpid(-1, &status, 0);
        if (pid < 0) throw std::runtime_error("demo: lost track of its session processes (waitpid failed)");
        const auto it = running.find(pid);
        if (it == running.end()) continue;
        const Job job = it->second;
        running.erase(it);
        sessionEnded(d, job, status, total, started, progress);
    }
    return progress;
}

// The sessions exported and analysed into the report.
int exportAndAnalyse(const DemoSetup& d, std::size_t total, std::chrono::steady_clock::time_point started) {
    const std::string& out = d.out;
    const std::string exportDir = (fs::path(out) / "export").string();
    exporter::ExportOptions options;
    exporter::exportResults(d.results.string(), exportDir, options, std::cerr);
    const std::string reportDir = (fs::path(out) / "report").string();
    const std::string command = shellQuoted(d.paths.analysisDir + "/analyze") + " " + shellQuoted(exportDir) +
        " --out " + shellQuoted(reportDir) + " 1>&2";
    std::cerr << "demo: analysing " << exportDir << "\n";
    const int status = std::system(command.c_str());
    if (status != 0) {
        std::cerr << "demo: the analysis failed (" << d.paths.analysisDir
                  << "/analyze exited non-zero); the sessions and CSVs are kept in " << out << "\n";
        return 1;
    }
    std::cout << "demo: " << total << " sessions in " << d.results.string() << ", every outcome replayed\n"
              << "demo: CSVs in " << exportDir << "\n"
              << "demo: the report in " << reportDir << "/report.md, with its figures\n";
    std::cerr << "demo: done in " << std::fixed << std::setprecision(0) << secondsSince(started) << " s\n";
    return 0;
}

}  // namespace

int runDemo(const ParsedArgs& args) {
    const DemoSetup d = readDemoSetup(args);
    fs::create_directories(d.results);
    fs::create_directories(d.logs);
    // One lock for the folder, taken here and inherited by every child: the demo's sessions
    // share it, and no `warplab run` writes into it meanwhile (nor another demo).
    std::string protocolNames;
    for (const auto& protocol : d.protocols)
        protocolNames += (protocolNames.empty() ? "" : ",") + protocol.stem().string();
    const session::ResultsFolderLock lock(d.results.string(), d.player + "-1.." + std::to_string(d.participants),
                                          protocolNames);

    std::deque<Job> waiting;
    for (int i = 1; i <= d.participants; ++i)
        for (const auto& protocol : d.protocols)
            waiting.push_back({i,
                               protocol,
                               d.logs / (d.player + "-" + std::to_string(i) + "-" + protocol.stem().string() + ".log"),
                               {}});
    const std::size_t total = waiting.size();
    const auto started = std::chrono::steady_clock::now();
    std::cerr << "demo: " << d.participants << " simulated participants (" << d.player << ") x " << d.protocols.size()
              << (d.protocols.size() == 1 ? " protocol, " : " protocols, ") << std::min<std::size_t>(d.jobs, total)
              << " at a time, into " << d.results.string() << "\n";

    const DemoProgress progress = runSessions(d, std::move(waiting), started);
    if (!progress.failure.empty()) {
        std::cerr << "demo: " << progress.failure << "\n"
                  << "demo: stopped after " << progress.finished << " of " << total << " sessions ("
                  << progress.reproduced << " replayed); they are kept in " << d.results.string() << "\n";
        return 1;
    }
    return exportAndAnalyse(d, total, started);
}

// The command's options, beside the code that reads them.
Command demoCommand() {
    return {
        {"demo",
         "The main job on a fresh machine: a small simulated study, headless, end to end. Simulated\n"
         "participants who see only the displayed frames play shooter-demo and click-demo in every\n"
         "condition, several sessions at once; each session is replayed and checked, all are exported,\n"
         "and the analysis writes a report with figures and the participants a real study would need.",
         "warplab demo [--out DIR] [--participants N] [--protocols LIST] [--jobs N]",
         {
             {"out", "DIR", "results/, logs/, export/ and report/ go here (it must hold no sessions yet)", "demo-out"},
             {"participants", "N", "simulated participants, each plays every protocol, 2..100", "8"},
             {"player", "sim|bot", "the perceptual simulated participant, or the scripted bot that reads the game",
              "sim"},
             {"protocols", "LIST", "protocols to play, by name (in protocol/) or file, separated by commas",
              "shooter-demo,click-demo"},
             {"jobs", "N", "sessions run at once, each in its own process, 1..64", "the machine's cores"},
             glOption("osmesa"),
             populationOption(),
             dataDirOption(),
         }},
        &runDemo};
}

}  // namespace warplab::app
