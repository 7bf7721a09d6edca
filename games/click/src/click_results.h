// The click game's own results: a row of matches.csv per match, and one of ratings.csv per
// rating answered after it (docs/click-study.md lists their columns).
#pragma once

#include <string>
#include <vector>

#include "game/event_detail.h"
#include "game/results.h"

namespace warplab::game {

// One answer on a rating screen after a match.
struct RatingResult {
    int statementIndex = 0;  // 0-based, in the protocol's order
    std::string statement;
    int value = 0;
    std::string answeredWith;  // "key" or "mouse"
    // The answers the screen offered, both included: the protocol's ratings.min and ratings.max,
    // which an analysis cannot know otherwise.
    int scaleMin = 1, scaleMax = 7;
};

// One match.
struct MatchResult {
    std::string round;
    bool scoredPhase = false;
    int match = -1;
    std::string condition;
    std::string standIn;  // method drawn in the condition's place ("" = the condition's own)
    int greenHits = 0, redHits = 0, misses = 0, clicks = 0;
    double durationS = 0.0;
    double endTime = kNotApplicable;  // display time of the match's last frame, s
    std::vector<RatingResult> ratings;  // as answered; a session cut short may lack some
};

// matches.csv (a span table, one rating_k column per statement) and ratings.csv, in that order.
std::vector<GameTable> clickTables(const std::vector<MatchResult>& matches);

// A click's cells of the click game's own columns of shots.csv, from its event's detail.
void writeClickShotCells(table::Cells& own, const EventDetail& click);

}  // namespace warplab::game
