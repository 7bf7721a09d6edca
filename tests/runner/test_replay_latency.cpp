// Uneven conditions end to end: a session run headless (the path `warplab run --headless` takes)
// and replayed (the path `warplab replay` takes) shows each mouse step and each change in the
// world's motion exactly as late as the schedule's viewLatency and sceneLatency say, frame by
// frame, for 60 fps on a 144 Hz display, a jittered and hitching 60 fps, and a recorded trace.
// The steps are the bot's own mouse moves, found in the replayed frames by the camera they show;
// the world changes are the target's bounces, found by where the frames draw it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "condition/schedule.h"
#include "game/random.h"
#include "game/registry.h"
#include "physics/bouncing_target.h"
#include "shooter/shooter_protocol.h"
#include "rerun.h"
#include "shooter_game.h"
#include "runner/session_runner.h"

namespace warplab::runner {
namespace {

namespace fs = std::filesystem;

// What a condition shows: a render rate 144 Hz does not divide, drawn jitter with periodic
// hitches, and a game's frame times given inline (7 frames of 118.7 ms, 59 frames a second).
const char* kProtocol = R"({"format_version":8,"name":"uneven-latency","game":"shooter",
 "display":{"refresh_hz":144,"refresh_mismatch":"warn"},
 "conditions":{
  "even60":{"render_hz":60},
  "rough60":{"render_hz":60,"frame_time_jitter":{"distribution":"normal","sd_ms":4},
             "hitches":{"ms":50,"every_s":0.4}},
  "traced":{"frame_times":{"ms":[16.7,8.3,33.4,12.5,16.7,20.0,11.1]}}},
 "acclimation":{"duration_s":0.5,"level":0,"mode":"even60"},
 "training":{"start_level":12,"base_speed_m_per_s":10,"shots_per_level_easy":1,"shots_per_level_hard":1,
  "time_limit_s":0.5,
  "high_mode":"even60","low_mode":"conv15"},
 "test":{"conditions":["even60","rough60","traced"],"targets_per_condition":6,
  "timeout_s":3,"pause_s":0.25,"supervisor_starts":false}})";

// One replayed display frame, as far as the latencies need it.
struct Replayed {
    double time = 0.0;
    std::string condition;
    std::int64_t scheduleStart = 0;  // the session frame its schedule started at
    double localTime = 0.0;  // its display time on that schedule's clock
    bool onTarget = false;  // a test trial's target on screen, not a pause
    float shownYaw = 0.0f, trueYaw = 0.0f;  // the camera it depicts; the one the mouse has made by now
    glm::dvec2 target{0.0};  // where it draws the target
    double sceneTime = 0.0;  // the instant whose world it depicts
    std::optional<game::ShooterGame::TrialView> trial;
};

struct Session {
    protocol::ShooterProtocol protocol;  // the session's stored copy
    std::uint64_t seed = 0;
    physics::TargetPlane plane;  // where the game's target bounces
    std::vector<Replayed> frames;
};

// Runs the protocol headless with the bot, then replays the stored session, checking that the
// replay reproduces every event and every frame's logged camera.
Session runAndReplay(const std::string& name) {
    const fs::path dir = fs::path(WARPLAB_BINARY_DIR) / "test-output" / "replay-latency" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "uneven.json") << kProtocol;
    HeadlessRun run;
    run.protocolPath = (dir / "uneven.json").string();
    run.participant = "P";
    run.resultsDir = dir.string();
    run.player = "bot:3";
    run.seed = 11;
    std::ostringstream progress;
    const std::string path = runHeadless(run, progress);

    const session::SessionData data = session::readSession(path);
    Session s;
    s.protocol = protocol::parseShooterProtocol(data.header.protocolJson, "session copy");
    s.seed = data.header.seed;
    const auto study = game::parseStudy(data.header.protocolJson, path);
    const auto played = study->newGame(data.header.seed, {data.header.displayWidth, data.header.displayHeight});
    auto* shooter = dynamic_cast<game::ShooterGame*>(played.get());
    EXPECT_NE(shooter, nullptr);
    if (!shooter) return s;
    s.plane = shooter->targetPlane();
    int loggedYawDiffers = 0;
    const Rerun r = rerun(data, *played, [&](std::size_t i, const game::ShownFrame& shown, std::size_t) {
        Replayed f;
        f.time = shown.time;
        f.condition = shown.condition.name;
        f.scheduleStart = shown.frame - shown.schedule.index;
        f.localTime = shown.schedule.displayTime;
        f.onTarget = shooter->currentPhase() == game::Phase::Test && !shown.frozen && !shown.scene.objects.empty();
        f.shownYaw = shown.camera.yaw;
        f.trueYaw = shooter->trueCamera().yaw;
        if (!shown.scene.objects.empty()) f.target = glm::dvec2(shown.scene.objects.front().position);
        f.sceneTime = shown.scene.time;
        f.trial = shooter->currentTrial();
        if (i < data.frames.size() && data.frames[i].cameraYaw != static_cast<double>(shown.camera.yaw))
            ++loggedYawDiffers;
        s.frames.push_back(f);
    });
    EXPECT_EQ(r.difference, "");
    EXPECT_EQ(r.reproduced, r.outcomes);
    EXPECT_EQ(loggedYawDiffers, 0) << "the replayed frames show other cameras than the frame log";
    EXPECT_EQ(data.frames.size(), s.frames.size());
    return s;
}

