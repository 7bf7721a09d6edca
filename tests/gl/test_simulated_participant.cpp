// The perceptual simulated participant: it finds objects in the displayed frame where
// they really project, it cannot know what the frame does not show, it plays well when it is
// given no delay and no noise and worse with a human delay, and the same seed gives the same
// inputs.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include <gtest/gtest.h>

#include "app/simulated_participant.h"
#include "game/click/click_game.h"
#include "game/registry.h"
#include "game/screen.h"
#include "gl/gl_test_support.h"

namespace warplab {
namespace {

const game::DisplaySize kDisplay{1920, 1080};

std::string protocolPath(const std::string& name) {
    return std::string(WARPLAB_SOURCE_DIR) + "/protocol/" + name + ".json";
}

// The shooter at 60 Hz with a generous timeout and a short pause: the behaviour tests need a
// dozen targets each, and half the frames of a 120 Hz display keep them quick on llvmpipe.
std::unique_ptr<game::Study> shooterAt60() {
    return game::parseStudy(R"({
      "format_version": 2, "name": "sim-test", "game": "shooter",
      "display": {"refresh_hz": 60.0, "vertical_fov_deg": 60.0, "refresh_mismatch": "warn"},
      "acclimation": {"duration_s": 1.0, "mode": "conv60"},
      "training": {"high_mode": "conv60", "low_mode": "conv15"},
      "test": {"conditions": ["conv60"], "targets_per_condition": 1, "timeout_s": 1.5, "pause_s": 0.25,
               "supervisor_starts": false}
    })",
                            "sim-test");
}

app::PerceptualPlayer playerFor(const game::Study& study, std::uint64_t seed, const app::ParticipantParams& params = {}) {
    testing::glContext();  // the player draws in the context current on this thread
    return app::PerceptualPlayer(nullptr, study, kDisplay, testing::sourceDataPaths(), seed, params);
}

// Plays free-play targets at `level` in `mode` until `targets` trials have ended; the share of
// them hit as displayed (the scored outcome of the shooter's protocols).
double hitRate(const game::Study& study, const std::string& mode, int level, int targets,
               const app::ParticipantParams& params, std::uint64_t seed = 1) {
    auto game = study.newFreePlay(seed, kDisplay, mode, level);
    auto player = playerFor(study, seed, params);
    game::FrameInput input = player.first();
    int ended = 0, hits = 0;
    for (int frame = 0; frame < 100000 && ended < targets; ++frame) {
        const game::ShownFrame shown = game->step(input);
        for (const auto& e : game->takeEvents()) {
            if (e.type != "shot" && e.type != "timeout") continue;
            ++ended;
            hits += e.displayedOutcome == "hit";
        }
        input = player.next(shown);
    }
    EXPECT_EQ(ended, targets);
    return static_cast<double>(hits) / targets;
}

app::ParticipantParams ideal() {
    app::ParticipantParams p;
    p.reactionS = 0.0;
    p.motorNoise = 0.0;
    p.motorNoiseFloorCountsPerS = 0.0;
    return p;
}

// ---------------------------------------------------------------------------------------------
// Perception

// Percept pixels the centroid may be off the exact projection of the centre: the disc's
// rasterised edge moves its centroid by a fraction of a pixel (0.3 at most, measured), and a
// sphere off the view axis projects to an ellipse whose centroid sits slightly outward of the
// centre's projection. Half a pixel still catches a pixel-centre convention gone wrong.
constexpr double kCentroidTolerancePx = 0.5;

// The radius of the disc with the area of a sphere's exact image, display pixels: off the view
// axis the image is an ellipse with semi-axes f sin(r) cos(r) / (cos^2(t) - sin^2(r)) and
// f sin(r) / sqrt(cos^2(t) - sin^2(r)), r the angular radius and t the angle off the axis.
double imageRadiusPx(const game::ScreenMapping& screen, const glm::dvec3& centre, double radius) {
    const glm::dvec3 axis = screen.ray({kDisplay.width * 0.5, kDisplay.height * 0.5});
    const glm::dvec3 to = centre - screen.eye();
    const double r = std::asin(radius / glm::length(to));
    const double t = std::acos(std::clamp(glm::dot(glm::normalize(to), axis), -1.0, 1.0));
    const double f = 1.0 / screen.radiansPerPixel();  // radians per pixel at the centre: 1 / focal length
    const double d = std::cos(t) * std::cos(t) - std::sin(r) * std::sin(r);
    return std::sqrt(f * std::sin(r) * std::cos(r) / d * f * std::sin(r) / std::sqrt(d));
}

