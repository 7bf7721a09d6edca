// A block of a discrimination task's adaptive procedures: each a QUEST+, a staircase or constant
// stimuli with its stopping rule, several interleaved at random (latency with and without late
// warp, say). Which procedure runs next is drawn from the block's seed and the number of answers
// so far, and each procedure is a function of its answers, so feeding a session's recorded
// answers again -- replay, or resume after a crash -- gives the same choices from then on.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "adaptive/quest_plus.h"
#include "adaptive/staircase.h"

namespace warplab::adaptive {

enum class Method { QuestPlus, Staircase, ConstantStimuli };

struct ProcedureSettings {
    Method method = Method::QuestPlus;
    QuestPlusSettings quest;  // QuestPlus: its levels are quest.stimuli
    StaircaseSettings staircase;  // Staircase and ConstantStimuli: their levels are staircase.stimuli
    int repeats = 10;  // ConstantStimuli: trials at each level; it stops after all of them
    // QuestPlus and Staircase stop after maxTrials answers, and QuestPlus also once its
    // threshold's 95 % credible interval is at most stopWidth wide (0: no such rule).
    int maxTrials = 0;
    double stopWidth = 0.0;
};

class Procedure {
public:
    // Throws std::invalid_argument for settings its method cannot run, or a stopping rule that
    // can never stop (no trial limit for QUEST+ or a staircase).
    Procedure(ProcedureSettings settings, std::uint64_t seed);

    std::size_t next() const;  // index into levels()
    const std::vector<double>& levels() const;
    void update(bool correct);
    bool finished() const;
    std::size_t trials() const { return trials_; }
    const ProcedureSettings& settings() const { return settings_; }
    // The method's own state: the posterior, the reversals.
    const std::optional<QuestPlus>& quest() const { return quest_; }
    const std::optional<Staircase>& staircase() const { return staircase_; }

private:
    ProcedureSettings settings_;
    std::optional<QuestPlus> quest_;
    std::optional<Staircase> staircase_;
    std::vector<std::size_t> order_;  // ConstantStimuli: every trial's level
    // QuestPlus: its choice for the coming trial, made once per answer (the costly part: an
    // expected entropy per level over the whole grid).
    std::size_t questNext_ = 0;
    std::size_t trials_ = 0;
};

class Block {
public:
    Block(const std::vector<ProcedureSettings>& procedures, std::uint64_t seed);

    // The procedure whose trial comes next, drawn among the unfinished ones; none once all have
    // finished.
    std::optional<std::size_t> nextProcedure() const;
    // The answer to that trial (at its procedure's next level).
    void answer(bool correct);
    const Procedure& procedure(std::size_t i) const { return procedures_.at(i); }
    std::size_t size() const { return procedures_.size(); }
    std::size_t answers() const { return answers_; }

private:
    std::vector<Procedure> procedures_;
    std::uint64_t seed_;
    std::size_t answers_ = 0;
};

}  // namespace warplab::adaptive
