#include "participants_csv.h"

#include <filesystem>

namespace warplab::exporter {
namespace {

// "name: value; name: value", over the participant's protocols in their order.
template <class Value>
std::string perProtocol(const ParticipantRow& r, const Value& value) {
    std::string out;
    for (const int index : r.participant.protocolOrder)
        out += (out.empty() ? "" : "; ") + r.plan.protocols[static_cast<std::size_t>(index)].name + ": " + value(index);
    return out;
}

}  // namespace

const std::vector<Column<ParticipantRow>>& participantColumns() {
    using F = CsvFile;
    using R = ParticipantRow;
    static const std::vector<Column<R>> columns = {
        {"participant", [](F& f, const R& r) { f.text(r.participant.id); }},
        {"seed", [](F& f, const R& r) { f.integer(static_cast<std::int64_t>(r.participant.seed)); }},
        {"protocol_order",
         [](F& f, const R& r) {
             std::string out;
             for (const int index : r.participant.protocolOrder)
                 out += (out.empty() ? "" : ";") + r.plan.protocols[static_cast<std::size_t>(index)].name;
             f.text(out);
         }},
        {"condition_orders",
         [](F& f, const R& r) {
             f.text(perProtocol(r, [&](int index) {
                 std::string list;
                 for (const auto& c : r.participant.conditionOrder[static_cast<std::size_t>(index)])
                     list += (list.empty() ? "" : " ") + c;
                 return list;
             }));
         }},
        {"cm_per_360",
         [](F& f, const R& r) {
             if (r.participant.settings.cmPer360)
                 f.number(*r.participant.settings.cmPer360);
             else
                 f.empty();
         }},
        {"mouse_dpi", [](F& f, const R& r) { f.number(r.participant.settings.mouseDpi); }},
        {"invert_y", [](F& f, const R& r) { f.boolean(r.participant.settings.invertY); }},
        {"status",
         [](F& f, const R& r) {
             f.text(perProtocol(r, [&](int index) -> std::string {
                 for (const auto& p : r.status.protocols)
                     if (p.protocolIndex == index) return plan::stateText(p);
                 return plan::stateName(plan::SessionState::NotStarted);
             }));
         }},
    };
    return columns;
}

std::string writeParticipants(const std::string& outDir, const plan::StudyPlan& studyPlan,
                              const std::vector<plan::SessionFacts>& sessions) {
    CsvFile csv((std::filesystem::path(outDir) / "participants.csv").string(), headerOf(participantColumns()));
    const std::vector<plan::ParticipantStatus> statuses = plan::studyStatus(studyPlan, sessions);
    for (std::size_t i = 0; i < studyPlan.participants.size(); ++i) {
        writeCells(csv, participantColumns(), ParticipantRow{studyPlan, studyPlan.participants[i], statuses[i]});
        csv.endRow();
    }
    csv.close();
    return csv.path();
}

}  // namespace warplab::exporter
