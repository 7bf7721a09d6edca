// The commands: one cmd_*.cpp each, holding its options and its run function, and what they share.
#pragma once

#include <string>
#include <vector>

#include "cli.h"
#include "participants/population.h"
#include "plan/status.h"
#include "plan/study_plan.h"
#include "renderer/context.h"
#include "renderer/conventional.h"

namespace warplab::app {

struct Command {
    CommandSpec spec;
    int (*run)(const ParsedArgs& args);
};

// Every command, in the order --help lists them (app.cpp).
const std::vector<Command>& commands();

// Each command's options and its run function, defined in its cmd_*.cpp.
Command infoCommand();
Command renderCommand();
Command benchCommand();
Command runCommand();
Command replayCommand();  // cmd_run.cpp: a replay runs the session again
Command exportCommand();
Command demoCommand();
Command conditionsCommand();
Command studyCommand();
Command checkCommand();

// Shared option helpers.
OptionSpec glOption(const std::string& defaultBackend);
OptionSpec dataDirOption();
renderer::GlBackend backendFrom(const ParsedArgs& args, renderer::GlBackend fallback);
// shaders/ and assets/ under --data-dir, else $WARPLAB_DATA_DIR, else the build's source tree.
// A --data-dir that is blank (exit 2), missing or not a folder (exit 1) is refused naming it.
renderer::DataPaths dataPathsFrom(const ParsedArgs& args);
// The folder an option names for a command's output, made with its parents if need be; one
// that cannot be made (a file of that name is there) is refused naming the option, before the
// command has done or printed anything else.
std::string outputFolder(const ParsedArgs& args, const std::string& option, const std::string& fallback);
// The simulated participants' population: --population FILE, else assets/population.json.
OptionSpec populationOption();
participants::Population populationFrom(const ParsedArgs& args, const renderer::DataPaths& paths);

// What --study DIR --participant ID [--protocol NAME] [--rig NAME] picks from a plan, for run and
// check (cmd_run.cpp): the participant's next protocol not yet done (or the one --protocol
// names), with their condition order, and the rig's results folder (made on its first use).
// Refused in one sentence naming study.json for a participant the plan does not list, one who
// has done every protocol, or one who is playing the protocol on any rig now.
struct StudyPick {
    std::string dir, rig;
    plan::StudyPlan plan;
    std::size_t participant = 0;  // into plan.participants
    plan::ProtocolStatus chosen;
    std::string protocolPath, protocolText, resultsDir;
};
StudyPick pickFromPlan(const ParsedArgs& args);

}  // namespace warplab::app
