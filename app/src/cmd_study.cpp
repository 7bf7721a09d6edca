// `warplab study init DIR ...` and `warplab study status DIR [--csv]`: a study plan made once for
// a whole study, and where the study stands (docs/study-plan.md). Running a participant is
// `warplab run --study DIR --participant ID` (cmd_run.cpp).
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "commands.h"
#include "table/csv.h"
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

const plan::ProtocolEntry& protocolOf(const plan::StudyPlan& plan, const plan::ProtocolStatus& s) {
    return plan.protocols[static_cast<std::size_t>(s.protocolIndex)];
}

std::string rigsText(const std::vector<std::string>& rigs) {
    std::string text;
    for (const std::string& rig : rigs) text += (text.empty() ? "" : ", ") + plan::rigText(rig);
    return text;
}

// "2 people, 1 bot": participants by the kind of player of their sessions.
std::string kindsText(const std::map<std::string, int>& kinds) {
    static const std::map<std::string, std::pair<const char*, const char*>> words = {
        {"human", {"person", "people"}},
        {"bot", {"bot", "bots"}},
        {"simulated", {"simulated participant", "simulated participants"}},
        {"replay", {"replay", "replays"}},
        {"mixed", {"with mixed players", "with mixed players"}}};
    std::string text;
    for (const char* kind : {"human", "bot", "simulated", "replay", "mixed"}) {
        const auto count = kinds.find(kind);
        if (count == kinds.end()) continue;
        const auto& [one, many] = words.at(kind);
        text += (text.empty() ? "" : ", ") + std::to_string(count->second) + " " + (count->second == 1 ? one : many);
    }
    return text;
}

std::string idsText(const std::vector<std::string>& ids) {
    std::string text;
    for (const std::string& id : ids) text += (text.empty() ? "" : ", ") + id;
    return text;
}

// Who is in the default export's analysis and by which players, and why the rest are not.
void printSummary(const std::vector<plan::ParticipantStatus>& status) {
    std::map<std::string, int> kinds;
    std::vector<std::string> flagged, running;
    for (const auto& p : status) {
        if (plan::inAnalysis(p)) ++kinds[plan::participantKind(p)];
        bool isFlagged = false;
        for (const plan::ProtocolStatus& s : p.protocols) {
            isFlagged = isFlagged || s.state == plan::SessionState::Flagged;
            if (s.running) running.push_back(p.id + " (" + plan::rigText(s.runningRig) + ")");
        }
        if (isFlagged) flagged.push_back(p.id);
    }
    int finished = 0;
    for (const auto& [kind, count] : kinds) finished += count;
    std::cout << finished << " of " << status.size() << " participants have done every protocol";
    if (finished > 0) std::cout << ": " << kindsText(kinds);
    std::cout << "\n";
    if (!flagged.empty())
        std::cout << flagged.size() << (flagged.size() == 1 ? " participant has" : " participants have")
                  << " a flagged session, which export leaves out unless --include-flagged: " << idsText(flagged)
                  << "\n";
    if (!running.empty())
        std::cout << running.size() << (running.size() == 1 ? " session is" : " sessions are")
                  << " running now: " << idsText(running) << "\n";
}

void writeStatusCsv(const plan::StudyPlan& studyPlan, const std::vector<plan::ParticipantStatus>& status) {
    table::CsvFile csv(std::cout,
                       {"participant", "position", "protocol", "status", "sessions", "done", "planned", "unit",
                        "detail", "player_kind", "complete_rigs"});
    for (const auto& p : status)
        for (std::size_t i = 0; i < p.protocols.size(); ++i) {
            const plan::ProtocolStatus& s = p.protocols[i];
            csv.text(p.id);
            csv.integer(static_cast<long long>(i + 1));
            csv.text(protocolOf(studyPlan, s).name);
            csv.text(s.running ? "running" : plan::stateName(s.state));
            csv.integer(s.sessions);
            if (s.unit.empty()) {
                csv.empty();
                csv.empty();
            } else {
                csv.integer(static_cast<long long>(s.done));
                csv.integer(static_cast<long long>(s.planned));
            }
            csv.text(s.unit);
            csv.text(s.running ? plan::stateLine(s) : s.detail);
            csv.text(s.playerKind);
            std::string rigs;
            for (const std::string& rig : s.completeRigs) rigs += (rigs.empty() ? "" : ";") + rig;
            csv.text(rigs);
            csv.endRow();
        }
    csv.close();
}

// --participants N and --ids A,B,...: how many participants, and their ids (empty: the default
// ones). Either may be given alone; both must agree.
std::pair<int, std::vector<std::string>> participantsAsked(const ParsedArgs& args) {
    auto ids = args.has("ids")
        ? commaSeparated(args.string("ids"), "option --ids needs participant ids separated by commas")
        : std::vector<std::string>{};
    const int count =
        static_cast<int>(args.integer("participants", static_cast<long long>(ids.size()), 1, plan::kMaxParticipants));
    if (!ids.empty() && static_cast<int>(ids.size()) != count)
        throw UsageError("option --ids names " + std::to_string(ids.size()) + " participants but --participants says " +
                         std::to_string(count));
    return {count, std::move(ids)};
}

