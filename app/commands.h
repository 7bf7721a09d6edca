// Private to app/: one function per subcommand, and what they share.
#pragma once

#include <string>
#include <vector>

#include "cli.h"
#include "renderer/context.h"
#include "renderer/conventional.h"

namespace warplab::app {

struct Command {
    CommandSpec spec;
    int (*run)(const ParsedArgs& args);
};

const std::vector<Command>& commands();

int runInfo(const ParsedArgs& args);
int runRender(const ParsedArgs& args);
int runBench(const ParsedArgs& args);
int runRun(const ParsedArgs& args);
int runReplay(const ParsedArgs& args);
int runExport(const ParsedArgs& args);
int runDemo(const ParsedArgs& args);

// Shared option helpers.
OptionSpec glOption(const std::string& defaultBackend);
OptionSpec dataDirOption();
renderer::GlBackend backendFrom(const ParsedArgs& args, renderer::GlBackend fallback);
// shaders/ and assets/ under --data-dir, else $WARPLAB_DATA_DIR, else the build's source tree.
renderer::DataPaths dataPathsFrom(const ParsedArgs& args);

}  // namespace warplab::app
