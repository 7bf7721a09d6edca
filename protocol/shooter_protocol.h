// The bouncing-target shooter study's protocol file (seed 004 sections 5.3.3-5.3.4 and
// Appendix B): what a session runs, as plain data. Every field is documented, with its JSON
// key, unit, range and source, in docs/protocol.md. The defaults are the study as published,
// so an unset field in a file means "as in the thesis".
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace warplab::protocol {

// A bad protocol file: one sentence naming the file and the JSON path of the culprit.
class ProtocolError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The newest protocol format this build reads and the one toJson writes.
inline constexpr int kShooterFormatVersion = 1;

// Mode ids a protocol may name. Kept here rather than taken from game/modes.h because the
// protocol module must not depend on game; a test on the game side keeps the two in sync.
inline constexpr std::array<std::string_view, 9> kKnownModes{
    "conv15", "conv30", "conv60", "conv120", "lag50", "lag100", "lag200", "warp15to120",
    "bireproj15to60"};

// The training staircase (seed 004 section 5.3.3, figure 31).
struct StaircaseSettings {
    double baseSpeed = 1.0;          // v0 in m/s, speed at difficulty 0 (v_d = v0 * 2^(d/6), eq. 12)
    int startLevel = 0;
    int maxLevel = 60;
    int shotsPerLevelEasy = 4;       // shots evaluated per level while everything is hit
    int shotsPerLevelHard = 16;      // ... once hit rates drop ("progressively more shots")
    std::string highMode = "conv120";  // stop when highMode's miss rate > lowMode's hit rate
    std::string lowMode = "conv15";
    double timeLimitS = 720;         // then the test starts at the level reached
};

struct ShooterProtocol {
    std::string name;
    std::string description;
    int formatVersion = kShooterFormatVersion;
    std::string game = "shooter";
    double refreshHz = 120;
    double verticalFovDeg = 60;
    double targetRadius = 0.35;            // metres
    double mouseRadiansPerCount = 0.0022;  // camera turn per mouse count
    double acclimationS = 300;
    int acclimationLevel = 0;
    std::string acclimationMode = "conv120";
    StaircaseSettings training;
    std::vector<std::string> conditions{"conv15", "conv120", "warp15to120"};
    int targetsPerCondition = 225;
    bool interleaveConditions = true;      // random order drawn from the session seed
    double timeoutS = 3;
    double pauseS = 1;
    std::string scoring = "displayed";     // or "world" (DESIGN.md "Scoring")
    bool supervisorStartsTest = true;      // the supervisor's Enter starts the recorded part
};

// sourceName is what messages call the file (its path). Throws ProtocolError.
ShooterProtocol parseShooterProtocol(const std::string& jsonText, const std::string& sourceName);
// A missing or unreadable file is a ProtocolError naming the path.
ShooterProtocol loadShooterProtocol(const std::string& path);
// Canonical form: every field, in a fixed order, 2-space indent, trailing newline. Parsing it
// gives back the same struct bit for bit, so the session stores this copy as the protocol it
// ran. Does not validate; parse what it writes to check a hand-built struct.
std::string toJson(const ShooterProtocol& protocol);

}  // namespace warplab::protocol