// The whole image lies in the view, with room to spare.
bool wellInView(const glm::dvec2& p, double radiusPx) {
    const double margin = 2.0 * radiusPx;
    return p.x > margin && p.x < kDisplay.width - margin && p.y > margin && p.y < kDisplay.height - margin;
}

TEST(SimulatedParticipant, EyeFindsTheShooterTargetWhereItProjects) {
    const auto study = game::loadStudy(protocolPath("shooter-quick"));
    testing::glContext();
    app::Eye eye(testing::sourceDataPaths(), kDisplay, study->rendering(), 160);
    const double perceptPx = static_cast<double>(kDisplay.width) / eye.width();
    auto game = study->newGame(3, kDisplay);
    int checked = 0, sized = 0;
    double worst = 0.0;
    for (int frame = 0; frame < 240; ++frame) {
        // Turn a little every frame, so the target is seen in many places in the view.
        const game::ShownFrame shown = game->step({frame % 80 < 40 ? 2.0 : -2.0, frame % 40 < 20 ? 1.0 : -1.0, 0, 0});
        const app::Percept percept = eye.see(shown);
        if (frame % 4 != 0 || shown.scene.objects.empty() || shown.frozen) continue;
        const game::ScreenMapping screen(shown.camera, kDisplay);
        const glm::dvec3 centre(shown.scene.objects.front().position);
        const auto truth = screen.project(centre);
        ASSERT_TRUE(truth.has_value());
        const double radiusPx = imageRadiusPx(screen, centre, 0.35);
        // Near the walls a pillar may hide part of it: judged where nothing can.
        const glm::dvec2 middle(kDisplay.width * 0.5, kDisplay.height * 0.5);
        if (!wellInView(*truth, radiusPx) || std::abs(truth->x - middle.x) > 0.3 * kDisplay.width) continue;
        ASSERT_EQ(percept.objects.size(), 1u) << "frame " << frame;
        const app::SeenObject& seen = percept.objects.front();
        EXPECT_EQ(seen.id, scene::kIdTarget);
        EXPECT_LE(glm::length(seen.centre - *truth) / perceptPx, kCentroidTolerancePx)
            << "frame " << frame << ": seen at (" << seen.centre.x << ", " << seen.centre.y << "), projects to ("
            << truth->x << ", " << truth->y << ")";
        worst = std::max(worst, glm::length(seen.centre - *truth) / perceptPx);
        // Its size: the exact image's, within half a pixel (the rasterised edge) -- or smaller,
        // where a pipe on the wall hides part of it, but mostly not.
        EXPECT_LE(seen.radiusPx / perceptPx, radiusPx / perceptPx + 0.5) << "frame " << frame;
        sized += std::abs(seen.radiusPx - radiusPx) / perceptPx <= 0.5;
        ++checked;
    }
    EXPECT_GE(checked, 20);
    EXPECT_GE(sized, checked * 8 / 10);
    std::printf("worst centroid error %.3f percept px over %d frames\n", worst, checked);
}

TEST(SimulatedParticipant, EyeFindsTheFallingSpheresAndTellsGreenFromRed) {
    const auto study = game::loadStudy(protocolPath("click-quick"));
    testing::glContext();
    app::Eye eye(testing::sourceDataPaths(), kDisplay, study->rendering(), 160);
    const double perceptPx = static_cast<double>(kDisplay.width) / eye.width();
    auto game = study->newFreePlay(2, kDisplay, "conv60", 0);
    int checked = 0, green = 0;
    double worst = 0.0;
    for (int frame = 0; frame < 150; ++frame) {
        const game::ShownFrame shown = game->step({});
        const app::Percept percept = eye.see(shown);
        if (frame % 10 != 0) continue;
        const game::ScreenMapping screen(shown.camera, kDisplay);
        for (const auto& o : shown.scene.objects) {
            const glm::dvec3 centre(o.position);
            const auto truth = screen.project(centre);
            const app::SeenObject* seen = nullptr;
            for (const auto& s : percept.objects)
                if (s.id == o.id) seen = &s;
            // Spheres hide each other: judge only those seen whole, their area-equivalent radius
            // within 0.55 percept px of the exact image's. (Seen whole, 3 to 5 px in radius, they
            // measure 0.3 to 0.5 px short -- pixel centres at the edge, and a polygon up to an
            // eighth of a pixel inside the sphere; at 0.6, spheres partly hidden slip in.)
            const double radiusPx = imageRadiusPx(screen, centre, o.halfExtents.x);
            if (!truth || seen == nullptr || std::abs(seen->radiusPx - radiusPx) > 0.55 * perceptPx) continue;
            EXPECT_LE(glm::length(seen->centre - *truth) / perceptPx, kCentroidTolerancePx) << "sphere " << o.id;
            worst = std::max(worst, glm::length(seen->centre - *truth) / perceptPx);
            EXPECT_EQ(seen->greenish(), o.colour.g > o.colour.r) << "sphere " << o.id;
            green += seen->greenish();
            ++checked;
        }
    }
    EXPECT_GE(checked, 50);
    std::printf("worst centroid error %.3f percept px over %d spheres\n", worst, checked);
    EXPECT_GE(green, 10);
    EXPECT_LE(green, checked - 10);
}

