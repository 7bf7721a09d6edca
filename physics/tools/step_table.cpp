// Prints, as a markdown table, what the falling spheres' internal step rate buys: for each
// rate, the errors against exact solutions (a fast floor bounce, fast glancing hits between
// two spheres), the energy the model loses where none should be lost, how deep contacts get
// within a step and what overlap a step leaves, and the cost. docs/click-physics.md explains
// the columns and picks the default rate from a run of this program.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <glm/glm.hpp>
#include <vector>

#include "physics/falling_spheres.h"

namespace {

using warplab::physics::FallingSpheres;
using warplab::physics::FallingSphereSettings;
using warplab::physics::Sphere;

constexpr int kRates[] = {120, 240, 480, 960, 1920, 3840};
constexpr double kGameSeconds = 60.0;
constexpr double kClickEveryS = 1.5;  // the scripted player removes a green sphere this often
constexpr std::uint64_t kSeed = 2011;
constexpr int kCostRuns = 5;

// The fastest a sphere gets in the game: it enters at the top moving down at spawnSpeed with
// up to spawnSpeed sideways, and falls the whole height of the box.
double fastestEntrySpeed(const FallingSphereSettings& s) {
    const double drop = (s.box.max.y - s.box.min.y) - 2.0 * s.radius;
    return std::sqrt(2.0 * s.spawnSpeed * s.spawnSpeed + 2.0 * s.gravity * drop);
}

double sphereEnergy(const FallingSphereSettings& s, const Sphere& sphere) {
    return 0.5 * glm::dot(sphere.velocity, sphere.velocity) +
        s.gravity * (sphere.position.y - (s.box.min.y + s.radius));
}

// The game's default scenario: 10 spheres for 60 s, with a scripted player clicking away the
// oldest green sphere every 1.5 s so that replacements keep entering at the top.
struct GameRun {
    double deepestContact = 0.0;  // m, within a step, before it is resolved
    double overlapLeft = 0.0;  // m, after a step
    double energyDrift = 0.0;  // relative, at the end (restitution 1 only)
    double energyRise = 0.0;  // relative, the most it was ever above the books
};

GameRun runGame(const FallingSphereSettings& settings, bool trackEnergy) {
    FallingSpheres world(settings, kSeed);
    const auto steps = static_cast<std::int64_t>(std::llround(kGameSeconds * settings.stepRateHz));
    const auto clickEvery = static_cast<std::int64_t>(std::llround(kClickEveryS * settings.stepRateHz));
    GameRun run;
    // Energy books: what the field starts with, minus what clicks take away, plus what new
    // spheres bring. With restitution 1 the exact model keeps the total equal to this.
    double books = trackEnergy ? world.kineticEnergy() + world.potentialEnergy() : 0.0;
    std::uint32_t nextNewId = static_cast<std::uint32_t>(world.spheres().size());
    for (std::int64_t k = 1; k <= steps; ++k) {
        world.step();
        run.deepestContact = std::max(run.deepestContact, world.lastStepContactDepth());
        run.overlapLeft = std::max(run.overlapLeft, world.maxPenetration());
        if (trackEnergy) {
            for (const Sphere& sphere : world.spheres()) {
                if (sphere.id >= nextNewId) {
                    books += sphereEnergy(settings, sphere);
                    nextNewId = sphere.id + 1;
                }
            }
            const double total = world.kineticEnergy() + world.potentialEnergy();
            run.energyRise = std::max(run.energyRise, (total - books) / books);
        }
        if (k % clickEvery == 0) {
            for (const Sphere& sphere : world.spheres()) {
                if (!sphere.green) continue;
                if (trackEnergy) books -= sphereEnergy(settings, sphere);
                world.remove(sphere.id);
                break;
            }
        }
    }
    if (trackEnergy) {
        run.energyDrift = (world.kineticEnergy() + world.potentialEnergy() - books) / books;
    }
    return run;
}

// Median wall-clock time of the game scenario, in microseconds per simulated second.
double costPerSimulatedSecond(const FallingSphereSettings& settings) {
    std::vector<double> micros;
    for (int run = 0; run < kCostRuns; ++run) {
        const auto start = std::chrono::steady_clock::now();
        runGame(settings, false);
        const auto stop = std::chrono::steady_clock::now();
        micros.push_back(std::chrono::duration<double, std::micro>(stop - start).count());
    }
    std::sort(micros.begin(), micros.end());
    return micros[micros.size() / 2] / kGameSeconds;
}

// A sphere entering at the top at the fastest downward speed bounces once off the floor.
// Exact: the parabola down, a bounce at restitution times the impact speed, the parabola up
// until it lands again. Returns the largest distance (m) between the simulated and the exact
// centre at any step of that flight, over starting heights that put the impact at 16
// different points within a step.
double floorBounceError(const FallingSphereSettings& settings) {
    const double g = settings.gravity, e = settings.restitution, r = settings.radius;
    const double dt = 1.0 / settings.stepRateHz;
    const double floorY = settings.box.min.y + r;
    const double v0 = -settings.spawnSpeed;
    double worst = 0.0;
    for (int phase = 0; phase < 16; ++phase) {
        const double height = (settings.box.max.y - r - floorY) - phase * (12.0 * dt / 16.0);
        Sphere sphere;
        sphere.position = {0.0, floorY + height, -8.5};
        sphere.velocity = {0.0, v0, 0.0};
        FallingSpheres world(settings, {sphere}, false);
        const double impactSpeed = std::sqrt(v0 * v0 + 2.0 * g * height);
        const double impactTime = (v0 + impactSpeed) / g;
        const double landingTime = impactTime + 2.0 * e * impactSpeed / g;
        for (;;) {
            world.step();
            const double t = world.time();
            if (t >= landingTime - 2.0 * dt) break;  // the next bounce is a new story
            double exactY;
            if (t < impactTime) {
                exactY = floorY + height + v0 * t - 0.5 * g * t * t;
            } else {
                const double after = t - impactTime;
                exactY = floorY + e * impactSpeed * after - 0.5 * g * after * after;
            }
            worst = std::max(worst, std::fabs(world.spheres()[0].position.y - exactY));
        }
    }
    return worst;
}

// Two of the fastest spheres meeting head-on (relative speed twice the fastest entry speed),
// off centre by impact parameters across the whole diameter, without gravity (it moves both
// alike, so it does not change a collision) and away from the walls. Exact: they touch when
// the centres are 2r apart, exchange (1 + e)/2 of the closing speed along the line between
// them then, and fly straight on. Returns the largest position error (m) of either sphere
// 0.1 s after the hit and the largest velocity error (relative to the closing speed), over
// 8 impact parameters and 4 phases within a step.
struct HitError {
    double position = 0.0;
    double velocity = 0.0;
};

HitError glancingHitError(FallingSphereSettings settings) {
    settings.gravity = 0.0;
    const double e = settings.restitution, r = settings.radius;
    const double dt = 1.0 / settings.stepRateHz;
    const double speed = 2.0 * fastestEntrySpeed(settings);
    const glm::dvec3 centre = 0.5 * (settings.box.min + settings.box.max);
    HitError worst;
    for (int k = 0; k < 8; ++k) {
        const double offset = (k + 0.5) / 8.0 * 2.0 * r;  // impact parameter
        for (int phase = 0; phase < 4; ++phase) {
            const double startGap = 1.5 + phase * speed * dt / 4.0;
            Sphere still, moving;
            still.id = 0;
            still.position = centre;
            moving.id = 1;
            moving.position = centre + glm::dvec3(-startGap, offset, 0.0);
            moving.velocity = {speed, 0.0, 0.0};
            FallingSpheres world(settings, {still, moving}, false);

            const double along = std::sqrt(4.0 * r * r - offset * offset);
            const double contactTime = (startGap - along) / speed;
            const glm::dvec3 normal = glm::dvec3(-along, offset, 0.0) / (2.0 * r);  // still -> moving
            const double closing = speed * along / (2.0 * r);
            const double exchange = 0.5 * (1.0 + e) * closing;
            const glm::dvec3 stillAfter = -exchange * normal;
            const glm::dvec3 movingAfter = moving.velocity + exchange * normal;
            const glm::dvec3 stillAtContact = centre;
            const glm::dvec3 movingAtContact = centre + 2.0 * r * normal;

            const auto steps = static_cast<std::int64_t>(std::ceil((contactTime + 0.1) * settings.stepRateHz));
            world.advance(steps);
            const double after = world.time() - contactTime;
            const Sphere& a = world.spheres()[0];
            const Sphere& b = world.spheres()[1];
            worst.position = std::max({worst.position, glm::length(a.position - (stillAtContact + stillAfter * after)),
                                       glm::length(b.position - (movingAtContact + movingAfter * after))});
            worst.velocity = std::max({worst.velocity, glm::length(a.velocity - stillAfter) / closing,
                                       glm::length(b.velocity - movingAfter) / closing});
        }
    }
    return worst;
}

// The deepest a contact gets within a step when the fastest spheres hit: twice the fastest
// entry speed straight into the floor, into a sphere resting on the floor, and two spheres
// head-on at that speed each, each started at 8 distances a step's travel apart so that the
// hit falls at 8 points within a step.
double fastImpactDepth(const FallingSphereSettings& settings) {
    const double r = settings.radius, floorY = settings.box.min.y + r;
    const double speed = 2.0 * fastestEntrySpeed(settings);
    const double z = 0.5 * (settings.box.min.z + settings.box.max.z);
    const double dt = 1.0 / settings.stepRateHz;
    const auto make = [](std::uint32_t id, glm::dvec3 p, glm::dvec3 v) {
        Sphere s;
        s.id = id;
        s.position = p;
        s.velocity = v;
        return s;
    };
    double deepest = 0.0;
    for (int phase = 0; phase < 8; ++phase) {
        const double shift = phase * speed * dt / 8.0;
        const std::vector<std::vector<Sphere>> cases = {
            {make(0, {0.0, floorY + 2.0 + shift, z}, {0.0, -speed, 0.0})},
            {make(0, {0.0, floorY, z}, {}), make(1, {0.0, floorY + 2.0 * r + 2.0 + shift, z}, {0.0, -speed, 0.0})},
            {make(0, {-2.0 - 2.0 * shift, 4.0, z}, {speed, 0.0, 0.0}),  // closing at 2 speed
             make(1, {2.0, 4.0, z}, {-speed, 0.0, 0.0})},
        };
        for (const std::vector<Sphere>& initial : cases) {
            FallingSpheres world(settings, initial, false);
            for (int k = 0; k < settings.stepRateHz / 4; ++k) {  // 0.25 s: well past each hit
                world.step();
                deepest = std::max(deepest, world.lastStepContactDepth());
            }
        }
    }
    return deepest;
}

}  // namespace

