// `warplab study init DIR ...` and `warplab study status DIR [--csv]`: a study plan made once for
// a whole study, and where the study stands (docs/study-plan.md). Running a participant is
// `warplab run --study DIR --participant ID` (cmd_run.cpp).
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "export/csv.h"
#include "plan/status.h"
#include "plan/study_plan.h"

namespace warplab::app {
namespace {

namespace fs = std::filesystem;

std::string orderText(const plan::StudyPlan& plan, const plan::ParticipantPlan& p) {
    std::string text;
    for (const int index : p.protocolOrder) {
        const plan::ProtocolEntry& entry = plan.protocols[static_cast<std::size_t>(index)];
        text += (text.empty() ? "" : "; ") + entry.name + " (";
        const auto& order = p.conditionOrder[static_cast<std::size_t>(index)];
        for (std::size_t i = 0; i < order.size(); ++i) text += (i ? " " : "") + order[i];
        text += std::string(entry.blocked ? "" : ", shuffled by the seed") + ")";
    }
    return text;
}

int runInit(const ParsedArgs& args, const std::string& dir) {
    if (!args.has("protocol")) throw UsageError("study init needs --protocol FILE[,FILE...]");
    if (!args.has("participants") && !args.has("ids")) throw UsageError("study init needs --participants N or --ids");
    for (const char* option : {"csv"})
        if (args.has(option)) throw UsageError(std::string("option --") + option + " only applies to study status");
    const auto protocols =
        commaSeparated(args.string("protocol"), "option --protocol needs protocol files separated by commas");
    const auto ids = args.has("ids")
        ? commaSeparated(args.string("ids"), "option --ids needs participant ids separated by commas")
        : std::vector<std::string>{};
    const int count =
        static_cast<int>(args.integer("participants", static_cast<long long>(ids.size()), 1, plan::kMaxParticipants));
    if (!ids.empty() && static_cast<int>(ids.size()) != count)
        throw UsageError("option --ids names " + std::to_string(ids.size()) + " participants but --participants says " +
                         std::to_string(count));
    const auto seed = static_cast<std::uint64_t>(args.integer("seed", 1, 0, 1LL << 62));
    fs::create_directories(dir);
    const plan::StudyPlan made = plan::makePlan(dir, protocols, count, ids, seed);
    plan::writePlan(dir, made);
    fs::create_directories(plan::resultsFolder(dir));
    std::cout << "study plan " << made.id << ": " << made.participants.size() << " participants, "
              << made.protocols.size() << " protocols, written to " << (fs::path(dir) / "study.json").string() << "\n";
    for (const plan::ParticipantPlan& p : made.participants)
        std::cout << "  " << p.id << "  seed " << p.seed << "  " << orderText(made, p) << "\n";
    std::cout << "next: warplab run --study " << dir << " --participant " << made.participants.front().id << "\n";
    return 0;
}

int runStatus(const ParsedArgs& args, const std::string& dir) {
    for (const char* option : {"protocol", "participants", "ids", "seed"})
        if (args.has(option)) throw UsageError(std::string("option --") + option + " only applies to study init");
    const plan::StudyPlan studyPlan = plan::readPlan(dir);
    const auto status = plan::studyStatus(dir, studyPlan);
    if (args.flag("csv")) {
        exporter::CsvFile csv(
            std::cout,
            {"participant", "position", "protocol", "status", "sessions", "done", "planned", "unit", "detail"});
        for (const auto& p : status)
            for (std::size_t i = 0; i < p.protocols.size(); ++i) {
                const plan::ProtocolStatus& s = p.protocols[i];
                csv.text(p.id);
                csv.integer(static_cast<long long>(i + 1));
                csv.text(studyPlan.protocols[static_cast<std::size_t>(s.protocolIndex)].name);
                csv.text(plan::stateName(s.state));
                csv.integer(s.sessions);
                if (s.unit.empty()) {
                    csv.empty();
                    csv.empty();
                } else {
                    csv.integer(static_cast<long long>(s.done));
                    csv.integer(static_cast<long long>(s.planned));
                }
                csv.text(s.unit);
                csv.text(s.detail);
                csv.endRow();
            }
        csv.close();
        return 0;
    }
    std::cout << "study plan " << studyPlan.id << " (" << (fs::path(dir) / "study.json").string() << ")\n";
    const plan::ParticipantStatus* next = nullptr;
    int finished = 0;
    for (const auto& p : status) {
        const int left = plan::nextProtocol(p);
        finished += left < 0;
        if (left >= 0 && !next) next = &p;
        std::cout << "  " << p.id << ":";
        for (const plan::ProtocolStatus& s : p.protocols) {
            std::cout << "  " << studyPlan.protocols[static_cast<std::size_t>(s.protocolIndex)].name << " "
                      << plan::stateText(s);
            if (s.sessions > 1) std::cout << " (" << s.sessions << " sessions)";
        }
        std::cout << "\n";
        for (const plan::ProtocolStatus& s : p.protocols)
            if (s.state != plan::SessionState::Done && s.state != plan::SessionState::NotStarted)
                std::cout << "      " << s.detail << "\n";
    }
    std::cout << finished << " of " << status.size() << " participants have done every protocol\n";
    if (next) {
        const plan::ProtocolStatus& s = next->protocols[static_cast<std::size_t>(plan::nextProtocol(*next))];
        const std::string& name = studyPlan.protocols[static_cast<std::size_t>(s.protocolIndex)].name;
        std::cout << "next: warplab run --study " << dir << " --participant " << next->id;
        if (!s.resumable.empty())
            std::cout << " --resume   (" << name << ": carries on " << fs::path(s.resumable).filename().string()
                      << " after its last completed trial or match; leave out --resume to start over)\n";
        else
            std::cout << "   (" << name << ")\n";
    }
    return 0;
}

int runStudy(const ParsedArgs& args) {
    const auto& words = args.positional();
    if (words.size() != 2 || (words[0] != "init" && words[0] != "status"))
        throw UsageError("give init DIR or status DIR");
    return words[0] == "init" ? runInit(args, words[1]) : runStatus(args, words[1]);
}

}  // namespace

// The command's options, beside the code that reads them.
Command studyCommand() {
    return {{"study",
             "Prepare a study once for all its participants, and see where it stands. init writes\n"
             "DIR/study.json: per participant an id, a distinct session seed, the order of the\n"
             "protocols and of each protocol's conditions (balanced Latin squares), and mouse\n"
             "settings to edit; then each participant plays with `warplab run --study DIR\n"
             "--participant ID`, into DIR/results. status says per participant and protocol what\n"
             "the sessions hold, and who is next (docs/study-plan.md).",
             "warplab study init DIR --protocol FILE[,FILE...] --participants N [--ids P01,...] [--seed S]\n"
             "       warplab study status DIR [--csv]",
             {
                 {"protocol", "FILE[,FILE...]", "init: the study's protocol files, copied into DIR/protocols/", ""},
                 {"participants", "N", "init: how many participants", "as many as --ids names"},
                 {"ids", "ID[,ID...]", "init: the participants' ids", "P01, P02, ..."},
                 {"seed", "S", "init: the seed the participants' session seeds are drawn from", "1"},
                 {"csv", "", "status: one CSV row per participant and protocol", ""},
             },
             true},
            &runStudy};
}

}  // namespace warplab::app
