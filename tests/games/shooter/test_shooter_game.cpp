// The shooter study as a pure function of protocol, seed and input: a bot plays the quick
// protocol to the end, replays reproduce it, and every condition's measured latency -- a mouse step
// and a bounce of the target, found in the displayed frames -- is what its schedule says.
#include <cmath>
#include <cstdio>
#include <map>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "shooter_bot.h"
#include "shooter_game.h"
#include "game/registry.h"
#include "session/records.h"
#include "shooter/shooter_protocol.h"
#include "scene/camera.h"

namespace warplab::game {
namespace {

protocol::ShooterProtocol quick() {
    return protocol::loadShooterProtocol(std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json");
}

struct Played {
    std::vector<FrameInput> inputs;
    std::vector<session::EventRecord> events;
    int frames = 0;
};

Played playWithBot(const protocol::ShooterProtocol& p, std::uint64_t seed, std::uint64_t botSeed) {
    ShooterGame game(p, seed, DisplaySize{});
    ShooterBot bot(botSeed, p);
    Played out;
    FrameInput input;
    while (!game.finished() && out.frames < 200000) {
        out.inputs.push_back(input);
        const ShownFrame shown = game.step(input);
        for (auto& e : game.takeEvents()) out.events.push_back(e);
        input = bot.next(shown);
        ++out.frames;
    }
    return out;
}

// "" when both runs logged the same events bit for bit, else the first difference.
std::string eventDifference(const std::vector<session::EventRecord>& a, const std::vector<session::EventRecord>& b) {
    if (a.size() != b.size()) return std::to_string(a.size()) + " events against " + std::to_string(b.size());
    for (std::size_t i = 0; i < a.size(); ++i)
        if (const std::string d = session::firstDifference(a[i], b[i]); !d.empty())
            return "event " + std::to_string(i) + ": " + d;
    return "";
}

double detailNumber(const session::EventRecord& e, const char* key) {
    return nlohmann::json::parse(e.detailJson).at(key).get<double>();
}

TEST(ShooterGame, BotPlaysTheQuickProtocolToTheEnd) {
    const auto p = quick();
    const Played played = playWithBot(p, 3, 5);
    ASSERT_LT(played.frames, 200000) << "never finished";
    int testOutcomes = 0, hits = 0, misses = 0;
    std::vector<std::string> phases;
    for (const auto& e : played.events) {
        if (e.type == "phase") phases.push_back(e.phase);
        if (e.phase == "test" && (e.type == "shot" || e.type == "timeout")) {
            ++testOutcomes;
            hits += e.displayedOutcome == "hit";
            misses += e.displayedOutcome != "hit";
            EXPECT_NEAR(detailNumber(e, "aim_time"), e.eventTime - detailNumber(e, "spawn_time"), 1e-12);
            EXPECT_LE(detailNumber(e, "aim_time"), p.timeoutS + 1e-9);
        }
    }
    EXPECT_EQ(testOutcomes, static_cast<int>(p.conditions.size()) * p.targetsPerCondition);
    EXPECT_GT(hits, 0) << "the bot should hit some targets";
    // How far it got, as study status says it: every test trial of those planned, and of a
    // session cut before its last trial, one fewer.
    const auto study = loadStudy(std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json");
    const Progress whole = study->progress(played.events);
    EXPECT_EQ(whole.unit, "test trials");
    EXPECT_EQ(whole.planned, p.conditions.size() * static_cast<std::size_t>(p.targetsPerCondition));
    EXPECT_EQ(whole.done, whole.planned);
    auto cut = played.events;
    while (cut.back().type != "shot" && cut.back().type != "timeout") cut.pop_back();
    cut.pop_back();
    EXPECT_EQ(study->progress(cut).done, whole.planned - 1);
    EXPECT_EQ(phases.front(), "acclimation");
    EXPECT_EQ(phases.back(), "done");
    EXPECT_NE(std::find(phases.begin(), phases.end(), "training"), phases.end());
    EXPECT_NE(std::find(phases.begin(), phases.end(), "test"), phases.end());
}

TEST(ShooterGame, SameSeedAndInputSameEventsBitForBit) {
    const auto p = quick();
    const Played a = playWithBot(p, 11, 2);
    // Replaying the recorded input into a fresh game gives the same events.
    ShooterGame game(p, 11, DisplaySize{});
    std::vector<session::EventRecord> replayed;
    for (const auto& in : a.inputs) {
        game.step(in);
        for (auto& e : game.takeEvents()) replayed.push_back(e);
    }
    EXPECT_EQ(eventDifference(a.events, replayed), "");
    // Another session seed spawns other targets: the outcomes differ.
    const Played b = playWithBot(p, 12, 2);
    EXPECT_NE(eventDifference(a.events, b.events), "");
}

// The pause after a shot shows the scored outcome: HIT in green, MISS and TIMEOUT in red.
TEST(ShooterGame, BannerNamesTheScoredOutcomeInItsColour) {
    const auto p = quick();
    ShooterGame game(p, 3, DisplaySize{});
    ShooterBot bot(5, p);
    FrameInput input;
    std::map<std::string, int> seen;
    while (!game.finished()) {
        const ShownFrame shown = game.step(input);
        if (!shown.banner.empty()) {
            ++seen[shown.banner];
            EXPECT_TRUE(shown.frozen);
            EXPECT_EQ(shown.bannerGood, shown.banner == "HIT") << shown.banner;
        }
        input = bot.next(shown);
    }
    EXPECT_GT(seen["HIT"], 0);
    EXPECT_GT(seen["MISS"] + seen["TIMEOUT"], 0);
}

// The participant sees where they are: the trial up and the count of its phase (the test) or
// of its level (training), numbered as the events number the trials.
TEST(ShooterGame, PhaseTextCountsTheTrialsOfThePhase) {
    const auto p = quick();
    ShooterGame game(p, 3, DisplaySize{});
    ShooterBot bot(5, p);
    FrameInput input;
    std::vector<int> testTrials;
    int trainingTrials = 0, trainingInLevel = 0;
    while (!game.finished()) {
        const ShownFrame shown = game.step(input);
        for (const auto& e : game.takeEvents()) {
            if (e.type != "shot" && e.type != "timeout") continue;
            int trial = 0, of = 0, level = 0;
            if (e.phase == "test") {
                ASSERT_EQ(std::sscanf(shown.phaseText.c_str(), "Test: trial %d of %d", &trial, &of), 2)
                    << shown.phaseText;
                EXPECT_EQ(of, static_cast<int>(p.conditions.size()) * p.targetsPerCondition);
                EXPECT_EQ(trial, e.trial + 1);
                testTrials.push_back(trial);
            } else if (e.phase == "training") {
                ASSERT_EQ(
                    std::sscanf(shown.phaseText.c_str(), "Training: level %d, trial %d of %d", &level, &trial, &of), 3)
                    << shown.phaseText;
                EXPECT_EQ(level, static_cast<int>(detailNumber(e, "difficulty")));
                trainingInLevel = trial == 1 ? 1 : trainingInLevel + 1;
                EXPECT_EQ(trial, trainingInLevel);
                EXPECT_TRUE(of == 2 * p.training.shotsPerLevelEasy || of == 2 * p.training.shotsPerLevelHard) << of;
                EXPECT_LE(trial, of);
                ++trainingTrials;
            }
        }
        input = bot.next(shown);
    }
    ASSERT_EQ(testTrials.size(), p.conditions.size() * static_cast<std::size_t>(p.targetsPerCondition));
    for (std::size_t i = 0; i < testTrials.size(); ++i) EXPECT_EQ(testTrials[i], static_cast<int>(i) + 1);
    EXPECT_GT(trainingTrials, 0);
}

// Each phase opens with its instructions until Enter; the phase's time runs from that Enter.
TEST(ShooterGame, EachPhaseOpensWithItsInstructionsUntilEnter) {
    auto p = quick();
    p.acclimationInstructions = "Read A";
    p.trainingInstructions = "Read T";
    p.testInstructions = "Read X";
    ShooterGame game(p, 3, DisplaySize{});
    ShownFrame shown = game.step({});
    EXPECT_EQ(shown.instructions, "Read A");
    EXPECT_TRUE(shown.promptsEnter);
    EXPECT_TRUE(shown.blank);
    for (int i = 0; i < 100; ++i) EXPECT_EQ(game.step({}).instructions, "Read A");
    game.takeEvents();
    shown = game.step({0, 0, 0, kKeyEnter});  // frame 101: the acclimation begins
    EXPECT_FALSE(shown.blank);
    EXPECT_FALSE(shown.scene.objects.empty()) << "the first target is up at once";
    auto events = game.takeEvents();
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].type, "instructions");
    EXPECT_EQ(events[0].phase, "acclimation");
    EXPECT_EQ(detailNumber(events[0], "read_s"), 101.0 / p.refreshHz);
    // The bot goes on through every screen; the acclimation lasted its duration from the Enter.
    ShooterBot bot(5, p);
    FrameInput input = bot.next(shown);
    std::vector<std::string> read;
    std::int64_t trainingOpened = -1;
    while (!game.finished()) {
        shown = game.step(input);
        for (const auto& e : game.takeEvents()) {
            if (e.type == "instructions") read.push_back(e.phase);
            if (e.type == "phase" && e.phase == "training") trainingOpened = e.frame;
        }
        if (!shown.instructions.empty()) {
            EXPECT_TRUE(shown.scene.objects.empty());
        }
        input = bot.next(shown);
    }
    EXPECT_EQ(read, (std::vector<std::string>{"training", "test"}));
    EXPECT_GE(trainingOpened, 101 + std::llround(p.acclimationS * p.refreshHz));
}

TEST(ShooterGame, TestConditionsComeInTheProtocolsNumbers) {
    auto p = quick();
    p.targetsPerCondition = 6;
    const Played played = playWithBot(p, 21, 1);
    std::map<std::string, int> perCondition;
    for (const auto& e : played.events)
        if (e.phase == "test" && (e.type == "shot" || e.type == "timeout")) ++perCondition[e.condition];
    for (const auto& c : p.conditions) EXPECT_EQ(perCondition[c], 6) << c;
}

// Conditions a lab composes, beside the presets: Kim et al.'s late warps (from the shipped
// protocol) and a warp at its own fill rate with a rotation late warp on top.
std::vector<condition::Condition> composedConditions() {
    std::vector<condition::Condition> list =
        protocol::loadShooterProtocol(std::string(WARPLAB_SOURCE_DIR) + "/protocol/latewarp-kim-quick.json")
            .conditionTable.defined();
    condition::Condition warp;
    warp.name = "warp30to60-late";
    warp.renderHz = 30;
    warp.lagFrames = 4;
    warp.fill = "warp-full";
    warp.fillHz = 60;
    warp.lateWarp = condition::LateWarp::Rotation;
    list.push_back(warp);
    // Uneven renders (docs/frame-pacing.md): a rate the refresh does not divide, seeded jitter
    // and hitches, held, warped and interpolated; and uneven fills.
    condition::Condition uneven;
    uneven.name = "uneven50";
    uneven.renderHz = 50;
    list.push_back(uneven);
    condition::Condition jitter = uneven;
    jitter.name = "jitter50-warp";
    jitter.fill = "warp-full";
    jitter.jitter = {condition::JitterShape::Normal, 4, 0};
    list.push_back(jitter);
    condition::Condition hitch;
    hitch.name = "hitch30-bireproj";
    hitch.renderHz = 30;
    hitch.fill = "bireproj";
    hitch.hitches = {80, 0.25, 0};
    list.push_back(hitch);
    // Fills at a rate the refresh does not divide (50 Hz on 120: 2, 3, 2, 3, 2 refreshes).
    condition::Condition warpFill;
    warpFill.name = "warp15-fill50";
    warpFill.renderHz = 15;
    warpFill.fill = "warp-full";
    warpFill.fillHz = 50;
    list.push_back(warpFill);
    condition::Condition bireprojFill = warpFill;
    bireprojFill.name = "bireproj15-fill50";
    bireprojFill.fill = "bireproj";
    list.push_back(bireprojFill);
    return list;
}

// The schedule a game runs a condition on from session frame `start`: jittered and hitching
// cadences are drawn from the game's seed (5 in ConditionRig) and where the schedule starts.
condition::ConditionSchedule gameSchedule(const condition::Condition& c, double refreshHz, const ShownFrame& shown) {
    return condition::ConditionSchedule(c, refreshHz, pacingSeed(5, shown.frame - shown.schedule.index));
}

// Every condition the latency tests measure: the presets, then the composed ones.
std::vector<std::string> measuredConditions() {
    std::vector<std::string> names = condition::presetNames();
    for (const auto& c : composedConditions()) names.push_back(c.name);
    return names;
}

// A game whose test phase shows one condition, reached without clicking (training times out).
struct ConditionRig {
    protocol::ShooterProtocol p;
    std::unique_ptr<ShooterGame> game;
    ShownFrame last;
    explicit ConditionRig(const std::string& condition) {
        p = quick();
        p.conditionTable = condition::ConditionTable(composedConditions());
        p.acclimationS = 0.0;
        p.supervisorStartsTest = false;
        p.training.timeLimitS = 0.001;  // the first training trial is the only one
        p.conditions = {condition};
        p.targetsPerCondition = 2;
        p.timeoutS = 2.5;
        game = std::make_unique<ShooterGame>(p, 5, DisplaySize{});
        for (int i = 0; i < 100000 && game->currentPhase() != Phase::Test; ++i) last = game->step({});
        // Settle onto a fresh test trial.
        while (last.frozen || last.scene.objects.empty()) last = game->step({});
    }
};

TEST(ShooterGame, MouseStepShowsWithEachConditionsViewLatency) {
    for (const auto& condition : measuredConditions()) {
        for (int phase = 0; phase < 8; ++phase) {
            ConditionRig rig(condition);
            for (int i = 0; i < 16 + phase; ++i) rig.last = rig.game->step({});
            const double before = rig.last.camera.yaw;
            const ShownFrame stepFrame = rig.game->step({100.0, 0.0, 0, 0});  // the step, read at this frame
            const double stepTime = stepFrame.time;
            const condition::ConditionSchedule schedule =
                gameSchedule(rig.p.conditionTable.at(condition), rig.p.refreshHz, stepFrame);
            const double local = stepFrame.schedule.displayTime;
            ShownFrame f = stepFrame;
            while (f.camera.yaw == before) f = rig.game->step({});
            EXPECT_NEAR(f.time - stepTime, schedule.viewLatency(local), 1e-9) << condition << " phase " << phase;
        }
    }
}

// A frame shows the input its inputFrame names (what a photodiode marker lights on): a mouse
// step at frame v first turns the view on the first frame whose inputFrame reaches v, in every
// condition. The freeze frame after a shot answers at once, whatever the condition's lag: the banner is
// the game's own response, so its inputFrame is its own frame.
TEST(ShooterGame, InputFrameIsTheInputTheViewShows) {
    for (const auto& condition : measuredConditions()) {
        for (int phase = 0; phase < 8; ++phase) {
            ConditionRig rig(condition);
            for (int i = 0; i < 16 + phase; ++i) rig.last = rig.game->step({});
            const double before = rig.last.camera.yaw;
            const ShownFrame stepFrame = rig.game->step({100.0, 0.0, 0, 0});
            ShownFrame f = stepFrame;
            for (int i = 0; i < 100 && f.inputFrame < stepFrame.frame; ++i) {
                EXPECT_EQ(f.camera.yaw, before)
                    << condition << ": frame " << f.frame << " shows the step before it says so";
                f = rig.game->step({});
            }
            EXPECT_NE(f.camera.yaw, before) << condition << ": frame " << f.frame << " says it shows the step";
        }
        ConditionRig rig(condition);
        const ShownFrame shot = rig.game->step({0.0, 0.0, kButtonLeft, 0});
        EXPECT_LE(shot.inputFrame, shot.frame) << condition;
        const ShownFrame frozen = rig.game->step({0.0, 0.0, kButtonLeft, 0});
        ASSERT_TRUE(frozen.frozen) << condition;
        EXPECT_EQ(frozen.inputFrame, frozen.frame) << condition;
    }
}

// What a late-warped frame shows, and so what its displayed outcome is judged on: the camera of
// the display instant; the target where the queued render had it (rotation) or moved on by its
// velocity to the display instant (depth), never where it truly is now.
TEST(ShooterGame, LateWarpShowsTheWorldOfItsRenderThroughTheCameraOfNow) {
    for (const std::string condition : {"lag60x5", "lag60x5-rotation", "lag60x5-depth"}) {
        SCOPED_TRACE(condition);
        ConditionRig rig(condition);
        for (int i = 0; i < 30; ++i) rig.last = rig.game->step({i % 3 == 0 ? 40.0 : 0.0, 0.0, 0, 0});
        int checked = 0;
        for (int i = 0; i < 40; ++i) {
            const double yawBefore = rig.last.camera.yaw;
            const ShownFrame f = rig.game->step({25.0, 0.0, 0, 0});  // turning every frame
            rig.last = f;
            if (f.frozen || f.scene.objects.empty()) continue;
            const auto trial = rig.game->currentTrial();
            ASSERT_TRUE(trial.has_value());
            const auto& plane = rig.game->targetPlane();
            const double sourceTime = static_cast<double>(f.sourceFrame) / rig.p.refreshHz;
            if (sourceTime < trial->spawnTime) continue;
            const glm::dvec2 atSource = physics::positionAt(plane, trial->motion, sourceTime - trial->spawnTime);
            const glm::dvec2 velocity = physics::velocityAt(plane, trial->motion, sourceTime - trial->spawnTime);
            const glm::dvec2 shown(f.scene.objects.front().position);
            const glm::dvec2 expected =
                condition == "lag60x5-depth" ? atSource + velocity * (f.time - sourceTime) : atSource;
            EXPECT_LT(glm::length(shown - expected), 1e-4) << "frame " << f.frame;
            if (condition != "lag60x5") {
                EXPECT_NE(f.camera.yaw, yawBefore) << "the late warp did not turn to the mouse of now";
                EXPECT_EQ(f.schedule.kind, condition::FrameKind::Warped);
            }
            ++checked;
        }
        EXPECT_GE(checked, 1);
    }
}

// A bounce is a step in the target's motion. It shows in the first displayed frame whose
// target leaves the straight line the target was on; that must come when the condition's schedule
// says (conventional: the next render; warp: the next source, since warped frames extrapolate
// the old velocity; bidirectional: the first B-frame interpolating towards a later I-frame).
TEST(ShooterGame, TargetBounceShowsWithEachConditionsSceneLatency) {
    for (const auto& condition : measuredConditions()) {
        ConditionRig rig(condition);
        bool measured = false;
        for (int attempt = 0; attempt < 8 && !measured; ++attempt) {
            while (rig.last.frozen || rig.last.scene.objects.empty()) rig.last = rig.game->step({});
            const auto trial = rig.game->currentTrial();
            ASSERT_TRUE(trial.has_value());
            const auto& plane = rig.game->targetPlane();
            const double now = rig.last.time, rel = now - trial->spawnTime;
            const glm::dvec2 p0 = physics::positionAt(plane, trial->motion, rel);
            const glm::dvec2 v0 = physics::velocityAt(plane, trial->motion, rel);
            auto until = [](double x, double v, double lo, double hi) { return v > 0 ? (hi - x) / v : (x - lo) / -v; };
            const double bounce =
                now + std::min(until(p0.x, v0.x, plane.minX, plane.maxX), until(p0.y, v0.y, plane.minY, plane.maxY));
            const std::int64_t scheduleStart = rig.last.frame - rig.last.schedule.index;
            const double localBounce = bounce - static_cast<double>(scheduleStart) / rig.p.refreshHz;
            const condition::ConditionSchedule schedule =
                gameSchedule(rig.p.conditionTable.at(condition), rig.p.refreshHz, rig.last);
            if (bounce + schedule.sceneLatency(localBounce) > trial->spawnTime + rig.p.timeoutS - 0.05) {
                while (!rig.last.frozen) rig.last = rig.game->step({});  // too late in this trial: next one
                continue;
            }
            for (int i = 0; i < 2000; ++i) {
                rig.last = rig.game->step({});
                ASSERT_FALSE(rig.last.frozen) << condition;
                if (rig.last.scene.objects.empty()) continue;
                const glm::dvec2 straight = p0 + v0 * (rig.last.scene.time - now);
                const glm::dvec3 shown(rig.last.scene.objects.front().position);
                // Positions cross to the renderer as float: 1e-4 m is well above their rounding
                // and far below a bounce's deviation one frame after it (2 |v| / 120 s).
                if (glm::length(glm::dvec2(shown) - straight) > 1e-4 && rig.last.scene.time > now) {
                    EXPECT_NEAR(rig.last.time - bounce, schedule.sceneLatency(localBounce), 1e-9) << condition;
                    measured = true;
                    break;
                }
            }
        }
        EXPECT_TRUE(measured) << condition << ": no bounce early enough in 8 trials";
    }
}

// Format 2: a trial times out after exactly round(timeout_s * refresh) frames, wherever its
// spawn frame falls. (Format 1 compared seconds after a division, so rounding made some
// trials one frame longer; the legacy run below shows this test would see it.)
std::map<std::int64_t, int> timeoutLengths(bool legacy) {
    auto p = quick();
    p.legacyRules = legacy;
    p.acclimationS = 0.0;
    p.training.timeLimitS = 0.001;
    p.timeoutS = 3.0;
    p.pauseS = 0.0;  // trials 361 frames apart, so spawn frames meet every residue of k / 120
    p.targetsPerCondition = 100;
    ShooterGame game(p, 9, DisplaySize{});
    std::map<std::int64_t, int> lengths;  // frames from spawn to timeout -> count
    for (int i = 0; i < 2000000 && !game.finished(); ++i) {
        game.step({});
        for (const auto& e : game.takeEvents())
            if (e.type == "timeout") ++lengths[e.frame - std::llround(detailNumber(e, "spawn_time") * p.refreshHz)];
    }
    return lengths;
}

TEST(ShooterGame, TimeoutLastsExactlyTheRoundedNumberOfFrames) {
    const auto lengths = timeoutLengths(false);
    ASSERT_EQ(lengths.size(), 1u) << "timeouts of several lengths";
    EXPECT_EQ(lengths.begin()->first, 360);
    EXPECT_GE(lengths.begin()->second, 300);
    EXPECT_GT(timeoutLengths(true).count(361), 0u)
        << "format 1's rounding no longer shows: is the test still able to fail?";
}

// Aims exactly at the world's target and clicks on the frame after it appears: every shot
// hits (scored by the world), so every evaluated training level moves up.
struct PerfectShooter {
    const protocol::ShooterProtocol& p;
    ShooterGame& game;
    FrameInput next() {
        FrameInput in;
        const auto trial = game.currentTrial();
        if (!trial) return in;
        const double t = static_cast<double>(game.frameIndex() + 1) / p.refreshHz - trial->spawnTime;
        if (t <= 0.0) return in;
        const glm::dvec2 xy = physics::positionAt(game.targetPlane(), trial->motion, t);
        const glm::dvec3 d = glm::dvec3(xy, game.targetPlane().z) - glm::dvec3(game.trueCamera().eye);
        const double yaw = std::atan2(d.x, -d.z), pitch = std::atan2(d.y, std::hypot(d.x, d.z));
        in.mouseDx = (yaw - game.trueCamera().yaw) / p.mouseRadiansPerCount;
        in.mouseDy = -(pitch - game.trueCamera().pitch) / p.mouseRadiansPerCount;
        in.buttons = kButtonLeft;
        return in;
    }
};

// Training shots left after the last evaluated level when the test began.
int unevaluatedTrainingShots(bool legacy, double timeLimitS) {
    auto p = quick();
    p.legacyRules = legacy;
    p.acclimationS = 0.0;
    p.scoring = protocol::Scoring::World;
    p.pauseS = 0.1;
    p.training.timeLimitS = timeLimitS;
    ShooterGame game(p, 4, DisplaySize{});
    PerfectShooter shooter{p, game};
    int sinceLevel = 0, hits = 0;
    FrameInput in;
    for (int i = 0; i < 100000 && game.currentPhase() != Phase::Test; ++i) {
        game.step(in);
        for (const auto& e : game.takeEvents()) {
            if (e.type == "level") sinceLevel = 0;
            if (e.type == "shot" && e.phase == "training") ++sinceLevel, hits += e.worldOutcome == "hit";
        }
        // Release the button between shots: the game scores presses.
        in = in.buttons ? FrameInput{} : shooter.next();
    }
    EXPECT_GT(hits, 0);
    return sinceLevel;
}

TEST(ShooterGame, ALevelFinishedBeforeTheTimeLimitIsEvaluated) {
    // Sweep the limit across two levels' worth of time so that, for some limits, a level's
    // last shot lands just before it.
    const int perLevel = 2 * quick().training.shotsPerLevelEasy;
    bool legacyLeftOne = false;
    for (int i = 0; i < 40; ++i) {
        const double limit = 0.5 + i * 0.05;
        EXPECT_LT(unevaluatedTrainingShots(false, limit), perLevel) << "time limit " << limit;
        legacyLeftOne = legacyLeftOne || unevaluatedTrainingShots(true, limit) >= perLevel;
    }
    EXPECT_TRUE(legacyLeftOne) << "format 1's early stop no longer shows: is the test still able to fail?";
}

// click_timing "input_reads": a press at a frame where conv15 does not read input counts at
// its next render; "display" counts it at once.
TEST(ShooterGame, ClickTimingChoosesWhenAPressCounts) {
    for (const auto timing : {protocol::ClickTiming::Display, protocol::ClickTiming::InputReads}) {
        auto p = quick();
        p.clickTiming = timing;
        p.acclimationS = 0.0;
        p.training.timeLimitS = 0.001;
        p.conditions = {"conv15"};
        p.timeoutS = 2.0;
        ShooterGame game(p, 3, DisplaySize{});
        ShownFrame last;
        for (int i = 0; i < 100000 && game.currentPhase() != Phase::Test; ++i) last = game.step({});
        while (last.frozen || last.scene.objects.empty()) last = game.step({});
        game.takeEvents();
        while (last.schedule.index % 8 != 2) last = game.step({});  // between conv15's renders
        const std::int64_t pressed = game.frameIndex() + 1;
        game.step({0, 0, kButtonLeft, 0});
        std::int64_t counted = -1;
        for (int i = 0; i < 16 && counted < 0; ++i) {
            for (const auto& e : game.takeEvents())
                if (e.type == "shot") counted = e.frame;
            if (counted < 0) game.step({});
        }
        EXPECT_EQ(counted - pressed, timing == protocol::ClickTiming::Display ? 0 : 5)
            << protocol::nameOf(timing);  // pressed at index 3, read at 8
    }
}

// The frame a trial times out on still shows the target: a click on it is a shot, with an aim
// time of exactly timeout_s, and only that frame without a click is a timeout
// (docs/shooter-study.md, "Test").
TEST(ShooterGame, AClickOnTheTimeoutFrameIsAShot) {
    auto p = quick();
    p.acclimationS = 0.0;
    p.training.timeLimitS = 0.001;
    p.conditions = {"conv120"};
    p.timeoutS = 1.0;
    const std::int64_t timeoutFrames = std::llround(p.timeoutS * p.refreshHz);
    std::map<std::string, std::vector<session::EventRecord>> ends;  // by whether it clicked
    for (const bool click : {false, true}) {
        ShooterGame game(p, 3, DisplaySize{});
        ShownFrame last;
        for (int i = 0; i < 100000 && game.currentPhase() != Phase::Test; ++i) last = game.step({});
        while (last.frozen || last.scene.objects.empty()) last = game.step({});
        game.takeEvents();
        const std::int64_t spawn = std::llround(game.currentTrial()->spawnTime * p.refreshHz);
        while (game.frameIndex() + 1 < spawn + timeoutFrames) {
            game.step({});
            ASSERT_TRUE(game.takeEvents().empty()) << "the trial ended before its timeout frame";
        }
        game.step(click ? FrameInput{0, 0, kButtonLeft, 0} : FrameInput{});
        ends[click ? "click" : "none"] = game.takeEvents();
    }
    ASSERT_EQ(ends["none"].size(), 1u);
    EXPECT_EQ(ends["none"][0].type, "timeout");
    ASSERT_EQ(ends["click"].size(), 1u);
    EXPECT_EQ(ends["click"][0].type, "shot");
    EXPECT_EQ(ends["click"][0].frame, ends["none"][0].frame);
    EXPECT_DOUBLE_EQ(detailNumber(ends["click"][0], "aim_time"), p.timeoutS);
}

}  // namespace
}  // namespace warplab::game
