// Private to export/: participants.csv, a study plan's participants beside their sessions
// (docs/export.md).
#pragma once

#include <string>
#include <vector>

#include "csv_columns.h"
#include "plan/status.h"
#include "plan/study_plan.h"

namespace warplab::exporter {

// One planned participant: their plan and where they stand (plan/status.h).
struct ParticipantRow {
    const plan::StudyPlan& plan;
    const plan::ParticipantPlan& participant;
    const plan::ParticipantStatus& status;
    const std::string& playerKinds;  // of their sessions the export read, ;-separated
};

// One place in one of a participant's orders: a row of orders.csv, the plan's orders as R reads
// them without splitting strings.
struct OrderRow {
    const std::string& participant;
    int protocolPosition;  // 1-based, in the order they play the protocols
    const std::string& protocol;
    int position;  // 1-based, in that protocol's counterbalanced order
    const std::string& condition;
};

const std::vector<Column<ParticipantRow>>& participantColumns();
const std::vector<Column<OrderRow>>& orderColumns();

// participants.csv and orders.csv in outDir: one row per planned participant, in plan order,
// and one per place in each of their condition orders; their paths. Their status and player
// kinds from the sessions the export read (those of other plans are passed over).
std::vector<std::string> writeParticipants(const std::string& outDir, const plan::StudyPlan& studyPlan,
                                           const std::vector<plan::SessionFacts>& sessions);

}  // namespace warplab::exporter