// A stretch of frames on one schedule of one condition with the target on screen: [first, last].
struct Stretch {
    std::size_t first = 0, last = 0;
};

std::vector<Stretch> stretches(const Session& s, const std::string& condition) {
    std::vector<Stretch> out;
    for (std::size_t i = 0; i < s.frames.size(); ++i) {
        const Replayed& f = s.frames[i];
        if (!f.onTarget || f.condition != condition) continue;
        if (!out.empty() && out.back().last + 1 == i && s.frames[out.back().first].scheduleStart == f.scheduleStart)
            out.back().last = i;
        else
            out.push_back({i, i});
    }
    return out;
}

condition::ConditionSchedule scheduleOf(const Session& s, const Replayed& f) {
    return condition::ConditionSchedule(s.protocol.conditionTable.at(f.condition), s.protocol.refreshHz,
                                        game::pacingSeed(s.seed, f.scheduleStart));
}

const std::vector<std::string> kUneven = {"even60", "rough60", "traced"};

// A mouse move at frame v is read at its display instant; it shows in the first frame whose
// camera is one the mouse made at v or later. Where the bot did not move, or its camera came
// back to one it had before, there is no step to see and v is passed over.
TEST(ReplayLatency, MouseStepsShowWithTheSchedulesViewLatencyFrameByFrame) {
    const Session s = runAndReplay("view");
    for (const std::string& condition : kUneven) {
        SCOPED_TRACE(condition);
        int measured = 0;
        std::set<std::int64_t> phases;  // refreshes since the schedule started
        for (const Stretch& st : stretches(s, condition)) {
            const condition::ConditionSchedule schedule = scheduleOf(s, s.frames[st.first]);
            for (std::size_t v = st.first + 1; v <= st.last; ++v) {
                const Replayed& step = s.frames[v];
                if (step.trueYaw == s.frames[v - 1].trueYaw) continue;
                const double expected = schedule.viewLatency(step.localTime);
                if (step.time + expected > s.frames[st.last].time) continue;  // shown after the stretch
                std::set<float> before;
                for (std::size_t w = v >= 400 ? v - 400 : 0; w < v; ++w) before.insert(s.frames[w].trueYaw);
                std::optional<std::size_t> shownAt;
                bool ambiguous = false;
                for (std::size_t k = v; k <= st.last && !shownAt && !ambiguous; ++k) {
                    bool after = false;
                    for (std::size_t u = v; u <= k; ++u) after = after || s.frames[u].trueYaw == s.frames[k].shownYaw;
                    const bool earlier = before.count(s.frames[k].shownYaw) > 0;
                    ambiguous = after && earlier;
                    if (after && !earlier) shownAt = k;
                    if (!after && !earlier) ADD_FAILURE() << "frame " << k << " shows a camera the mouse never made";
                }
                if (ambiguous) continue;
                ASSERT_TRUE(shownAt) << "step at frame " << v << " never shown; expected after " << expected;
                EXPECT_NEAR(s.frames[*shownAt].time - step.time, expected, 1e-9) << "step at frame " << v;
                ++measured;
                phases.insert(static_cast<std::int64_t>(v) - step.scheduleStart);
            }
        }
        std::set<std::int64_t> cycle;
        for (const std::int64_t p : phases) cycle.insert(p % 12);
        EXPECT_EQ(cycle.size(), 12u) << "steps at every refresh of 60 fps on 144 Hz's 12-refresh cycle";
        EXPECT_GE(measured, 500);
    }
}

