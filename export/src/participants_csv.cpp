#include "participants_csv.h"

#include <filesystem>
#include <map>
#include <set>

#include "session/session_store.h"

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
    using F = CellWriter;
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
        // Empty before they have played.
        {"player_kind", [](F& f, const R& r) { f.text(r.playerKinds); }},
    };
    return columns;
}

const std::vector<Column<OrderRow>>& orderColumns() {
    using F = CellWriter;
    using R = OrderRow;
    static const std::vector<Column<R>> columns = {
        {"participant", [](F& f, const R& r) { f.text(r.participant); }},
        {"protocol_position", [](F& f, const R& r) { f.integer(r.protocolPosition); }},
        {"protocol", [](F& f, const R& r) { f.text(r.protocol); }},
        {"position", [](F& f, const R& r) { f.integer(r.position); }},
        {"condition", [](F& f, const R& r) { f.text(r.condition); }},
    };
    return columns;
}

std::vector<std::string> writeParticipants(const std::string& outDir, const plan::StudyPlan& studyPlan,
                                           const std::vector<plan::SessionFacts>& sessions) {
    const std::filesystem::path dir(outDir);
    CsvFile csv((dir / "participants.csv").string(), headerOf(participantColumns()));
    CsvFile orders((dir / "orders.csv").string(), headerOf(orderColumns()));
    std::map<std::string, std::set<std::string>> kinds;
    for (const plan::SessionFacts& s : sessions)
        if (s.header.planId == studyPlan.id) kinds[s.header.participant].insert(session::playerKind(s.header.player));
    const std::vector<plan::ParticipantStatus> statuses = plan::studyStatus(studyPlan, sessions);
    for (std::size_t i = 0; i < studyPlan.participants.size(); ++i) {
        const plan::ParticipantPlan& p = studyPlan.participants[i];
        std::string joined;
        for (const std::string& kind : kinds[p.id]) joined += (joined.empty() ? "" : ";") + kind;
        writeCells(csv, participantColumns(), ParticipantRow{studyPlan, p, statuses[i], joined});
        csv.endRow();
        int protocolPosition = 0;
        for (const int index : p.protocolOrder) {
            ++protocolPosition;
            const auto& conditions = p.conditionOrder[static_cast<std::size_t>(index)];
            for (std::size_t k = 0; k < conditions.size(); ++k) {
                writeCells(orders, orderColumns(),
                           OrderRow{p.id, protocolPosition, studyPlan.protocols[static_cast<std::size_t>(index)].name,
                                    static_cast<int>(k) + 1, conditions[k]});
                orders.endRow();
            }
        }
    }
    csv.close();
    orders.close();
    return {csv.path(), orders.path()};
}

}  // namespace warplab::exporter
