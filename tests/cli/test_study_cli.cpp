// `warplab study init / status` and `run --study`, as a supervisor uses them: a plan made once,
// participants run from it with their own seeds and orders, the status after each, and the
// refusals that keep a study's data whole.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/cli_support.h"
#include "session/session_store.h"

namespace {

namespace fs = std::filesystem;
using warplab::testing::contains;
using warplab::testing::warplab;

std::string scratch(const std::string& name) { return warplab::testing::scratch("cli-study", name); }

std::string protocolFile(const char* name) { return std::string(WARPLAB_SOURCE_DIR) + "/protocol/" + name; }

nlohmann::json planOf(const std::string& dir) {
    std::ifstream in(dir + "/study.json");
    return nlohmann::json::parse(in);
}

// The counterbalanced list of a stored protocol (shooter test.conditions, click matches.conditions).
std::vector<std::string> listOf(const nlohmann::json& protocol) {
    return protocol["game"] == "click" ? protocol["matches"]["modes"].get<std::vector<std::string>>()
                                       : protocol["test"]["conditions"].get<std::vector<std::string>>();
}

// Six bot participants: init, each runs their first protocol, status, export. Each session has
// its participant's own seed and the condition order the plan gave them, and carries the plan.
TEST(CliStudy, SixParticipantsRunFromThePlanWithTheirOwnSeedsAndOrders) {
    const std::string base = scratch("six"), dir = base + "/study";
    const auto init = warplab("study init " + dir + " --protocol " + protocolFile("shooter-quick.json") + "," +
                              protocolFile("click-quick.json") + " --participants 6 --seed 11");
    ASSERT_EQ(init.status, 0) << init.output;
    EXPECT_TRUE(contains(init.output, "next: warplab run --study " + dir + " --participant P01")) << init.output;
    const nlohmann::json plan = planOf(dir);
    ASSERT_EQ(plan["participants"].size(), 6u);

    std::set<std::uint64_t> seeds;
    std::set<std::vector<std::string>> orders;
    for (const auto& p : plan["participants"]) {
        const std::string id = p["id"];
        const auto run = warplab("run --study " + dir + " --participant " + id + " --headless --player bot:2");
        ASSERT_EQ(run.status, 0) << run.output;
        const std::string path = run.output.substr(run.output.rfind(dir + "/results/"));
        const auto data = warplab::session::readSession(path.substr(0, path.find('\n')));
        EXPECT_TRUE(data.completed) << data.note;
        EXPECT_EQ(data.header.planId, plan["id"].get<std::string>());
        EXPECT_EQ(data.header.participant, id);
        EXPECT_EQ(data.header.seed, p["seed"].get<std::uint64_t>());
        seeds.insert(data.header.seed);
        // The first protocol of the participant's order, with the participant's condition order.
        const nlohmann::json stored = nlohmann::json::parse(data.header.protocolJson);
        const int first = p["protocol_order"][0];
        EXPECT_EQ(stored["name"], plan["protocols"][first]["name"]) << id;
        EXPECT_EQ(listOf(stored), p["condition_order"][first].get<std::vector<std::string>>()) << id;
        orders.insert(listOf(stored));
        EXPECT_EQ(warplab("replay " + path.substr(0, path.find('\n'))).status, 0) << id;
    }
    EXPECT_EQ(seeds.size(), 6u) << "every participant has a seed of their own";
    EXPECT_EQ(orders.size(), 6u) << "six rows of the squares, six orders";

    const auto status = warplab("study status " + dir + " --csv");
    ASSERT_EQ(status.status, 0) << status.output;
    int done = 0, notStarted = 0;
    std::istringstream lines(status.output);
    for (std::string line; std::getline(lines, line);) {
        done += contains(line, ",done,1,");
        notStarted += contains(line, ",not started,0,");
    }
    EXPECT_EQ(done, 6) << status.output;
    EXPECT_EQ(notStarted, 6) << status.output;
    const auto human = warplab("study status " + dir);
    EXPECT_TRUE(contains(human.output, "next: warplab run --study " + dir + " --participant P01")) << human.output;

    const auto exported = warplab("export " + dir + "/results --out " + base + "/export");
    EXPECT_EQ(exported.status, 0) << exported.output;
    // Every session row says which plan it was run from.
    std::ifstream sessionsCsv(base + "/export/sessions.csv");
    int fromThePlan = 0;
    for (std::string line; std::getline(sessionsCsv, line);)
        fromThePlan += contains(line, plan["id"].get<std::string>());
    EXPECT_EQ(fromThePlan, 6);
}

// What must not happen to a study's data, each refused in one sentence naming the plan, exit 1,
// with no session written.
TEST(CliStudy, RefusalsNameThePlanAndWriteNothing) {
    const std::string dir = scratch("refusals") + "/study";
    ASSERT_EQ(warplab("study init " + dir + " --protocol " + protocolFile("shooter-quick.json") + " --ids A,B").status,
              0);
    const std::string results = dir + "/results";
    const auto sessions = [&] {
        return static_cast<int>(std::distance(fs::directory_iterator(results), fs::directory_iterator()));
    };
    ASSERT_EQ(warplab("run --study " + dir + " --participant A --headless").status, 0);
    ASSERT_EQ(sessions(), 1);

    const auto again = warplab("run --study " + dir + " --participant A --headless");
    EXPECT_EQ(again.status, 1);
    EXPECT_TRUE(contains(again.output, "has done every protocol")) << again.output;
    const auto named = warplab("run --study " + dir + " --participant A --protocol shooter-quick --headless");
    EXPECT_EQ(named.status, 1);
    EXPECT_TRUE(contains(named.output, "already has a complete session of shooter-quick")) << named.output;
    const auto stranger = warplab("run --study " + dir + " --participant C --headless");
    EXPECT_EQ(stranger.status, 1);
    EXPECT_TRUE(contains(stranger.output, "has no participant 'C' (it plans A, B)")) << stranger.output;
    EXPECT_EQ(warplab("run --study " + dir + " --participant B --seed 3 --headless").status, 2);
    EXPECT_EQ(warplab("run --study " + dir + " --participant B --out /tmp --headless").status, 2);
    EXPECT_EQ(sessions(), 1);

    // --again records another, on purpose.
    EXPECT_EQ(warplab("run --study " + dir + " --participant A --protocol shooter-quick --again --headless").status, 0);
    EXPECT_EQ(sessions(), 2);

    // The protocol copy edited after the plan was made: the study would no longer be the one
    // planned.
    std::ofstream(dir + "/protocols/shooter-quick.json", std::ios::app) << "\n";
    const auto changed = warplab("run --study " + dir + " --participant B --headless");
    EXPECT_EQ(changed.status, 1);
    EXPECT_TRUE(contains(changed.output, "study.json': protocols[0].file")) << changed.output;
    EXPECT_TRUE(contains(changed.output, "has changed since the plan was made")) << changed.output;
    EXPECT_EQ(sessions(), 2);

    // A plan made twice in one folder would change the study under its sessions.
    const auto twice =
        warplab("study init " + dir + " --protocol " + protocolFile("shooter-quick.json") + " --participants 2");
    EXPECT_EQ(twice.status, 1) << twice.output;
}

// The plan in the export: three bot participants, one who played both protocols, one who played
// the first of theirs, one who has not started; participants.csv lists all three with the seeds,
// orders and mouse settings of study.json and where each stands, found beside the results folder
// or named with --study. A session of another plan in the folder is named and not counted.
TEST(CliStudy, TheExportListsEveryPlannedParticipantWithTheirSeedOrdersAndStatus) {
    const std::string base = scratch("participants-csv"), dir = base + "/study", other = base + "/other";
    const std::string protocols = protocolFile("shooter-quick.json") + "," + protocolFile("click-quick.json");
    ASSERT_EQ(warplab("study init " + dir + " --protocol " + protocols + " --participants 3 --seed 5").status, 0);
    nlohmann::json plan = planOf(dir);
    // A participant's mouse, edited into the plan as a lab would.
    plan["participants"][1]["settings"] = {{"cm_per_360", 34.5}, {"mouse_dpi", 1600}, {"invert_y", true}};
    std::ofstream(dir + "/study.json") << plan.dump(2);
    for (const char* id : {"P01", "P01", "P02"}) {
        const auto run = warplab("run --study " + dir + " --participant " + id + " --headless --player bot:2");
        ASSERT_EQ(run.status, 0) << run.output;
    }
    ASSERT_EQ(warplab("study init " + other + " --protocol " + protocols + " --participants 1").status, 0);
    ASSERT_EQ(warplab("run --study " + other + " --participant P01 --headless --player bot:2").status, 0);
    for (const auto& entry : fs::directory_iterator(other + "/results"))
        if (entry.path().extension() == ".warplab-session")
            fs::copy_file(entry.path(), dir + "/results/zz-other-" + entry.path().filename().string());

    // The words and values the plan gives, per participant.
    // kind: who played their sessions, "" before any was exported.
    const auto expectedRow = [&](const nlohmann::json& p, const std::vector<std::string>& states,
                                 const std::string& kind) {
        std::string order, conditions, status;
        for (std::size_t k = 0; k < p["protocol_order"].size(); ++k) {
            const int index = p["protocol_order"][k];
            const std::string name = plan["protocols"][index]["name"];
            order += (k ? ";" : "") + name;
            std::string list;
            for (const auto& c : p["condition_order"][index]) list += (list.empty() ? "" : " ") + c.get<std::string>();
            conditions += (k ? "; " : "") + name + ": " + list;
            status += (k ? "; " : "") + name + ": " + states[k];
        }
        const auto& settings = p["settings"];
        const std::string cm =
            settings.contains("cm_per_360") && !settings["cm_per_360"].is_null() ? settings["cm_per_360"].dump() : "";
        const std::string dpi = settings.contains("mouse_dpi") ? settings["mouse_dpi"].dump() : "800";
        const std::string invert = settings.value("invert_y", false) ? "true" : "false";
        return p["id"].get<std::string>() + "," + std::to_string(p["seed"].get<std::uint64_t>()) + "," + order + "," +
            conditions + "," + cm + "," + dpi + "," + invert + "," + status + "," + kind;
    };
    const std::string expected =
        "participant,seed,protocol_order,condition_orders,cm_per_360,mouse_dpi,invert_y,status,player_kind\n" +
        expectedRow(plan["participants"][0], {"done", "done"}, "bot") + "\n" +
        expectedRow(plan["participants"][1], {"done", "not started"}, "bot") + "\n" +
        expectedRow(plan["participants"][2], {"not started", "not started"}, "") + "\n";

    // A lock file a killed run left behind is neither a session nor in the way.
    std::ofstream(dir + "/results/.warplab-lock") << R"({"pid":1,"participant":"P03"})";
    const auto status = warplab("study status " + dir);
    EXPECT_EQ(status.status, 0) << status.output;
    EXPECT_FALSE(contains(status.output, "warplab-lock")) << status.output;
    EXPECT_TRUE(contains(status.output, "next: warplab run --study " + dir + " --participant P02")) << status.output;

    const auto beside = warplab("export " + dir + "/results --out " + base + "/export");
    ASSERT_EQ(beside.status, 0) << beside.output;
    const auto read = [](const std::string& path) {
        std::ifstream in(path);
        return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    };
    EXPECT_EQ(read(base + "/export/participants.csv"), expected);
    EXPECT_TRUE(contains(beside.output, base + "/export/participants.csv")) << beside.output;
    EXPECT_TRUE(
        contains(beside.output,
                 "1 session was run from another study plan (plan_id " + planOf(other)["id"].get<std::string>() + ")"))
        << beside.output;

    // Named with --study, from a results folder that is not beside it.
    const std::string moved = base + "/elsewhere";
    fs::copy(dir + "/results", moved);
    const auto named = warplab("export " + moved + " --study " + dir + " --out " + base + "/export2");
    ASSERT_EQ(named.status, 0) << named.output;
    EXPECT_EQ(read(base + "/export2/participants.csv"), expected);
    // Without a plan to be found: a warning, the other CSVs, no participants.csv.
    const auto lost = warplab("export " + moved + " --out " + base + "/export3");
    EXPECT_EQ(lost.status, 0) << lost.output;
    EXPECT_TRUE(contains(lost.output, "there is no '" + base + "/study.json'")) << lost.output;
    EXPECT_FALSE(fs::exists(base + "/export3/participants.csv"));
    // --study naming no plan: one sentence, exit 1, nothing written.
    const auto wrong = warplab("export " + moved + " --study " + base + " --out " + base + "/export4");
    EXPECT_EQ(wrong.status, 1) << wrong.output;
    EXPECT_TRUE(contains(wrong.output, base + "/study.json")) << wrong.output;
    EXPECT_FALSE(fs::exists(base + "/export4/sessions.csv"));
}

}  // namespace
