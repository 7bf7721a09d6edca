// The shooter study as a pure function of protocol, seed and input: a bot plays the quick
// protocol to the end, replays reproduce it, and every mode's measured latency -- a mouse step
// and a bounce of the target, found in the displayed frames -- is what its schedule says.
#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "game/bot_player.h"
#include "game/shooter_game.h"
#include "protocol/shooter_protocol.h"

namespace warplab::game {
namespace {

protocol::ShooterProtocol quick() {
    return protocol::loadShooterProtocol(std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json");
}

struct Played {
    std::vector<FrameInput> inputs;
    std::vector<protocol::EventRecord> events;
    int frames = 0;
};

Played playWithBot(const protocol::ShooterProtocol& p, std::uint64_t seed, std::uint64_t botSeed) {
    ShooterGame game(p, seed, 16.0 / 9.0);
    BotPlayer bot(botSeed, p);
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

bool sameEvents(const std::vector<protocol::EventRecord>& a, const std::vector<protocol::EventRecord>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const auto &x = a[i], &y = b[i];
        if (x.frame != y.frame || x.type != y.type || x.phase != y.phase || x.trial != y.trial || x.mode != y.mode ||
            x.difficulty != y.difficulty || x.targetSpeed != y.targetSpeed || x.spawnTime != y.spawnTime ||
            x.eventTime != y.eventTime || x.worldOutcome != y.worldOutcome ||
            x.displayedOutcome != y.displayedOutcome || x.angularErrorDeg != y.angularErrorDeg ||
            x.detailJson != y.detailJson)
            return false;
    }
    return true;
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
            EXPECT_NEAR(e.aimTime, e.eventTime - e.spawnTime, 1e-12);
            EXPECT_LE(e.aimTime, p.timeoutS + 1e-9);
        }
    }
    EXPECT_EQ(testOutcomes, static_cast<int>(p.conditions.size()) * p.targetsPerCondition);
    EXPECT_GT(hits, 0) << "the bot should hit some targets";
    EXPECT_EQ(phases.front(), "acclimation");
    EXPECT_EQ(phases.back(), "done");
    EXPECT_NE(std::find(phases.begin(), phases.end(), "training"), phases.end());
    EXPECT_NE(std::find(phases.begin(), phases.end(), "test"), phases.end());
}

TEST(ShooterGame, SameSeedAndInputSameEventsBitForBit) {
    const auto p = quick();
    const Played a = playWithBot(p, 11, 2);
    // Replaying the recorded input into a fresh game gives the same events.
    ShooterGame game(p, 11, 16.0 / 9.0);
    std::vector<protocol::EventRecord> replayed;
    for (const auto& in : a.inputs) {
        game.step(in);
        for (auto& e : game.takeEvents()) replayed.push_back(e);
    }
    EXPECT_TRUE(sameEvents(a.events, replayed));
    // Another session seed spawns other targets: the outcomes differ.
    const Played b = playWithBot(p, 12, 2);
    EXPECT_FALSE(sameEvents(a.events, b.events));
}

TEST(ShooterGame, TestConditionsComeInTheProtocolsNumbers) {
    auto p = quick();
    p.targetsPerCondition = 6;
    const Played played = playWithBot(p, 21, 1);
    std::map<std::string, int> perMode;
    for (const auto& e : played.events)
        if (e.phase == "test" && (e.type == "shot" || e.type == "timeout")) ++perMode[e.mode];
    for (const auto& c : p.conditions) EXPECT_EQ(perMode[c], 6) << c;
}

// A game whose test phase shows one mode, reached without clicking (training times out).
struct ModeRig {
    protocol::ShooterProtocol p;
    std::unique_ptr<ShooterGame> game;
    ShownFrame last;
    explicit ModeRig(const std::string& mode) {
        p = quick();
        p.acclimationS = 0.0;
        p.supervisorStartsTest = false;
        p.training.timeLimitS = 0.001;  // the first training trial is the only one
        p.conditions = {mode};
        p.targetsPerCondition = 2;
        p.timeoutS = 2.5;
        game = std::make_unique<ShooterGame>(p, 5, 16.0 / 9.0);
        for (int i = 0; i < 100000 && game->phase() != Phase::Test; ++i) last = game->step({});
        // Settle onto a fresh test trial.
        while (last.frozen || last.scene.objects.empty()) last = game->step({});
    }
};

TEST(ShooterGame, MouseStepShowsWithEachModesViewLatency) {
    for (const auto& mode : modeIds()) {
        for (int phase = 0; phase < 8; ++phase) {
            ModeRig rig(mode);
            for (int i = 0; i < 16 + phase; ++i) rig.last = rig.game->step({});
            const double before = rig.last.camera.yaw;
            const ShownFrame stepFrame = rig.game->step({100.0, 0.0, 0, 0});  // the step, read at this frame
            const double stepTime = stepFrame.time;
            const ModeSchedule schedule(modeSpec(mode), rig.p.refreshHz);
            const double local = stepFrame.schedule.displayTime;
            ShownFrame f = stepFrame;
            while (f.camera.yaw == before) f = rig.game->step({});
            EXPECT_NEAR(f.time - stepTime, schedule.viewLatency(local), 1e-9) << mode << " phase " << phase;
        }
    }
}

// A bounce is a step in the target's motion. It shows in the first displayed frame whose
// target leaves the straight line the target was on; that must come when the mode's schedule
// says (conventional: the next render; warp: the next source, since warped frames extrapolate
// the old velocity; bidirectional: the first B-frame interpolating towards a later I-frame).
TEST(ShooterGame, TargetBounceShowsWithEachModesSceneLatency) {
    for (const auto& mode : modeIds()) {
        ModeRig rig(mode);
        const ModeSchedule schedule(modeSpec(mode), rig.p.refreshHz);
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
            const double bounce = now + std::min(until(p0.x, v0.x, plane.minX, plane.maxX),
                                                 until(p0.y, v0.y, plane.minY, plane.maxY));
            const std::int64_t scheduleStart = rig.last.frame - rig.last.schedule.index;
            const double localBounce = bounce - static_cast<double>(scheduleStart) / rig.p.refreshHz;
            if (bounce + schedule.sceneLatency(localBounce) > trial->spawnTime + rig.p.timeoutS - 0.05) {
                while (!rig.last.frozen) rig.last = rig.game->step({});  // too late in this trial: next one
                continue;
            }
            for (int i = 0; i < 2000; ++i) {
                rig.last = rig.game->step({});
                ASSERT_FALSE(rig.last.frozen) << mode;
                if (rig.last.scene.objects.empty()) continue;
                const glm::dvec2 straight = p0 + v0 * (rig.last.scene.time - now);
                const glm::dvec3 shown(rig.last.scene.objects.front().position);
                // Positions cross to the renderer as float: 1e-4 m is well above their rounding
                // and far below a bounce's deviation one frame after it (2 |v| / 120 s).
                if (glm::length(glm::dvec2(shown) - straight) > 1e-4 && rig.last.scene.time > now) {
                    EXPECT_NEAR(rig.last.time - bounce, schedule.sceneLatency(localBounce), 1e-9) << mode;
                    measured = true;
                    break;
                }
            }
        }
        EXPECT_TRUE(measured) << mode << ": no bounce early enough in 8 trials";
    }
}

}  // namespace
}  // namespace warplab::game
