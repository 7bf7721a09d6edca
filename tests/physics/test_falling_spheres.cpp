// The click game's falling spheres (physics/falling_spheres.h): the hard cases of
// docs/click-physics.md, each against an independent expectation (a closed-form parabola, the
// textbook two-body and simultaneous-impact answers, conservation laws, a binomial bound)
// rather than the model's own formulas. Every tolerance says why it is that size.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <glm/glm.hpp>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/falling_spheres.h"

namespace warplab::physics {
namespace {

const FallingSphereSettings kDefaults;
const double kFloorY = kDefaults.box.min.y + kDefaults.radius;  // centre of a sphere on the floor
const double kMidZ = 0.5 * (kDefaults.box.min.z + kDefaults.box.max.z);
const double kStep = 1.0 / kDefaults.stepRateHz;
// How far gravity pulls a sphere resting on something during one step before the contact
// puts it back: the scale of everything a resting contact may do.
const double kOneStepSag = 0.5 * kDefaults.gravity * kStep * kStep;  // 5.3 micrometres

Sphere makeSphere(std::uint32_t id, glm::dvec3 position, glm::dvec3 velocity = glm::dvec3(0.0)) {
    Sphere sphere;
    sphere.id = id;
    sphere.position = position;
    sphere.velocity = velocity;
    return sphere;
}

double totalEnergy(const FallingSpheres& world) { return world.kineticEnergy() + world.potentialEnergy(); }

std::int64_t stepsFor(const FallingSphereSettings& settings, double seconds) {
    return static_cast<std::int64_t>(std::llround(seconds * settings.stepRateHz));
}

// The fastest a sphere gets in the game, worked out from the settings: it enters at the top
// moving down at up to spawnSpeed with up to spawnSpeed sideways, and falls the whole height.
double fastestSpeed(const FallingSphereSettings& s) {
    const double drop = (s.box.max.y - s.box.min.y) - 2.0 * s.radius;
    const double down = std::sqrt(s.spawnSpeed * s.spawnSpeed + 2.0 * s.gravity * drop);
    return std::sqrt(down * down + s.spawnSpeed * s.spawnSpeed);
}

// The whole sphere inside the box, compared exactly: a sphere must never leave it.
void expectAllInsideBox(const FallingSpheres& world, const std::string& when) {
    const FallingSphereSettings& s = world.settings();
    for (const Sphere& sphere : world.spheres()) {
        for (int axis = 0; axis < 3; ++axis) {
            ASSERT_GE(sphere.position[axis], s.box.min[axis] + s.radius)
                << "sphere " << sphere.id << " axis " << axis << " " << when;
            ASSERT_LE(sphere.position[axis], s.box.max[axis] - s.radius)
                << "sphere " << sphere.id << " axis " << axis << " " << when;
        }
    }
}

template <typename F>
void expectInvalidArgumentNaming(F&& call, const std::string& name) {
    try {
        call();
        ADD_FAILURE() << "expected std::invalid_argument naming " << name;
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find(name), std::string::npos)
            << "message '" << e.what() << "' does not name " << name;
    }
}

// ---------------------------------------------------------------------------------------
// Hard case 1: stacks at rest stay at rest

struct RestReport {
    double moved = 0.0;  // furthest any sphere got from where it started, m
    double overlapLeft = 0.0;  // deepest overlap after a step, m
    double sagInStep = 0.0;  // deepest contact within a step, before it is resolved, m
    double speed = 0.0;  // fastest any sphere moved, m/s
};

RestReport holdForAMinute(const FallingSphereSettings& settings, const std::vector<Sphere>& stack) {
    FallingSpheres world(settings, stack, false);
    RestReport report;
    const std::int64_t steps = stepsFor(settings, 60.0);
    for (std::int64_t k = 0; k < steps; ++k) {
        world.step();
        for (std::size_t i = 0; i < stack.size(); ++i) {
            const Sphere& sphere = world.spheres()[i];
            report.moved = std::max(report.moved, glm::length(sphere.position - stack[i].position));
            report.speed = std::max(report.speed, glm::length(sphere.velocity));
        }
        report.overlapLeft = std::max(report.overlapLeft, world.maxPenetration());
        report.sagInStep = std::max(report.sagInStep, world.lastStepContactDepth());
    }
    return report;
}

// A minute is 57,600 steps: anything that creeps, sinks or jitters shows up well beyond
// these. Two steps' sag (10.6 um, about 1/700 of a pixel at the box with the game's camera)
// bounds position and overlap; 1 mm/s bounds speed (gravity adds 10 mm/s every step, and the
// resting contacts must take it out again: at 1 mm/s a sphere moves 17 um per 60 Hz frame).
constexpr double kRestSpeed = 1e-3;

void expectAtRest(const RestReport& r) {
    EXPECT_LE(r.moved, 2.0 * kOneStepSag);
    EXPECT_LE(r.overlapLeft, 2.0 * kOneStepSag);
    // Within a step a resting contact sinks by one step's sag, the spheres above it by theirs
    // on top of it.
    EXPECT_LE(r.sagInStep, 2.0 * kOneStepSag);
    EXPECT_LE(r.speed, kRestSpeed);
}

TEST(FallingSpheresRest, ColumnOfThreeStaysPutForAMinute) {
    const double r = kDefaults.radius;
    const std::vector<Sphere> column = {makeSphere(0, {0.0, kFloorY, kMidZ}),
                                        makeSphere(1, {0.0, kFloorY + 2.0 * r, kMidZ}),
                                        makeSphere(2, {0.0, kFloorY + 4.0 * r, kMidZ})};
    expectAtRest(holdForAMinute(kDefaults, column));
}

TEST(FallingSpheresRest, PyramidBetweenTwoWallsStaysPutForAMinute) {
    // Three on the floor touching, held by walls exactly three diameters apart, two on top in
    // the grooves. Without friction the walls are what make it stable: in a wider box the
    // top spheres would push the row apart and fall through.
    FallingSphereSettings settings = kDefaults;
    const double r = settings.radius;
    settings.box.min.x = -3.0 * r;
    settings.box.max.x = 3.0 * r;
    const double grooveY = kFloorY + 2.0 * r * std::sqrt(3.0) / 2.0;
    const std::vector<Sphere> pyramid = {makeSphere(0, {-2.0 * r, kFloorY, kMidZ}),
                                         makeSphere(1, {0.0, kFloorY, kMidZ}), makeSphere(2, {2.0 * r, kFloorY, kMidZ}),
                                         makeSphere(3, {-r, grooveY, kMidZ}), makeSphere(4, {r, grooveY, kMidZ})};
    expectAtRest(holdForAMinute(settings, pyramid));
}

TEST(FallingSpheresRest, SphereLandingSlowlyStaysDownInsteadOfMicroBouncing) {
    // Landing from 0.2 mm (0.063 m/s) at restitution 1: below the resting threshold, so the
    // contact is plastic; without it the sphere would hop 0.2 mm high for ever.
    FallingSphereSettings settings = kDefaults;
    settings.restitution = 1.0;
    FallingSpheres world(settings, {makeSphere(0, {0.0, kFloorY + 2e-4, kMidZ})}, false);
    world.advance(stepsFor(settings, 1.0));
    const Sphere& sphere = world.spheres()[0];
    // On the floor the contact puts it back exactly where it was each step, bar rounding.
    EXPECT_NEAR(sphere.position.y, kFloorY, 1e-12);
    EXPECT_LE(std::fabs(sphere.velocity.y), 1e-9);
}

// ---------------------------------------------------------------------------------------
// Hard case 2: several contacts at once

TEST(FallingSpheresContacts, StrikerIntoATouchingRowConservesMomentumAndTheSimultaneousAnswer) {
    // A striker hits the end of a row of three touching spheres on the floor. All contacts
    // of a touching row act at once, so the exact answer is the simultaneous-impact one: the
    // row leaves as one body at V(1 + e)/(n + 1), the striker at V(1 - n e)/(n + 1). (A real
    // Newton's cradle has gaps; that case is the next test.)
    for (const double e : {0.0, 0.5, 0.7, 1.0}) {
        SCOPED_TRACE("restitution " + std::to_string(e));
        FallingSphereSettings settings = kDefaults;
        settings.restitution = e;
        const double r = settings.radius, v = 3.0;
        FallingSpheres world(
            settings,
            {makeSphere(0, {-2.0, kFloorY, kMidZ}, {v, 0.0, 0.0}), makeSphere(1, {0.0, kFloorY, kMidZ}),
             makeSphere(2, {2.0 * r, kFloorY, kMidZ}), makeSphere(3, {4.0 * r, kFloorY, kMidZ})},
            false);
        const double energyBefore = totalEnergy(world);
        for (int k = 0; k < 480; ++k) {  // 0.5 s: the hit is at 0.37 s, no side wall is reached
            world.step();
            double momentum = 0.0;
            for (const Sphere& sphere : world.spheres()) momentum += sphere.velocity.x;
            // Contact impulses come in equal and opposite pairs and the floor pushes straight
            // up, so only rounding (1e-16 of 3 m/s per operation) may change it.
            ASSERT_NEAR(momentum, v, 1e-12) << "step " << k;
            for (int i = 0; i + 1 < 4; ++i) {
                ASSERT_LT(world.spheres()[i].position.x, world.spheres()[i + 1].position.x)
                    << "spheres " << i << " and " << i + 1 << " passed through, step " << k;
            }
            // What the overlap correction's last sweep leaves: a fraction of one step's
            // travel at 3 m/s (3 mm), far below anything visible.
            ASSERT_LE(world.maxPenetration(), 1e-6) << "step " << k;
        }
        EXPECT_LE(totalEnergy(world), energyBefore + 1e-12);
        // 20 Gauss-Seidel sweeps get within ~1e-6 of the converged impulses.
        const double n = 3.0;
        EXPECT_NEAR(world.spheres()[0].velocity.x, v * (1.0 - n * e) / (n + 1.0), 1e-4);
        for (int i = 1; i < 4; ++i) {
            EXPECT_NEAR(world.spheres()[i].velocity.x, v * (1.0 + e) / (n + 1.0), 1e-4);
        }
    }
}

TEST(FallingSpheresContacts, NewtonsCradleWithGapsPassesTheMomentumToTheLastSphere) {
    // With 1 cm gaps the hits are separate two-body collisions a few steps apart; at
    // restitution 1 each one stops the hitter and the last sphere leaves at the striker's
    // speed: the classic cradle.
    FallingSphereSettings settings = kDefaults;
    settings.restitution = 1.0;
    const double spacing = 2.0 * settings.radius + 0.01, v = 3.0;
    FallingSpheres world(settings,
                         {makeSphere(0, {-2.0, kFloorY, kMidZ}, {v, 0.0, 0.0}), makeSphere(1, {0.0, kFloorY, kMidZ}),
                          makeSphere(2, {spacing, kFloorY, kMidZ}), makeSphere(3, {2.0 * spacing, kFloorY, kMidZ})},
                         false);
    world.advance(480);
    // Each binary collision along an exact axis is exact bar rounding.
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(world.spheres()[i].velocity.x, 0.0, 1e-12) << i;
    EXPECT_NEAR(world.spheres()[3].velocity.x, v, 1e-12);
    EXPECT_NEAR(world.kineticEnergy(), 0.5 * v * v, 1e-9);
}

TEST(FallingSpheresContacts, SphereDroppedIntoTheGrooveOfTwoHitsBothAlike) {
    // C falls 1 m onto A and B, which touch on the floor; it meets both at the same instant,
    // along normals 30 degrees from vertical. Exact simultaneous answer (frictionless, floor
    // holding A and B down): each of A, B leaves sideways at sqrt(3) (1 + e) w / 7, where w is
    // C's speed at the touch, and C goes straight up or down, never sideways.
    for (const double e : {0.7, 1.0}) {
        SCOPED_TRACE("restitution " + std::to_string(e));
        FallingSphereSettings settings = kDefaults;
        settings.restitution = e;
        const double r = settings.radius, drop = 1.0;
        FallingSpheres world(settings,
                             {makeSphere(0, {-r, kFloorY, kMidZ}), makeSphere(1, {r, kFloorY, kMidZ}),
                              makeSphere(2, {0.0, kFloorY + std::sqrt(3.0) * r + drop, kMidZ})},
                             false);
        const double w = std::sqrt(2.0 * settings.gravity * drop);
        const double sideways = std::sqrt(3.0) * (1.0 + e) * w / 7.0;
        bool hit = false;
        for (int k = 0; k < 960; ++k) {
            world.step();
            const Sphere& a = world.spheres()[0];
            const Sphere& b = world.spheres()[1];
            const Sphere& c = world.spheres()[2];
            ASSERT_NEAR(a.velocity.x + b.velocity.x + c.velocity.x, 0.0, 1e-12) << "step " << k;
            // Mirror symmetry. The impulses converge to it (20 sweeps: ~1e-5 m/s left); the
            // overlap correction, also swept in a fixed order, settles a little to one side
            // (measured 0.05 mm; 0.1 mm is 1/90 of a pixel).
            ASSERT_NEAR(a.velocity.x, -b.velocity.x, 1e-4) << "step " << k;
            ASSERT_NEAR(c.position.x, 0.0, 1e-4) << "step " << k;
            ASSERT_LE(world.maxPenetration(), 1e-6) << "step " << k;
            if (!hit && b.velocity.x > 0.0) {
                hit = true;
                // C is sped up by gravity until the step in which the touch is seen: up to
                // g dt = 0.01 m/s, 0.2% of w; the floor's sag adds as much again.
                EXPECT_NEAR(b.velocity.x, sideways, 0.01 * sideways);
            }
        }
        EXPECT_TRUE(hit);
    }
}

// ---------------------------------------------------------------------------------------
// Hard case 3: energy never rises

TEST(FallingSpheresEnergy, NeverRisesAndAtRestitutionOneBarelyFalls) {
    for (const double e : {0.0, 0.5, 0.9, 1.0}) {
        SCOPED_TRACE("restitution " + std::to_string(e));
        FallingSphereSettings settings = kDefaults;
        settings.restitution = e;
        FallingSpheres world(settings, 7);  // no remove(), so nothing ever enters
        const double start = totalEnergy(world);
        double highest = start;
        const std::int64_t steps = stepsFor(settings, 20.0);
        for (std::int64_t k = 0; k < steps; ++k) {
            world.step();
            highest = std::max(highest, totalEnergy(world));
            // In exact arithmetic the flight between contacts keeps the energy (the update is
            // the exact parabola) and every contact keeps or loses it; 19,200 steps of
            // rounding at 1e-16 of the total stay far below 1e-12 of it.
            ASSERT_LE(totalEnergy(world), start + 1e-12 * start) << "step " << k;
        }
        RecordProperty("highest_rise_" + std::to_string(static_cast<int>(e * 10)), std::to_string(highest - start));
        if (e == 1.0) {
            // Where nothing should be lost, the model loses only what its resting threshold
            // and the unconverged rest of simultaneous contacts take: measured 0.04% over
            // these 20 s, and the step table follows it over 60 s at every rate.
            EXPECT_GE(totalEnergy(world), 0.99 * start);
        }
    }
}

TEST(FallingSpheresEnergy, HitIntoANeighbourAlreadyMovingAwayGivesNoEnergy) {
    // C hits B, which touches A while A drifts away from it. Holding A and B together (the
    // usual "keep every touching contact from closing") would do work on that separating
    // pair: at restitution 1 the total would rise by about 1%. No gravity, mid-air: only the
    // three spheres' kinetic energy is in play.
    FallingSphereSettings settings = kDefaults;
    settings.gravity = 0.0;
    settings.restitution = 1.0;
    const double r = settings.radius, v = 3.0, drift = 0.05;
    const glm::dvec3 centre(0.0, 4.75, kMidZ);
    FallingSpheres world(
        settings,
        {makeSphere(0, centre, {-drift, 0.0, 0.0}), makeSphere(1, centre + glm::dvec3(2.0 * r, 0.0, 0.0)),
         makeSphere(2, centre + glm::dvec3(4.0 * r + 0.5 * v * kStep, 0.0, 0.0), {-v, 0.0, 0.0})},
        false);
    const double before = world.kineticEnergy();
    for (int k = 0; k < 96; ++k) {
        world.step();
        // Rounding only (1e-16 of 4.5 J/kg per operation).
        ASSERT_LE(world.kineticEnergy(), before + 1e-12) << "step " << k;
        double momentum = 0.0;
        for (const Sphere& sphere : world.spheres()) momentum += sphere.velocity.x;
        ASSERT_NEAR(momentum, -v - drift, 1e-12) << "step " << k;
    }
    EXPECT_LT(world.spheres()[0].velocity.x, -drift) << "the hit should have reached A";
}

// ---------------------------------------------------------------------------------------
// Hard case 4: the fastest spheres never pass through anything

TEST(FallingSpheresFast, FastestSpeedIsWorkedOutFromTheSettings) {
    // 7.6 m of fall after entering at 2 m/s down and 2 m/s sideways.
    EXPECT_NEAR(fastestSpeed(kDefaults), std::sqrt(8.0 + 2.0 * 9.81 * 7.6), 1e-12);
    EXPECT_NEAR(fastestSpeed(kDefaults), 12.53, 0.01);
}

struct FastCase {
    std::string name;
    double closingFactor;  // closing speed in units of the firing speed
    double drop;  // how far gravity pulls it towards the hit first, m
    std::vector<Sphere> spheres;
    // Not negative while nothing has passed through: the relative position along the
    // approach axis (for the floor, the height of the centre above the floor contact, which
    // is 0 while touching).
    std::function<double(const FallingSpheres&)> side;
};

TEST(FallingSpheresFast, FastestSpheresNeverLeaveTheBoxNorPassThrough) {
    for (const int rate : {120, 960}) {  // the lowest rate in the step table and the default
        for (const double factor : {1.0, 2.0}) {
            FallingSphereSettings settings = kDefaults;
            settings.stepRateHz = rate;
            const double v = factor * fastestSpeed(settings);
            const double r = settings.radius;
            const double dt = 1.0 / rate;
            const glm::dvec3 corner = glm::normalize(glm::dvec3(-1.0, -1.0, -1.0));
            std::vector<FastCase> cases;
            cases.push_back({"straight down at the floor",
                             1.0,
                             2.0,
                             {makeSphere(0, {0.0, kFloorY + 2.0, kMidZ}, {0.0, -v, 0.0})},
                             [](const FallingSpheres& w) { return w.spheres()[0].position.y - kFloorY; }});
            cases.push_back({"into the floor corner",
                             1.0,
                             1.2,
                             {makeSphere(0, {0.0, kFloorY + 1.2, kMidZ}, v * corner)},
                             [](const FallingSpheres& w) { return w.spheres()[0].position.y - kFloorY; }});
            cases.push_back(
                {"head-on at each other",
                 2.0,
                 0.0,
                 {makeSphere(0, {-2.0, 4.0, kMidZ}, {v, 0.0, 0.0}), makeSphere(1, {2.0, 4.0, kMidZ}, {-v, 0.0, 0.0})},
                 [](const FallingSpheres& w) { return w.spheres()[1].position.x - w.spheres()[0].position.x; }});
            cases.push_back(
                {"down onto a sphere resting on the floor",
                 1.0,
                 2.0,
                 {makeSphere(0, {0.0, kFloorY, kMidZ}),
                  makeSphere(1, {0.0, kFloorY + 2.0 * r + 2.0, kMidZ}, {0.0, -v, 0.0})},
                 [](const FallingSpheres& w) { return w.spheres()[1].position.y - w.spheres()[0].position.y; }});
            for (const FastCase& c : cases) {
                SCOPED_TRACE(c.name + " at " + std::to_string(factor) + "x the fastest speed, " + std::to_string(rate) +
                             " Hz");
                FallingSpheres world(settings, c.spheres, false);
                // Contacts are found after the step that makes them, so none is deeper than
                // one step's closing travel at the speed of the hit (the firing speed plus
                // what gravity added on the way; both spheres moving: twice), plus gravity's
                // part within the step.
                const double hitSpeed = std::sqrt(v * v + 2.0 * settings.gravity * c.drop);
                const double deepestAllowed = c.closingFactor * hitSpeed * dt + settings.gravity * dt * dt;
                for (int k = 0; k < rate / 2; ++k) {  // 0.5 s: every hit is within 0.2 s
                    world.step();
                    expectAllInsideBox(world, "step " + std::to_string(k));
                    ASSERT_GE(c.side(world), 0.0) << "passed through at step " << k;
                    ASSERT_LE(world.lastStepContactDepth(), deepestAllowed) << "step " << k;
                    // Overlap left after a step: an isolated pair or a sphere against a wall is
                    // resolved in one sweep of the correction; a sphere pressed onto one that
                    // rests on the floor has half its overlap left after each sweep (the lower
                    // one gives way by half, the floor pushes it back), so 2^-sweeps of the
                    // deepest contact. The spheres are separating by then: the next step
                    // finishes it.
                    ASSERT_LE(world.maxPenetration(), std::ldexp(deepestAllowed, -settings.positionIterations))
                        << "step " << k;
                }
            }
        }
    }
}

TEST(FallingSpheresFast, HeadOnHitExchangesExactlyAtAnyRate) {
    // Equal masses meeting head-on at +-v leave at -+e v: the textbook answer.
    for (const int rate : {120, 960}) {
        FallingSphereSettings settings = kDefaults;
        settings.stepRateHz = rate;
        const double v = 2.0 * fastestSpeed(settings), e = settings.restitution;
        FallingSpheres world(
            settings,
            {makeSphere(0, {-2.0, 4.0, kMidZ}, {v, 0.0, 0.0}), makeSphere(1, {2.0, 4.0, kMidZ}, {-v, 0.0, 0.0})},
            false);
        world.advance(rate / 5);  // they meet after 0.06 s
        EXPECT_NEAR(world.spheres()[0].velocity.x, -e * v, 1e-12) << rate << " Hz";
        EXPECT_NEAR(world.spheres()[1].velocity.x, e * v, 1e-12) << rate << " Hz";
    }
}

// ---------------------------------------------------------------------------------------
// Against exact solutions: flight, floor bounce, glancing hit

TEST(FallingSpheresExact, FlightIsTheExactParabola) {
    const glm::dvec3 start(-3.0, 2.0, kMidZ), velocity(1.5, 6.0, 0.25);
    FallingSpheres world(kDefaults, {makeSphere(0, start, velocity)}, false);
    for (int k = 1; k <= 900; ++k) {  // 0.94 s, before it lands
        world.step();
        const double t = k * kStep;
        const glm::dvec3 exact = start + velocity * t + glm::dvec3(0.0, -0.5 * 9.81 * t * t, 0.0);
        // One rounding per step in a sum of ~1e3 steps of ~1e-2 m: 1e-12 m is generous.
        ASSERT_NEAR(world.spheres()[0].position.x, exact.x, 1e-12) << k;
        ASSERT_NEAR(world.spheres()[0].position.y, exact.y, 1e-12) << k;
        ASSERT_NEAR(world.spheres()[0].position.z, exact.z, 1e-12) << k;
        ASSERT_NEAR(world.spheres()[0].velocity.y, velocity.y - 9.81 * t, 1e-12) << k;
    }
    EXPECT_EQ(world.time(), 900.0 / 960.0);  // a division, not a sum of steps
}

TEST(FallingSpheresExact, FloorBounceRisesExactlyAsHighAndLagsAtMostOneStep) {
    // Dropped from the top at the fastest entry speed, at 16 points of contact within a step.
    const double g = kDefaults.gravity, e = kDefaults.restitution;
    const double v0 = -kDefaults.spawnSpeed;
    for (int phase = 0; phase < 16; ++phase) {
        SCOPED_TRACE("phase " + std::to_string(phase));
        const double height = (kDefaults.box.max.y - kDefaults.radius - kFloorY) - 0.75 * kStep * phase;
        FallingSpheres world(kDefaults, {makeSphere(0, {0.0, kFloorY + height, kMidZ}, {0.0, v0, 0.0})}, false);
        const double impactSpeed = std::sqrt(v0 * v0 + 2.0 * g * height);
        const double impactTime = (v0 + impactSpeed) / g;
        const double landingTime = impactTime + 2.0 * e * impactSpeed / g;
        double apex = 0.0, worst = 0.0;
        while (world.time() < landingTime - 2.0 * kStep) {
            world.step();
            const double t = world.time();
            const double after = t - impactTime;
            const double exactY = t < impactTime ? kFloorY + height + v0 * t - 0.5 * g * t * t
                                                 : kFloorY + e * impactSpeed * after - 0.5 * g * after * after;
            const double y = world.spheres()[0].position.y;
            worst = std::max(worst, std::fabs(y - exactY));
            if (t > impactTime) apex = std::max(apex, y - kFloorY);
        }
        // The rebound speed is restitution times the speed at the instant of contact, so the
        // apex is exact; sampling at step ends misses the very top by up to g dt^2 / 8.
        const double exactApex = std::pow(e * impactSpeed, 2) / (2.0 * g);
        EXPECT_NEAR(apex, exactApex, g * kStep * kStep / 8.0 + 1e-9);
        // The bounce is seen at the end of the step it happened in, so the flight after it
        // runs up to one step late: never more than the rebound speed times a step.
        EXPECT_LE(worst, e * impactSpeed * kStep + 1e-9);
    }
}

TEST(FallingSpheresExact, GlancingHitsLeaveAlongTheExactDirections) {
    // A fast sphere hits a still one off centre, without gravity (it moves both alike). The
    // exact answer exchanges (1 + e)/2 of the closing speed along the line between the
    // centres at the instant they touch. The line at the overlap, a step later, would send the
    // struck sphere off up to 1.3 degrees wrong for the glancing ones at this speed.
    FallingSphereSettings settings = kDefaults;
    settings.gravity = 0.0;
    const double r = settings.radius, e = settings.restitution;
    const double speed = 2.0 * fastestSpeed(kDefaults);
    const glm::dvec3 centre(0.0, 4.75, kMidZ);
    for (int k = 0; k < 8; ++k) {
        const double offset = (k + 0.5) / 8.0 * 2.0 * r;
        SCOPED_TRACE("impact parameter " + std::to_string(offset));
        FallingSpheres world(
            settings, {makeSphere(0, centre), makeSphere(1, centre + glm::dvec3(-1.5, offset, 0.0), {speed, 0.0, 0.0})},
            false);
        world.advance(stepsFor(settings, 0.15));
        const double along = std::sqrt(4.0 * r * r - offset * offset);
        const glm::dvec3 normal = glm::dvec3(-along, offset, 0.0) / (2.0 * r);
        const double exchange = 0.5 * (1.0 + e) * speed * along / (2.0 * r);
        const glm::dvec3 stillAfter = -exchange * normal;
        const glm::dvec3 movingAfter = glm::dvec3(speed, 0.0, 0.0) + exchange * normal;
        // Exact bar rounding in the time-of-contact solve (1e-9 of 25 m/s is generous).
        EXPECT_NEAR(glm::length(world.spheres()[0].velocity - stillAfter), 0.0, 1e-9 * speed);
        EXPECT_NEAR(glm::length(world.spheres()[1].velocity - movingAfter), 0.0, 1e-9 * speed);
    }
}

// ---------------------------------------------------------------------------------------
// Hard case 5: determinism, removal, spawning

struct Trajectory {
    std::vector<std::uint32_t> ids;
    std::vector<double> numbers;  // positions and velocities, in sphere order
};

Trajectory runWithClicks(std::uint64_t seed) {
    FallingSpheres world(kDefaults, seed);
    Trajectory out;
    for (int k = 1; k <= 10000; ++k) {
        world.step();
        if (k % 700 == 0) {
            for (const Sphere& s : world.spheres()) {
                if (s.green) {
                    world.remove(s.id);
                    break;
                }
            }
        }
    }
    for (const Sphere& s : world.spheres()) {
        out.ids.push_back(s.id);
        for (int axis = 0; axis < 3; ++axis) {
            out.numbers.push_back(s.position[axis]);
            out.numbers.push_back(s.velocity[axis]);
        }
    }
    return out;
}

TEST(FallingSpheresDeterminism, SameSeedSameBitsDifferentSeedDifferent) {
    const Trajectory a = runWithClicks(12345), b = runWithClicks(12345), c = runWithClicks(12346);
    ASSERT_EQ(a.ids, b.ids);
    ASSERT_EQ(a.numbers.size(), b.numbers.size());
    EXPECT_EQ(std::memcmp(a.numbers.data(), b.numbers.data(), a.numbers.size() * sizeof(double)), 0);
    EXPECT_GT(a.ids.back(), 9u) << "the clicks should have brought new spheres in";
    ASSERT_EQ(a.numbers.size(), c.numbers.size());
    EXPECT_NE(std::memcmp(a.numbers.data(), c.numbers.data(), a.numbers.size() * sizeof(double)), 0);
}

TEST(FallingSpheresDeterminism, GoldenInitialFieldPinsTheGenerator) {
    // Integer PRNG and IEEE arithmetic only: these bits must come out on every machine. A
    // change here changes every logged click session's world.
    const FallingSpheres world(kDefaults, 20240601);
    const Sphere& first = world.spheres()[0];
    EXPECT_EQ(first.position.x, 0x1.250d4e0e0a12bp+1);
    EXPECT_EQ(first.position.y, 0x1.926d5b80aee36p+2);
    EXPECT_EQ(first.velocity.z, 0x1.a16b63db367dep+0);
    EXPECT_EQ(first.green, true);
}

TEST(FallingSpheresField, InitialFieldFillsTheUpperHalfWithoutOverlap) {
    for (std::uint64_t seed = 0; seed < 50; ++seed) {
        const FallingSpheres world(kDefaults, seed);
        const std::vector<Sphere>& spheres = world.spheres();
        ASSERT_EQ(spheres.size(), 10u);
        expectAllInsideBox(world, "seed " + std::to_string(seed));
        const double midY = 0.5 * (kDefaults.box.min.y + kDefaults.box.max.y);
        for (std::size_t i = 0; i < spheres.size(); ++i) {
            EXPECT_EQ(spheres[i].id, i);
            EXPECT_GE(spheres[i].position.y - kDefaults.radius, midY - 1e-12);
            const glm::dvec3 v = spheres[i].velocity;
            EXPECT_LE(std::hypot(v.x, v.z), kDefaults.spawnSpeed);
            EXPECT_LE(v.y, 0.0);
            EXPECT_GE(v.y, -kDefaults.spawnSpeed);
        }
        EXPECT_EQ(world.maxPenetration(), 0.0);
    }
}

TEST(FallingSpheresSpawning, RemoveUnknownIdReturnsFalse) {
    FallingSpheres world(kDefaults, 1);
    EXPECT_FALSE(world.remove(10));  // the next id, not yet created
    EXPECT_FALSE(world.remove(999));
    EXPECT_TRUE(world.remove(3));
    EXPECT_FALSE(world.remove(3));  // already gone
    EXPECT_EQ(world.spheres().size(), 9u);
}

TEST(FallingSpheresSpawning, ReplacementEntersAtTheTopAfterTheDelayWithANewId) {
    FallingSpheres world(kDefaults, 1);
    world.advance(100);
    const std::int64_t delaySteps = stepsFor(kDefaults, kDefaults.spawnDelayS);  // 480
    std::uint32_t expectedId = 10;
    for (int click = 0; click < 5; ++click) {
        ASSERT_TRUE(world.remove(world.spheres()[2].id));
        const std::int64_t removedAt = world.stepCount();
        while (world.stepCount() < removedAt + delaySteps) {
            ASSERT_EQ(world.spheres().size(), 9u) << "step " << world.stepCount();
            world.step();
        }
        ASSERT_EQ(world.spheres().size(), 10u);
        const Sphere& entered = world.spheres().back();
        EXPECT_EQ(entered.id, expectedId++);
        EXPECT_EQ(entered.position.y, kDefaults.box.max.y - kDefaults.radius);
        EXPECT_LE(std::hypot(entered.velocity.x, entered.velocity.z), kDefaults.spawnSpeed);
        EXPECT_LE(entered.velocity.y, 0.0);
        EXPECT_GE(entered.velocity.y, -kDefaults.spawnSpeed);
        for (const Sphere& other : world.spheres()) {
            if (other.id == entered.id) continue;
            EXPECT_GE(glm::length(other.position - entered.position), 2.0 * kDefaults.radius);
        }
        for (std::size_t i = 1; i < world.spheres().size(); ++i) {
            EXPECT_LT(world.spheres()[i - 1].id, world.spheres()[i].id);
        }
        world.advance(37);
    }
}

TEST(FallingSpheresSpawning, BlockedEntryWaitsForRoom) {
    // A column one sphere wide, no gravity: a sphere parked at the top blocks every entry
    // position, so the replacement waits until it is gone and then enters the next step.
    FallingSphereSettings settings = kDefaults;
    settings.gravity = 0.0;
    settings.box.min = {-0.5, 0.0, -0.5};
    settings.box.max = {0.5, 10.0, 0.5};
    settings.sphereCount = 2;
    settings.spawnDelayS = 0.0;
    settings.spawnSpeed = 0.0;
    const double topY = settings.box.max.y - settings.radius;
    FallingSpheres world(settings, {makeSphere(0, {0.0, topY, 0.0}), makeSphere(1, {0.0, 5.0, 0.0})}, true);
    ASSERT_TRUE(world.remove(1));
    world.advance(100);
    EXPECT_EQ(world.spheres().size(), 1u);
    EXPECT_EQ(world.pendingSpawns(), 1u);
    ASSERT_TRUE(world.remove(0));
    world.step();
    ASSERT_EQ(world.spheres().size(), 1u);  // the first waiting one entered...
    EXPECT_EQ(world.spheres()[0].id, 2u);
    EXPECT_EQ(world.pendingSpawns(), 1u);  // ...and now blocks the second
}

TEST(FallingSpheresSpawning, GreenShareOfNewSpheresIsWithinBinomialBounds) {
    for (const double share : {0.5, 0.2}) {
        FallingSphereSettings settings = kDefaults;
        settings.greenShare = share;
        settings.spawnDelayS = 0.0;
        FallingSpheres world(settings, 99);
        const int clicks = 4000;
        int spawned = 0, green = 0;
        std::uint32_t nextNew = 10;
        for (int k = 0; k < clicks + 100; ++k) {  // 100 more steps for any that wait for room
            if (k < clicks) world.remove(world.spheres().front().id);
            world.step();
            for (const Sphere& s : world.spheres()) {
                if (s.id >= nextNew) {
                    ++spawned;
                    green += s.green ? 1 : 0;
                    nextNew = s.id + 1;
                }
            }
        }
        ASSERT_EQ(spawned, clicks);
        ASSERT_EQ(world.spheres().size(), 10u);
        // Deterministic, but another seed must not fail by chance: 4.5 standard deviations
        // leave about 1 in 150,000.
        const double sd = std::sqrt(spawned * share * (1.0 - share));
        EXPECT_NEAR(green, spawned * share, 4.5 * sd) << "share " << share;
    }
}

// ---------------------------------------------------------------------------------------
// Hard case 6: invalid settings and states

TEST(FallingSpheresSettings, OutOfRangeFieldsThrowNamingTheField) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    struct Bad {
        const char* field;
        void (*change)(FallingSphereSettings&);
    };
    const Bad bad[] = {
        {"gravity", [](FallingSphereSettings& s) { s.gravity = -9.81; }},
        {"gravity", [](FallingSphereSettings& s) { s.gravity = std::numeric_limits<double>::infinity(); }},
        {"restitution", [](FallingSphereSettings& s) { s.restitution = 1.01; }},
        {"restitution", [](FallingSphereSettings& s) { s.restitution = -0.1; }},
        {"stepRateHz", [](FallingSphereSettings& s) { s.stepRateHz = 0; }},
        {"stepRateHz", [](FallingSphereSettings& s) { s.stepRateHz = -960; }},
        {"radius", [](FallingSphereSettings& s) { s.radius = 0.0; }},
        {"radius", [](FallingSphereSettings& s) { s.radius = 2.0; }},  // the box is 3.8 m deep
        {"sphereCount", [](FallingSphereSettings& s) { s.sphereCount = 1000; }},
        {"sphereCount", [](FallingSphereSettings& s) { s.sphereCount = -1; }},
        {"greenShare", [](FallingSphereSettings& s) { s.greenShare = 1.5; }},
        {"spawnDelayS", [](FallingSphereSettings& s) { s.spawnDelayS = -0.5; }},
        {"spawnSpeed", [](FallingSphereSettings& s) { s.spawnSpeed = -1.0; }},
        {"box", [](FallingSphereSettings& s) { s.box.max.y = s.box.min.y; }},
        {"restingSpeed", [](FallingSphereSettings& s) { s.restingSpeed = -1.0; }},
        {"velocityIterations", [](FallingSphereSettings& s) { s.velocityIterations = 0; }},
        {"positionIterations", [](FallingSphereSettings& s) { s.positionIterations = 0; }},
    };
    for (const Bad& b : bad) {
        FallingSphereSettings settings;
        b.change(settings);
        expectInvalidArgumentNaming([&] { FallingSpheres(settings, 1); },
                                    std::string("FallingSphereSettings.") + b.field);
        expectInvalidArgumentNaming([&] { FallingSpheres(settings, {}, false); },
                                    std::string("FallingSphereSettings.") + b.field);
    }
    FallingSphereSettings settings;
    settings.restitution = nan;
    expectInvalidArgumentNaming([&] { FallingSpheres(settings, 1); }, "restitution must be in [0, 1]");
    // The edges of the ranges are allowed.
    settings = FallingSphereSettings{};
    settings.gravity = 0.0;
    settings.restitution = 1.0;
    settings.greenShare = 0.0;
    settings.sphereCount = 0;
    EXPECT_NO_THROW(FallingSpheres(settings, 1));
}

