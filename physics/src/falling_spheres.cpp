#include "physics/falling_spheres.h"

#include "physics/splitmix.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

namespace warplab::physics {
namespace {

// A new sphere tries this many positions at the top before waiting for the next step.
constexpr int kSpawnTries = 8;

void requireSetting(bool ok, const char* field, const std::string& what) {
    if (!ok) {
        throw std::invalid_argument(std::string("FallingSphereSettings.") + field + " " + what);
    }
}

bool finite(glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::uint64_t nextRandom(std::uint64_t& state) { return splitmix64(state); }

// Horizontal velocity uniform in the disc of radius spawnSpeed (by rejection: sqrt-free and
// trig-free, so the same bits everywhere), vertical uniform in [-spawnSpeed, 0].
glm::dvec3 entryVelocity(std::uint64_t& rng, double spawnSpeed) {
    double a = 0.0, b = 0.0;
    // Acceptance is pi/4 per try; the bound only keeps the loop finite.
    for (int attempt = 0; attempt < 256; ++attempt) {
        a = 2.0 * uniform01(rng) - 1.0;
        b = 2.0 * uniform01(rng) - 1.0;
        if (a * a + b * b <= 1.0) break;
        a = b = 0.0;
    }
    return {a * spawnSpeed, -uniform01(rng) * spawnSpeed, b * spawnSpeed};
}

// The lattice of diameter-sized cells the initial field is drawn from: the upper half of the
// box (at least one layer). Cells are stretched to fill each axis, so a sphere can sit
// anywhere in its cell without touching a neighbour's.
struct StartLattice {
    glm::dvec3 origin{0.0};
    glm::dvec3 cell{0.0};
    int nx = 0, ny = 0, nz = 0;
    long long capacity() const { return static_cast<long long>(nx) * ny * nz; }
};

StartLattice startLattice(const FallingSphereSettings& s) {
    const double diameter = 2.0 * s.radius;
    const glm::dvec3 size = s.box.max - s.box.min;
    const double layerHeight = std::min(size.y, std::max(0.5 * size.y, diameter));
    const auto cellsAlong = [diameter](double length) {
        // length >= diameter was validated; max(1, ...) guards a rounding of the division.
        return std::max(1, static_cast<int>(std::min(1e6, std::floor(length / diameter))));
    };
    StartLattice lattice;
    lattice.nx = cellsAlong(size.x);
    lattice.ny = cellsAlong(layerHeight);
    lattice.nz = cellsAlong(size.z);
    lattice.origin = {s.box.min.x, s.box.max.y - layerHeight, s.box.min.z};
    lattice.cell = {size.x / lattice.nx, layerHeight / lattice.ny, size.z / lattice.nz};
    return lattice;
}

void validate(const FallingSphereSettings& s) {
    const SphereBox& box = s.box;
    requireSetting(
        finite(box.min) && finite(box.max) && box.min.x < box.max.x && box.min.y < box.max.y && box.min.z < box.max.z,
        "box", "must be finite with min < max on every axis");
    requireSetting(std::isfinite(s.gravity) && s.gravity >= 0.0, "gravity", "must be finite and >= 0 (it points down)");
    const glm::dvec3 size = box.max - box.min;
    requireSetting(std::isfinite(s.radius) && s.radius > 0.0 && 2.0 * s.radius < size.x && 2.0 * s.radius < size.y &&
                       2.0 * s.radius < size.z,
                   "radius", "must be > 0 with a diameter smaller than the box on every axis");
    requireSetting(s.restitution >= 0.0 && s.restitution <= 1.0, "restitution", "must be in [0, 1]");
    requireSetting(s.stepRateHz > 0, "stepRateHz", "must be > 0");
    requireSetting(s.sphereCount >= 0, "sphereCount", "must be >= 0");
    const long long capacity = startLattice(s).capacity();
    requireSetting(s.sphereCount <= capacity, "sphereCount",
                   "must be at most " + std::to_string(capacity) +
                       " for this box and radius (the field starts without overlap in the "
                       "upper half of the box)");
    requireSetting(s.greenShare >= 0.0 && s.greenShare <= 1.0, "greenShare", "must be in [0, 1]");
    requireSetting(std::isfinite(s.spawnDelayS) && s.spawnDelayS >= 0.0 && s.spawnDelayS * s.stepRateHz < 4e18,
                   "spawnDelayS", "must be finite and >= 0");
    requireSetting(std::isfinite(s.spawnSpeed) && s.spawnSpeed >= 0.0, "spawnSpeed", "must be finite and >= 0");
    requireSetting(std::isfinite(s.restingSpeed) && s.restingSpeed >= 0.0, "restingSpeed", "must be finite and >= 0");
    requireSetting(s.velocityIterations >= 1, "velocityIterations", "must be >= 1");
    requireSetting(s.positionIterations >= 1, "positionIterations", "must be >= 1");
}

bool insideBox(const FallingSphereSettings& s, glm::dvec3 p) {
    const double r = s.radius;
    return p.x >= s.box.min.x + r && p.x <= s.box.max.x - r && p.y >= s.box.min.y + r && p.y <= s.box.max.y - r &&
        p.z >= s.box.min.z + r && p.z <= s.box.max.z - r;
}

}  // namespace

FallingSpheres::FallingSpheres(const FallingSphereSettings& settings, std::uint64_t seed)
    : settings_(settings), rngState_(seed) {
    validate(settings_);
    const StartLattice lattice = startLattice(settings_);
    const double r = settings_.radius;

    // sphereCount distinct cells (Floyd's sampling: memory in the count, not the lattice),
    // used in the order drawn.
    const long long cellCount = lattice.capacity();
    std::set<long long> taken;
    std::vector<long long> cells;
    for (long long j = cellCount - settings_.sphereCount; j < cellCount; ++j) {
        const long long t = static_cast<long long>(nextRandom(rngState_) % static_cast<std::uint64_t>(j + 1));
        const long long cell = taken.count(t) ? j : t;
        taken.insert(cell);
        cells.push_back(cell);
    }
    spheres_.reserve(cells.size());
    for (const long long cell : cells) {
        const int ix = static_cast<int>(cell % lattice.nx);
        const int iy = static_cast<int>(cell / lattice.nx % lattice.ny);
        const int iz = static_cast<int>(cell / (static_cast<long long>(lattice.nx) * lattice.ny));

        // Anywhere in the cell that keeps the whole sphere inside it. n * (size / n) can
        // round an ulp past the far wall, hence the min: a placement bound, not dynamics.
        const auto coordinate = [&](int axis, int index) {
            const double cellSize = lattice.cell[axis];
            const double slack = std::max(0.0, cellSize - 2.0 * r);
            const double c = lattice.origin[axis] + index * cellSize + r + uniform01(rngState_) * slack;
            return std::min(c, settings_.box.max[axis] - r);
        };
        Sphere sphere;
        sphere.id = nextId_++;
        sphere.position.x = coordinate(0, ix);
        sphere.position.y = coordinate(1, iy);
        sphere.position.z = coordinate(2, iz);
        sphere.velocity = entryVelocity(rngState_, settings_.spawnSpeed);
        sphere.green = uniform01(rngState_) < settings_.greenShare;
        spheres_.push_back(sphere);
    }
}

FallingSpheres::FallingSpheres(const FallingSphereSettings& settings, std::vector<Sphere> initial, bool spawn,
                               std::uint64_t seed)
    : settings_(settings), spheres_(std::move(initial)), rngState_(seed), spawn_(spawn) {
    validate(settings_);
    for (std::size_t i = 0; i < spheres_.size(); ++i) {
        const Sphere& sphere = spheres_[i];
        const std::string name = "FallingSpheres: initial[" + std::to_string(i) + "]";
        if (i > 0 && sphere.id <= spheres_[i - 1].id) {
            throw std::invalid_argument(name + ".id must be greater than the one before it");
        }
        if (!finite(sphere.position) || !finite(sphere.velocity)) {
            throw std::invalid_argument(name + " must have a finite position and velocity");
        }
        if (!insideBox(settings_, sphere.position)) {
            throw std::invalid_argument(name + ".position must keep the whole sphere inside the box");
        }
    }
    if (!spheres_.empty()) {
        if (spheres_.back().id == std::numeric_limits<std::uint32_t>::max()) {
            throw std::invalid_argument("FallingSpheres: initial ids leave no id for a new sphere");
        }
        nextId_ = spheres_.back().id + 1;
    }
}

double FallingSpheres::time() const {
    return static_cast<double>(stepCount_) / static_cast<double>(settings_.stepRateHz);
}

void FallingSpheres::advance(std::int64_t steps) {
    if (steps < 0) {
        throw std::invalid_argument("FallingSpheres::advance: steps must be >= 0");
    }
    for (std::int64_t i = 0; i < steps; ++i) step();
}

void FallingSpheres::step() {
    integrate();
    findContacts();
    resolveVelocities();
    resolveOverlaps();
    ++stepCount_;
    spawnDue();
}

double FallingSpheres::restingThreshold() const {
    return std::max(settings_.restingSpeed, 2.0 * settings_.gravity / settings_.stepRateHz);
}

// Gravity is the only force and it is constant, so the ballistic update is exact: this is
// velocity Verlet, which for a constant force is the closed-form parabola. Between contacts
// the total energy is therefore conserved up to rounding.
void FallingSpheres::integrate() {
    const double dt = 1.0 / settings_.stepRateHz;
    const glm::dvec3 g(0.0, -settings_.gravity, 0.0);
    for (Sphere& sphere : spheres_) {
        sphere.position += sphere.velocity * dt + g * (0.5 * dt * dt);
        sphere.velocity += g * dt;
    }
}

// Contacts are found after integration. Besides overlaps, a sphere a hair short of touching
// (closer than a resting contact closes in one step) is a contact too: the overlap correction
// leaves stacks and rows with gaps of that kind (and spheres placed touching are an ulp
// apart), and without them those contacts would flicker in and out from step to step.
void FallingSpheres::findContacts() {
    contacts_.clear();
    const double dt = 1.0 / settings_.stepRateHz;
    const double margin = restingThreshold() * dt;
    const double r = settings_.radius;
    const glm::dvec3& lo = settings_.box.min;
    const glm::dvec3& hi = settings_.box.max;
    double deepest = 0.0;
    for (std::size_t i = 0; i < spheres_.size(); ++i) {
        const glm::dvec3 p = spheres_[i].position;
        for (int axis = 0; axis < 3; ++axis) {
            glm::dvec3 normal(0.0);
            normal[axis] = 1.0;
            const double lowDepth = (lo[axis] + r) - p[axis];
            if (lowDepth >= -margin) contacts_.push_back({i, i, normal, lowDepth});
            const double highDepth = p[axis] - (hi[axis] - r);
            if (highDepth >= -margin) contacts_.push_back({i, i, -normal, highDepth});
            deepest = std::max({deepest, lowDepth, highDepth});
        }
    }
    const double reach = 2.0 * r + margin;
    for (std::size_t i = 0; i < spheres_.size(); ++i) {
        for (std::size_t j = i + 1; j < spheres_.size(); ++j) {
            const glm::dvec3 d = spheres_[j].position - spheres_[i].position;
            const double distanceSquared = glm::dot(d, d);
            if (distanceSquared >= reach * reach) continue;
            const double distance = std::sqrt(distanceSquared);
            // Coincident centres have no direction between them: push apart vertically.
            glm::dvec3 normal = distance > 0.0 ? d / distance : glm::dvec3(0.0, 1.0, 0.0);
            const double depth = 2.0 * r - distance;
            // Both spheres fall alike, so within a step they close in a straight line: the
            // instant they touched, and the direction between them then, follow exactly from
            // the overlap and the relative velocity. The impulse acts along that direction, as
            // in the exact collision; the direction at the overlap turns with its depth, which
            // would deflect a glancing hit by an angle that grows with the step.
            const glm::dvec3 relative = spheres_[j].velocity - spheres_[i].velocity;
            const double approach = glm::dot(d, relative);  // < 0 while closing
            if (depth > 0.0 && approach < 0.0) {
                // Time back to touching: the positive root of |d - relative t| = 2r, in the
                // form that does not cancel (the other root is negative).
                const double speedSquared = glm::dot(relative, relative);
                const double discriminant = approach * approach - speedSquared * (distanceSquared - 4.0 * r * r);
                const double back = (distanceSquared - 4.0 * r * r) / (approach - std::sqrt(discriminant));
                const glm::dvec3 touching = d - relative * back;
                const double touchingLength = glm::length(touching);
                // Only an overlap made within this step is traced back; older ones (a spawn in
                // a crowd, an explicit start) keep the direction they have now.
                if (back <= dt && touchingLength > 0.0) normal = touching / touchingLength;
            }
            contacts_.push_back({i, j, normal, depth});
            deepest = std::max(deepest, depth);
        }
    }
    lastStepContactDepth_ = deepest;
}

// Sequential impulses (Catto's accumulated form of projected Gauss-Seidel) in a fixed order:
// walls, then pairs by index. Each taking part gets a target separating speed, and the sweeps
// adjust each contact's total impulse, never below zero, until every one meets its target:
// - touching or overlapping and closing: restitution times the closing speed, or 0 below the
//   resting threshold;
// - a hair apart (within the margin above) and closing no faster than a resting contact:
//   -gap / dt, free to close the gap in the next step but not to pass it;
// - a gap closing faster takes no part: it collides properly a step later;
// - already separating: minus its separating speed (and the gap): it may turn round but close
//   no faster than it was leaving. Holding it at 0, as is usual, would give energy whenever
//   a hit elsewhere drives a separating pair together.
// Converged, this is the simultaneous-impact answer: a symmetric drop stays symmetric, a
// stack's contacts all hold, and no contact leaves faster than restitution allows, so the
// kinetic energy does not rise (docs/click-physics.md).
void FallingSpheres::resolveVelocities() {
    const double e = settings_.restitution;
    const double resting = restingThreshold();
    const double g = settings_.gravity;
    const double rate = settings_.stepRateHz;
    const auto separating = [this](const Contact& c) {
        const glm::dvec3 relative =
            c.a == c.b ? spheres_[c.a].velocity : spheres_[c.b].velocity - spheres_[c.a].velocity;
        return glm::dot(relative, c.normal);
    };
    for (Contact& c : contacts_) {
        const double closing = -separating(c);
        c.impulse = 0.0;
        c.active = true;
        if (closing < 0.0) {
            // Already separating: it may turn round, but close no faster than it was leaving
            // (plus the gap, if any). That target gives an impulse no work to do, so the
            // energy promise holds, yet the contact still holds its sphere when impulses
            // elsewhere in a stack push the two together.
            c.target = closing + std::min(c.depth, 0.0) * rate;
            continue;
        }
        if (c.depth < 0.0) {
            c.active = closing <= resting;
            c.target = c.depth * rate;
            continue;
        }
        // A sphere c.depth past the floor reached it moving slower than it moves now: gravity
        // sped it up over that last stretch. Bouncing the speed it had at the floor makes the
        // rebound as high as the exact one and pays for the lift the overlap correction then
        // gives it; what resting contacts lose to this is what gravity gave them in the step.
        double impact = closing;
        if (c.a == c.b && c.depth > 0.0 && c.normal.y > 0.0) {
            impact = std::sqrt(std::max(0.0, closing * closing - 2.0 * g * c.normal.y * c.depth));
        }
        c.target = impact > resting ? e * impact : 0.0;
    }
    for (int sweep = 0; sweep < settings_.velocityIterations; ++sweep) {
        bool changed = false;
        for (Contact& c : contacts_) {
            if (!c.active) continue;
            // Unit masses: a wall contact moves one sphere (effective mass 1), a pair two
            // (effective mass 1/2), so each takes half the change of relative velocity.
            const double effectiveMass = c.a == c.b ? 1.0 : 0.5;
            const double total = std::max(0.0, c.impulse + effectiveMass * (c.target - separating(c)));
            const double change = total - c.impulse;
            if (change == 0.0) continue;
            changed = true;
            c.impulse = total;
            if (c.a == c.b) {
                spheres_[c.a].velocity += change * c.normal;
            } else {
                spheres_[c.a].velocity -= change * c.normal;
                spheres_[c.b].velocity += change * c.normal;
            }
        }
        // A sweep that changed nothing leaves the next one the same state: stopping early
        // changes no bits, only saves the sweeps once every contact meets its target.
        if (!changed) break;
    }
}

// Overlaps are removed by moving positions only (no velocity bias, so no energy is injected
// as speed): a pair is pushed apart equally along its normal, which keeps its centre of mass
// and so its potential energy; a wall puts the sphere back on its surface. The walls come
// last in every sweep, so a step always ends with every sphere inside the box; what is left
// of a pair overlap after the last sweep is resolved in the next step.
void FallingSpheres::resolveOverlaps() {
    const double r = settings_.radius;
    const double diameter = 2.0 * r;
    const glm::dvec3 lo = settings_.box.min + glm::dvec3(r);
    const glm::dvec3 hi = settings_.box.max - glm::dvec3(r);
    for (int sweep = 0; sweep < settings_.positionIterations; ++sweep) {
        bool moved = false;
        for (std::size_t i = 0; i < spheres_.size(); ++i) {
            for (std::size_t j = i + 1; j < spheres_.size(); ++j) {
                const glm::dvec3 d = spheres_[j].position - spheres_[i].position;
                const double distanceSquared = glm::dot(d, d);
                if (distanceSquared >= diameter * diameter) continue;
                const double distance = std::sqrt(distanceSquared);
                const glm::dvec3 normal = distance > 0.0 ? d / distance : glm::dvec3(0.0, 1.0, 0.0);
                const glm::dvec3 half = (0.5 * (diameter - distance)) * normal;
                spheres_[i].position -= half;
                spheres_[j].position += half;
                moved = true;
            }
        }
        for (Sphere& sphere : spheres_) {
            for (int axis = 0; axis < 3; ++axis) {
                if (sphere.position[axis] < lo[axis]) {
                    sphere.position[axis] = lo[axis];
                    moved = true;
                }
                if (sphere.position[axis] > hi[axis]) {
                    sphere.position[axis] = hi[axis];
                    moved = true;
                }
            }
        }
        if (!moved) break;  // as for the impulses: the next sweep would change nothing
    }
}

bool FallingSpheres::remove(std::uint32_t id) {
    const auto it = std::lower_bound(spheres_.begin(), spheres_.end(), id,
                                     [](const Sphere& sphere, std::uint32_t wanted) { return sphere.id < wanted; });
    if (it == spheres_.end() || it->id != id) return false;
    spheres_.erase(it);
    const std::size_t present = spheres_.size() + pendingSpawnSteps_.size();
    if (spawn_ && present < static_cast<std::size_t>(settings_.sphereCount)) {
        const auto delaySteps = static_cast<std::int64_t>(std::llround(settings_.spawnDelayS * settings_.stepRateHz));
        pendingSpawnSteps_.push_back(stepCount_ + delaySteps);
    }
    return true;
}

void FallingSpheres::spawnDue() {
    // Due spawns enter in the order they were scheduled; one that finds no room keeps its
    // place (and the ones behind it wait) until the next step.
    std::size_t entered = 0;
    while (entered < pendingSpawnSteps_.size() && pendingSpawnSteps_[entered] <= stepCount_ && trySpawn()) {
        ++entered;
    }
    pendingSpawnSteps_.erase(pendingSpawnSteps_.begin(),
                             pendingSpawnSteps_.begin() + static_cast<std::ptrdiff_t>(entered));
}

bool FallingSpheres::trySpawn() {
    if (nextId_ == std::numeric_limits<std::uint32_t>::max()) {
        throw std::length_error("FallingSpheres: sphere ids exhausted");
    }
    const double r = settings_.radius;
    const glm::dvec3 lo = settings_.box.min + glm::dvec3(r);
    const glm::dvec3 hi = settings_.box.max - glm::dvec3(r);
    for (int attempt = 0; attempt < kSpawnTries; ++attempt) {
        const glm::dvec3 candidate(lo.x + uniform01(rngState_) * (hi.x - lo.x), hi.y,
                                   lo.z + uniform01(rngState_) * (hi.z - lo.z));
        const bool free = std::none_of(spheres_.begin(), spheres_.end(), [&](const Sphere& s) {
            const glm::dvec3 d = s.position - candidate;
            return glm::dot(d, d) < 4.0 * r * r;
        });
        if (!free) continue;
        Sphere sphere;
        sphere.id = nextId_++;
        sphere.position = candidate;
        sphere.velocity = entryVelocity(rngState_, settings_.spawnSpeed);
        sphere.green = uniform01(rngState_) < settings_.greenShare;
        spheres_.push_back(sphere);
        return true;
    }
    return false;
}

double FallingSpheres::kineticEnergy() const {
    double sum = 0.0;
    for (const Sphere& sphere : spheres_) sum += 0.5 * glm::dot(sphere.velocity, sphere.velocity);
    return sum;
}

double FallingSpheres::potentialEnergy() const {
    const double floorContactY = settings_.box.min.y + settings_.radius;
    double sum = 0.0;
    for (const Sphere& sphere : spheres_) {
        sum += settings_.gravity * (sphere.position.y - floorContactY);
    }
    return sum;
}

double FallingSpheres::maxPenetration() const {
    const double r = settings_.radius;
    const glm::dvec3 lo = settings_.box.min + glm::dvec3(r);
    const glm::dvec3 hi = settings_.box.max - glm::dvec3(r);
    double deepest = 0.0;
    for (std::size_t i = 0; i < spheres_.size(); ++i) {
        const glm::dvec3 p = spheres_[i].position;
        for (int axis = 0; axis < 3; ++axis) {
            deepest = std::max({deepest, lo[axis] - p[axis], p[axis] - hi[axis]});
        }
        for (std::size_t j = i + 1; j < spheres_.size(); ++j) {
            deepest = std::max(deepest, 2.0 * r - glm::length(spheres_[j].position - p));
        }
    }
    return deepest;
}

}  // namespace warplab::physics
