// A population of simulated participants, not a clone: each participant's parameters are drawn
// from stated distributions, seeded by the participant's seed, so that a simulated study has
// people who differ from one another as a real study's do -- faster and slower, steadier and
// shakier, lenient and harsh on the rating scale.
//
// The population is data: assets/population.json (docs/simulated-participant.md says how its
// medians were fitted to one paper's people and checked against the other's). `warplab run
// --population FILE` and `warplab demo --population FILE` play another.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "participants/participant.h"

namespace warplab::participants {

// How one parameter varies across participants. Log-normal traits (positive scales: times,
// gains, noise) vary by a factor: the median times exp(spread x z). Normal traits (shares,
// biases) vary by an amount: the median plus spread x z. Either is clamped to [min, max].
struct TraitSpec {
    const char* name;  // the key in the population file
    double ParticipantParams::*field;
    bool logNormal;
    double min, max;  // what a drawn participant may have; a median outside is refused
    const char* what;  // for the docs and error messages
};
// Every trait a population sets, in the file's order. The single list: the reader, the
// draw, the header's record of a participant and the docs' table follow it.
const std::vector<TraitSpec>& traitSpecs();

struct TraitSpread {
    double median = 0.0;
    double spread = 0.0;  // 0: every participant has the median
};

struct Population {
    std::vector<TraitSpread> traits;  // one per traitSpecs() entry, in its order
    std::string description;  // where its values come from
};

// The model's own defaults (ParticipantParams{}) as medians, with no spread: every participant
// the same typical one. What tests that want one known participant use.
Population uniformPopulation();

class PopulationError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};
// Reads a population file. Throws PopulationError in one sentence naming the file and the
// field for a file that is missing or not JSON, an unknown or missing trait, a median outside
// the trait's range or a negative spread.
Population readPopulation(const std::string& path);
Population parsePopulation(const std::string& json, const std::string& source);
std::string populationJson(const Population& population);
// The population shipped in assetDir (assets/population.json).
std::string populationPath(const std::string& assetDir);

// The participant with this seed: each trait drawn from its own stream of the seed (so adding a
// trait to the list changes no other's draw), from the population's median and spread.
ParticipantParams drawParticipant(const Population& population, std::uint64_t seed);

// The traits of one participant as a JSON object, keys as in the population file; what a
// session's header records of a simulated participant.
std::string participantJson(const ParticipantParams& params);

}  // namespace warplab::participants
