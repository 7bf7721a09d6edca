#include "app/app.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sys/stat.h>

#include "commands.h"
#include "games/games.h"
#include "renderer/mesh.h"

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
    // The summaries line up two spaces after the longest name, so that none runs into its name.
    std::size_t width = 0;
    for (const auto& c : commands()) width = std::max(width, c.spec.name.size());
    for (const auto& c : commands()) {
        std::string name = "  " + c.spec.name;
        name.resize(width + 4, ' ');
        text += name + c.spec.summary.substr(0, c.spec.summary.find('\n')) + "\n";
    }
    return text;
}

}  // namespace

OptionSpec glOption(const std::string& defaultBackend) {
    return {"gl", "osmesa|egl|window",
            "OpenGL context: headless Mesa (osmesa), headless EGL (a GPU where there is one), or an SDL window",
            defaultBackend};
}

OptionSpec dataDirOption() {
    return {"data-dir", "DIR", "folder holding shaders/, assets/ and analysis/",
            "$WARPLAB_DATA_DIR or the source tree"};
}

renderer::GlBackend backendFrom(const ParsedArgs& args, renderer::GlBackend fallback) {
    if (!args.has("gl")) return fallback;
    try {
        return renderer::parseBackend(args.string("gl"));
    } catch (const renderer::ContextError& e) {
        throw UsageError(std::string("option --gl: ") + e.what());
    }
}

OptionSpec populationOption() {
    return {"population", "FILE",
            "with simulated participants: the population their traits are drawn from (docs/simulated-participant.md)",
            "assets/population.json"};
}

participants::Population populationFrom(const ParsedArgs& args, const renderer::DataPaths& paths) {
    return participants::readPopulation(args.has("population") ? args.path("population", "")
                                                               : participants::populationPath(paths.assetDir));
}

renderer::DataPaths dataPathsFrom(const ParsedArgs& args) {
    std::string root = WARPLAB_DEFAULT_DATA_DIR;
    if (const char* env = std::getenv("WARPLAB_DATA_DIR"); env != nullptr && *env != '\0') root = env;
    if (args.has("data-dir")) {
        root = args.path("data-dir", "");  // "" would mean the folder /
        if (!isDirectory(root))
            throw renderer::AssetError("option --data-dir: '" + root + "' " +
                                       (std::filesystem::exists(root) ? "is not a folder" : "does not exist"));
    }
    renderer::DataPaths paths{root + "/shaders", root + "/assets", root + "/analysis"};
    if (!isDirectory(paths.shaderDir))
        throw renderer::AssetError("cannot find warplab's shaders: '" + paths.shaderDir +
                                   "' is not a folder (set --data-dir or WARPLAB_DATA_DIR)");
    return paths;
}

std::string outputFolder(const ParsedArgs& args, const std::string& option, const std::string& fallback) {
    const std::string dir = args.path(option, fallback);
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (!isDirectory(dir))
        throw std::runtime_error(
            "option --" + option + ": cannot make the folder '" + dir + "' (" +
            (std::filesystem::exists(dir) ? std::string("a file of that name is there") : error.message()) + ")");
    return dir;
}

const std::vector<Command>& commands() {
    // The order --help lists them in.
    static const std::vector<Command> list = {infoCommand(),       checkCommand(),  renderCommand(), benchCommand(),
                                              runCommand(),        replayCommand(), exportCommand(), demoCommand(),
                                              conditionsCommand(), studyCommand()};
    return list;
}

int run(const std::vector<std::string>& args) {
    // Every command may read a protocol: the games are known before anything else happens.
    games::registerGames();
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
