// The population simulated participants are drawn from (participants/population.h): draws
// reproducible from the seed and different across participants, the file refused in one
// sentence naming the field, and ratings that differ from one participant to the next.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "participants/participant.h"
#include "participants/population.h"

namespace warplab {
namespace {

using participants::traitSpecs;

participants::Population shipped() {
    return participants::readPopulation(participants::populationPath(std::string(WARPLAB_SOURCE_DIR) + "/assets"));
}

TEST(Population, TheShippedPopulationReadsAndSetsEveryTraitWithASpread) {
    const participants::Population p = shipped();
    ASSERT_EQ(p.traits.size(), traitSpecs().size());
    EXPECT_FALSE(p.description.empty());
    for (std::size_t i = 0; i < p.traits.size(); ++i) EXPECT_GT(p.traits[i].spread, 0.0) << traitSpecs()[i].name;
}

TEST(Population, DrawsAreReproducibleFromTheSeedAndDifferAcrossParticipants) {
    const participants::Population p = shipped();
    constexpr int kPeople = 40;
    std::vector<participants::ParticipantParams> people;
    for (int seed = 1; seed <= kPeople; ++seed) people.push_back(participants::drawParticipant(p, seed));
    for (std::size_t t = 0; t < traitSpecs().size(); ++t) {
        const auto& spec = traitSpecs()[t];
        std::set<double> values;
        double sum = 0.0, sum2 = 0.0;
        for (int i = 0; i < kPeople; ++i) {
            const double v = people[i].*spec.field;
            EXPECT_EQ(v, participants::drawParticipant(p, static_cast<std::uint64_t>(i + 1)).*spec.field)
                << spec.name << ": seed " << i + 1 << " drew another value the second time";
            EXPECT_GE(v, spec.min) << spec.name;
            EXPECT_LE(v, spec.max) << spec.name;
            values.insert(v);
            const double x = spec.logNormal ? std::log(v) : v;
            sum += x;
            sum2 += x * x;
        }
        EXPECT_GE(values.size(), static_cast<std::size_t>(kPeople * 3 / 4)) << spec.name << ": too many alike";
        // The spread drawn is the spread asked for (loosely: 40 draws, and clamping).
        const double mean = sum / kPeople, sd = std::sqrt((sum2 - kPeople * mean * mean) / (kPeople - 1));
        EXPECT_GT(sd, 0.5 * p.traits[t].spread) << spec.name;
        EXPECT_LT(sd, 1.6 * p.traits[t].spread) << spec.name;
        const double median = spec.logNormal ? std::log(p.traits[t].median) : p.traits[t].median;
        EXPECT_NEAR(mean, median, 0.6 * p.traits[t].spread) << spec.name;
    }
    // One trait's draw does not move with another's: a seed's reaction time is its own.
    participants::Population noSpreadElsewhere = p;
    for (std::size_t t = 0; t < traitSpecs().size(); ++t)
        if (std::string(traitSpecs()[t].name) != "reaction_s") noSpreadElsewhere.traits[t].spread = 0.0;
    EXPECT_EQ(participants::drawParticipant(noSpreadElsewhere, 7).reactionS,
              participants::drawParticipant(p, 7).reactionS);
}

TEST(Population, TheUniformPopulationIsTheModelsDefaults) {
    const participants::ParticipantParams typical;
    for (std::uint64_t seed : {1u, 2u, 99u}) {
        const auto drawn = participants::drawParticipant(participants::uniformPopulation(), seed);
        for (const auto& spec : traitSpecs()) EXPECT_EQ(drawn.*spec.field, typical.*spec.field) << spec.name;
    }
}

TEST(Population, AParticipantsTraitsAreWrittenAsJsonForTheHeader) {
    participants::ParticipantParams p;
    p.reactionS = 0.25;
    const std::string json = participants::participantJson(p);
    for (const auto& spec : traitSpecs())
        EXPECT_NE(json.find(std::string("\"") + spec.name + "\":"), std::string::npos);
    EXPECT_NE(json.find("\"reaction_s\":0.25"), std::string::npos) << json;
    // And the file the fit writes reads back as it was.
    const participants::Population again =
        participants::parsePopulation(participants::populationJson(shipped()), "written");
    for (std::size_t t = 0; t < traitSpecs().size(); ++t) {
        EXPECT_EQ(again.traits[t].median, shipped().traits[t].median);
        EXPECT_EQ(again.traits[t].spread, shipped().traits[t].spread);
    }
}

std::string refusal(const std::string& json) {
    try {
        participants::parsePopulation(json, "pop.json");
    } catch (const participants::PopulationError& e) {
        return e.what();
    }
    return "(accepted)";
}

TEST(Population, ABadFileIsRefusedNamingTheFileAndTheField) {
    std::string good = participants::populationJson(shipped());
    EXPECT_EQ(refusal(good), "(accepted)");
    const auto replaced = [&](const std::string& from, const std::string& to) {
        std::string text = good;
        const auto at = text.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        return text.replace(at, from.size(), to);
    };
    EXPECT_NE(refusal("{").find("population file 'pop.json': malformed JSON at line 1, column 2"), std::string::npos);
    EXPECT_EQ(refusal("{}"), "population file 'pop.json': traits is required but missing");
    EXPECT_NE(refusal(replaced("\"reaction_s\"", "\"reaction_time\""))
                  .find("population file 'pop.json': traits.reaction_time is not a known field (traits may have "
                        "reaction_s, pursuit_gain,"),
              std::string::npos);
    EXPECT_EQ(refusal(replaced("\"pursuit_gain\": {\n      \"median\"", "\"pursuit_gain\": {\n      \"mean\"")),
              "population file 'pop.json': traits.pursuit_gain.mean is not a known field (traits.pursuit_gain may "
              "have median, spread)");
    EXPECT_NE(
        refusal(replaced("\"delay_adaptation\": {\n      \"median\": ", "\"delay_adaptation\": {\n      \"median\": 7"))
            .find("traits.delay_adaptation.median must be a number between 0 and 1, got 7"),
        std::string::npos);
    EXPECT_NE(refusal(replaced("\"rating_noise\": {\n      \"median\": ", "\"rating_noise\": {\n      \"median\": -"))
                  .find("traits.rating_noise.median"),
              std::string::npos);
    EXPECT_NE(
        refusal(replaced("\"spread\": ", "\"spread\": -")).find(".spread must be a number between 0 and 10, got -"),
        std::string::npos);
    // Every trait must be there: a missing one is named with what it is.
    std::string missing = good;
    const auto at = missing.find("\"motor_noise\"");
    missing.erase(at, missing.find('}', at) + 2 - at);
    EXPECT_NE(refusal(missing).find("traits.motor_noise is required but missing (hand velocity noise"),
              std::string::npos)
        << refusal(missing);
    EXPECT_THROW(participants::readPopulation("/nonexistent/population.json"), participants::PopulationError);
}

// What the population reader accepted without a word before it was the strict reader's: each
// is refused in one sentence naming the file and the field (or line).
TEST(Population, EveryKeyTypeAndByteOfTheFileIsChecked) {
    const std::string good = participants::populationJson(shipped());
    const auto replaced = [&](const std::string& from, const std::string& to) {
        std::string text = good;
        const auto at = text.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        return text.replace(at, from.size(), to);
    };
    const std::string firstTrait = "\"reaction_s\": {\n      \"median\": 0.2,\n      \"spread\": 0.12\n    }";
    const auto inFirstTrait = [&](const std::string& lines) {
        return replaced("\"median\": 0.2,\n", "\"median\": 0.2,\n      " + lines + "\n");
    };
    const std::size_t start = good.find("\"description\": ") + 15, end = good.find(",\n", start);
    const std::string afterLastLine = std::to_string(std::count(good.begin(), good.end(), '\n') + 1);
    const auto described = [&](const std::string& value) {
        return std::string(good).replace(start, end - start, value);
    };
    const struct {
        const char* what;
        std::string text;
        std::string says;
    } cases[] = {
        {"an unknown key", replaced("\"traits\": {", "\"colour\": \"red\",\n  \"traits\": {"),
         "colour is not a known field (the top level may have description, traits)"},
        {"a misspelt description", replaced("\"description\":", "\"descripton\":"), "descripton is not a known field"},
        {"a misspelt section beside the real one", replaced("\"traits\": {", "\"trait\": {},\n  \"traits\": {"),
         "trait is not a known field"},
        {"an unknown key in a trait", inFirstTrait("\"mean\": 0.3,"),
         "traits.reaction_s.mean is not a known field (traits.reaction_s may have median, spread)"},
        {"a misspelt key in a trait", inFirstTrait("\"sprad\": 0.1,"), "traits.reaction_s.sprad is not a known field"},
        {"a median written twice", inFirstTrait("\"median\": 0.3,"), "traits.reaction_s.median appears more than once"},
        {"a spread written twice", inFirstTrait("\"spread\": 0.3,"), "traits.reaction_s.spread appears more than once"},
        {"a trait written twice", replaced(firstTrait, firstTrait + ",\n    " + firstTrait),
         "traits.reaction_s appears more than once"},
        {"the description written twice", replaced("\"traits\": {", "\"description\": \"again\",\n  \"traits\": {"),
         "description appears more than once"},
        {"the traits written twice", replaced("\"description\":", "\"traits\": {},\n  \"description\":"),
         "traits appears more than once"},
        {"a number as the description", described("5"), "description must be a text of at most 1000 bytes"},
        {"null as the description", described("null"), "description must be a text of at most 1000 bytes"},
        {"an array as the description", described("[\"a\"]"), "description must be a text of at most 1000 bytes"},
        {"an object as the description", described("{}"), "description must be a text of at most 1000 bytes"},
        {"true as the description", described("true"), "description must be a text of at most 1000 bytes"},
        {"a control character in the description", described("\"bell \\u0007\""),
         "description must be a text of at most 1000 bytes without control characters"},
        {"a description over 1000 bytes", described("\"" + std::string(1001, 'x') + "\""),
         "description must be a text of at most 1000 bytes"},
        {"a trailing NUL", good + std::string(1, '\0'), "has a NUL byte at line " + afterLastLine},
        {"a NUL and a second document", good + std::string(1, '\0') + "{\"traits\": 1}",
         "has a NUL byte at line " + afterLastLine},
        {"a number beyond a double", replaced("\"median\": 0.2", "\"median\": 1e999"),
         "unreadable JSON at line 5, number overflow parsing '1e999' (beyond what a double holds)"},
    };
    ASSERT_EQ(refusal(good), "(accepted)");
    for (const auto& c : cases) {
        const std::string message = refusal(c.text);
        EXPECT_EQ(message.rfind("population file 'pop.json': ", 0), 0u) << c.what << ": " << message;
        EXPECT_NE(message.find(c.says), std::string::npos) << c.what << ": " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << c.what << ": " << message;
    }
}

// Ratings: the same match felt alike, rated differently by different participants (their
// scale use, bias and noise), and alike by participants drawn without spread.
std::vector<int> ratingsOf(const participants::Population& population, int people) {
    std::vector<int> ratings;
    for (int seed = 1; seed <= people; ++seed) {
        participants::TaskKnowledge knowledge;
        knowledge.display = {1920, 1080};
        knowledge.pixelsPerCount = 1.0;
        participants::SimulatedParticipant participant(knowledge, participants::drawParticipant(population, seed),
                                                       static_cast<std::uint64_t>(seed));
        double t = 0.0;
        for (int frame = 0; frame < 60; ++frame, t += 1.0 / 60.0) {  // a second of an empty match
            participants::Percept p;
            p.time = t;
            p.pointer = game::PointerKind::Cursor;
            p.pointerAt = {960.0, 540.0};
            participant.act(p);
        }
        participants::Percept question;
        question.sceneShown = false;
        question.question = game::QuestionPrompt{};
        question.question->prompt = "The animation was smooth";
        int answer = 0;
        for (int frame = 0; frame < 180 && answer == 0; ++frame, t += 1.0 / 60.0) {
            question.time = t;
            const game::FrameInput input = participant.act(question);
            for (int v = 1; v <= 7; ++v)
                if (input.keys & game::digitKey(v)) answer = v;
        }
        EXPECT_NE(answer, 0) << "participant " << seed << " never answered";
        ratings.push_back(answer);
    }
    return ratings;
}

TEST(Population, RatingsVaryAcrossParticipants) {
    const std::vector<int> alike = ratingsOf(participants::uniformPopulation(), 6);
    EXPECT_EQ(std::set<int>(alike.begin(), alike.end()).size(), 1u);
    const std::vector<int> drawn = ratingsOf(shipped(), 24);
    double sum = 0.0, sum2 = 0.0;
    for (int r : drawn) {
        sum += r;
        sum2 += r * r;
    }
    const double n = static_cast<double>(drawn.size()), mean = sum / n;
    const double sd = std::sqrt((sum2 - n * mean * mean) / (n - 1));
    // The papers' people: SDs about 1 on the 1..7 scale (Yang et al. 2011, Table 2).
    EXPECT_GT(sd, 0.5);
    EXPECT_LT(sd, 1.5);
    EXPECT_GE(std::set<int>(drawn.begin(), drawn.end()).size(), 3u);
}

}  // namespace
}  // namespace warplab

namespace warplab {
namespace {

// The docs' table of traits names every trait the model has (and says what the file sets).
TEST(Population, TheDocsNameEveryTrait) {
    std::ifstream in(std::string(WARPLAB_SOURCE_DIR) + "/docs/simulated-participant.md");
    std::stringstream text;
    text << in.rdbuf();
    ASSERT_FALSE(text.str().empty());
    for (const auto& spec : traitSpecs())
        EXPECT_NE(text.str().find(std::string("| `") + spec.name + "` |"), std::string::npos) << spec.name;
}

}  // namespace
}  // namespace warplab