int main() {
    const FallingSphereSettings defaults;
    std::printf(
        "Falling spheres, default settings (restitution %.2g, %d spheres, radius %.2f m); "
        "fastest entry speed %.2f m/s.\n\n",
        defaults.restitution, defaults.sphereCount, defaults.radius, fastestEntrySpeed(defaults));
    std::printf(
        "| step rate (Hz) | step (ms) | floor bounce error (mm) | glancing hit error (mm) "
        "| hit velocity error (%%) | energy drift at e = 1 (%%) | highest energy rise (%%) "
        "| deepest contact in a step (mm) | overlap left by a step (mm) "
        "| cost (µs per simulated s) |\n");
    std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const int rate : kRates) {
        FallingSphereSettings settings = defaults;
        settings.stepRateHz = rate;
        const GameRun game = runGame(settings, false);
        FallingSphereSettings elastic = settings;
        elastic.restitution = 1.0;
        const GameRun energy = runGame(elastic, true);
        const double bounce = floorBounceError(settings);
        const HitError hit = glancingHitError(settings);
        const double deepest = std::max(game.deepestContact, fastImpactDepth(settings));
        const double cost = costPerSimulatedSecond(settings);
        std::printf("| %d | %.3f | %.2f | %.2f | %.1e | %+.3f | %.1e | %.1f | %.1e | %.0f |\n", rate, 1e3 / rate,
                    1e3 * bounce, 1e3 * hit.position, 100.0 * hit.velocity, 100.0 * energy.energyDrift,
                    100.0 * energy.energyRise, 1e3 * deepest, 1e3 * std::max(game.overlapLeft, energy.overlapLeft),
                    cost);
        std::fflush(stdout);
    }
    return 0;
}
