// Private to export/: participants.csv, a study plan's participants beside their sessions
// (docs/export.md).
#pragma once

#include <string>
#include <vector>

#include "columns.h"
#include "plan/status.h"
#include "plan/study_plan.h"

namespace warplab::exporter {

// One planned participant: their plan and where they stand (plan/status.h).
struct ParticipantRow {
    const plan::StudyPlan& plan;
    const plan::ParticipantPlan& participant;
    const plan::ParticipantStatus& status;
};

const std::vector<Column<ParticipantRow>>& participantColumns();

// participants.csv in outDir: one row per planned participant, in plan order; its path.
// Their status from the sessions the export read (those of other plans are passed over).
std::string writeParticipants(const std::string& outDir, const plan::StudyPlan& studyPlan,
                              const std::vector<plan::SessionFacts>& sessions);

}  // namespace warplab::exporter
