// A toy protocol file (toy.md): the shared header and conditions, display.refresh_hz, and the
// play section, read by the strict field kit every game's parser is built from.
#pragma once

#include <string>
#include <vector>

#include "condition/condition.h"

namespace warplab::toy {

inline constexpr int kToyFormatVersion = 1;
inline constexpr double kMaxSecondsPerCondition = 300;  // one condition between two commit points at most

struct ToyProtocol {
    int formatVersion = kToyFormatVersion;
    std::string name, description;
    std::string game = "toy";
    condition::ConditionTable conditionTable;  // the presets and the file's own conditions
    double refreshHz = 120;  // display.refresh_hz
    std::vector<std::string> conditions{"conv60"};  // play.conditions, in the order played
    bool shuffle = false;  // play.shuffle: the session seed orders them
    double secondsPerCondition = 4;  // play.seconds_per_condition
};

ToyProtocol parseToyProtocol(const std::string& jsonText, const std::string& sourceName);
// The canonical copy a session stores; parses back to the same struct.
std::string toJson(const ToyProtocol& p);

}  // namespace warplab::toy
