// A block of interleaved procedures: the draw of which runs next, the stopping rules, and a
// block resumed from its recorded answers choosing as the uninterrupted one does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <vector>

#include "adaptive/block.h"
#include "physics/splitmix.h"

namespace warplab::adaptive {
namespace {

std::vector<double> levels() {
    std::vector<double> out;
    for (int k = 0; k < 16; ++k) out.push_back(2.0 * std::pow(40.0, k / 15.0));  // 2 to 80 ms
    return out;
}

ProcedureSettings quest(int maxTrials) {
    ProcedureSettings p;
    p.method = Method::QuestPlus;
    p.quest.stimuli = levels();
    p.quest.thresholds = levels();
    p.quest.slopes = {1.5, 3, 5};
    p.quest.lapses = {0.02};
    p.maxTrials = maxTrials;
    return p;
}

ProcedureSettings staircase(int maxTrials) {
    ProcedureSettings p;
    p.method = Method::Staircase;
    p.staircase.stimuli = levels();
    p.staircase.start = 12;
    p.maxTrials = maxTrials;
    return p;
}

ProcedureSettings constant(int repeats) {
    ProcedureSettings p;
    p.method = Method::ConstantStimuli;
    p.staircase.stimuli = {5, 10, 20, 40};
    p.repeats = repeats;
    return p;
}

// A simulated observer: procedure i's dimension has threshold 8 ms times (i + 1).
struct Observer {
    std::uint64_t chance;
    bool answer(const Block& b, std::size_t i) {
        const Procedure& p = b.procedure(i);
        const double x = p.levels()[p.next()];
        return physics::uniform01(chance) < PsychometricFunction{}.probability(x, 8.0 * (i + 1), 3.0, 0.02);
    }
};

struct Trial {
    std::size_t procedure, level;
    bool correct;
};

std::vector<Trial> play(Block& block, Observer& observer, std::size_t limit = 100000) {
    std::vector<Trial> out;
    while (out.size() < limit) {
        const auto i = block.nextProcedure();
        if (!i) break;
        const std::size_t level = block.procedure(*i).next();
        const bool correct = observer.answer(block, *i);
        block.answer(correct);
        out.push_back({*i, level, correct});
    }
    return out;
}

TEST(Block, InterleavesItsProceduresAtRandomUntilEachStops) {
    const std::vector<ProcedureSettings> settings = {quest(30), quest(20), staircase(25), constant(3)};
    Block block(settings, 11);
    Observer observer{5};
    const std::vector<Trial> trials = play(block, observer);
    ASSERT_EQ(trials.size(), 30u + 20u + 25u + 12u);
    std::vector<std::size_t> count(4, 0);
    for (const Trial& t : trials) ++count[t.procedure];
    EXPECT_EQ(count, (std::vector<std::size_t>{30, 20, 25, 12}));
    std::set<std::size_t> early;
    for (std::size_t k = 0; k < 12; ++k) early.insert(trials[k].procedure);
    EXPECT_GE(early.size(), 3u) << "interleaved, not one after another";
    for (std::size_t i = 0; i < 4; ++i) EXPECT_TRUE(block.procedure(i).finished()) << i;
    EXPECT_FALSE(block.nextProcedure());
    EXPECT_THROW(block.answer(true), std::logic_error);

    // Seeded: the same again, and another seed another order.
    Block again(settings, 11);
    Observer same{5};
    const std::vector<Trial> replayed = play(again, same);
    ASSERT_EQ(replayed.size(), trials.size());
    for (std::size_t k = 0; k < trials.size(); ++k) ASSERT_EQ(replayed[k].procedure, trials[k].procedure) << k;
    Block other(settings, 12);
    Observer third{5};
    const std::vector<Trial> reordered = play(other, third);
    std::size_t differ = 0;
    for (std::size_t k = 0; k < 20; ++k) differ += reordered[k].procedure != trials[k].procedure;
    EXPECT_GT(differ, 5u);
}

// A session killed after 23 answers and resumed: the block rebuilt from the recorded answers
// chooses every later procedure and level as the uninterrupted one did.
TEST(Block, ResumedFromItsAnswersItChoosesAsIfNeverStopped) {
    const std::vector<ProcedureSettings> settings = {quest(25), staircase(25), constant(2)};
    Block whole(settings, 77);
    Observer observer{9};
    const std::vector<Trial> uninterrupted = play(whole, observer);

    Block resumed(settings, 77);
    for (std::size_t k = 0; k < 23; ++k) {
        ASSERT_EQ(resumed.nextProcedure(), uninterrupted[k].procedure);
        resumed.answer(uninterrupted[k].correct);
    }
    EXPECT_EQ(resumed.answers(), 23u);
    for (std::size_t k = 23; k < uninterrupted.size(); ++k) {
        const auto i = resumed.nextProcedure();
        ASSERT_TRUE(i);
        ASSERT_EQ(*i, uninterrupted[k].procedure) << "trial " << k;
        ASSERT_EQ(resumed.procedure(*i).next(), uninterrupted[k].level) << "trial " << k;
        resumed.answer(uninterrupted[k].correct);
    }
    EXPECT_FALSE(resumed.nextProcedure());
}

TEST(Block, QuestPlusStopsWhenItsIntervalIsNarrowEnough) {
    ProcedureSettings narrow = quest(400);
    narrow.stopWidth = 6.0;  // ms
    Block block({narrow}, 3);
    Observer observer{21};
    const std::vector<Trial> trials = play(block, observer);
    EXPECT_LT(trials.size(), 400u);
    // Each trial at the level QUEST+ itself chooses after the answers before it.
    QuestPlus alone(narrow.quest);
    for (const Trial& trial : trials) {
        ASSERT_EQ(trial.level, alone.next());
        alone.update(trial.level, trial.correct);
    }
    const Estimate t = block.procedure(0).quest()->threshold();
    EXPECT_LE(t.high - t.low, 6.0);
    EXPECT_GT(trials.size(), 10u);
}

TEST(Block, RefusesAProcedureThatCouldNeverStop) {
    EXPECT_THROW(Procedure(quest(0), 1), std::invalid_argument);
    EXPECT_THROW(Procedure(staircase(0), 1), std::invalid_argument);
    ProcedureSettings none = constant(1);
    none.staircase.stimuli.clear();
    EXPECT_THROW(Procedure(none, 1), std::invalid_argument);
    EXPECT_THROW(Block({}, 1), std::invalid_argument);
}

}  // namespace
}  // namespace warplab::adaptive