TEST(FallingSpheresSettings, TooManySpheresToStartWithoutOverlapThrows) {
    // The default box's upper half holds a lattice of 14 x 4 x 4 diameter cells.
    FallingSphereSettings settings;
    settings.sphereCount = 224;
    EXPECT_NO_THROW(FallingSpheres(settings, 3));
    const FallingSpheres full(settings, 3);
    EXPECT_EQ(full.maxPenetration(), 0.0);
    settings.sphereCount = 225;
    expectInvalidArgumentNaming([&] { FallingSpheres(settings, 3); }, "FallingSphereSettings.sphereCount");
}

TEST(FallingSpheresSettings, ExplicitStatesAreChecked) {
    const double r = kDefaults.radius;
    expectInvalidArgumentNaming(
        [&] {
            FallingSpheres(kDefaults, {makeSphere(0, {0.0, kFloorY - 0.01, kMidZ})}, false);
        },
        "initial[0].position");
    expectInvalidArgumentNaming(
        [&] {
            FallingSpheres(kDefaults, {makeSphere(4, {0.0, 3.0, kMidZ}), makeSphere(4, {2.0, 3.0, kMidZ})}, false);
        },
        "initial[1].id");
    expectInvalidArgumentNaming(
        [&] {
            FallingSpheres(kDefaults,
                           {makeSphere(0, {0.0, 3.0, kMidZ}, {std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0})},
                           false);
        },
        "initial[0]");
    // Touching the walls is inside.
    EXPECT_NO_THROW(FallingSpheres(
        kDefaults, {makeSphere(0, kDefaults.box.min + glm::dvec3(r)), makeSphere(1, kDefaults.box.max - glm::dvec3(r))},
        false));
    FallingSpheres world(kDefaults, 1);
    EXPECT_THROW(world.advance(-1), std::invalid_argument);
}

TEST(FallingSpheresSettings, ExplicitStateWithSpawningContinuesTheIds) {
    FallingSphereSettings settings = kDefaults;
    settings.sphereCount = 2;
    settings.spawnDelayS = 0.0;
    FallingSpheres world(settings, {makeSphere(5, {0.0, 3.0, kMidZ}), makeSphere(9, {2.0, 3.0, kMidZ})}, true, 4);
    ASSERT_TRUE(world.remove(5));
    world.step();
    ASSERT_EQ(world.spheres().size(), 2u);
    EXPECT_EQ(world.spheres()[1].id, 10u);
    // Without spawning nothing enters.
    FallingSpheres quiet(settings, {makeSphere(0, {0.0, 3.0, kMidZ})}, false);
    ASSERT_TRUE(quiet.remove(0));
    quiet.advance(10);
    EXPECT_TRUE(quiet.spheres().empty());
    EXPECT_EQ(quiet.pendingSpawns(), 0u);
}

}  // namespace
}  // namespace warplab::physics
