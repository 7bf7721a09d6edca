// Seeded randomness every game shares, drawn from physics/splitmix.h, never from the
// standard library's distributions, whose use of their engines is unspecified: a seed means
// the same trial order, spawns and bot behaviour on every machine.
#pragma once

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "physics/splitmix.h"

namespace warplab::game {

// One splitmix64 output for a given state: a well-mixed function of x.
inline std::uint64_t mix(std::uint64_t x) { return physics::splitmix64(x); }

// A seed for one purpose (tag) and one item (index) of a session.
inline std::uint64_t subSeed(std::uint64_t seed, int tag, int index) {
    return mix(seed ^ mix((static_cast<std::uint64_t>(tag) << 32) ^ static_cast<std::uint32_t>(index)));
}

// The seed of one schedule's render cadence (condition/pacing.h: jitter, random hitches): a
// stream of the session's seed per schedule, told apart by the session frame it starts at, so
// trials differ from one another and a replay draws the same cadence.
inline constexpr int kTagPacing = 90;
inline std::uint64_t pacingSeed(std::uint64_t seed, std::int64_t scheduleStart) {
    return subSeed(seed, kTagPacing, static_cast<int>(scheduleStart));
}

// Fisher-Yates with our own generator.
template <typename T>
void shuffle(std::vector<T>& items, std::uint64_t seed) {
    std::uint64_t state = seed;
    for (std::size_t i = items.size(); i > 1; --i) {
        state = mix(state);
        const std::size_t j = static_cast<std::size_t>(state % i);
        std::swap(items[i - 1], items[j]);
    }
}

// A stream of numbers for bots. Their inputs are recorded, so replay never depends on these
// numbers being the same elsewhere; they are anyway.
class Random {
public:
    explicit Random(std::uint64_t seed) : state_(seed) {}
    double uniform() {  // (0, 1): never 0, so log() below stays finite
        return (static_cast<double>(physics::splitmix64(state_) >> 11) + 0.5) * 0x1.0p-53;
    }
    double gaussian() {  // Box-Muller
        constexpr double kTwoPi = 6.28318530717958647692;
        const double u = uniform();
        return std::sqrt(-2.0 * std::log(u)) * std::cos(kTwoPi * uniform());
    }

private:
    std::uint64_t state_;
};

}  // namespace warplab::game