TEST(SimulatedParticipant, PictureRegistrationFindsHowFarTheViewTurned) {
    const auto study = game::loadStudy(protocolPath("shooter-quick"));
    testing::glContext();
    app::Eye eye(testing::sourceDataPaths(), kDisplay, study->rendering(), 160);
    auto game = study->newGame(3, kDisplay);
    const app::Percept home = eye.see(game->step({}));
    // Turn by a known number of counts, then compare the views: the start view's centre must be
    // found where the turn puts it, within a cell of the picture (4 percept pixels, ~2.7 degrees:
    // enough to turn back to where targets appear).
    const double radiansPerCount = study->mouseRadiansPerCount();
    const double f = 0.5 * kDisplay.height / std::tan(glm::radians(30.0));
    for (const glm::dvec2 counts : {glm::dvec2(40, 0), glm::dvec2(-90, 0), glm::dvec2(0, 40), glm::dvec2(60, -50)}) {
        auto turned = study->newGame(3, kDisplay);
        app::Eye eye2(testing::sourceDataPaths(), kDisplay, study->rendering(), 160);
        const app::Percept now = eye2.see(turned->step({counts.x, counts.y, 0, 0}));
        const auto shift = app::whereViewIs(home.picture, now.picture);
        ASSERT_TRUE(shift.has_value());
        const double yaw = counts.x * radiansPerCount, pitch = -counts.y * radiansPerCount;
        const glm::dvec2 expected(-f * std::tan(yaw), f * std::tan(pitch) / std::cos(yaw));
        EXPECT_LE(glm::length(*shift - expected), home.picture.cellPx.x)
            << "turned by (" << counts.x << ", " << counts.y << ") counts: found (" << shift->x << ", " << shift->y
            << "), expected (" << expected.x << ", " << expected.y << ")";
    }
}

// ---------------------------------------------------------------------------------------------
// The control law's parts (no GL)

TEST(SimulatedParticipant, MotionEstimateRecoversAParabolaAndALine) {
    const glm::dvec2 p0(100.0, 50.0), v(300.0, -40.0), a(0.0, 1150.0);
    std::vector<app::Sample> samples;
    for (int i = 0; i <= 12; ++i) {
        const double t = 2.0 + i / 60.0;
        const double s = t - 2.2;
        samples.push_back({t, p0 + v * s + 0.5 * a * s * s});
    }
    const app::MotionEstimate parabola = app::estimateMotion(samples, true);
    EXPECT_NEAR(glm::length(parabola.position - p0), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(parabola.velocity - v), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(parabola.acceleration - a), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(parabola.positionAt(2.4) - (p0 + v * 0.2 + 0.5 * a * 0.04)), 0.0, 1e-6);
    // Without acceleration, a line: exact for a line, and no acceleration from a parabola.
    const app::MotionEstimate line = app::estimateMotion(samples, false);
    EXPECT_EQ(line.acceleration, glm::dvec2(0.0));
    EXPECT_NEAR(line.velocity.x, v.x, 1e-6);
    // One sample: where it was, at rest.
    const app::MotionEstimate one = app::estimateMotion({{1.0, {3.0, 4.0}}}, true);
    EXPECT_EQ(one.position, glm::dvec2(3.0, 4.0));
    EXPECT_EQ(one.velocity, glm::dvec2(0.0));
}