// The instants a bouncing target turns, in (from, to], session seconds.
std::vector<double> bounces(const physics::TargetPlane& plane, const game::ShooterGame::TrialView& trial, double from,
                            double to) {
    std::vector<double> out;
    const auto axis = [&](double lo, double hi, double start, double velocity) {
        const double width = hi - lo;
        if (velocity == 0.0) return;
        // The unfolded line start + velocity t meets a wall at lo + n width.
        const double a = (start + velocity * (from - trial.spawnTime) - lo) / width;
        const double b = (start + velocity * (to - trial.spawnTime) - lo) / width;
        for (double n = std::ceil(std::min(a, b)); n <= std::max(a, b); ++n) {
            const double t = trial.spawnTime + (lo + n * width - start) / velocity;
            if (t > from && t <= to) out.push_back(t);
        }
    };
    axis(plane.minX, plane.maxX, trial.motion.start.x, trial.motion.velocity.x);
    axis(plane.minY, plane.maxY, trial.motion.start.y, trial.motion.velocity.y);
    std::sort(out.begin(), out.end());
    return out;
}

// A bounce shows in the first frame that draws the target off the line it was on. A bounce
// whose frames depict the world before the bounce before it or after the one after it, or
// whose first frame after it depicts an instant so close to it that the turn is under float
// rounding, cannot be told and is passed over.
TEST(ReplayLatency, TargetBouncesShowWithTheSchedulesSceneLatencyFrameByFrame) {
    const Session s = runAndReplay("scene");
    for (const std::string& condition : kUneven) {
        SCOPED_TRACE(condition);
        int measured = 0;
        for (const Stretch& st : stretches(s, condition)) {
            const Replayed& first = s.frames[st.first];
            ASSERT_TRUE(first.trial);
            const condition::ConditionSchedule schedule = scheduleOf(s, first);
            const auto& trial = *first.trial;
            const double clockStart = static_cast<double>(first.scheduleStart) / s.protocol.refreshHz;
            const std::vector<double> all = bounces(s.plane, trial, first.time - 0.2, s.frames[st.last].time);
            for (std::size_t n = 0; n < all.size(); ++n) {
                const double b = all[n];
                if (b <= first.time) continue;
                const double expected = schedule.sceneLatency(b - clockStart);
                if (b + expected > s.frames[st.last].time) continue;
                const double before = b - 1e-6;
                const glm::dvec2 p0 = physics::positionAt(s.plane, trial.motion, before - trial.spawnTime);
                const glm::dvec2 v0 = physics::velocityAt(s.plane, trial.motion, before - trial.spawnTime);
                std::optional<std::size_t> shownAt;
                bool ambiguous = false;
                for (std::size_t k = st.first; k <= st.last && !shownAt && !ambiguous; ++k) {
                    const Replayed& f = s.frames[k];
                    if (f.time < b) continue;
                    const glm::dvec2 straight = p0 + v0 * (f.sceneTime - before);
                    const glm::dvec2 truth = physics::positionAt(s.plane, trial.motion, f.sceneTime - trial.spawnTime);
                    // Positions cross to the renderer as float: 1e-4 m is well above their rounding.
                    const double turn = glm::length(truth - straight);
                    // Off the line by a turn too small to tell, or by the bounce before or after.
                    ambiguous = (turn > 0.0 && turn < 1e-3) || (n > 0 && f.sceneTime <= all[n - 1]) ||
                        (n + 1 < all.size() && f.sceneTime > all[n + 1]);
                    if (glm::length(f.target - straight) > 1e-4) shownAt = k;
                }
                if (ambiguous) continue;
                ASSERT_TRUE(shownAt) << "bounce at " << b << " never shown";
                EXPECT_NEAR(s.frames[*shownAt].time - b, expected, 1e-9) << "bounce at " << b;
                ++measured;
            }
        }
        EXPECT_GE(measured, 20);
    }
}

}  // namespace
}  // namespace warplab::runner
