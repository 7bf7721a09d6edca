// The click game's world (seed 000 section 8): red and green spheres falling under gravity in
// an axis-aligned box, bouncing off its walls and each other, with a replacement entering at
// the top some time after a sphere is clicked away. Unlike the shooter's target this world
// has no closed form, so it is integrated with a fixed internal step that does not depend on
// the render rate; rendering only samples it. The model, its hard cases and the step-rate
// table are in docs/click-physics.md.
//
// Deterministic: a seed, the settings and the steps at which remove() is called give the
// same bits on every run of the same build (splitmix64, no <random> distributions, no
// unordered containers, every sum taken in sphere order).
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace warplab::physics {

struct SphereBox {  // the walls; the floor is min.y. Metres, y up.
    glm::dvec3 min{-6.4, 0.5, -10.4};
    glm::dvec3 max{6.4, 9.0, -6.6};
};

// Validated by the FallingSpheres constructors; every field out of range throws
// std::invalid_argument naming it ("FallingSphereSettings.restitution must be in [0, 1]").
struct FallingSphereSettings {
    SphereBox box;  // min < max on every axis
    double gravity = 9.81;  // m/s^2 downwards; >= 0
    double radius = 0.45;  // every sphere, metres; a diameter must fit every axis
    double restitution = 0.9;  // [0, 1], all contacts (the click protocol's default)
    int stepRateHz = 960;  // internal steps per second (fixed); the game requires its
        // display refresh to divide it
    int sphereCount = 10;  // the field is kept at this many
    double greenShare = 0.5;  // probability a new sphere is green
    double spawnDelayS = 0.5;  // a replacement enters this long after a sphere is removed
    double spawnSpeed = 2.0;  // max |horizontal velocity| (m/s) of a new sphere; it enters
        // moving down at up to this too

    // Added beyond the game's interface; the defaults are what docs/click-physics.md measured.
    // A contact closing slower than resting = max(restingSpeed, 2 * gravity / stepRateHz) m/s
    // gets restitution 0: a resting sphere closes at gravity / stepRateHz every step, and
    // bouncing that back would make it jitter; 0.1 m/s rebounds at most 0.5 mm, invisible.
    // Spheres closer than resting / stepRateHz to touching also count as in contact.
    double restingSpeed = 0.1;
    int velocityIterations = 20;  // >= 1 sweeps over the contacts per step (impulses)
    int positionIterations = 10;  // >= 1 sweeps resolving overlaps per step
};

struct Sphere {
    std::uint32_t id = 0;  // 0, 1, 2, ... in order of creation, never reused
    bool green = false;
    glm::dvec3 position{0.0}, velocity{0.0};
};

class FallingSpheres {
public:
    // Throws std::invalid_argument naming the settings field that is out of range.
    // The initial field: sphereCount spheres placed without overlap in the upper half of the
    // box (deterministic from seed), with the velocities a new sphere enters with. At most as
    // many spheres as fit a lattice of diameter-sized cells in that upper half are allowed.
    FallingSpheres(const FallingSphereSettings& settings, std::uint64_t seed);
    // An explicit initial state, for tests and hard cases: the spheres as given (ids strictly
    // increasing, every sphere inside the box, finite; overlaps are allowed and get resolved).
    // With spawn false nothing ever enters; with spawn true remove() schedules a replacement
    // while fewer than sphereCount spheres are present or pending, drawn from seed.
    FallingSpheres(const FallingSphereSettings& settings, std::vector<Sphere> initial, bool spawn,
                   std::uint64_t seed = 0);

    void step();  // one internal step of 1/stepRateHz s
    void advance(std::int64_t steps);  // `steps` (>= 0) internal steps
    std::int64_t stepCount() const { return stepCount_; }
    double time() const;  // stepCount / stepRateHz, computed as a division (no accumulated sum)
    const std::vector<Sphere>& spheres() const { return spheres_; }  // ordered by id
    const FallingSphereSettings& settings() const { return settings_; }

    // Removes the sphere (a clicked green one); false if no such id. A replacement is
    // scheduled spawnDelayS later, rounded to the nearest whole step (it appears at the end of
    // the first step() that reaches that count, so a zero delay means the next step),
    // entering at the top of the box at a random x, z where it does not overlap another
    // sphere; if none of a few deterministic tries is free it tries again the next step.
    bool remove(std::uint32_t id);
    std::size_t pendingSpawns() const { return pendingSpawnSteps_.size(); }

    double kineticEnergy() const;  // sum 0.5 v^2 per unit mass (all masses equal)
    double potentialEnergy() const;  // sum g * (y - floorContactY), floorContactY = min.y + r
    // Deepest overlap now: sphere-sphere (2r - distance) or sphere-wall, metres, >= 0. What a
    // step leaves behind; the wall part is always 0 (walls are the last constraint resolved).
    double maxPenetration() const;
    // Deepest overlap the last step() found after moving the spheres, before resolving it:
    // how far a contact got into a wall or another sphere within one step (0 before any step).
    double lastStepContactDepth() const { return lastStepContactDepth_; }

private:
    struct Contact {
        std::size_t a = 0;
        std::size_t b = 0;  // == a for a wall
        glm::dvec3 normal{0.0};  // into the box for a wall; from a towards b for a pair
        double depth = 0.0;  // overlap after integration, metres (may be a hair < 0)
        bool active = false;  // takes part in this step's impulses
        double target = 0.0;  // separating speed it must reach, m/s
        double impulse = 0.0;  // accumulated this step, >= 0
    };

    void integrate();
    void findContacts();
    void resolveVelocities();
    void resolveOverlaps();
    void spawnDue();
    bool trySpawn();
    double restingThreshold() const;

    FallingSphereSettings settings_;
    std::vector<Sphere> spheres_;
    std::vector<std::int64_t> pendingSpawnSteps_;  // non-decreasing
    std::vector<Contact> contacts_;  // reused every step
    std::uint64_t rngState_ = 0;
    std::uint32_t nextId_ = 0;
    std::int64_t stepCount_ = 0;
    double lastStepContactDepth_ = 0.0;
    bool spawn_ = true;
};

}  // namespace warplab::physics
