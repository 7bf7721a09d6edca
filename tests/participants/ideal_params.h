// A participant without reaction time or motor noise, for the tests that need its control
// law alone: shared by the participant's own tests and the GL ones that play sessions.
#pragma once

#include "participants/participant.h"

namespace warplab {

inline participants::ParticipantParams ideal() {
    participants::ParticipantParams p;
    p.reactionS = 0.0;
    p.motorNoise = 0.0;
    p.motorNoiseFloorCountsPerS = 0.0;
    return p;
}

}  // namespace warplab