int runInit(const ParsedArgs& args, const std::string& dir) {
    if (!args.has("protocol")) throw UsageError("study init needs --protocol FILE[,FILE...]");
    if (!args.has("participants") && !args.has("ids")) throw UsageError("study init needs --participants N or --ids");
    for (const char* option : {"csv"})
        if (args.has(option)) throw UsageError(std::string("option --") + option + " only applies to study status");
    const auto protocols =
        commaSeparated(args.string("protocol"), "option --protocol needs protocol files separated by commas");
    const auto [count, ids] = participantsAsked(args);
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

// study add DIR --participants N [--ids ...]: the plan grown at its end, as one made at the new
// size would be (plan::extendPlan); rows already there are never touched.
int runAdd(const ParsedArgs& args, const std::string& dir) {
    if (!args.has("participants") && !args.has("ids")) throw UsageError("study add needs --participants N or --ids");
    for (const char* option : {"csv", "protocol", "seed"})
        if (args.has(option))
            throw UsageError(std::string("option --") + option +
                             (std::string(option) == "csv" ? " only applies to study status"
                                                           : " only applies to study init: a plan keeps its own"));
    const auto [count, ids] = participantsAsked(args);
    const plan::StudyPlan before = plan::readPlan(dir);
    const plan::StudyPlan grown = plan::extendPlan(dir, before, count, ids);
    plan::writePlan(dir, grown);
    std::cout << "study plan " << grown.id << ": " << count << " participant" << (count == 1 ? "" : "s") << " added, "
              << grown.participants.size() << " in all, written to " << (fs::path(dir) / "study.json").string() << "\n";
    for (std::size_t i = before.participants.size(); i < grown.participants.size(); ++i) {
        const plan::ParticipantPlan& p = grown.participants[i];
        std::cout << "  " << p.id << "  seed " << p.seed << "  " << orderText(grown, p) << "\n";
    }
    std::cout << "next: warplab run --study " << dir << " --participant "
              << grown.participants[before.participants.size()].id << "\n";
    return 0;
}

int runStatus(const ParsedArgs& args, const std::string& dir) {
    for (const char* option : {"protocol", "participants", "ids", "seed"})
        if (args.has(option))
            throw UsageError(std::string("option --") + option + " only applies to study init and study add");
    const plan::StudyPlan studyPlan = plan::readPlan(dir);
    const auto status = plan::studyStatus(dir, studyPlan);
    if (args.flag("csv")) {
        writeStatusCsv(studyPlan, status);
        return 0;
    }
    std::cout << "study plan " << studyPlan.id << " (" << (fs::path(dir) / "study.json").string() << ")\n";
    for (const auto& p : status) {
        const std::string kind = plan::participantKind(p);
        std::cout << "  " << p.id << (kind.empty() ? "" : " (" + kind + ")") << ":";
        for (const plan::ProtocolStatus& s : p.protocols) {
            std::cout << "  " << protocolOf(studyPlan, s).name << " " << plan::stateLine(s);
            if (s.sessions > 1) std::cout << " (" << s.sessions << " sessions)";
        }
        std::cout << "\n";
        for (const plan::ProtocolStatus& s : p.protocols) {
            if (s.state == plan::SessionState::Flagged)
                std::cout << "      " << s.detail << " (export leaves it out unless --include-flagged)\n";
            else if (s.state != plan::SessionState::Done && s.state != plan::SessionState::NotStarted)
                std::cout << "      " << s.detail << "\n";
            if (s.completeRigs.size() > 1)
                std::cout << "      " << protocolOf(studyPlan, s).name << " was played to the end on "
                          << s.completeRigs.size() << " rigs (" << rigsText(s.completeRigs)
                          << "): the participant played it twice; export includes both unless one is moved out\n";
        }
    }
    printSummary(status);
    const plan::ParticipantStatus* next = plan::nextParticipant(status);
    if (next) {
        const plan::ProtocolStatus& s = next->protocols[static_cast<std::size_t>(plan::nextProtocol(*next))];
        const std::string& name = protocolOf(studyPlan, s).name;
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
    if (words.size() != 2 || (words[0] != "init" && words[0] != "add" && words[0] != "status"))
        throw UsageError("give init DIR, add DIR or status DIR");
    if (words[0] == "init") return runInit(args, words[1]);
    return words[0] == "add" ? runAdd(args, words[1]) : runStatus(args, words[1]);
}

}  // namespace

// The command's options, beside the code that reads them.
Command studyCommand() {
    return {
        {"study",
         "Prepare a study once for all its participants, and see where it stands. init writes\n"
         "DIR/study.json: per participant an id, a distinct session seed, the order of the\n"
         "protocols and of each protocol's conditions (balanced Latin squares), and mouse\n"
         "settings to edit; then each participant plays with `warplab run --study DIR\n"
         "--participant ID`, into DIR/results. status says per participant and protocol what\n"
         "the sessions hold (in every rig's folder), who played, who is running, and who is next;\n"
         "add grows the plan by the rows a plan made at the larger size would have (docs/study-plan.md).",
         "warplab study init DIR --protocol FILE[,FILE...] --participants N [--ids P01,...] [--seed S]\n"
         "       warplab study add DIR --participants N [--ids ID,...]\n"
         "       warplab study status DIR [--csv]",
         {
             {"protocol", "FILE[,FILE...]", "init: the study's protocol files, copied into DIR/protocols/", ""},
             {"participants", "N", "init, add: how many participants (add: how many more)", "as many as --ids names"},
             {"ids", "ID[,ID...]", "init, add: the participants' ids", "P01, P02, ... (add: the next numbers)"},
             {"seed", "S", "init: the seed the participants' session seeds are drawn from", "1"},
             {"csv", "", "status: one CSV row per participant and protocol", ""},
         },
         true},
        &runStudy};
}

}  // namespace warplab::app
