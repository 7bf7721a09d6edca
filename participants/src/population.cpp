#include "participants/population.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "game/random.h"

namespace warplab::participants {
namespace {

using P = ParticipantParams;

// A trait's own random stream: keyed by its name, not its place in the list.
std::uint64_t traitSeed(std::uint64_t seed, const char* name) {
    std::uint64_t h = 1469598103934665603ULL;  // FNV-1a
    for (const char* c = name; *c != '\0'; ++c) h = (h ^ static_cast<unsigned char>(*c)) * 1099511628211ULL;
    return game::mix(game::mix(seed ^ 0x9E0B1A7E5ULL) ^ h);
}

std::string numberText(double v) {
    std::ostringstream out;
    out.precision(6);
    out << v;
    return out.str();
}

}  // namespace

const std::vector<TraitSpec>& traitSpecs() {
    static const std::vector<TraitSpec> specs = {
        {"reaction_s", &P::reactionS, true, 0.1, 0.5, "visual reaction time, s"},
        {"pursuit_gain", &P::pursuitGain, false, 0.3, 1.2, "share of the target's velocity the hand follows"},
        {"correction_per_s", &P::correctionPerS, true, 1.0, 30.0, "share of the aiming error closed per second"},
        {"motion_window_s", &P::motionWindowS, true, 0.05, 0.8, "how long a target is watched to judge its motion, s"},
        {"motor_noise", &P::motorNoise, true, 0.0, 0.5, "hand velocity noise per unit of commanded speed"},
        {"click_within", &P::clickWithin, true, 0.1, 1.5, "click when the error is under this share of the radius"},
        {"min_aim_s", &P::minAimS, true, 0.0, 1.0, "least time aimed at a target before clicking, s"},
        {"urgency_per_s", &P::urgencyPerS, true, 0.0, 5.0, "growth of the click criterion per second of aiming"},
        {"delay_adaptation", &P::delayAdaptation, false, 0.0, 1.0,
         "share of the display's delay, as seen, that the internal model bridges"},
        {"rating_scale", &P::ratingScale, true, 0.1, 1.5, "how much of the rating scale is used (1: all of it)"},
        {"rating_bias", &P::ratingBias, false, -3.0, 3.0, "shift of every rating, scale points"},
        {"rating_noise", &P::ratingNoise, true, 0.0, 3.0, "standard deviation of one answer's noise, scale points"},
    };
    return specs;
}

Population uniformPopulation() {
    Population p;
    const ParticipantParams typical;
    for (const auto& spec : traitSpecs()) p.traits.push_back({typical.*spec.field, 0.0});
    p.description = "the model's defaults, every participant alike";
    return p;
}

Population parsePopulation(const std::string& text, const std::string& source) {
    const auto fail = [&](const std::string& what) -> PopulationError {
        return PopulationError("population file '" + source + "': " + what);
    };
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        throw fail(std::string("is not JSON (") + e.what() + ")");
    }
    if (!j.is_object()) throw fail("is not a JSON object");
    if (!j.contains("traits") || !j["traits"].is_object()) throw fail("has no 'traits' object");
    const auto& traits = j["traits"];
    for (const auto& item : traits.items()) {
        const bool known = std::any_of(traitSpecs().begin(), traitSpecs().end(),
                                       [&](const TraitSpec& s) { return item.key() == s.name; });
        if (!known) throw fail("traits." + item.key() + " is not a trait of the model");
    }
    Population p;
    if (j.contains("description") && j["description"].is_string()) p.description = j["description"];
    for (const auto& spec : traitSpecs()) {
        const std::string field = std::string("traits.") + spec.name;
        if (!traits.contains(spec.name)) throw fail(field + " is missing (" + spec.what + ")");
        const auto& t = traits[spec.name];
        if (!t.is_object() || !t.contains("median") || !t["median"].is_number() || !t.contains("spread") ||
            !t["spread"].is_number())
            throw fail(field + " needs a number 'median' and a number 'spread'");
        TraitSpread s{t["median"].get<double>(), t["spread"].get<double>()};
        if (!(s.median >= spec.min && s.median <= spec.max) || (spec.logNormal && s.median <= 0.0))
            throw fail(field + ".median is " + numberText(s.median) + ", outside " + numberText(spec.min) + ".." +
                       numberText(spec.max));
        if (!(s.spread >= 0.0 && s.spread <= 10.0))
            throw fail(field + ".spread is " + numberText(s.spread) + ", not between 0 and 10");
        p.traits.push_back(s);
    }
    return p;
}

Population readPopulation(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw PopulationError("cannot read the population file '" + path + "'");
    std::ostringstream text;
    text << in.rdbuf();
    return parsePopulation(text.str(), path);
}

std::string populationJson(const Population& population) {
    nlohmann::ordered_json j;
    j["description"] = population.description;
    nlohmann::ordered_json traits = nlohmann::ordered_json::object();
    for (std::size_t i = 0; i < traitSpecs().size(); ++i)
        traits[traitSpecs()[i].name] = {{"median", population.traits.at(i).median},
                                        {"spread", population.traits.at(i).spread}};
    j["traits"] = traits;
    return j.dump(2) + "\n";
}

std::string populationPath(const std::string& assetDir) { return assetDir + "/population.json"; }

ParticipantParams drawParticipant(const Population& population, std::uint64_t seed) {
    ParticipantParams params;
    const auto& specs = traitSpecs();
    if (population.traits.size() != specs.size())
        throw std::invalid_argument("drawParticipant: the population has " + std::to_string(population.traits.size()) +
                                    " traits, the model " + std::to_string(specs.size()));
    for (std::size_t i = 0; i < specs.size(); ++i) {
        const TraitSpread& t = population.traits[i];
        game::Random random(traitSeed(seed, specs[i].name));
        const double z = random.gaussian();
        const double value = specs[i].logNormal ? t.median * std::exp(t.spread * z) : t.median + t.spread * z;
        params.*specs[i].field = std::clamp(value, specs[i].min, specs[i].max);
    }
    return params;
}

std::string participantJson(const ParticipantParams& params) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    for (const auto& spec : traitSpecs()) j[spec.name] = params.*spec.field;
    return j.dump();
}

}  // namespace warplab::participants
