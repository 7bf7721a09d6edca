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
#include <nlohmann/json.hpp>

#include "participants/eye.h"
#include "participants/population.h"
#include "participants/ideal_params.h"
#include "click_game.h"
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

participants::PerceptualPlayer playerFor(const game::Study& study, std::uint64_t seed,
                                         const participants::ParticipantParams& params = {}) {
    testing::glContext();  // the player draws in the context current on this thread
    return participants::PerceptualPlayer(nullptr, study, kDisplay, testing::sourceDataPaths(), seed, params);
}

// Plays free-play targets at `level` in `mode` until `targets` trials have ended; the share of
// them hit as displayed (the scored outcome of the shooter's protocols).
double hitRate(const game::Study& study, const std::string& condition, int level, int targets,
               const participants::ParticipantParams& params, std::uint64_t seed = 1) {
    auto game = study.newFreePlay(seed, kDisplay, condition, level);
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
    participants::Eye eye(testing::sourceDataPaths(), kDisplay, study->rendering(), 160);
    const double perceptPx = static_cast<double>(kDisplay.width) / eye.width();
    auto game = study->newGame(3, kDisplay);
    int checked = 0, sized = 0;
    double worst = 0.0;
    for (int frame = 0; frame < 240; ++frame) {
        // Turn a little every frame, so the target is seen in many places in the view.
        const game::ShownFrame shown = game->step({frame % 80 < 40 ? 2.0 : -2.0, frame % 40 < 20 ? 1.0 : -1.0, 0, 0});
        const participants::Percept percept = eye.see(shown);
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
        const participants::SeenObject& seen = percept.objects.front();
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
    participants::Eye eye(testing::sourceDataPaths(), kDisplay, study->rendering(), 160);
    const double perceptPx = static_cast<double>(kDisplay.width) / eye.width();
    auto game = study->newFreePlay(2, kDisplay, "conv60", 0);
    int checked = 0, green = 0;
    double worst = 0.0;
    for (int frame = 0; frame < 150; ++frame) {
        const game::ShownFrame shown = game->step({});
        const participants::Percept percept = eye.see(shown);
        if (frame % 10 != 0) continue;
        const game::ScreenMapping screen(shown.camera, kDisplay);
        for (const auto& o : shown.scene.objects) {
            const glm::dvec3 centre(o.position);
            const auto truth = screen.project(centre);
            const participants::SeenObject* seen = nullptr;
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
    participants::Eye eye(testing::sourceDataPaths(), kDisplay, study->rendering(), 160);
    auto game = study->newGame(3, kDisplay);
    const participants::Percept home = eye.see(game->step({}));
    // Turn by a known number of counts, then compare the views: the start view's centre must be
    // found where the turn puts it, within a cell of the picture (4 percept pixels, ~2.7 degrees:
    // enough to turn back to where targets appear).
    const double radiansPerCount = study->mouseRadiansPerCount();
    const double f = 0.5 * kDisplay.height / std::tan(glm::radians(30.0));
    for (const glm::dvec2 counts : {glm::dvec2(40, 0), glm::dvec2(-90, 0), glm::dvec2(0, 40), glm::dvec2(60, -50)}) {
        auto turned = study->newGame(3, kDisplay);
        participants::Eye eye2(testing::sourceDataPaths(), kDisplay, study->rendering(), 160);
        const participants::Percept now = eye2.see(turned->step({counts.x, counts.y, 0, 0}));
        const auto shift = participants::whereViewIs(home.picture, now.picture);
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

// ---------------------------------------------------------------------------------------------
// It knows only what is shown

// act() takes a Percept and nothing else; a ShownFrame (the world as the game keeps it) does not
// convert to one. Only the Eye reads ShownFrames.
static_assert(std::is_invocable_r_v<game::FrameInput, decltype(&participants::SimulatedParticipant::act),
                                    participants::SimulatedParticipant&, const participants::Percept&>);
static_assert(!std::is_invocable_v<decltype(&participants::SimulatedParticipant::act),
                                   participants::SimulatedParticipant&, const game::ShownFrame&>);
static_assert(!std::is_convertible_v<game::ShownFrame, participants::Percept>);

TEST(SimulatedParticipant, ATargetTheFrameDoesNotShowIsNotSeen) {
    const auto study = game::loadStudy(protocolPath("shooter-quick"));
    testing::glContext();
    participants::Eye eye(testing::sourceDataPaths(), kDisplay, study->rendering(), 160);
    auto game = study->newGame(3, kDisplay);
    // Turned half round: the game's frame still holds the target, the picture does not.
    const game::ShownFrame shown = game->step({3.14159 / study->mouseRadiansPerCount(), 0, 0, 0});
    ASSERT_FALSE(shown.scene.objects.empty());
    EXPECT_TRUE(eye.see(shown).objects.empty());
    // And in a lagged condition, what is seen is the lagged picture: the target where the frame on
    // screen depicts it, not where the world has it.
    const auto click = game::loadStudy(protocolPath("click-quick"));
    auto lagged = click->newFreePlay(4, kDisplay, "lag200", 0);
    participants::Eye eye2(testing::sourceDataPaths(), kDisplay, click->rendering(), 160);
    game::ShownFrame last;
    for (int frame = 0; frame < 60; ++frame) eye2.see(last = lagged->step({}));
    const participants::Percept percept = eye2.see(last = lagged->step({}));
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

// A world changed where the frame does not show it -- every object's velocity, the condition's name,
// the outcome the game has judged -- with the pictures unchanged: the same actions, to the bit.
// An eye that let any of it through to the participant would make them differ.
TEST(SimulatedParticipant, AChangedWorldWithIdenticalFramesGivesIdenticalActions) {
    const auto study = shooterAt60();
    auto game = study->newFreePlay(2, kDisplay, "conv60", 12);
    auto honest = playerFor(*study, 4);
    auto fooled = playerFor(*study, 4);
    game::FrameInput input = honest.first();
    fooled.first();
    int moved = 0, presses = 0;
    for (int frame = 0; frame < 360; ++frame) {
        const game::ShownFrame shown = game->step(input);
        game::ShownFrame changed = shown;
        changed.condition.name = "another";
        changed.feedback = shown.feedback.empty() ? "" : "timeout";
        for (auto* snapshot : {&changed.scene, &changed.render.scene})
            for (auto& o : snapshot->objects) {
                o.velocity = -3.0f * o.velocity + glm::vec3(5.0f, 0.0f, 1.0f);
                o.angularVelocity = glm::vec3(9.0f);
            }
        input = honest.next(shown);
        const game::FrameInput other = fooled.next(changed);
        ASSERT_EQ(std::memcmp(&input.mouseDx, &other.mouseDx, sizeof(double)), 0) << "frame " << frame;
        ASSERT_EQ(std::memcmp(&input.mouseDy, &other.mouseDy, sizeof(double)), 0) << "frame " << frame;
        ASSERT_EQ(input.buttons, other.buttons) << "frame " << frame;
        moved += input.mouseDx != 0.0;
        presses += input.buttons != 0;
    }
    EXPECT_GT(moved, 120);  // it played: the comparison is of actions, not of idleness
    EXPECT_GE(presses, 2);
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
    participants::ParticipantParams quick;
    quick.reactionS = 0.0;
    participants::ParticipantParams slow;
    slow.reactionS = 0.4;
    const double quickRate = hitRate(*study, "conv60", 12, 12, quick);
    const double slowRate = hitRate(*study, "conv60", 12, 12, slow);
    // Measured: 12/12 against 5/12 (20 targets: 1.00 against 0.40).
    EXPECT_LT(slowRate, quickRate - 0.3) << "hit rate " << quickRate << " without delay, " << slowRate << " with 0.4 s";
}

// The demo's shooter calibrates its difficulty as the thesis did (seed 004 §5.3.3): its
// training staircase raises the target's speed until the 120 Hz misses outnumber the 15 Hz
// hits, so the test runs where 120 Hz is not saturated. A participant drawn from the shipped
// population, as `warplab demo` draws them.
TEST(SimulatedParticipant, TheDemoShootersStaircaseEndsWhere120HzIsNotSaturated) {
    const auto study = game::loadStudy(protocolPath("shooter-demo"));
    const auto population =
        participants::readPopulation(participants::populationPath(testing::sourceDataPaths().assetDir));
    constexpr std::uint64_t kSeed = 3;
    testing::glContext();
    participants::PerceptualPlayer player(nullptr, *study, kDisplay, testing::sourceDataPaths(), kSeed,
                                          participants::drawParticipant(population, kSeed));
    auto game = study->newGame(kSeed, kDisplay);
    game::FrameInput input = player.first();
    std::vector<nlohmann::json> levels;
    bool limited = false;
    for (int frame = 0; frame < 400 * 120 && game->phase() != "test"; ++frame) {
        const game::ShownFrame shown = game->step(input);
        for (const auto& e : game->takeEvents()) {
            if (e.type == "level") levels.push_back(nlohmann::json::parse(e.detailJson));
            limited = limited || e.type == "training_limit";
        }
        input = player.next(shown);
    }
    ASSERT_EQ(game->phase(), "test");
    ASSERT_FALSE(levels.empty());
    EXPECT_FALSE(limited) << "the staircase ran out of time at level " << levels.back()["difficulty"];
    const auto& last = levels.back();
    // Stopped by the thesis's rule, above where it started ...
    EXPECT_GT(last["high_miss_rate"].get<double>(), last["low_hit_rate"].get<double>());
    EXPECT_GT(last["difficulty"].get<int>(), levels.front()["difficulty"].get<int>());
    // ... where 120 Hz misses: a hit rate below 0.9 (measured: 0.5 at level 13, 4 shots).
    EXPECT_LT(1.0 - last["high_miss_rate"].get<double>(), 0.9);
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
