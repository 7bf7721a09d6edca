#include "toy_protocol.h"

#include "protocol/fields.h"
#include "toy/toy.h"

namespace warplab::toy {
namespace {

namespace fields = protocol::fields;
using fields::at;
using fields::Json;
using P = ToyProtocol;
using K = fields::Keys<P>;

// Every key of a toy protocol below the top level, once (toy.md lists each).
const std::vector<fields::Section<P>>& sections() {
    static const std::vector<fields::Section<P>> list{
        {"display", {K::number("refresh_hz", at(&P::refreshHz), {1, false, fields::kRefreshLimitHz, false})}},
        {"play",
         {K::conditionList("conditions", at(&P::conditions)), K::boolean("shuffle", at(&P::shuffle)),
          K::number("seconds_per_condition", at(&P::secondsPerCondition), {0, true, kMaxSecondsPerCondition, false})}},
    };
    return list;
}

}  // namespace

std::vector<std::string> toyProtocolKeys() { return fields::keyPaths(sections()); }

ToyProtocol parseToyProtocol(const std::string& jsonText, const std::string& sourceName) {
    fields::Reader r(sourceName);
    const Json document = r.parseObject(jsonText);
    ToyProtocol p;
    r.requireGame(document, kGameName);
    p.formatVersion = r.formatVersion(document, kToyFormatVersion);
    r.requireKnownKeys(document, "", fields::topLevelKeys(sections()));
    r.nameAndDescription(document, p.name, p.description);
    p.conditionTable = condition::ConditionTable(r.conditions(document, p.formatVersion, 1, 1));
    fields::readSections(r, document, sections(), p.formatVersion, p);
    r.requireConditionsRun(p.refreshHz);
    r.requireConditions("play.conditions", p.conditions, p.refreshHz);
    r.requireConditionsUsed();
    return p;
}

std::string toJson(const ToyProtocol& p) { return fields::protocolText(p, sections()); }

std::string toyProtocol(const std::vector<std::string>& conditions, double secondsEach, bool shuffle) {
    ToyProtocol p;
    p.name = "toy";
    for (const std::string& c : conditions) p.name += "-" + c;
    p.conditions = conditions;
    p.secondsPerCondition = secondsEach;
    p.shuffle = shuffle;
    return toJson(p);
}

std::string toyProtocol(const std::string& condition, double seconds) {
    return toyProtocol(std::vector<std::string>{condition}, seconds);
}

}  // namespace warplab::toy