TEST(SimulatedParticipant, ItClicksOnlyWhenBothThePredictedAndTheSeenErrorAreSmall) {
    app::ParticipantParams p;
    const double r = 10.0;  // within 0.7 * 10
    EXPECT_TRUE(app::decidesToClick({3.0, 0.0}, {0.0, 3.0}, r, 0.5, p));
    EXPECT_FALSE(app::decidesToClick({8.0, 0.0}, {0.0, 3.0}, r, 0.5, p));  // predicted off
    EXPECT_FALSE(app::decidesToClick({3.0, 0.0}, {0.0, 8.0}, r, 0.5, p));  // seen off
    EXPECT_FALSE(app::decidesToClick({3.0, 0.0}, {0.0, 3.0}, r, 0.05, p));  // not aimed long enough
}

// The participant alone, fed percepts made by hand: a green object on screen and the cursor
// where its own counts have moved it. It gets there and clicks it -- from percepts alone.
TEST(SimulatedParticipant, FromPerceptsAloneItMovesTheCursorOntoAGreenObjectAndClicks) {
    app::TaskKnowledge knowledge;
    knowledge.display = kDisplay;
    knowledge.pixelsPerCount = 1.0;
    knowledge.greenOnly = true;
    app::SimulatedParticipant participant(knowledge, {}, 7);
    glm::dvec2 cursor(960.0, 540.0);
    const glm::dvec2 target(1400.0, 300.0);
    int clickedAt = -1;
    for (int frame = 0; frame < 120 && clickedAt < 0; ++frame) {
        app::Percept percept;
        percept.time = frame / 60.0;
        percept.pointer = game::PointerKind::Cursor;
        percept.pointerAt = cursor;
        app::SeenObject red{scene::kIdFirstSphere, {900.0, 520.0}, 50.0, {0.8, 0.1, 0.1}, 60};
        app::SeenObject green{scene::kIdFirstSphere + 1, target, 50.0, {0.1, 0.8, 0.1}, 60};
        percept.objects = {red, green};
        const game::FrameInput input = participant.act(percept);
        EXPECT_EQ(input.mouseDx, std::round(input.mouseDx));  // whole counts, as a mouse sends
        cursor = glm::clamp(cursor + glm::dvec2(input.mouseDx, input.mouseDy), glm::dvec2(0.0),
                            glm::dvec2(kDisplay.width, kDisplay.height));
        if (input.buttons & game::kButtonLeft) clickedAt = frame;
    }
    ASSERT_GE(clickedAt, 0) << "never clicked; the cursor ended at " << cursor.x << ", " << cursor.y;
    EXPECT_LT(glm::length(cursor - target), 0.7 * 50.0);
    // Not before it could have seen the object (a reaction time) and moved there.
    EXPECT_GT(clickedAt / 60.0, 0.3);
}

// ---------------------------------------------------------------------------------------------
// It knows only what is shown

// act() takes a Percept and nothing else; a ShownFrame (the world as the game keeps it) does not
// convert to one. Only the Eye reads ShownFrames.
static_assert(std::is_invocable_r_v<game::FrameInput, decltype(&app::SimulatedParticipant::act),
                                    app::SimulatedParticipant&, const app::Percept&>);
static_assert(!std::is_invocable_v<decltype(&app::SimulatedParticipant::act), app::SimulatedParticipant&,
                                   const game::ShownFrame&>);
static_assert(!std::is_convertible_v<game::ShownFrame, app::Percept>);

