#include "discrimination/discrimination_protocol.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "protocol/fields.h"
#include "spellings.h"

namespace warplab::discrimination {
namespace {

namespace fields = protocol::fields;
using fields::at;
using fields::elementPath;
using fields::formatNumber;
using fields::joinPath;
using fields::Json;
using fields::NumberRange;
using P = DiscriminationProtocol;
using S = ProcedureSpec;
using K = fields::Keys<P>;
using KS = fields::Keys<S>;

// Bounds no study needs to exceed (docs/protocol.md, "Limits that keep a session's data safe"):
// a trial is committed when it is answered, so two intervals and a blank are the longest
// stretch of frames held.
constexpr double kIntervalLimitS = 60;
constexpr double kBlankLimitS = 60;
constexpr double kSpeedLimit = 100;  // m/s
constexpr double kRadiusLimit = 5;  // m, within the hangar's view
constexpr int kTrialLimit = 2000;  // per procedure: hours of two-interval trials
constexpr int kLevelLimit = 200;
constexpr int kGridLimit = 200;  // values in one grid
constexpr std::size_t kPriorLimit = 200000;  // grid combinations, each an expected entropy per level and trial
constexpr int kProcedureLimit = 20;

// A list of numbers, each within `range`, rising strictly where `rising`.
fields::Key<S> numberList(const char* name, std::vector<double> S::*member, NumberRange range, bool rising,
                          bool allowEmpty = false) {
    return KS::make(name, at(member), [=](const fields::Reader& r, const Json* o, const std::string& path, S& s) {
        const Json* list = r.array(o, path, name, "numbers", allowEmpty);
        if (!list) return;
        std::vector<double> read;
        for (std::size_t i = 0; i < list->size(); ++i) {
            const std::string where = elementPath(joinPath(path, name), i);
            read.push_back(r.numberAt((*list)[i], where, range));
            if (rising && i > 0 && !(read[i] > read[i - 1]))
                r.fail(where,
                       "must be greater than the value before it (" + formatNumber(read[i - 1]) +
                           "): the list rises, got " + formatNumber(read[i]));
        }
        if (read.size() > static_cast<std::size_t>(kGridLimit) && rising)
            r.fail(joinPath(path, name),
                   "has " + std::to_string(read.size()) + " values; at most " + std::to_string(kGridLimit) +
                       " are allowed");
        s.*member = std::move(read);
    });
}

// The keys of each element of procedures[]. "name", "reference" and "levels" are required.
const std::vector<fields::Key<S>>& procedureKeys() {
    static const std::vector<fields::Key<S>> keys = [] {
        auto required = [](const char* name, fields::Key<S> k) {
            auto read = k.read;
            k.read = [name, read](const fields::Reader& r, const Json* o, const std::string& path, S& s) {
                if (!o->contains(name)) r.fail(joinPath(path, name), "is required but missing");
                read(r, o, path, s);
            };
            return k;
        };
        const NumberRange any{-1e9, false, 1e9, false};
        fields::Key<S> dimension = KS::make("dimension", at(&S::dimension),
                                            [](const fields::Reader& r, const Json* o, const std::string& path, S& s) {
                                                std::vector<const char*> allowed;
                                                for (const auto& d : condition::dimensionSpellings())
                                                    allowed.push_back(d.name);
                                                std::string name = condition::dimensionName(s.dimension);
                                                r.choice(o, path, "dimension", allowed, name);
                                                s.dimension = *condition::dimensionNamed(name);
                                            });
        dimension.write = [](Json& o, const S& s) { o["dimension"] = condition::dimensionName(s.dimension); };
        return std::vector<fields::Key<S>>{
            required("name",
                     KS::make("name", at(&S::name),
                              [](const fields::Reader& r, const Json* o, const std::string& path, S& s) {
                                  s.name = r.line(o->at("name"), joinPath(path, "name"));
                              })),
            required("reference", KS::conditionId("reference", at(&S::reference))),
            dimension,
            KS::choice("method", at(&S::method)),
            required("levels", numberList("levels", &S::levels, any, false)),
            KS::choice("shape", at(&S::shape)),
            KS::choice("scale", at(&S::scale)),
            numberList("thresholds", &S::thresholds, any, true, true),
            numberList("slopes", &S::slopes, {0, true, 1e6, false}, true, true),
            numberList("lapses", &S::lapses, {0, false, 0.5, true}, true),
            numberList("prior", &S::prior, {0, false, 1e12, false}, false, true),
            KS::number("percent_correct", at(&S::percentCorrect), {50, true, 100, true}),
            KS::integer("max_trials", at(&S::maxTrials), 0, kTrialLimit),
            KS::number("stop_width", at(&S::stopWidth), {0, false, 1e9, false}),
            KS::integer("up", at(&S::up), 1, 10),
            KS::integer("down", at(&S::down), 1, 10),
            KS::number("start", at(&S::start), any),
            KS::make("steps", at(&S::steps),
                     [](const fields::Reader& r, const Json* o, const std::string& path, S& s) {
                         const Json* list = r.array(o, path, "steps", "whole numbers");
                         if (!list) return;
                         std::vector<int> read;
                         for (std::size_t i = 0; i < list->size(); ++i)
                             read.push_back(static_cast<int>(
                                 r.integerAt((*list)[i], elementPath(joinPath(path, "steps"), i), 1, kLevelLimit)));
                         s.steps = std::move(read);
                     }),
            KS::integer("reversals_averaged", at(&S::reversalsAveraged), 1, 100),
            KS::integer("repeats", at(&S::repeats), 1, 100),
        };
    }();
    return keys;
}

void readProcedures(const fields::Reader& r, const Json* trials, const std::string& path, P& p) {
    const Json* list = r.array(trials, path, "procedures", "procedures");
    if (!list) return;
    if (list->size() > static_cast<std::size_t>(kProcedureLimit))
        r.fail(joinPath(path, "procedures"),
               "has " + std::to_string(list->size()) + " procedures; at most " + std::to_string(kProcedureLimit) +
                   " are allowed");
    std::vector<S> read;
    std::vector<std::string> names;
    for (std::size_t i = 0; i < list->size(); ++i) {
        const Json& item = (*list)[i];
        const std::string where = elementPath(joinPath(path, "procedures"), i);
        if (!item.is_object()) r.fail(where, "must be an object, got " + fields::describe(item));
        S spec;
        fields::readKeys(r, item, where, procedureKeys(), p.formatVersion, spec);
        names.push_back(spec.name);
        read.push_back(std::move(spec));
    }
    r.requireDistinct(names, [&](std::size_t i) { return elementPath(joinPath(path, "procedures"), i) + ".name"; });
    p.procedures = std::move(read);
}

void writeProcedures(Json& trials, const P& p) {
    trials["procedures"] = Json::array();
    for (const S& spec : p.procedures) {
        Json item = Json::object();
        fields::writeKeys(item, procedureKeys(), p.formatVersion, spec);
        trials["procedures"].push_back(item);
    }
}

// Every key of a discrimination protocol below the top level, once (the game's page lists each).
const std::vector<fields::Section<P>>& sections() {
    static const std::vector<fields::Section<P>> list = [] {
        std::vector<fields::Key<P>> display = {
            K::number("refresh_hz", at(&P::refreshHz), {1, false, fields::kRefreshLimitHz, false}),
            K::number("vertical_fov_deg", at(&P::verticalFovDeg),
                      {protocol::kMinVerticalFovDeg, false, protocol::kMaxVerticalFovDeg, false}),
            K::choice("refresh_mismatch", at(&P::refreshMismatch)),
        };
        for (auto& k : fields::renderKeys<P>(1)) display.push_back(k);
        return std::vector<fields::Section<P>>{
            {"display", display},
            {"input",
             {K::number("mouse_radians_per_count", at(&P::mouseRadiansPerCount), {0.000001, false, 0.1, false})}},
            {"target",
             {K::number("radius_m", at(&P::targetRadius), {0.01, false, kRadiusLimit, false}),
              K::number("speed_m_per_s", at(&P::targetSpeed), {0, false, kSpeedLimit, false})}},
            {"trials",
             {K::number("interval_s", at(&P::intervalS), {0, true, kIntervalLimitS, false}),
              K::number("blank_s", at(&P::blankS), {0, false, kBlankLimitS, false}),
              K::make("question", at(&P::question),
                      [](const fields::Reader& r, const Json* o, const std::string& path, P& p) {
                          if (o->contains("question"))
                              p.question = r.line(o->at("question"), joinPath(path, "question"));
                      }),
              K::make("instructions", at(&P::instructions),
                      [](const fields::Reader& r, const Json* o, const std::string& path, P& p) {
                          r.paragraph(o, path, "instructions", p.instructions);
                      }),
              K::custom("procedures", readProcedures, writeProcedures)}},
        };
    }();
    return list;
}

// What each procedure's fields say together, and whether the display can show its levels:
// checked once every field is final, each in one sentence naming its path.
void checkProcedure(const fields::Reader& r, const P& p, const S& s, const std::string& where) {
    const condition::Condition& reference = p.conditionTable.at(s.reference);
    const double ref = referenceLevel(p, s);
    const std::string key = condition::dimensionName(s.dimension);
    for (std::size_t i = 0; i < s.levels.size(); ++i) {
        const std::string at = elementPath(joinPath(where, "levels"), i);
        condition::Condition test;
        try {
            test = condition::varied(reference, s.dimension, s.levels[i]);
        } catch (const std::invalid_argument& e) {
            r.fail(at, "must be a level " + key + " can take: " + e.what());
        }
        if (const auto problem = condition::problem(test, p.refreshHz))
            r.fail(at,
                   "is " + formatNumber(s.levels[i]) + ", which this display (" + formatNumber(p.refreshHz) +
                       " Hz) cannot show: " + (problem->part.empty() ? "" : problem->part + " ") + problem->reason);
        const double stimulus = condition::stimulusOf(s.dimension, ref, s.levels[i]);
        if (!(stimulus > 0))
            r.fail(at,
                   "must be worse than the reference " + s.reference + "'s " + key + " of " + formatNumber(ref) +
                       (s.dimension == condition::Dimension::RenderHz ? " (lower)" : " (higher)") + ", got " +
                       formatNumber(s.levels[i]));
        if (i > 0 && !(stimulus > condition::stimulusOf(s.dimension, ref, s.levels[i - 1])))
            r.fail(at,
                   "must be further from the reference's " + key + " than the level before it (" +
                       formatNumber(s.levels[i - 1]) + "), got " + formatNumber(s.levels[i]));
    }
    if (s.levels.size() > static_cast<std::size_t>(kLevelLimit))
        r.fail(joinPath(where, "levels"),
               "has " + std::to_string(s.levels.size()) + " levels; at most " + std::to_string(kLevelLimit) +
                   " are allowed");
    const double topLapse = s.lapses.back();
    if (!(s.percentCorrect < 100 * (1 - topLapse)))
        r.fail(joinPath(where, "percent_correct"),
               "must be below " + formatNumber(100 * (1 - topLapse)) +
                   " %, the most a function with the largest lapse (" + formatNumber(topLapse) + ") reaches, got " +
                   formatNumber(s.percentCorrect));
    const bool log = s.scale == adaptive::Scale::Log;
    if (s.method == adaptive::Method::QuestPlus) {
        if (s.thresholds.empty() || s.slopes.empty())
            r.fail(joinPath(where, s.thresholds.empty() ? "thresholds" : "slopes"),
                   "is required by method \"quest_plus\": the grid of the unknown it names");
        if (log && s.thresholds.front() <= 0)
            r.fail(elementPath(joinPath(where, "thresholds"), 0),
                   "must be more than 0 on scale \"log\", got " + formatNumber(s.thresholds.front()));
        const std::size_t combinations = s.thresholds.size() * s.slopes.size() * s.lapses.size();
        if (combinations > kPriorLimit)
            r.fail(where,
                   "has " + std::to_string(combinations) + " combinations of thresholds, slopes and lapses; at most " +
                       std::to_string(kPriorLimit) + " are allowed");
        if (!s.prior.empty() && s.prior.size() != combinations)
            r.fail(joinPath(where, "prior"),
                   "must have one weight per combination of thresholds, slopes and lapses (" +
                       std::to_string(combinations) + "), got " + std::to_string(s.prior.size()));
        if (!s.prior.empty() && std::all_of(s.prior.begin(), s.prior.end(), [](double w) { return w == 0; }))
            r.fail(joinPath(where, "prior"), "must give some combination a weight above 0");
    }
    // A key another method reads would be silently ignored: refused, naming the method it is for.
    const S defaults;
    const struct {
        const char* key;
        adaptive::Method method;
        bool set;
    } only[] = {
        {"thresholds", adaptive::Method::QuestPlus, !s.thresholds.empty()},
        {"slopes", adaptive::Method::QuestPlus, !s.slopes.empty()},
        {"prior", adaptive::Method::QuestPlus, !s.prior.empty()},
        {"stop_width", adaptive::Method::QuestPlus, s.stopWidth != defaults.stopWidth},
        {"up", adaptive::Method::Staircase, s.up != defaults.up},
        {"down", adaptive::Method::Staircase, s.down != defaults.down},
        {"start", adaptive::Method::Staircase, s.start != defaults.start},
        {"steps", adaptive::Method::Staircase, s.steps != defaults.steps},
        {"reversals_averaged", adaptive::Method::Staircase, s.reversalsAveraged != defaults.reversalsAveraged},
        {"repeats", adaptive::Method::ConstantStimuli, s.repeats != defaults.repeats},
    };
    for (const auto& o : only)
        if (o.set && o.method != s.method)
            r.fail(joinPath(where, o.key),
                   std::string("is only for method \"") + protocol::nameOf(o.method) +
                       "\", and this procedure's method is \"" + protocol::nameOf(s.method) + "\"");
    if (s.method == adaptive::Method::ConstantStimuli && s.maxTrials != 0)
        r.fail(joinPath(where, "max_trials"),
               "is not for method \"constant_stimuli\", which stops once every level has had its repeats");
    if (s.method != adaptive::Method::ConstantStimuli && s.maxTrials < 1)
        r.fail(joinPath(where, "max_trials"),
               std::string("must be at least 1 for method \"") + protocol::nameOf(s.method) +
                   "\": without a trial limit it may never stop (required)");
    if (s.method == adaptive::Method::Staircase && s.start != 0 &&
        std::find(s.levels.begin(), s.levels.end(), s.start) == s.levels.end())
        r.fail(joinPath(where, "start"),
               "must be one of the levels (or 0 for the easiest), got " + formatNumber(s.start));
    try {
        adaptive::Procedure(procedureSettings(p, s), 0);
    } catch (const std::exception& e) {
        r.fail(where, std::string("cannot run: ") + e.what());
    }
}

}  // namespace

double referenceLevel(const DiscriminationProtocol& p, const ProcedureSpec& spec) {
    return condition::levelOf(p.conditionTable.at(spec.reference), spec.dimension, p.refreshHz);
}

std::vector<double> stimuli(const DiscriminationProtocol& p, const ProcedureSpec& spec) {
    const double ref = referenceLevel(p, spec);
    std::vector<double> out;
    for (double level : spec.levels) out.push_back(condition::stimulusOf(spec.dimension, ref, level));
    return out;
}

adaptive::ProcedureSettings procedureSettings(const DiscriminationProtocol& p, const ProcedureSpec& spec) {
    adaptive::ProcedureSettings s;
    s.method = spec.method;
    s.maxTrials = spec.maxTrials;
    s.stopWidth = spec.stopWidth;
    s.repeats = spec.repeats;
    const std::vector<double> levels = stimuli(p, spec);
    s.quest.function = {spec.shape, spec.scale, 0.5};
    s.quest.stimuli = levels;
    s.quest.thresholds = spec.thresholds;
    s.quest.slopes = spec.slopes;
    s.quest.lapses = spec.lapses;
    s.quest.prior = spec.prior;
    s.staircase.stimuli = levels;
    s.staircase.higherIsEasier = true;
    s.staircase.up = spec.up;
    s.staircase.down = spec.down;
    s.staircase.steps = spec.steps;
    const auto start = std::find(spec.levels.begin(), spec.levels.end(), spec.start);
    s.staircase.start =
        start == spec.levels.end() ? levels.size() - 1 : static_cast<std::size_t>(start - spec.levels.begin());
    return s;
}

condition::Condition testCondition(const DiscriminationProtocol& p, const ProcedureSpec& spec, std::size_t level) {
    return condition::varied(p.conditionTable.at(spec.reference), spec.dimension, spec.levels.at(level));
}

std::vector<std::string> discriminationProtocolKeys() {
    return fields::keyPaths(sections(), {{"trials.procedures", fields::keyNames(procedureKeys())}});
}

DiscriminationProtocol parseDiscriminationProtocol(const std::string& jsonText, const std::string& sourceName) {
    fields::Reader r(sourceName);
    const Json document = r.parseObject(jsonText);
    P p;
    r.requireGame(document, kGameName);
    p.formatVersion = r.formatVersion(document, kFormatVersion);
    r.requireKnownKeys(document, "", fields::topLevelKeys(sections()));
    r.nameAndDescription(document, p.name, p.description);
    p.conditionTable = condition::ConditionTable(r.conditions(document, p.formatVersion, 1, 1));
    fields::readSections(r, document, sections(), p.formatVersion, p);
    if (p.procedures.empty()) r.fail("trials.procedures", "is required: the block's adaptive procedures, at least one");
    r.requireConditionsRun(p.refreshHz);
    for (std::size_t i = 0; i < p.procedures.size(); ++i) {
        const std::string where = elementPath("trials.procedures", i);
        r.requireCondition(joinPath(where, "reference"), p.procedures[i].reference, p.refreshHz);
        checkProcedure(r, p, p.procedures[i], where);
    }
    r.requireConditionsUsed();
    return p;
}

std::string toJson(const DiscriminationProtocol& p) { return fields::protocolText(p, sections()); }

}  // namespace warplab::discrimination
