// The click game as a pure function of protocol, seed and input: the bot plays the quick
// protocol to the end with every match and rating, replays reproduce it bit for bit, the
// cursor and spheres on screen are as late as each condition's schedule says, and clicks are
// judged against the world and against the frame on screen.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <utility>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "click_bot.h"
#include "condition/readme_latency_table.h"
#include "click_game.h"
#include "game/screen.h"
#include "click/click_protocol.h"
#include "game/registry.h"
#include "session/records.h"

namespace warplab::game {
namespace {

const DisplaySize kDisplay{1280, 720};

protocol::ClickProtocol quick() {
    return protocol::loadClickProtocol(std::string(WARPLAB_SOURCE_DIR) + "/protocol/click-quick.json");
}

nlohmann::json detail(const session::EventRecord& e) { return nlohmann::json::parse(e.detailJson); }

struct Played {
    std::vector<FrameInput> inputs;
    std::vector<session::EventRecord> events;
};

Played playWithBot(const protocol::ClickProtocol& p, std::uint64_t seed, std::uint64_t botSeed) {
    ClickGame game(p, seed, kDisplay);
    ClickBot bot(botSeed, p, kDisplay);
    Played out;
    FrameInput input = bot.first();
    for (int i = 0; i < 1000000 && !game.finished(); ++i) {
        out.inputs.push_back(input);
        const ShownFrame shown = game.step(input);
        for (auto& e : game.takeEvents()) out.events.push_back(e);
        input = bot.next(shown);
    }
    return out;
}

// Steps through the ready screen into the first match.
ShownFrame startFirstMatch(ClickGame& game) {
    ShownFrame shown = game.step({0, 0, 0, kKeyEnter});
    while (shown.blank) shown = game.step({});
    return shown;
}

TEST(ClickGame, BotPlaysEveryMatchAndAnswersEveryRating) {
    const auto p = quick();
    const Played played = playWithBot(p, 3, 7);
    std::map<int, std::set<std::string>> conditionsPerRound;
    int matches = 0, ratings = 0, clicks = 0, greens = 0, byKey = 0, byMouse = 0;
    for (const auto& e : played.events) {
        if (e.type == "match") {
            ++matches;
            conditionsPerRound[detail(e)["round"] == "practice" ? 0 : 1].insert(e.condition);
            EXPECT_EQ(
                detail(e)["clicks"].get<int>(),
                detail(e)["green_hits"].get<int>() + detail(e)["red_hits"].get<int>() + detail(e)["misses"].get<int>());
        }
        if (e.type == "rating") {
            ++ratings;
            const int v = detail(e)["value"];
            EXPECT_GE(v, p.ratingMin);
            EXPECT_LE(v, p.ratingMax);
            EXPECT_EQ(v,
                      botRating(condition::preset(e.condition), p.refreshHz, detail(e)["statement_index"], p.ratingMin,
                                p.ratingMax));
            (detail(e)["answered_with"] == "key" ? byKey : byMouse) += 1;
        }
        if (e.type == "click") {
            ++clicks;
            greens += detail(e)["scored"] == "green";
        }
    }
    const int expected = static_cast<int>(p.conditions.size()) * 2;  // one match per condition per round
    EXPECT_EQ(matches, expected);
    EXPECT_EQ(ratings, expected * 4);
    EXPECT_EQ(byKey, byMouse) << "the bot answers half by key, half by clicking the box";
    for (const auto& [round, conditions] : conditionsPerRound)
        EXPECT_EQ(conditions.size(), p.conditions.size()) << round;
    EXPECT_GT(clicks, expected);
    EXPECT_GT(greens, clicks / 4) << "the bot should hit green spheres";
    EXPECT_EQ(played.events.back().type, "phase");
    EXPECT_EQ(played.events.back().phase, "done");
    // How far it got, as study status says it: every match planned, and one fewer without the last.
    const auto study = loadStudy(std::string(WARPLAB_SOURCE_DIR) + "/protocol/click-quick.json");
    const Progress whole = study->progress(played.events);
    EXPECT_EQ(whole.unit, "matches");
    EXPECT_EQ(whole.planned, static_cast<std::size_t>(expected));
    EXPECT_EQ(whole.done, whole.planned);
    auto cut = played.events;
    while (cut.back().type != "match") cut.pop_back();
    cut.pop_back();
    EXPECT_EQ(study->progress(cut).done, whole.planned - 1);
}

TEST(ClickGame, SameSeedAndInputSameEventsBitForBit) {
    const auto p = quick();
    const Played a = playWithBot(p, 11, 2);
    ClickGame game(p, 11, kDisplay);
    std::vector<session::EventRecord> replayed;
    for (const auto& in : a.inputs) {
        game.step(in);
        for (auto& e : game.takeEvents()) replayed.push_back(e);
    }
    ASSERT_EQ(a.events.size(), replayed.size());
    for (std::size_t i = 0; i < replayed.size(); ++i)
        ASSERT_EQ(session::firstDifference(a.events[i], replayed[i]), "") << "event " << i;
    // Another session seed: other spheres, other match order, other outcomes.
    const Played b = playWithBot(p, 12, 2);
    bool differ = a.events.size() != b.events.size();
    for (std::size_t i = 0; !differ && i < a.events.size(); ++i)
        differ = !session::firstDifference(a.events[i], b.events[i]).empty();
    EXPECT_TRUE(differ);
}

// The participant sees where they are in the round: "Match 2 of 7 (practice)", "Match 5 of 7",
// during the match and on its rating screens.
TEST(ClickGame, PhaseTextCountsTheMatchesOfTheRound) {
    const auto p = quick();
    ClickGame game(p, 3, kDisplay);
    ClickBot bot(7, p, kDisplay);
    FrameInput input = bot.first();
    std::map<std::string, std::vector<int>> seen;  // round -> the match numbers shown, in order
    const int perRound = static_cast<int>(p.conditions.size());
    while (!game.finished()) {
        const ShownFrame shown = game.step(input);
        game.takeEvents();
        if (!shown.condition.name.empty() || shown.question) {
            int n = 0, of = 0;
            ASSERT_EQ(std::sscanf(shown.phaseText.c_str(), "Match %d of %d", &n, &of), 2) << shown.phaseText;
            EXPECT_EQ(of, perRound);
            const bool practice = shown.phaseText.find("(practice)") != std::string::npos;
            auto& numbers = seen[practice ? "practice" : "scored"];
            if (numbers.empty() || numbers.back() != n) numbers.push_back(n);
        }
        input = bot.next(shown);
    }
    std::vector<int> oneToN(static_cast<std::size_t>(perRound));
    for (int i = 0; i < perRound; ++i) oneToN[static_cast<std::size_t>(i)] = i + 1;
    EXPECT_EQ(seen["practice"], oneToN);
    EXPECT_EQ(seen["scored"], oneToN);
}

TEST(ClickGame, EveryMatchLastsItsFramesAndOrdersConditionsBySeed) {
    auto p = quick();
    ClickGame a(p, 5, kDisplay), b(p, 6, kDisplay);
    std::vector<std::string> orderA, orderB;
    for (const auto& m : a.matches()) orderA.push_back(m.condition);
    for (const auto& m : b.matches()) orderB.push_back(m.condition);
    EXPECT_NE(orderA, orderB);
    const Played played = playWithBot(p, 5, 1);
    std::map<int, std::int64_t> start;
    for (const auto& e : played.events) {
        if (e.type == "match_start") start[e.trial] = e.frame;
        if (e.type == "match") {
            // match_start is logged on the screen frame that begins it; play starts on the next.
            EXPECT_EQ(e.frame - start.at(e.trial), std::llround(p.matchS * p.refreshHz));
        }
    }
    EXPECT_EQ(start.size(), a.matches().size());
}

// A match's first frame is its schedule's frame 0, rendered: the frames after it (held, or
// interpolated towards it) are made from it. (Starting the schedule on the screen frame that
// begins the match left them no source.)
TEST(ClickGame, EveryMatchOpensWithARender) {
    const auto p = quick();
    ClickGame game(p, 3, kDisplay);
    ClickBot bot(7, p, kDisplay);
    FrameInput input = bot.first();
    bool previousBlank = true;
    int openings = 0;
    while (!game.finished()) {
        const ShownFrame shown = game.step(input);
        if (previousBlank && !shown.blank) {
            ++openings;
            EXPECT_EQ(shown.schedule.index, 0) << shown.condition.name;
            EXPECT_TRUE(shown.rendersNow) << shown.condition.name;
            EXPECT_EQ(shown.sourceFrame, shown.frame - (shown.schedule.index - shown.schedule.sourceIndex))
                << shown.condition.name;
        }
        previousBlank = shown.blank;
        input = bot.next(shown);
    }
    EXPECT_EQ(openings, static_cast<int>(game.matches().size()));
}

// The cursor is drawn into the frame, so a mouse step shows with the condition's view latency --
// the same schedule the shooter's reticle follows.
TEST(ClickGame, CursorStepShowsWithEachConditionsViewLatency) {
    for (const auto& condition : quick().conditions) {
        for (int phase = 0; phase < 4; ++phase) {
            auto p = quick();
            p.conditions = {condition};
            p.rounds = {{"only", true, 1, ""}};  // no instructions screen
            ClickGame game(p, 2, kDisplay);
            ShownFrame shown = startFirstMatch(game);
            for (int i = 0; i < 30 + phase; ++i) shown = game.step({});
            const glm::dvec2 before = shown.cursor;
            const ShownFrame stepFrame = game.step({40.0, 0.0, 0, 0});
            const condition::ConditionSchedule schedule(condition::preset(condition), p.refreshHz);
            ShownFrame f = stepFrame;
            while (f.cursor == before) f = game.step({});
            EXPECT_NEAR(f.time - stepFrame.time, schedule.viewLatency(stepFrame.schedule.displayTime), 1e-9)
                << condition << " phase " << phase;
            EXPECT_DOUBLE_EQ(f.cursor.x - before.x, 40.0 * p.cursorPixelsPerCount) << condition;
        }
    }
}

// Moves the cursor onto a moving green sphere and clicks (defined below).
FrameInput clickOnGreen(const ClickGame& game, const protocol::ClickProtocol& p);

// The README's latency table in a real run, at each display rate its section names (the
// table's 120 Hz, the click game's 60 Hz), for every condition that rate can run. A cursor step comes
// with frame v's input: it happened in (v - 1, v], so when frame k first shows it, it is k - v
// to k - v + 1 frames old, and over every phase of the cycle those give the row's view latency,
// least and most. A click at v takes its sphere from the world after v's sample: the change
// lies in (v, v + 1], and the first frame k without the sphere shows it k - v - 1 to k - v
// frames late, within the row's scene latency and at worst its maximum. (The scene minimum is a
// change of motion, which a B-frame shows as it interpolates towards the later I-frame; a
// sphere that is gone is gone from the depicted instant on.)
TEST(ClickGame, ReadmeLatencyTableHoldsInARealRun) {
    const readme::ReadmeLatencyTable table = readme::readmeLatencyTable();
    EXPECT_EQ(table.displayRatesHz, (std::set<double>{60.0, 120.0}));
    int checked = 0;
    for (const double refresh : table.displayRatesHz) {
        const double frameMs = 1000.0 / refresh;
        for (const readme::ReadmeLatencyRow& row : table.rows) {
            auto p = quick();
            p.refreshHz = refresh;
            p.conditions = {row.id};
            p.rounds = {{"only", true, 1, ""}};  // no instructions screen
            if (!p.conditionTable.check(row.id, refresh).empty()) continue;  // conv120 at 60 Hz
            SCOPED_TRACE(row.id + " at " + std::to_string(static_cast<int>(refresh)) + " Hz");
            ++checked;

            std::int64_t viewLo = 1 << 30, viewHi = -1;
            for (int phase = 0; phase < 16; ++phase) {
                ClickGame game(p, 2, kDisplay);
                ShownFrame shown = startFirstMatch(game);
                for (int i = 0; i < 40 + phase; ++i) shown = game.step({});
                const glm::dvec2 before = shown.cursor;
                const ShownFrame stepFrame = game.step({40.0, 0.0, 0, 0});
                ShownFrame f = stepFrame;
                for (int i = 0; i < 100 && f.cursor == before; ++i) f = game.step({});
                ASSERT_NE(f.cursor, before);
                viewLo = std::min(viewLo, f.frame - stepFrame.frame);
                viewHi = std::max(viewHi, f.frame - stepFrame.frame + 1);
            }
            EXPECT_NEAR(static_cast<double>(viewLo) * frameMs, row.viewMinMs, 0.05);
            EXPECT_NEAR(static_cast<double>(viewHi) * frameMs, row.viewMaxMs, 0.05);

            p.matchS = 8;
            ClickGame game(p, 4, kDisplay);
            startFirstMatch(game);
            std::map<std::int64_t, std::int64_t> clickedAt, lastShown;  // by sphere id: frames
            std::int64_t end = 0;
            for (int i = 0; i < std::lround(p.matchS * refresh) - 10 && game.world() != nullptr; ++i) {
                const ShownFrame shown = game.step(i % 7 == 3 ? clickOnGreen(game, p) : FrameInput{});
                end = shown.frame;
                for (const auto& o : shown.scene.objects) lastShown[o.id - scene::kIdFirstSphere] = shown.frame;
                for (const auto& e : game.takeEvents())
                    if (e.type == "click" && detail(e)["scored"] == "green")
                        clickedAt[detail(e)["world_sphere"].get<std::int64_t>()] = e.frame;
            }
            std::int64_t sceneLo = 1 << 30, sceneHi = -1;
            int vanished = 0;
            for (const auto& [id, v] : clickedAt) {
                if (static_cast<double>(end - v) * frameMs < row.sceneMaxMs + 2 * frameMs) continue;  // still on screen
                const std::int64_t k = lastShown.at(id) + 1;  // the first frame without it
                sceneLo = std::min(sceneLo, k - v - 1);
                sceneHi = std::max(sceneHi, k - v);
                ++vanished;
            }
            ASSERT_GE(vanished, 10);
            EXPECT_GE(static_cast<double>(sceneLo) * frameMs, row.sceneMinMs - 0.05);
            EXPECT_NEAR(static_cast<double>(sceneHi) * frameMs, row.sceneMaxMs, 0.05);
        }
    }
    EXPECT_EQ(checked, 9 + 7) << "every row at 120 Hz, and the seven the click game runs at 60 Hz";
}

// A press is on screen where the README's latency table says: the first frame whose inputFrame
// reaches the press's frame v (what a photodiode marker lights on) is the first whose cursor
// shows a step made with the press, and over every phase of the cycle it comes k - v to
// k - v + 1 frames after the press happened (in (v - 1, v]), the row's view latency, least and
// most. So lag50 at 60 Hz lights 3 frames after the press's, warp15to120 at 120 Hz on its own
// frame: the first frame made after the press. Screens show their own frame's input.
TEST(ClickGame, APressIsOnScreenWhereTheReadmeLatencyTableSays) {
    const readme::ReadmeLatencyTable table = readme::readmeLatencyTable();
    int checked = 0;
    for (const double refresh : table.displayRatesHz) {
        const double frameMs = 1000.0 / refresh;
        for (const readme::ReadmeLatencyRow& row : table.rows) {
            auto p = quick();
            p.refreshHz = refresh;
            p.conditions = {row.id};
            p.rounds = {{"only", true, 1, ""}};  // no instructions screen
            if (!p.conditionTable.check(row.id, refresh).empty()) continue;  // conv120 at 60 Hz
            SCOPED_TRACE(row.id + " at " + std::to_string(static_cast<int>(refresh)) + " Hz");
            ++checked;
            std::int64_t lo = 1 << 30, hi = -1;
            for (int phase = 0; phase < 16; ++phase) {
                ClickGame game(p, 2, kDisplay);
                const ShownFrame ready = game.step({});
                EXPECT_EQ(ready.inputFrame, ready.frame) << "a screen";
                ShownFrame shown = game.step({0, 0, 0, kKeyEnter});
                while (shown.blank) shown = game.step({});
                for (int i = 0; i < 40 + phase; ++i) shown = game.step({});
                const glm::dvec2 before = shown.cursor;
                const ShownFrame press = game.step({40.0, 0.0, kButtonLeft, 0});
                ShownFrame f = press;
                for (int i = 0; i < 100 && f.inputFrame < press.frame; ++i) {
                    EXPECT_EQ(f.cursor, before) << "frame " << f.frame << " shows the press before it says so";
                    f = game.step({});
                }
                ASSERT_GE(f.inputFrame, press.frame);
                EXPECT_NE(f.cursor, before) << "frame " << f.frame << " says it shows the press but does not";
                lo = std::min(lo, f.frame - press.frame);
                hi = std::max(hi, f.frame - press.frame + 1);
                if (row.id == "lag50" && refresh == 60.0) {
                    EXPECT_EQ(f.frame, press.frame + 3);
                }
                if (row.id == "warp15to120") {
                    EXPECT_EQ(f.frame, press.frame);
                }
            }
            EXPECT_NEAR(static_cast<double>(lo) * frameMs, row.viewMinMs, 0.05);
            EXPECT_NEAR(static_cast<double>(hi) * frameMs, row.viewMaxMs, 0.05);
        }
    }
    EXPECT_EQ(checked, 9 + 7) << "every row at 120 Hz, and the seven the click game runs at 60 Hz";
}

// What a lag or conventional frame shows is the world of the frame it was rendered at; a
// bireproj B-frame lies on the straight line between its two I-frames.
TEST(ClickGame, DisplayedSpheresAreTheWorldAtTheDepictedInstant) {
    for (const auto& condition : quick().conditions) {
        auto p = quick();
        p.conditions = {condition};
        p.rounds = {{"only", true, 1, ""}};  // no instructions screen
        ClickGame game(p, 8, kDisplay);
        startFirstMatch(game);
        std::map<std::int64_t, std::vector<physics::Sphere>> world;  // by session frame
        int compared = 0;
        for (int i = 0; i < 90; ++i) {
            const ShownFrame shown = game.step({});
            world[shown.frame] = game.world()->spheres();
            const std::int64_t depicted = std::llround(shown.scene.time * p.refreshHz);
            if (!world.count(depicted) || shown.schedule.made == condition::FrameKind::Interpolated) {
                if (shown.schedule.made != condition::FrameKind::Interpolated) continue;
                // Interpolated: every shown sphere lies between its two I-frame positions.
                if (!world.count(shown.sourceFrame) || !world.count(shown.nextSourceFrame)) continue;
                const auto& a = world.at(shown.sourceFrame);
                const auto& b = world.at(shown.nextSourceFrame);
                for (const auto& o : shown.scene.objects) {
                    const std::uint32_t id = o.id - scene::kIdFirstSphere;
                    const auto pa = std::find_if(a.begin(), a.end(), [&](auto& s) { return s.id == id; });
                    const auto pb = std::find_if(b.begin(), b.end(), [&](auto& s) { return s.id == id; });
                    if (pa == a.end() || pb == b.end()) continue;
                    const double w =
                        double(depicted - shown.sourceFrame) / double(shown.nextSourceFrame - shown.sourceFrame);
                    const glm::dvec3 expected = pa->position + (pb->position - pa->position) * w;
                    EXPECT_LT(glm::length(glm::dvec3(o.position) - expected), 1e-5) << condition;
                    ++compared;
                }
                continue;
            }
            const auto& truth = world.at(depicted);
            ASSERT_EQ(shown.scene.objects.size(), truth.size()) << condition << " frame " << shown.frame;
            for (std::size_t j = 0; j < truth.size(); ++j) {
                // Positions cross to the renderer as float.
                EXPECT_LT(glm::length(glm::dvec3(shown.scene.objects[j].position) - truth[j].position), 1e-5)
                    << condition;
                ++compared;
            }
        }
        EXPECT_GT(compared, 100) << condition;
    }
}

// Moves the cursor onto a moving green sphere (where it will be after this frame's physics)
// and clicks, in one frame. Resting spheres are skipped: lag cannot matter for them.
FrameInput clickOnGreen(const ClickGame& game, const protocol::ClickProtocol& p) {
    const ScreenMapping screen(game.camera(), kDisplay);
    for (const auto& s : game.world()->spheres()) {
        if (!s.green || glm::length(s.velocity) < 2.0) continue;
        const auto at = screen.project(s.position + s.velocity / p.refreshHz);
        if (!at || at->x < 50 || at->y < 50 || at->x > kDisplay.width - 50 || at->y > kDisplay.height - 50) continue;
        const glm::dvec2 move = (*at - game.cursor()) / p.cursorPixelsPerCount;
        return {move.x, move.y, kButtonLeft, 0};
    }
    return {};
}

struct ClickTally {
    std::map<std::string, int> world, displayed, scored;
    int removedAfterGreen = 0, greens = 0;
};

ClickTally aimAtTheWorld(const std::string& condition, protocol::Scoring scoring) {
    auto p = quick();
    p.conditions = {condition};
    p.rounds = {{"only", true, 1, ""}};  // no instructions screen
    p.matchS = 20;
    p.scoring = scoring;
    ClickGame game(p, 4, kDisplay);
    startFirstMatch(game);
    ClickTally tally;
    for (int i = 0; i < 1100 && game.world() != nullptr; ++i) {
        const FrameInput in = i % 6 == 5 ? clickOnGreen(game, p) : FrameInput{};
        game.step(in);
        for (const auto& e : game.takeEvents()) {
            if (e.type != "click") continue;
            ++tally.world[e.worldOutcome];
            ++tally.displayed[e.displayedOutcome];
            const std::string scored = detail(e)["scored"];
            ++tally.scored[scored];
            if (scored == "green") {
                ++tally.greens;
                const std::int64_t id =
                    detail(e)[scoring == protocol::Scoring::World ? "world_sphere" : "displayed_sphere"];
                const auto& now = game.world()->spheres();
                tally.removedAfterGreen += std::none_of(now.begin(), now.end(), [&](auto& s) { return s.id == id; });
            }
        }
    }
    return tally;
}

TEST(ClickGame, ClicksAreJudgedAgainstTheWorldAndAgainstTheFrameOnScreen) {
    // At 60 fps the frame on screen is the world of this very frame: both agree on nearly every click.
    ClickTally now = aimAtTheWorld("conv60", protocol::Scoring::World);

    EXPECT_GT(now.world.at("green"), 20);
    EXPECT_GE(now.world.at("green"), now.displayed["green"]);
    EXPECT_LE(now.world["miss"] + now.world["red"], now.world.at("green") / 10);
    EXPECT_EQ(now.removedAfterGreen, now.greens) << "a clicked sphere vanishes";
    // 200 ms late, the spheres on screen are elsewhere: aiming at the world hits far less on screen.
    ClickTally late = aimAtTheWorld("lag200", protocol::Scoring::World);
    EXPECT_GT(late.world.at("green"), 20);
    EXPECT_LT(late.displayed["green"], late.world.at("green") / 2);
    // Scored as displayed, the same clicks mostly miss.
    ClickTally judgedOnScreen = aimAtTheWorld("lag200", protocol::Scoring::Displayed);
    EXPECT_LT(judgedOnScreen.scored["green"], judgedOnScreen.world.at("green") / 2);
    EXPECT_EQ(judgedOnScreen.removedAfterGreen, judgedOnScreen.greens);
}

// Under lag the image of a clicked sphere lingers; a second click on it is a miss. With lag200
// (12 frames at 60 Hz) and displayed scoring, the cursor is put where a green sphere is now, so
// that 12 frames later the screen shows cursor and sphere together: the first click there
// scores green and takes the sphere; the same image two frames on is a ghost.
TEST(ClickGame, AGhostOfAClickedSphereCannotBeScoredTwice) {
    auto p = quick();
    p.conditions = {"lag200"};
    p.rounds = {{"only", true, 1, ""}};  // no instructions screen
    p.scoring = protocol::Scoring::Displayed;
    p.matchS = 20;
    ClickGame game(p, 4, kDisplay);
    startFirstMatch(game);
    for (int i = 0; i < 40; ++i) game.step({});
    const ScreenMapping screen(game.camera(), kDisplay);
    std::optional<glm::dvec2> target;
    for (const auto& s : game.world()->spheres()) {
        const auto at = screen.project(s.position);
        if (s.green && at && at->x > 50 && at->y > 50 && at->x < kDisplay.width - 50 && at->y < kDisplay.height - 50) {
            target = *at;
            break;
        }
    }
    ASSERT_TRUE(target.has_value()) << "no green sphere in view";
    const glm::dvec2 move = (*target - game.cursor()) / p.cursorPixelsPerCount;
    game.step({move.x, move.y, 0, 0});  // frame F: the cursor on the sphere as the world has it one frame on
    for (int i = 0; i < 11; ++i) game.step({});
    game.takeEvents();
    std::vector<std::string> scored, displayed;
    for (const FrameInput& in : {FrameInput{0, 0, kButtonLeft, 0}, FrameInput{}, FrameInput{0, 0, kButtonLeft, 0}}) {
        game.step(in);
        for (const auto& e : game.takeEvents())
            if (e.type == "click") scored.push_back(detail(e)["scored"]), displayed.push_back(e.displayedOutcome);
    }
    // Both clicks land on the green sphere's image; only the first takes it.
    EXPECT_EQ(displayed, (std::vector<std::string>{"green", "green"}));
    EXPECT_EQ(scored, (std::vector<std::string>{"green", "miss"}));
}

// Steps through the time a new statement ignores presses (the frame that showed it was one).
void waitOutSettle(ClickGame& game, const protocol::ClickProtocol& p) {
    for (long i = 1; i < std::lround(kAnswerSettleS * p.refreshHz); ++i) game.step({});
}

std::vector<int> ratingValues(ClickGame& game) {
    std::vector<int> values;
    for (const auto& e : game.takeEvents())
        if (e.type == "rating") values.push_back(detail(e)["value"]);
    return values;
}

// A one-match protocol whose match is over in half a second: its rating screen comes quickly.
protocol::ClickProtocol oneShortMatch() {
    auto p = quick();
    p.conditions = {"conv60"};
    p.rounds = {{"only", true, 1, ""}};  // no instructions screen
    p.matchS = 0.5;
    return p;
}

TEST(ClickGame, ADoubleClickOnARatingBoxAnswersOneStatement) {
    const auto p = oneShortMatch();
    ClickGame game(p, 1, kDisplay);
    ShownFrame shown = startFirstMatch(game);
    while (!shown.question) shown = game.step({});
    waitOutSettle(game, p);
    const glm::dvec4 box = shown.question->boxes[4];
    const glm::dvec2 move = glm::dvec2(box.x + box.z / 2, box.y + box.w / 2) - game.cursor();
    game.step({move.x, move.y, 0, 0});
    game.takeEvents();
    // Press, release, press again 100 ms (6 frames at 60 Hz) later, release: one double click.
    game.step({0, 0, kButtonLeft, 0});
    for (int i = 0; i < 5; ++i) game.step({});
    shown = game.step({0, 0, kButtonLeft, 0});
    shown = game.step({});
    EXPECT_EQ(ratingValues(game), std::vector<int>{5});
    EXPECT_EQ(shown.question->index, 1);  // the second statement waits for its own answer
    // The same goes for a double tap on a digit key; a press after the settle time answers.
    waitOutSettle(game, p);
    game.step({0, 0, 0, digitKey(2)});
    game.step({});
    game.step({0, 0, 0, digitKey(2)});
    shown = game.step({});
    EXPECT_EQ(ratingValues(game), std::vector<int>{2});
    EXPECT_EQ(shown.question->index, 2);
}

TEST(ClickGame, APressHeldFromTheMatchOrPastTheSettleTimeAnswersNothing) {
    const auto p = oneShortMatch();
    ClickGame game(p, 1, kDisplay);
    ShownFrame shown = startFirstMatch(game);
    while (!shown.question) shown = game.step({0, 0, 0, digitKey(4)});  // held down into the screen
    for (int i = 0; i < 2 * std::lround(kAnswerSettleS * p.refreshHz); ++i) game.step({0, 0, 0, digitKey(4)});
    EXPECT_TRUE(ratingValues(game).empty());
    game.step({});  // released: the next press answers
    game.step({0, 0, 0, digitKey(4)});
    EXPECT_EQ(ratingValues(game), std::vector<int>{4});
}

// Each round opens with its instructions: on screen until Enter, then its first match; an
// event says when the participant went on.
TEST(ClickGame, EachRoundOpensWithItsInstructionsUntilEnter) {
    auto p = oneShortMatch();
    p.questions.clear();
    p.rounds = {{"a", false, 1, "Read A"}, {"b", true, 1, "Read B"}};
    ClickGame game(p, 1, kDisplay);
    ShownFrame shown = game.step({0, 0, 0, kKeyEnter});  // the supervisor's ready screen
    EXPECT_TRUE(shown.instructions.empty());
    for (int i = 0; i < 30; ++i) {
        shown = game.step({});
        EXPECT_EQ(shown.instructions, "Read A");
        EXPECT_TRUE(shown.promptsEnter);
        EXPECT_TRUE(shown.blank);
    }
    game.takeEvents();
    game.step({0, 0, 0, kKeyEnter});
    auto events = game.takeEvents();
    ASSERT_GE(events.size(), 1u);
    EXPECT_EQ(events[0].type, "instructions");
    EXPECT_EQ(events[0].phase, "a");
    EXPECT_EQ(detail(events[0])["read_s"].get<double>(), 31.0 / p.refreshHz);
    shown = game.step({});
    EXPECT_FALSE(shown.blank);
    EXPECT_EQ(shown.condition.name, "conv60");
    while (!shown.blank) shown = game.step({});
    EXPECT_EQ(shown.instructions, "Read B");  // the next round opens with its own
    shown = game.step({0, 0, 0, kKeyEnter});
    shown = game.step({});
    EXPECT_FALSE(shown.blank);
    // A round without instructions starts its first match straight away.
    p.rounds = {{"a", true, 1, ""}};
    ClickGame plain(p, 1, kDisplay);
    plain.step({0, 0, 0, kKeyEnter});
    EXPECT_FALSE(plain.step({}).blank);
}

TEST(ClickGame, TheBotReadsTheInstructionsAndPlaysOn) {
    auto p = quick();
    for (auto& round : p.rounds) round.instructions = protocol::kClickTaskInstructions;
    const Played played = playWithBot(p, 3, 7);
    int instructions = 0, matches = 0;
    for (const auto& e : played.events) {
        instructions += e.type == "instructions";
        matches += e.type == "match";
    }
    EXPECT_EQ(instructions, static_cast<int>(p.rounds.size()));
    EXPECT_EQ(matches, 2 * static_cast<int>(p.conditions.size()));
    ClickGame replay(p, 3, kDisplay);
    std::vector<session::EventRecord> again;
    for (const auto& in : played.inputs) {
        replay.step(in);
        for (auto& e : replay.takeEvents()) again.push_back(e);
    }
    ASSERT_EQ(again.size(), played.events.size());
    for (std::size_t i = 0; i < again.size(); ++i) EXPECT_EQ(session::firstDifference(again[i], played.events[i]), "");
}

TEST(ClickGame, RatingsAreAnsweredByKeyOrByClickingABox) {
    const auto p = oneShortMatch();
    ClickGame game(p, 1, kDisplay);
    ShownFrame shown = startFirstMatch(game);
    while (!shown.question) shown = game.step({});
    EXPECT_EQ(shown.question->boxes.size(), 7u);
    waitOutSettle(game, p);
    game.step({0, 0, 0, digitKey(9)});  // out of range: ignored
    game.step({-5000, -5000, 0, 0});  // the top left corner, far from the boxes
    game.step({0, 0, kButtonLeft, 0});  // not on a box: ignored
    game.step({});
    shown = game.step({0, 0, 0, digitKey(3)});
    EXPECT_EQ(shown.question->index, 0);  // this frame still shows the first statement
    shown = game.step({});
    EXPECT_EQ(shown.question->index, 1);
    waitOutSettle(game, p);
    // Click box 6 (value 6).
    const glm::dvec4 box = shown.question->boxes[5];
    const glm::dvec2 move = glm::dvec2(box.x + box.z / 2, box.y + box.w / 2) - game.cursor();
    shown = game.step({move.x, move.y, 0, 0});
    EXPECT_EQ(shown.question->highlighted, 5);
    game.step({0, 0, kButtonLeft, 0});
    std::vector<int> values;
    std::vector<std::string> how;
    for (const auto& e : game.takeEvents())
        if (e.type == "rating") values.push_back(detail(e)["value"]), how.push_back(detail(e)["answered_with"]);
    EXPECT_EQ(values, (std::vector<int>{3, 6}));
    EXPECT_EQ(how, (std::vector<std::string>{"key", "mouse"}));
}

TEST(ClickBot, RatesEachConditionByItsSchedulesLatencyAsTheFormerFormulaDid) {
    // The formula the bot used before it asked the schedule, the oracle: the ratings, whole
    // numbers, must not move for any preset, statement or scale on the click game's 60 Hz.
    struct Former {
        double renderRateHz, lagMs, shownRate;
        bool bidirectional;
    };
    const std::map<std::string, Former> former = {
        {"conv15", {15, 0, 15, false}},    {"conv30", {30, 0, 30, false}},       {"conv60", {60, 0, 60, false}},
        {"conv120", {120, 0, 120, false}}, {"lag50", {60, 50, 60, false}},       {"lag100", {60, 100, 60, false}},
        {"lag200", {60, 200, 60, false}},  {"warp15to120", {15, 0, 120, false}}, {"bireproj15to60", {15, 0, 60, true}},
    };
    auto rating = [](const Former& m, int statement, int min, int max) {
        double latencyMs = 500.0 / m.renderRateHz + m.lagMs;
        if (m.bidirectional) latencyMs += 1000.0 / m.renderRateHz;
        const int smooth = static_cast<int>(std::lround(1.0 + 6.0 * std::min(1.0, m.shownRate / 60.0)));
        const int responsive = std::clamp(static_cast<int>(std::lround(7.0 - latencyMs / 25.0)), 1, 7);
        const int enjoyed = static_cast<int>(std::lround((smooth + responsive) / 2.0));
        const int values[4] = {enjoyed, 8 - enjoyed, responsive, smooth};
        return std::clamp(values[statement % 4], min, max);
    };
    for (const char* condition : {"conv15", "conv30", "conv60", "lag50", "lag100", "lag200", "bireproj15to60"})
        for (int statement = 0; statement < 8; ++statement)
            for (const auto& [min, max] : {std::pair{1, 7}, std::pair{1, 5}, std::pair{0, 10}, std::pair{3, 4}})
                EXPECT_EQ(botRating(condition::preset(condition), 60.0, statement, min, max),
                          rating(former.at(condition), statement, min, max))
                    << condition << " statement " << statement << " on " << min << ".." << max;
}

}  // namespace
}  // namespace warplab::game
