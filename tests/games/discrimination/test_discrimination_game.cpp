// The discrimination task as a pure function of protocol, seed and input: what a trial shows,
// interval by interval; the bot's observer recovered by QUEST+; sessions that run, replay and
// export through the same runner as every game; and a session cut mid-procedure and resumed
// choosing the levels the uninterrupted one chose.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "discrimination/discrimination_protocol.h"
#include "discrimination/discrimination_study.h"
#include "discrimination_bot.h"
#include "discrimination_game.h"
#include "discrimination_results.h"
#include "export/export.h"
#include "runner/session_runner.h"
#include "session/records.h"
#include "session/session_store.h"
#include "support/cut_session.h"

namespace warplab::discrimination {
namespace {

namespace fs = std::filesystem;
const game::DisplaySize kDisplay{320, 180};

std::string protocolPath(const std::string& name) {
    return std::string(WARPLAB_SOURCE_DIR) + "/protocol/" + name + ".json";
}

DiscriminationProtocol load(const std::string& name) {
    std::ifstream in(protocolPath(name));
    std::stringstream text;
    text << in.rdbuf();
    return parseDiscriminationProtocol(text.str(), name);
}

nlohmann::json detail(const session::EventRecord& e) { return nlohmann::json::parse(e.detailJson); }

struct Played {
    std::vector<game::ShownFrame> frames;
    std::vector<session::EventRecord> events;
};

Played playWithBot(const DiscriminationProtocol& p, std::uint64_t seed, BotSettings settings = {},
                   bool keepFrames = false) {
    DiscriminationGame game(p, seed, kDisplay);
    DiscriminationBot bot(seed + 100, p, settings);
    Played out;
    game::FrameInput input = bot.first();
    for (int i = 0; i < 2000000 && !game.finished(); ++i) {
        const game::ShownFrame shown = game.step(input);
        for (auto& e : game.takeEvents()) out.events.push_back(e);
        if (keepFrames) out.frames.push_back(shown);
        input = bot.next(shown);
    }
    return out;
}

std::vector<session::EventRecord> judgements(const std::vector<session::EventRecord>& events) {
    std::vector<session::EventRecord> out;
    std::copy_if(events.begin(), events.end(), std::back_inserter(out),
                 [](const session::EventRecord& e) { return e.type == "judgement"; });
    return out;
}

// Each trial: interval 1, a blank, interval 2, the question; one interval the reference, the
// other its test condition, of the judgement's level; both start from the resting view with the
// target on the same path.
TEST(DiscriminationGame, ATrialIsTwoIntervalsABlankAndTheQuestion) {
    const DiscriminationProtocol p = load("latency-jnd-quick");
    const Played played = playWithBot(p, 7, {}, true);
    const auto answered = judgements(played.events);
    ASSERT_EQ(answered.size(), 16u) << "8 trials of each of two procedures";
    const auto intervalFrames = static_cast<std::size_t>(std::llround(p.intervalS * p.refreshHz));
    std::size_t i = 0, trial = 0;
    while (trial < answered.size()) {
        while (played.frames[i].phaseText != intervalText(1)) ++i;
        const nlohmann::json d = detail(answered[trial]);
        const std::string test = d["test_condition"];
        std::string shownIn[2];
        glm::vec3 firstTarget[2];
        for (int interval : {1, 2}) {
            while (played.frames[i].phaseText != intervalText(interval)) {
                ASSERT_TRUE(played.frames[i].blank) << "only a blank lies between the intervals";
                ++i;
            }
            shownIn[interval - 1] = played.frames[i].condition.name;
            EXPECT_EQ(played.frames[i].camera.yaw, 0.0f) << "each interval starts from the resting view";
            ASSERT_FALSE(played.frames[i].scene.objects.empty()) << "a lagged interval shows the target at once";
            ASSERT_TRUE(played.frames[i].rendersNow);
            firstTarget[interval - 1] = played.frames[i].render.scene.objects.at(0).position;
            for (std::size_t k = 0; k < intervalFrames; ++k, ++i)
                ASSERT_EQ(played.frames[i].phaseText, intervalText(interval)) << "trial " << trial;
        }
        ASSERT_TRUE(played.frames[i].question.has_value()) << "the question follows interval 2";
        const int testInterval = d["test_interval"];
        EXPECT_EQ(shownIn[testInterval - 1], test);
        EXPECT_EQ(shownIn[2 - testInterval], answered[trial].condition) << "the other interval is the reference";
        EXPECT_EQ(test, answered[trial].condition + "@lag_frames=" + std::to_string(d["level"].get<int>()));
        EXPECT_EQ(firstTarget[0], firstTarget[1]) << "the same path in both intervals, rendered from its start";
        EXPECT_EQ(d["correct"].get<bool>(), d["answer"].get<int>() != testInterval);
        ++trial;
    }
    EXPECT_EQ(played.events.back().type, "done");
}

// Which interval is the test's is drawn, about half each; and the same seed draws the same.
TEST(DiscriminationGame, TheTestIntervalIsDrawnFromTheSeed) {
    const DiscriminationProtocol p = load("latency-jnd-quick");
    int first = 0, all = 0;
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        const auto a = judgements(playWithBot(p, seed).events);
        const auto b = judgements(playWithBot(p, seed).events);
        ASSERT_EQ(a.size(), b.size());
        for (std::size_t i = 0; i < a.size(); ++i) {
            EXPECT_EQ(session::firstDifference(a[i], b[i]), "");
            first += detail(a[i])["test_interval"].get<int>() == 1;
            ++all;
        }
    }
    EXPECT_GT(first, all / 4);
    EXPECT_LT(first, all * 3 / 4);
}

// The bot's observer has a known function; QUEST+'s 95 % interval of the stimulus at 75 %
// correct covers its true value in most seeded sessions.
TEST(DiscriminationGame, QuestPlusRecoversTheBotsObserver) {
    DiscriminationProtocol p = load("latency-jnd-quick");
    p.procedures.resize(1);
    p.procedures[0].maxTrials = 40;
    p.intervalS = 0.2;  // the observer judges from the conditions, not from looking
    p.blankS = 0.0;
    const BotSettings settings;
    const Observer& o = settings.observer;
    const double truth = o.function.stimulusAt(75, o.thresholds.at(condition::Dimension::LagFrames), o.slope, o.lapse);
    int covered = 0;
    const int runs = 20;
    for (int run = 0; run < runs; ++run) {
        const Played played = playWithBot(p, 1000 + static_cast<std::uint64_t>(run), settings);
        const auto rows = resultTables(p, played.events)[1].rows;
        ASSERT_EQ(rows.size(), 1u);
        const std::vector<std::string>& cells = rows[0].cells.written();
        const double low = std::stod(cells.at(13)), high = std::stod(cells.at(14));
        covered += low <= truth && truth <= high;
    }
    EXPECT_GE(covered, 16) << "of " << runs << "; the true 75 % point is " << truth;
}

// thresholds.csv's QUEST+ threshold: the posterior's mean and quantiles of the stimulus at the
// stated percent correct, here summed out over the grid by hand.
TEST(DiscriminationResults, TheThresholdIsThePosteriorOfTheStimulusAtThePercentCorrect) {
    adaptive::QuestPlusSettings s;
    s.function = {adaptive::Shape::Logistic, adaptive::Scale::Linear, 0.5};
    s.stimuli = {1, 2, 3, 4};
    s.thresholds = {1, 2, 3};
    s.slopes = {1, 3};
    s.lapses = {0.0, 0.05};
    adaptive::QuestPlus quest(s);
    for (const auto& [level, correct] : std::vector<std::pair<std::size_t, bool>>{{3, true}, {1, false}, {2, true}})
        quest.update(level, correct);
    double mean = 0.0;
    std::vector<std::pair<double, double>> points;
    std::size_t i = 0;
    for (double t : s.thresholds)
        for (double b : s.slopes)
            for (double l : s.lapses) {
                // Logistic: 0.8 = 0.5 + (0.5 - l) / (1 + exp(-b (x - t))), solved for x.
                const double x = t - std::log((0.5 - l) / (0.8 - 0.5) - 1.0) / b;
                mean += x * quest.posterior()[i];
                points.emplace_back(x, quest.posterior()[i++]);
            }
    std::sort(points.begin(), points.end());
    double cumulative = 0.0, low = NAN, high = NAN;
    for (const auto& [x, w] : points) {
        cumulative += w;
        if (std::isnan(low) && cumulative >= 0.025) low = x;
        if (std::isnan(high) && cumulative >= 0.975) high = x;
    }
    const adaptive::Estimate e = thresholdAt(quest, 80);
    EXPECT_NEAR(e.mean, mean, 1e-12);
    EXPECT_NEAR(e.low, low, 1e-12);
    EXPECT_NEAR(e.high, high, 1e-12);
    EXPECT_LT(e.low, e.high);
}

fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::path(testing::TempDir()) / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// Through the runner: a bot session records, replays every judgement, and exports both tables.
TEST(DiscriminationSession, RunsReplaysAndExports) {
    const fs::path dir = freshDir("warplab-discrimination-session");
    fs::create_directories(dir / "results");
    runner::HeadlessRun run;
    run.protocolPath = protocolPath("latency-jnd-quick");
    run.participant = "P1";
    run.resultsDir = (dir / "results").string();
    run.player = "bot";
    run.displayWidth = kDisplay.width;
    run.displayHeight = kDisplay.height;
    std::ostringstream progress;
    const std::string path = runner::runHeadless(run, progress);
    const runner::ReplayResult replay = runner::replaySession(path);
    EXPECT_TRUE(replay.completed);
    EXPECT_EQ(replay.outcomes, 16u);
    EXPECT_EQ(replay.reproduced, 16u) << replay.difference;

    std::ostringstream log;
    exporter::exportResults((dir / "results").string(), (dir / "export").string(), {}, log);
    auto lines = [&](const char* file) {
        std::ifstream in(dir / "export" / file);
        std::vector<std::string> out;
        for (std::string line; std::getline(in, line);) out.push_back(line);
        return out;
    };
    const auto trials = lines("discrimination_trials.csv");
    ASSERT_EQ(trials.size(), 17u);
    EXPECT_EQ(trials[0].rfind("participant,session,procedure,trial,procedure_trial,method,dimension,", 0), 0u);
    const auto thresholds = lines("thresholds.csv");
    ASSERT_EQ(thresholds.size(), 3u) << "one row per procedure";
    EXPECT_NE(thresholds[1].find(",lag,quest_plus,lag_frames,conv120,display frames,8,1,"), std::string::npos)
        << thresholds[1];
}

// A session killed mid-procedure and resumed plays on as the uninterrupted one: the same
// procedures at the same levels, every event the same.
TEST(DiscriminationSession, AResumedSessionChoosesTheLevelsTheUninterruptedOneChose) {
    const fs::path dir = freshDir("warplab-discrimination-resume");
    for (const char* folder : {"whole", "cut", "resumed"}) fs::create_directories(dir / folder);
    runner::HeadlessRun run;
    run.protocolPath = protocolPath("latency-jnd-quick");
    run.participant = "P1";
    run.resultsDir = (dir / "whole").string();
    run.player = "bot";
    run.seed = 11;
    run.displayWidth = kDisplay.width;
    run.displayHeight = kDisplay.height;
    std::ostringstream progress;
    const session::SessionData whole = session::readSession(runner::runHeadless(run, progress));
    ASSERT_TRUE(whole.completed);

    // Cut after the fifth judgement, as a kill just after its commit leaves it.
    std::size_t kept = 0;
    for (int answered = 0; kept < whole.events.size() && answered < 5; ++kept)
        answered += whole.events[kept].type == "judgement";
    const std::string cut = testing_sessions::cutSession(whole, kept, (dir / "cut").string());
    runner::HeadlessRun resume = run;
    resume.resumeFrom = cut;
    resume.resultsDir = (dir / "resumed").string();
    const session::SessionData resumed = session::readSession(runner::runHeadless(resume, progress));
    EXPECT_TRUE(resumed.completed);
    ASSERT_EQ(resumed.header.resumed.size(), 1u);
    const auto a = judgements(whole.events), b = judgements(resumed.events);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(detail(a[i])["procedure"], detail(b[i])["procedure"]) << "trial " << i;
        EXPECT_EQ(detail(a[i])["level"], detail(b[i])["level"]) << "trial " << i;
        EXPECT_EQ(session::firstDifference(a[i], b[i]), "") << "trial " << i;
    }
}

}  // namespace
}  // namespace warplab::discrimination

namespace warplab::discrimination {
namespace {

// A study plan takes the task: its references as the list, never blocked, since the session
// seed interleaves the procedures' trials; the participant's copy is the file as it is.
TEST(DiscriminationStudy, AStudyPlanTakesItWithoutAnOrderToBalance) {
    std::ifstream in(protocolPath("latency-jnd-quick"));
    std::stringstream text;
    text << in.rdbuf();
    const auto study = parseDiscriminationStudy(text.str(), "latency-jnd-quick.json");
    const auto list = study->counterbalanced();
    ASSERT_TRUE(list.has_value());
    EXPECT_EQ(list->conditions, (std::vector<std::string>{"conv120", "latewarp120"}));
    EXPECT_FALSE(list->blocked);
    EXPECT_EQ(study->withConditionOrder(text.str(), {"latewarp120", "conv120"}), text.str());
    EXPECT_EQ(study->progress({}).planned, 16u);
}

}  // namespace
}  // namespace warplab::discrimination
