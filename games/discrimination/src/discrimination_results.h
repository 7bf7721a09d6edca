// A discrimination session's events as export's rows: every answered trial
// (discrimination_trials.csv) and each procedure's estimates (thresholds.csv).
#pragma once

#include <vector>

#include "discrimination/discrimination_protocol.h"
#include "game/results.h"
#include "session/rows.h"

namespace warplab::discrimination {

std::vector<game::GameTable> emptyTables();
// The two tables with this session's rows.
std::vector<game::GameTable> resultTables(const DiscriminationProtocol& protocol,
                                          const std::vector<session::EventRecord>& events);

// What QUEST+'s posterior says of the stimulus at percentCorrect: its mean and 95 % credible
// interval over the grid.
adaptive::Estimate thresholdAt(const adaptive::QuestPlus& quest, double percentCorrect);

}  // namespace warplab::discrimination
