#include "participants/population.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "game/random.h"
#include "strict/json.h"

namespace warplab::participants {
namespace {

using P = ParticipantParams;

// A trait's own random stream: keyed by its name, not its place in the list.
std::uint64_t traitSeed(std::uint64_t seed, const char* name) {
    std::uint64_t h = 1469598103934665603ULL;  // FNV-1a
    for (const char* c = name; *c != '\0'; ++c) h = (h ^ static_cast<unsigned char>(*c)) * 1099511628211ULL;
    return game::mix(game::mix(seed ^ 0x9E0B1A7E5ULL) ^ h);
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

namespace {

[[noreturn]] void raisePopulationError(const std::string& sentence) { throw PopulationError(sentence); }

// The shipped file is under 2 KB; a population is a dozen traits and a paragraph.
constexpr std::size_t kMaxPopulationBytes = 64 << 10;
constexpr double kMaxSpread = 10;

strict::Source populationSource(const std::string& path) {
    return {"population file", path, kMaxPopulationBytes, raisePopulationError};
}

Population fromJson(const strict::Reader& r, const strict::Json& document) {
    r.requireKnownKeys(document, "", {"description", "traits"});
    Population p;
    r.paragraph(&document, "", "description", p.description);
    const strict::Json& traits = r.objectAt(r.required(document, "", "traits"), "traits");
    std::vector<const char*> names;
    for (const auto& spec : traitSpecs()) names.push_back(spec.name);
    r.requireKnownKeys(traits, "traits", names);
    for (const auto& spec : traitSpecs()) {
        const std::string field = strict::joinPath("traits", spec.name);
        if (!traits.contains(spec.name)) r.fail(field, std::string("is required but missing (") + spec.what + ")");
        const strict::Json& t = r.objectAt(traits.at(spec.name), field);
        r.requireKnownKeys(t, field, {"median", "spread"});
        // A log-normal trait's median scales a factor: it must be above 0 even where the
        // trait's own range starts at 0.
        const strict::NumberRange median{spec.min, spec.logNormal && spec.min <= 0.0, spec.max, false};
        p.traits.push_back(
            {r.numberAt(r.required(t, field, "median"), field + ".median", median),
             r.numberAt(r.required(t, field, "spread"), field + ".spread", {0, false, kMaxSpread, false})});
    }
    return p;
}

}  // namespace

Population parsePopulation(const std::string& text, const std::string& source) {
    const strict::Reader r(populationSource(source));
    return fromJson(r, r.parseObject(text));
}

Population readPopulation(const std::string& path) {
    const strict::Reader r(populationSource(path));
    return fromJson(r, r.readObject());
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
