// splitmix64 (Steele, Lea, Flood 2014): tiny and fully specified by integer arithmetic, so a
// seed means the same numbers with every compiler and standard library (the <random>
// distributions do not promise that). The one copy: physics, the games and the bots draw
// from it.
#pragma once

#include <cstdint>

namespace warplab::physics {

// Advances `state` and returns the next number of its stream.
inline std::uint64_t splitmix64(std::uint64_t& state) {
    state += 0x9E3779B97F4A7C15ULL;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

// Uniform in [0, 1): the top 53 bits, exactly representable.
inline double uniform01(std::uint64_t& state) { return static_cast<double>(splitmix64(state) >> 11) * 0x1.0p-53; }

}  // namespace warplab::physics
