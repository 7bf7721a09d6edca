// The study plan: what makePlan draws (seeds, counterbalanced orders) over the shipped quick
// protocols, study.json written and read back, every refusal of a hand-edited study.json naming
// the file and the row or field, and the protocol a participant's session runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "game/registry.h"
#include "plan/latin_square.h"
#include "plan/study_plan.h"

namespace warplab::plan {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

const std::string kShooter = std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json";
const std::string kClick = std::string(WARPLAB_SOURCE_DIR) + "/protocol/click-quick.json";
const std::vector<std::string> kShooterConditions{"conv15", "conv120", "warp15to120"};
const std::vector<std::string> kClickConditions{"conv60", "conv30", "conv15",        "lag50",
                                                "lag100", "lag200", "bireproj15to60"};

// An empty folder build/test-output/plan/<name>.
std::string scratch(const std::string& name) {
    const fs::path dir = fs::path(WARPLAB_BINARY_DIR) / "test-output" / "plan" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir.string();
}

std::string readText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void writeText(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// A written plan of six participants over both quick protocols, seed 42.
std::string writtenPlan(const std::string& name) {
    const std::string dir = scratch(name);
    writePlan(dir, makePlan(dir, {kShooter, kClick}, 6, {}, 42));
    return dir;
}

// study.json edited by hand, as a lab might.
void edit(const std::string& dir, const std::function<void(Json&)>& change) {
    const fs::path path = fs::path(dir) / "study.json";
    Json document = Json::parse(readText(path));
    change(document);
    writeText(path, document.dump(2));
}

// The message readPlan refuses the folder with ("" when it reads).
std::string refusal(const std::string& dir) {
    try {
        readPlan(dir);
    } catch (const PlanError& e) {
        return e.what();
    }
    return "";
}

// Every refusal starts with the file it is about.
void expectRefusal(const std::string& dir, const std::vector<std::string>& parts) {
    const std::string message = refusal(dir);
    ASSERT_FALSE(message.empty()) << "the edited plan was read";
    EXPECT_EQ(message.rfind("study plan '" + (fs::path(dir) / "study.json").string() + "': ", 0), 0u) << message;
    for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message << "\nlacks " << part;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

bool isRowOf(const std::vector<std::string>& order, const std::vector<std::string>& conditions) {
    for (const auto& row : balancedLatinSquare(static_cast<int>(conditions.size()))) {
        std::vector<std::string> named;
        for (int c : row) named.push_back(conditions[c]);
        if (named == order) return true;
    }
    return false;
}

void expectSameParticipants(const StudyPlan& a, const StudyPlan& b) {
    ASSERT_EQ(a.participants.size(), b.participants.size());
    for (std::size_t i = 0; i < a.participants.size(); ++i) {
        const auto &x = a.participants[i], &y = b.participants[i];
        EXPECT_EQ(x.id, y.id);
        EXPECT_EQ(x.seed, y.seed);
        EXPECT_EQ(x.protocolOrder, y.protocolOrder);
        EXPECT_EQ(x.conditionOrder, y.conditionOrder);
        EXPECT_EQ(x.settings.cmPer360, y.settings.cmPer360);
        EXPECT_EQ(x.settings.mouseDpi, y.settings.mouseDpi);
        EXPECT_EQ(x.settings.invertY, y.settings.invertY);
    }
}

TEST(StudyPlan, SixParticipantsOverBothQuickProtocols) {
    const std::string dir = scratch("six");
    const StudyPlan plan = makePlan(dir, {kShooter, kClick}, 6, {}, 42);

    EXPECT_EQ(plan.formatVersion, 1);
    EXPECT_EQ(plan.id.size(), 32u);
    EXPECT_EQ(plan.seed, 42u);
    ASSERT_EQ(plan.protocols.size(), 2u);
    const ProtocolEntry& shooter = plan.protocols[0];
    EXPECT_EQ(shooter.file, "protocols/shooter-quick.json");
    EXPECT_EQ(shooter.name, "shooter-quick");
    EXPECT_EQ(shooter.game, "shooter");
    EXPECT_EQ(shooter.conditions, kShooterConditions);
    EXPECT_FALSE(shooter.blocked);  // test.interleave is true
    EXPECT_EQ(shooter.hash.size(), 16u);
    EXPECT_EQ(readText(fs::path(dir) / shooter.file), readText(kShooter));
    const ProtocolEntry& click = plan.protocols[1];
    EXPECT_EQ(click.file, "protocols/click-quick.json");
    EXPECT_EQ(click.game, "click");
    EXPECT_EQ(click.conditions, kClickConditions);
    EXPECT_FALSE(click.blocked);  // matches.shuffle is true
    EXPECT_EQ(readText(fs::path(dir) / click.file), readText(kClick));
    EXPECT_NE(shooter.hash, click.hash);

    ASSERT_EQ(plan.participants.size(), 6u);
    std::set<std::uint64_t> seeds;
    std::vector<std::vector<int>> shooterPositions(3, std::vector<int>(3, 0));
    for (std::size_t i = 0; i < 6; ++i) {
        const ParticipantPlan& p = plan.participants[i];
        EXPECT_EQ(p.id, "P0" + std::to_string(i + 1));
        EXPECT_NE(p.seed, 0u);
        EXPECT_LE(p.seed, kMaxParticipantSeed);
        seeds.insert(p.seed);
        // Two protocols: the square's two rows, alternately.
        EXPECT_EQ(p.protocolOrder, (i % 2 == 0 ? std::vector<int>{0, 1} : std::vector<int>{1, 0})) << p.id;
        ASSERT_EQ(p.conditionOrder.size(), 2u);
        EXPECT_TRUE(isRowOf(p.conditionOrder[0], kShooterConditions)) << p.id;
        EXPECT_TRUE(isRowOf(p.conditionOrder[1], kClickConditions)) << p.id;
        for (int k = 0; k < 3; ++k) {
            const auto at = std::find(kShooterConditions.begin(), kShooterConditions.end(), p.conditionOrder[0][k]);
            ++shooterPositions[at - kShooterConditions.begin()][k];
        }
        EXPECT_FALSE(p.settings.cmPer360.has_value());
    }
    EXPECT_EQ(seeds.size(), 6u);
    // Six participants take all six rows of the three conditions' square: each condition is
    // then in each position twice.
    for (const auto& counts : shooterPositions) EXPECT_EQ(counts, (std::vector<int>{2, 2, 2}));
    // The click conditions' fourteen rows: six participants, six different rows.
    std::set<std::vector<std::string>> clickOrders;
    for (const auto& p : plan.participants) clickOrders.insert(p.conditionOrder[1]);
    EXPECT_EQ(clickOrders.size(), 6u);
}

TEST(StudyPlan, IsAFunctionOfItsArgumentsButForIdAndTime) {
    const StudyPlan a = makePlan(scratch("same-a"), {kShooter, kClick}, 6, {}, 42);
    const StudyPlan b = makePlan(scratch("same-b"), {kShooter, kClick}, 6, {}, 42);
    expectSameParticipants(a, b);
    EXPECT_NE(a.id, b.id);
    EXPECT_EQ(a.protocols[0].hash, b.protocols[0].hash);
    const StudyPlan c = makePlan(scratch("same-c"), {kShooter, kClick}, 6, {}, 43);
    for (std::size_t i = 0; i < 6; ++i) EXPECT_NE(a.participants[i].seed, c.participants[i].seed);
}

// A plan grows by the rows a plan made at the larger size has there: the same ids, seeds and
// orders, in two steps or in one; the rows it had are kept as they were.
TEST(StudyPlan, GrownIsTheSameAsMadeAtThatSize) {
    const StudyPlan once = makePlan(scratch("grown-once"), {kShooter, kClick}, 11, {}, 42);
    const StudyPlan start = makePlan(scratch("grown"), {kShooter, kClick}, 4, {}, 42);
    const StudyPlan grown = extendPlan(scratch("grown"), extendPlan(scratch("grown"), start, 3, {}), 4, {});
    ASSERT_EQ(grown.participants.size(), once.participants.size());
    for (std::size_t i = 0; i < once.participants.size(); ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(grown.participants[i].id, once.participants[i].id);
        EXPECT_EQ(grown.participants[i].seed, once.participants[i].seed);
        EXPECT_EQ(grown.participants[i].protocolOrder, once.participants[i].protocolOrder);
        EXPECT_EQ(grown.participants[i].conditionOrder, once.participants[i].conditionOrder);
    }
    EXPECT_EQ(grown.id, start.id);
    // A row edited by hand keeps its seed, and no new row takes it.
    StudyPlan edited = start;
    edited.participants[0].seed = once.participants[4].seed;
    const StudyPlan around = extendPlan(scratch("grown"), edited, 1, {"X"});
    EXPECT_EQ(around.participants[0].seed, once.participants[4].seed);
    EXPECT_NE(around.participants[4].seed, once.participants[4].seed);
    EXPECT_EQ(around.participants[4].id, "X");
    // An id the plan has is refused, naming it.
    try {
        extendPlan(scratch("grown"), start, 1, {"P02"});
        ADD_FAILURE() << "P02 is in the plan already";
    } catch (const PlanError& e) {
        EXPECT_NE(std::string(e.what()).find("participant id \"P02\" is already in the plan"), std::string::npos)
            << e.what();
    }
}

TEST(StudyPlan, NamesParticipantsAsGivenOrZeroPadded) {
    EXPECT_EQ(makePlan(scratch("ids-12"), {kShooter}, 12, {}, 1).participants[11].id, "P12");
    EXPECT_EQ(makePlan(scratch("ids-12b"), {kShooter}, 12, {}, 1).participants[0].id, "P01");
    EXPECT_EQ(makePlan(scratch("ids-100"), {kShooter}, 100, {}, 1).participants[6].id, "P007");
    const StudyPlan named = makePlan(scratch("ids-named"), {kShooter}, 2, {"anna", "bo"}, 1);
    EXPECT_EQ(named.participants[1].id, "bo");
    EXPECT_EQ(findParticipant(named, "bo"), &named.participants[1]);
    EXPECT_EQ(findParticipant(named, "carl"), nullptr);
}

std::string makeRefusal(const std::function<void()>& make) {
    try {
        make();
    } catch (const PlanError& e) {
        return e.what();
    }
    return "";
}

TEST(StudyPlan, MakeRefusesWhatCannotBeAPlan) {
    const std::string dir = scratch("make-refusals");
    EXPECT_NE(makeRefusal([&] {
                  makePlan(dir, {kShooter}, 2, {"a", "a"}, 1);
              }).find("\"a\" is given twice"),
              std::string::npos);
    EXPECT_NE(makeRefusal([&] {
                  makePlan(dir, {kShooter}, 3, {"a", "b"}, 1);
              }).find("2 participant ids"),
              std::string::npos);
    EXPECT_NE(makeRefusal([&] { makePlan(dir, {kShooter}, 0, {}, 1); }).find("between 1 and"), std::string::npos);

    // Two files of one name would overwrite each other in protocols/.
    const std::string other = scratch("make-refusals-other");
    fs::copy_file(kShooter, fs::path(other) / "shooter-quick.json");
    EXPECT_NE(makeRefusal([&] {
                  makePlan(dir, {kShooter, other + "/shooter-quick.json"}, 2, {}, 1);
              }).find("have the same file name"),
              std::string::npos);

    // A protocol that does not load is refused with its loader's sentence, and nothing is copied.
    const fs::path broken = fs::path(other) / "broken.json";
    writeText(broken, "{\"format_version\": 1, \"name\": \"x\", \"game\": \"shooter\", \"test\": {\"timout_s\": 1}}");
    const std::string message = makeRefusal([&] { makePlan(dir, {kShooter, broken.string()}, 2, {}, 1); });
    EXPECT_EQ(message.rfind("protocol '" + broken.string() + "': test.timout_s is not a known field", 0), 0u)
        << message;
    EXPECT_FALSE(fs::exists(fs::path(dir) / "protocols"));

    // A plan is made once.
    writePlan(dir, makePlan(dir, {kShooter}, 2, {}, 1));
    EXPECT_NE(makeRefusal([&] { makePlan(dir, {kShooter}, 2, {}, 1); }).find("already holds a study plan"),
              std::string::npos);
}

TEST(StudyPlan, ReadsBackWhatItWrote) {
    const std::string dir = scratch("round-trip");
    StudyPlan plan = makePlan(dir, {kShooter, kClick}, 6, {}, 42);
    plan.participants[2].settings.cmPer360 = 34.5;
    plan.participants[2].settings.mouseDpi = 1600;
    plan.participants[3].settings.invertY = true;
    writePlan(dir, plan);
    EXPECT_FALSE(fs::exists(fs::path(dir) / ".study.json.partial"));
    const StudyPlan back = readPlan(dir);
    EXPECT_EQ(back.formatVersion, plan.formatVersion);
    EXPECT_EQ(back.id, plan.id);
    EXPECT_EQ(back.createdAt, plan.createdAt);
    EXPECT_EQ(back.seed, plan.seed);
    ASSERT_EQ(back.protocols.size(), plan.protocols.size());
    for (std::size_t p = 0; p < plan.protocols.size(); ++p) {
        EXPECT_EQ(back.protocols[p].file, plan.protocols[p].file);
        EXPECT_EQ(back.protocols[p].name, plan.protocols[p].name);
        EXPECT_EQ(back.protocols[p].game, plan.protocols[p].game);
        EXPECT_EQ(back.protocols[p].hash, plan.protocols[p].hash);
        EXPECT_EQ(back.protocols[p].conditions, plan.protocols[p].conditions);
        EXPECT_EQ(back.protocols[p].blocked, plan.protocols[p].blocked);
    }
    expectSameParticipants(back, plan);
    // Written again, the same bytes: the text is a function of the plan.
    const std::string text = readText(fs::path(dir) / "study.json");
    writePlan(dir, back);
    EXPECT_EQ(readText(fs::path(dir) / "study.json"), text);
    // One participant per object, its lists on one line.
    EXPECT_NE(text.find("      \"protocol_order\": [0, 1],\n"), std::string::npos) << text;
    EXPECT_NE(text.find("\"settings\": {\"cm_per_360\": 34.5, \"mouse_dpi\": 1600, \"invert_y\": false}"),
              std::string::npos)
        << text;
}

TEST(StudyPlan, ReadRefusesUnknownAndMissingKeys) {
    const std::string dir = writtenPlan("keys");
    edit(dir, [](Json& d) { d["sed"] = 1; });
    expectRefusal(dir, {"sed is not a known field"});
    edit(dir, [](Json& d) {
        d.erase("sed");
        d["participants"][2]["colour"] = "red";
    });
    expectRefusal(dir, {"participants[2] (\"P03\") colour is not a known field"});
    edit(dir, [](Json& d) {
        d["participants"][2].erase("colour");
        d["participants"][1].erase("seed");
    });
    expectRefusal(dir, {"participants[1] (\"P02\") seed is required but missing"});
    edit(dir, [](Json& d) {
        d["participants"][1]["seed"] = 7;
        d["protocols"][1].erase("hash");
    });
    expectRefusal(dir, {"protocols[1].hash is required but missing"});
    edit(dir, [](Json& d) { d["protocols"][1]["hash"] = 12; });
    expectRefusal(dir, {"protocols[1].hash must be a string, got 12"});
    edit(dir, [](Json& d) {
        d.erase("protocols");
        d["participants"][0]["settings"]["dpi"] = 400;
    });
    expectRefusal(dir, {"protocols is required but missing"});
}

TEST(StudyPlan, ReadRefusesANewerFormatBeforeItsKeys) {
    const std::string dir = writtenPlan("version");
    edit(dir, [](Json& d) {
        d["format_version"] = 2;
        d["something_new"] = true;
    });
    expectRefusal(dir, {"format_version 2 is newer than this warplab supports (1)"});
}

TEST(StudyPlan, ReadRefusesAKeyWrittenTwice) {
    const std::string dir = writtenPlan("twice");
    const fs::path path = fs::path(dir) / "study.json";
    std::string text = readText(path);
    text.replace(text.find("\"seed\": 42,"), 11, "\"seed\": 42, \"seed\": 43,");
    writeText(path, text);
    expectRefusal(dir, {"seed appears more than once"});
}

TEST(StudyPlan, ReadRefusesRepeatedIdsAndSeeds) {
    const std::string dir = writtenPlan("repeats");
    edit(dir, [](Json& d) { d["participants"][3]["id"] = "P01"; });
    expectRefusal(dir, {"participants[3] (\"P01\") id \"P01\" is also the id of participants[0]"});
    edit(dir, [](Json& d) {
        d["participants"][3]["id"] = "P04";
        d["participants"][4]["seed"] = d["participants"][1]["seed"];
    });
    expectRefusal(dir, {"participants[4] (\"P05\") seed", "is also the seed of participants[1] (\"P02\")"});
    edit(dir, [](Json& d) { d["participants"][4]["seed"] = 0; });
    expectRefusal(dir, {"participants[4] (\"P05\") seed must be an integer between 1 and 9007199254740991, got 0"});
    edit(dir, [](Json& d) { d["participants"][4]["seed"] = std::uint64_t{1} << 53; });
    expectRefusal(dir,
                  {"participants[4] (\"P05\") seed must be an integer between 1 and 9007199254740991, got "
                   "9007199254740992"});
    edit(dir, [](Json& d) { d["participants"][4]["seed"] = -5; });
    expectRefusal(dir, {"participants[4] (\"P05\") seed must be an integer"});
}

TEST(StudyPlan, ReadRefusesOrdersThatAreNotPermutations) {
    const std::string dir = writtenPlan("orders");
    edit(dir, [](Json& d) { d["participants"][1]["protocol_order"] = {0, 0}; });
    expectRefusal(dir, {"participants[1] (\"P02\") protocol_order is [0, 0], not an order of the 2 protocols"});
    edit(dir, [](Json& d) { d["participants"][1]["protocol_order"] = {1}; });
    expectRefusal(dir, {"participants[1] (\"P02\") protocol_order is [1]"});
    edit(dir, [](Json& d) {
        d["participants"][1]["protocol_order"] = {1, 0};
        d["participants"][0]["condition_order"][0][1] = "conv25";
    });
    expectRefusal(dir,
                  {"participants[0] (\"P01\") condition_order[0][1] is \"conv25\", not a condition of protocols[0]"});
    edit(dir, [](Json& d) { d["participants"][0]["condition_order"][0] = {"conv15", "conv120"}; });
    expectRefusal(dir,
                  {"participants[0] (\"P01\") condition_order[0] is [\"conv15\", \"conv120\"], not an order of the 3"});
    edit(dir, [](Json& d) { d["participants"][0]["condition_order"][0] = {"conv15", "conv120", "conv15"}; });
    expectRefusal(dir, {"participants[0] (\"P01\") condition_order[0][2] is \"conv15\" again"});
    edit(dir, [](Json& d) { d["participants"][0]["condition_order"].erase(1); });
    expectRefusal(dir,
                  {"participants[0] (\"P01\") condition_order must hold one list for each of the 2 protocols, not 1"});
}

TEST(StudyPlan, ReadRefusesAProtocolCopyMissingOrChanged) {
    const std::string dir = writtenPlan("copies");
    const fs::path copy = fs::path(dir) / "protocols" / "click-quick.json";
    const std::string original = readText(copy);
    writeText(copy, original + " ");
    expectRefusal(dir, {"protocols[1].file \"protocols/click-quick.json\" has changed since the plan was made"});
    fs::remove(copy);
    expectRefusal(dir, {"protocols[1].file \"protocols/click-quick.json\": no such file"});
    writeText(copy, original);
    EXPECT_EQ(refusal(dir), "");
    edit(dir, [](Json& d) { d["protocols"][1]["file"] = "../click-quick.json"; });
    expectRefusal(dir, {"protocols[1].file \"../click-quick.json\" must be a path inside the plan folder"});
    edit(dir, [](Json& d) {
        d["protocols"][1]["file"] = "protocols/click-quick.json";
        d["protocols"][1]["conditions"].erase(0);
    });
    expectRefusal(dir, {"protocols[1].conditions is [", "but the file lists [\"conv60\""});
    edit(dir, [](Json& d) {
        d["protocols"][1]["conditions"] = {"conv60", "conv30", "conv15", "lag50", "lag100", "lag200", "bireproj15to60"};
        d["protocols"][1]["blocked"] = true;
    });
    expectRefusal(dir, {"protocols[1].blocked is true, but the file shuffles the list"});
}

TEST(StudyPlan, ReadRefusesMouseSettingsNoOneHas) {
    const std::string dir = writtenPlan("settings");
    edit(dir, [](Json& d) { d["participants"][5]["settings"]["cm_per_360"] = 0; });
    expectRefusal(dir, {"participants[5] (\"P06\") settings.cm_per_360 must be a number between", "got 0"});
    edit(dir, [](Json& d) { d["participants"][5]["settings"]["cm_per_360"] = -12.5; });
    expectRefusal(dir, {"participants[5] (\"P06\") settings.cm_per_360", "got -12.5"});
    edit(dir, [](Json& d) {
        d["participants"][5]["settings"]["cm_per_360"] = 30;
        d["participants"][5]["settings"]["mouse_dpi"] = 0;
    });
    expectRefusal(dir, {"participants[5] (\"P06\") settings.mouse_dpi must be a number between", "got 0"});
    edit(dir, [](Json& d) { d["participants"][5]["settings"]["mouse_dpi"] = "800"; });
    expectRefusal(
        dir,
        {"participants[5] (\"P06\") settings.mouse_dpi must be a number between 1 and 100000, got string \"800\""});
    edit(dir, [](Json& d) { d["participants"][5]["settings"] = Json::object(); });
    EXPECT_EQ(refusal(dir), "");  // unset means the defaults
    EXPECT_EQ(readPlan(dir).participants[5].settings.mouseDpi, 800);
}

// What the plan's own JSON reader took before the strict reader read plans: bytes after the
// document, and a number beyond a double named without its line.
TEST(StudyPlan, ReadRefusesBytesAfterTheJsonAndNamesTheLineOfANumberBeyondADouble) {
    const std::string dir = writtenPlan("strict");
    const fs::path path = fs::path(dir) / "study.json";
    const std::string text = readText(path);
    const auto lines = std::count(text.begin(), text.end(), '\n');
    writeText(path, text + std::string(1, '\0') + "garbage");
    expectRefusal(dir, {"has a NUL byte at line " + std::to_string(lines + 1)});
    writeText(path, text + std::string(1, '\0'));
    expectRefusal(dir, {"has a NUL byte at line " + std::to_string(lines + 1)});
    std::string huge = text;
    huge.replace(huge.find("\"seed\": 42"), 10, "\"seed\": 1e999");
    writeText(path, huge);
    expectRefusal(dir, {"unreadable JSON at line 5, number overflow parsing '1e999'"});
    writeText(path, text);
    EXPECT_EQ(refusal(dir), "");
}

TEST(StudyPlan, ReadRefusesAMissingPlan) {
    const std::string dir = scratch("none");
    expectRefusal(dir, {"no such file"});
}

// The list a protocol's canonical copy holds, through the game's own parser.
std::vector<std::string> parsedList(const std::string& text, const char* section, const char* list) {
    const auto study = game::parseStudy(text, "participant copy");
    return Json::parse(study->protocolJson())[section][list].get<std::vector<std::string>>();
}

TEST(StudyPlan, AParticipantsProtocolHasTheirOrderAndNothingElseChanged) {
    const std::string dir = writtenPlan("participant-protocol");
    const StudyPlan plan = readPlan(dir);
    const ParticipantPlan* p = findParticipant(plan, "P04");
    ASSERT_NE(p, nullptr);
    const std::string shooter = participantProtocolJson(dir, plan, *p, 0);
    const std::string click = participantProtocolJson(dir, plan, *p, 1);
    EXPECT_EQ(parsedList(shooter, "test", "conditions"), p->conditionOrder[0]);
    EXPECT_EQ(parsedList(click, "matches", "modes"), p->conditionOrder[1]);
    EXPECT_NE(p->conditionOrder[1], kClickConditions);  // P04 does not have the file's own order

    // Everything but the list is the file's.
    Json mine = Json::parse(click), file = Json::parse(readText(kClick));
    mine["matches"].erase("modes");
    file["matches"].erase("modes");
    EXPECT_EQ(mine, file);

    EXPECT_THROW(participantProtocolJson(dir, plan, *p, 2), PlanError);
    writeText(fs::path(dir) / "protocols" / "shooter-quick.json", readText(kShooter) + "\n");
    try {
        participantProtocolJson(dir, plan, *p, 0);
        ADD_FAILURE() << "a changed copy was used";
    } catch (const PlanError& e) {
        EXPECT_NE(std::string(e.what()).find("has changed since the plan was made"), std::string::npos) << e.what();
    }
}

TEST(StudyPlan, AParticipantsProtocolAddsAListTheFileLeftToItsDefault) {
    const std::string source = scratch("default-list");
    const fs::path minimal = fs::path(source) / "minimal.json";
    writeText(minimal, "{\"format_version\": 1, \"name\": \"minimal\", \"game\": \"shooter\"}\n");
    const std::string dir = scratch("default-list-plan");
    const StudyPlan plan = makePlan(dir, {minimal.string()}, 2, {}, 5);
    EXPECT_EQ(plan.protocols[0].conditions, kShooterConditions);  // the shooter's default
    writePlan(dir, plan);
    const std::string text = participantProtocolJson(dir, plan, plan.participants[1], 0);
    EXPECT_EQ(parsedList(text, "test", "conditions"), plan.participants[1].conditionOrder[0]);
}

}  // namespace
}  // namespace warplab::plan