TEST(SimulatedParticipant, ATargetTheFrameDoesNotShowIsNotSeen) {
    const auto study = game::loadStudy(protocolPath("shooter-quick"));
    testing::glContext();
    app::Eye eye(testing::sourceDataPaths(), kDisplay, study->rendering(), 160);
    auto game = study->newGame(3, kDisplay);
    // Turned half round: the game's frame still holds the target, the picture does not.
    const game::ShownFrame shown = game->step({3.14159 / study->mouseRadiansPerCount(), 0, 0, 0});
    ASSERT_FALSE(shown.scene.objects.empty());
    EXPECT_TRUE(eye.see(shown).objects.empty());
    // And in a lagged mode, what is seen is the lagged picture: the target where the frame on
    // screen depicts it, not where the world has it.
    const auto click = game::loadStudy(protocolPath("click-quick"));
    auto lagged = click->newFreePlay(4, kDisplay, "lag200", 0);
    app::Eye eye2(testing::sourceDataPaths(), kDisplay, click->rendering(), 160);
    game::ShownFrame last;
    for (int frame = 0; frame < 60; ++frame) eye2.see(last = lagged->step({}));
    const app::Percept percept = eye2.see(last = lagged->step({}));
    const game::ScreenMapping screen(last.camera, kDisplay);
    const auto* world = dynamic_cast<const game::ClickGame&>(*lagged).world();
    ASSERT_NE(world, nullptr);
    int compared = 0;
    for (const auto& seen : percept.objects)
        for (const auto& o : last.scene.objects)  // the spheres as the frame on screen depicts them
            for (const auto& now : world->spheres())
                if (o.id == seen.id && game::ClickGame::objectId(now) == o.id && glm::length(now.velocity) > 2.0) {
                    const double toShown = glm::length(seen.centre - *screen.project(glm::dvec3(o.position)));
                    const double toWorld = glm::length(seen.centre - *screen.project(now.position));
                    EXPECT_LE(toShown, 3.0 * 12.0) << "sphere " << o.id;
                    EXPECT_GT(toWorld, toShown + 24.0) << "sphere " << o.id;
                    ++compared;
                }
    EXPECT_GE(compared, 1);
}

// ---------------------------------------------------------------------------------------------
// Behaviour

TEST(SimulatedParticipant, WithoutDelayOrNoiseItHitsASlowTargetNearlyAlways) {
    const auto study = shooterAt60();
    EXPECT_GE(hitRate(*study, "conv60", 0, 12, ideal()), 11.0 / 12.0);
}

TEST(SimulatedParticipant, ALongerReactionTimeLowersItsHitRate) {
    // A fast target (level 12, 4 m/s: it bounces about every second), with the default motor
    // noise: predicting it across a longer delay fails more often, at the bounces above all.
    const auto study = shooterAt60();
    app::ParticipantParams quick;
    quick.reactionS = 0.0;
    app::ParticipantParams slow;
    slow.reactionS = 0.4;
    const double quickRate = hitRate(*study, "conv60", 12, 12, quick);
    const double slowRate = hitRate(*study, "conv60", 12, 12, slow);
    // Measured: 12/12 against 5/12 (20 targets: 1.00 against 0.40).
    EXPECT_LT(slowRate, quickRate - 0.3) << "hit rate " << quickRate << " without delay, " << slowRate << " with 0.4 s";
}

// A reticle game made by hand: targets at fixed directions in the world, the view turned by the
// participant's own counts, and the percepts it would get -- the target where the view puts it,
// the pictures left empty, so the view can only be judged by the hand's own turn.
struct HandMadeShooter {
    app::TaskKnowledge knowledge;
    double yaw = 0.0;  // where the view looks, radians (positive: right)
    HandMadeShooter() {
        knowledge.display = kDisplay;
        knowledge.refreshHz = 60.0;
        knowledge.radiansPerCount = 0.0022;
    }
    double focal() const { return 0.5 * kDisplay.height / std::tan(glm::radians(knowledge.verticalFovDeg) / 2.0); }
    app::Percept see(double time, std::optional<double> targetYaw) const {
        app::Percept p;
        p.time = time;
        p.pointer = game::PointerKind::Reticle;
        p.pointerAt = {kDisplay.width * 0.5, kDisplay.height * 0.5};
        if (targetYaw && std::abs(*targetYaw - yaw) < 0.9) {
            const glm::dvec2 at(kDisplay.width * 0.5 + focal() * std::tan(*targetYaw - yaw), kDisplay.height * 0.5);
            p.objects.push_back({scene::kIdTarget, at, 25.0, {0.9, 0.25, 0.15}, 40});
        }
        return p;
    }
    // Acts on the percept; returns the hand's turn this frame, radians per second.
    double act(app::SimulatedParticipant& participant, const app::Percept& percept) {
        const game::FrameInput input = participant.act(percept);
        yaw += input.mouseDx * knowledge.radiansPerCount;
        clicked = (input.buttons & game::kButtonLeft) != 0;
        return std::abs(input.mouseDx) * knowledge.radiansPerCount * knowledge.refreshHz;
    }
    bool clicked = false;  // in the last act()
};

