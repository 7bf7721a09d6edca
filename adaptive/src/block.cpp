#include "adaptive/block.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "physics/splitmix.h"

namespace warplab::adaptive {

Procedure::Procedure(ProcedureSettings settings, std::uint64_t seed) : settings_(std::move(settings)) {
    switch (settings_.method) {
        case Method::QuestPlus:
            quest_.emplace(settings_.quest);
            questNext_ = quest_->next();
            break;
        case Method::Staircase: staircase_.emplace(settings_.staircase); break;
        case Method::ConstantStimuli:
            if (settings_.staircase.stimuli.empty()) throw std::invalid_argument("constant stimuli need levels");
            order_ = constantStimuliOrder(settings_.staircase.stimuli.size(), settings_.repeats, seed);
            return;
    }
    if (settings_.maxTrials < 1)
        throw std::invalid_argument("an adaptive procedure needs a trial limit of 1 or more, or it may never stop");
    if (settings_.stopWidth < 0.0) throw std::invalid_argument("a stopping width cannot be negative");
}

const std::vector<double>& Procedure::levels() const {
    return settings_.method == Method::QuestPlus ? settings_.quest.stimuli : settings_.staircase.stimuli;
}

std::size_t Procedure::next() const {
    if (quest_) return questNext_;
    if (staircase_) return staircase_->next();
    return order_.at(trials_);
}

void Procedure::update(bool correct) {
    if (finished()) throw std::logic_error("an answer to a procedure that has finished");
    if (quest_) {
        quest_->update(questNext_, correct);
        questNext_ = quest_->next();
    }
    if (staircase_) staircase_->update(correct);
    ++trials_;
}

bool Procedure::finished() const {
    if (settings_.method == Method::ConstantStimuli) return trials_ >= order_.size();
    if (trials_ >= static_cast<std::size_t>(settings_.maxTrials)) return true;
    if (quest_ && settings_.stopWidth > 0.0 && trials_ > 0) {
        const Estimate t = quest_->threshold();
        return t.high - t.low <= settings_.stopWidth;
    }
    return false;
}

Block::Block(const std::vector<ProcedureSettings>& procedures, std::uint64_t seed) : seed_(seed) {
    if (procedures.empty()) throw std::invalid_argument("a block needs at least one procedure");
    std::uint64_t state = seed;  // each procedure's own seed (constant stimuli shuffle with it)
    for (const ProcedureSettings& p : procedures) procedures_.emplace_back(p, physics::splitmix64(state));
}

std::optional<std::size_t> Block::nextProcedure() const {
    std::vector<std::size_t> open;
    for (std::size_t i = 0; i < procedures_.size(); ++i)
        if (!procedures_[i].finished()) open.push_back(i);
    if (open.empty()) return std::nullopt;
    // A draw of its own per answer, so that the choice depends only on the seed and how many
    // answers came before it.
    std::uint64_t state = seed_ ^ (0xd1b54a32d192ed03ULL * (answers_ + 1));
    const auto pick = static_cast<std::size_t>(physics::uniform01(state) * static_cast<double>(open.size()));
    return open[std::min(pick, open.size() - 1)];
}

void Block::answer(bool correct) {
    const std::optional<std::size_t> i = nextProcedure();
    if (!i) throw std::logic_error("an answer to a block whose procedures have all finished");
    procedures_[*i].update(correct);
    ++answers_;
}

}  // namespace warplab::adaptive
