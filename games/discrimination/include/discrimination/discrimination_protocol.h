// The discrimination task's protocol file (docs/discrimination-study.md): two-interval forced
// choice between a reference condition and the same condition with one part -- the stimulus
// dimension -- made worse by a level an adaptive procedure chooses. What a session runs, as
// plain data; every key is documented, with its range, on the game's page.
#pragma once

#include <string>
#include <vector>

#include "adaptive/block.h"
#include "condition/condition.h"
#include "condition/stimulus.h"
#include "protocol/study_protocol.h"

namespace warplab::discrimination {

inline constexpr const char* kGameName = "discrimination";
inline constexpr int kFormatVersion = 1;

// One adaptive procedure of the block (procedures[]): what it varies, against what, and how it
// chooses and stops.
struct ProcedureSpec {
    std::string name;  // names it in the export; unique within the protocol
    std::string reference;  // a condition id: the better interval of each of its trials
    condition::Dimension dimension = condition::Dimension::LagFrames;
    adaptive::Method method = adaptive::Method::QuestPlus;
    // The values of the dimension's part the test interval may take, each worse than the
    // reference's and further from it than the one before (lags rising, rates falling).
    std::vector<double> levels;
    // The psychometric function of the stimulus (condition::stimulusOf: how much worse than the
    // reference) that QUEST+ assumes and the analysis refits.
    adaptive::Shape shape = adaptive::Shape::Weibull;
    adaptive::Scale scale = adaptive::Scale::Log;
    std::vector<double> thresholds, slopes;  // QUEST+'s grids; rising, in stimulus units
    std::vector<double> lapses{0.02};  // QUEST+'s lapse grid; its mean is the refit's fixed lapse
    std::vector<double> prior;  // QUEST+: weights over the grids, empty for uniform
    double percentCorrect = 75;  // the threshold reported is the stimulus at this percent correct
    int maxTrials = 0;  // QUEST+ and staircase: stop after this many trials (required)
    double stopWidth = 0;  // QUEST+: also stop once the threshold's 95 % interval is this narrow (0: never)
    // Staircase: after `down` correct in a row one level harder, after `up` wrong one easier,
    // starting at `start` (a level; 0: the easiest), levels per step after k reversals.
    int up = 1, down = 2;
    double start = 0;
    std::vector<int> steps{1};
    int reversalsAveraged = 6;  // its threshold: the mean stimulus at the last this many reversals
    int repeats = 10;  // constant stimuli: trials at each level
};

struct DiscriminationProtocol {
    int formatVersion = kFormatVersion;
    std::string name, description;
    std::string game = kGameName;
    condition::ConditionTable conditionTable;  // the presets and the file's own conditions
    double refreshHz = 120;
    double verticalFovDeg = 60;
    protocol::RefreshMismatch refreshMismatch = protocol::RefreshMismatch::Refuse;
    protocol::RenderSettings rendering;
    double mouseRadiansPerCount = 0.0022;  // the view's turn per mouse count, as the shooter's
    double targetRadius = 0.35;  // m
    double targetSpeed = 3.0;  // m/s, the bouncing target of each interval
    double intervalS = 2.5;  // each of a trial's two intervals
    double blankS = 0.5;  // between them, and after the answer before the next trial
    std::string question = "Which interval was more responsive?";
    std::string instructions =
        "Each trial shows the ball twice, in interval 1 and then interval 2. Follow it with the "
        "mouse both times. Then press 1 or 2 for the interval that felt more responsive. If you "
        "cannot tell, guess.";
    std::vector<ProcedureSpec> procedures;
};

// Throws protocol::ProtocolError: one sentence naming the file and the JSON path.
DiscriminationProtocol parseDiscriminationProtocol(const std::string& jsonText, const std::string& sourceName);
// The canonical copy a session stores; parses back to the same struct.
std::string toJson(const DiscriminationProtocol& p);
// Every key as a JSON path, header first, in the parser's table order (the page lists each).
std::vector<std::string> discriminationProtocolKeys();

// The reference's value of the procedure's dimension, each level's stimulus, and the adaptive
// procedure they make (its levels are the stimuli).
double referenceLevel(const DiscriminationProtocol& p, const ProcedureSpec& spec);
std::vector<double> stimuli(const DiscriminationProtocol& p, const ProcedureSpec& spec);
adaptive::ProcedureSettings procedureSettings(const DiscriminationProtocol& p, const ProcedureSpec& spec);
// The condition of the test interval at levels[level].
condition::Condition testCondition(const DiscriminationProtocol& p, const ProcedureSpec& spec, std::size_t level);

}  // namespace warplab::discrimination