// A target that is suddenly elsewhere -- a new one where the last was shot, or the view
// misjudged -- is a jump, not a speed: aiming at it must not fling the view (before, a 0.5 rad
// jump between two frames was fitted as 30 rad/s and the view turned away for good).
TEST(SimulatedParticipant, AJumpInWhatItSeesIsNotTakenForMotion) {
    HandMadeShooter world;
    app::ParticipantParams params = ideal();
    params.reactionS = 0.2;
    app::SimulatedParticipant participant(world.knowledge, params, 3);
    double fastest = 0.0;
    int clicksOnTarget = 0;
    for (int frame = 0; frame < 120; ++frame) {
        // Appearing at 1 s, drifting right at 0.2 rad/s (every frame shows it somewhere new),
        // and two frames later suddenly half a radian to the left.
        const double t = frame / 60.0;
        const double targetYaw = (frame < 63 ? 0.1 : -0.4) + 0.2 * t;
        const std::optional<double> shown = frame < 60 ? std::nullopt : std::optional<double>(targetYaw);
        fastest = std::max(fastest, world.act(participant, world.see(t, shown)));
        // On it at the next frame, where the press counts (the target's radius: 25 px, 0.027 rad).
        clicksOnTarget += world.clicked && std::abs(world.yaw - (targetYaw + 0.2 / 60.0)) < 0.027;
    }
    // Following at 0.2 rad/s and closing the 0.5 rad seen at correctionPerS (8/s): 4.2 rad/s.
    EXPECT_LE(fastest, 4.5);
    EXPECT_EQ(clicksOnTarget, 1) << "it did not shoot the target where it jumped to";
}

// Turned far from where it started, with nothing in view and no picture it recognises, it turns
// back by how far its hand has turned, to where targets appear.
TEST(SimulatedParticipant, LostItTurnsBackByItsHandsOwnTurn) {
    HandMadeShooter world;
    app::SimulatedParticipant participant(world.knowledge, ideal(), 5);
    int frame = 0;
    for (; frame < 120 && world.yaw < 0.6; ++frame)  // a target draws it far right ...
        world.act(participant, world.see(frame / 60.0, 0.7));
    ASSERT_GE(world.yaw, 0.6);
    const int gone = frame;
    for (; frame < gone + 120; ++frame) world.act(participant, world.see(frame / 60.0, std::nullopt));  // ... and is gone
    EXPECT_LE(std::abs(world.yaw), glm::radians(ideal().homeWithinDeg) + 0.01);
}

// ---------------------------------------------------------------------------------------------
// Determinism

std::vector<game::FrameInput> inputsOf(const game::Study& study, std::uint64_t sessionSeed, std::uint64_t playerSeed,
                                       int frames) {
    auto game = study.newGame(sessionSeed, kDisplay);
    auto player = playerFor(study, playerSeed);
    std::vector<game::FrameInput> inputs{player.first()};
    for (int frame = 0; frame < frames && !game->finished(); ++frame)
        inputs.push_back(player.next(game->step(inputs.back())));
    return inputs;
}

bool sameBytes(const std::vector<game::FrameInput>& a, const std::vector<game::FrameInput>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::memcmp(&a[i].mouseDx, &b[i].mouseDx, sizeof(double)) != 0 ||
            std::memcmp(&a[i].mouseDy, &b[i].mouseDy, sizeof(double)) != 0 || a[i].buttons != b[i].buttons ||
            a[i].keys != b[i].keys)
            return false;
    return true;
}

TEST(SimulatedParticipant, TheSameSeedGivesTheSameInputsAndAnotherSeedOthers) {
    for (const char* name : {"shooter-quick", "click-quick"}) {
        const auto study = game::loadStudy(protocolPath(name));
        const auto first = inputsOf(*study, 5, 9, 300);
        const auto again = inputsOf(*study, 5, 9, 300);
        EXPECT_TRUE(sameBytes(first, again)) << name;
        EXPECT_FALSE(sameBytes(first, inputsOf(*study, 5, 10, 300))) << name << ": the player's seed changes nothing";
        int moved = 0, presses = 0;
        for (const auto& in : first) {
            moved += in.mouseDx != 0.0 || in.mouseDy != 0.0;
            presses += in.buttons != 0 || in.keys != 0;
        }
        EXPECT_GT(moved, 100) << name;
        EXPECT_GE(presses, 1) << name;
    }
}

}  // namespace
}  // namespace warplab
