// The rows of a session's tables as plain structs -- its header, and one input, frame and event
// row -- and the format versions that shaped them: what a game produces and replay compares,
// without the store that writes and reads them (session_store.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace warplab::session {

// 5: the input table's `text`, what was typed on each frame (a text question's answer); files
// of versions 1 to 4 have no such column and read with text "".
// 4: the header says where an interrupted session was resumed (`resumed`).
// 3: a random per-session id in the header, and each commit's checksum chained to the one
// before it (the first to the header's), so that commits cannot be mixed between sessions.
// 2: game-neutral frame and event rows (game-specific fields in detail_json). Version 1 files
// (shooter only) are still read: their shooter columns are folded into detail_json exactly as
// the shooter writes them today, so they replay (docs/session-format.md, "Version 1"); version
// 2 files read with unchained checksums and no session id.
inline constexpr int kSessionFormatVersion = 6;
inline constexpr int kOldestSessionFormatVersion = 1;
inline constexpr int kSessionIdSince = 3;
inline constexpr int kResumedSince = 4;
inline constexpr int kTypedTextSince = 5;
inline constexpr int kPlayerModelSince = 6;

// An interrupted session this one carries on (warplab run --resume): its recorded frames up to
// `frame` were re-simulated, checked and copied into this session, which went on from there.
struct Resumption {
    std::string sessionId;  // the interrupted session's session_id
    std::string file;  // its file name when it was resumed
    std::string startedAt;  // its started_at
    std::string player;  // who played it
    std::int64_t frame = 0;  // the first frame played after resuming: the ones before are its
    std::string resumedAt;  // ISO 8601 UTC: when it was resumed
};

struct SessionHeader {
    std::string protocolJson;  // the protocol copied in full
    std::uint64_t seed = 0;
    std::string participant;  // data, never a path
    std::string appVersion, glRenderer, glVersion;
    double refreshHz = 120;
    // The display the session ran on (or stands for): its aspect ratio shapes the view, so
    // replay needs it to reproduce what was under the reticle.
    int displayWidth = 1920, displayHeight = 1080;
    std::string startedAt;  // ISO 8601 UTC; when empty, create() stores the current time
    std::string player;  // "human", "bot:7", "replay:<path>"
    // 32 hex digits drawn at random when the session is created (create() ignores what is
    // passed): what tells one session from another, and a copy from a twin run with the same
    // participant, seed and start time. "" in files older than format version 3.
    std::string sessionId;
    // The study plan the session was run from (docs/study-plan.md: its `id`); "" for a session
    // run without one, and in files older than format version 3.
    std::string planId;
    // The sessions this one carries on, oldest first: one for each time it was interrupted and
    // resumed (a resumed session interrupted again carries its predecessor's list and itself).
    // Empty for a session played in one go, and in files older than format version 4.
    std::vector<Resumption> resumed;
    // A simulated player's own parameters as a JSON object (a simulated participant's traits,
    // drawn from its seed: participants/population.h); "" for a person, a bot or a replay, and
    // in files older than format version 6.
    std::string playerModel;
    // The photodiode marker the session's window drew (docs/live-sessions.md): "off" or its
    // corner ("top_left" ...), as --photon-marker or else the protocol's display.photon_marker
    // chose it; "off" for a headless session (no window). "" in files written before it was
    // stored, whose window drew the protocol's unless --photon-marker said otherwise. Stored as
    // meta `photon_marker` outside header_checksum, so that readers before it read the file
    // as they always did (they pass over a meta key they do not know); "" stores nothing.
    std::string photonMarker;
    int formatVersion = kSessionFormatVersion;  // as read; the writer writes only this one
};

// One row per displayed frame: enough to replay the session exactly.
struct InputRecord {
    std::int64_t frame = 0;
    double displayTime = 0;  // seconds on the display clock
    double mouseDx = 0, mouseDy = 0;
    std::uint32_t buttons = 0;
    std::uint32_t keys = 0;
    // What was typed since the previous frame (game::FrameInput::text): UTF-8, each Backspace
    // as '\b'; "" when nothing was, and in files older than format version 5.
    std::string text;
};

// Per displayed frame: what was shown and how it went.
struct FrameRecord {
    std::int64_t frame = 0;
    std::string condition;  // condition id, e.g. "warp15to120"
    std::string kind;  // "rendered" | "held" | "warped" | "interpolated" | "frozen" | "screen" | "skipped"
    double frameMs = 0;  // measured present to present (live sessions); 0 headless
    double renderMs = 0;  // measured: making the frame (render, warp or blend, HUD) to glFinish; 0 headless
    int missedVsyncs = 0;
    double cameraYaw = 0, cameraPitch = 0;  // radians, scene::CameraState convention
    std::string detailJson;  // the game's own per-frame state, a JSON object ("" = none):
        // shooter {"target":[x,y,z]}, click {"cursor":[x,y],"spheres":[...]}
};

// FrameRecord::kind of a display frame the session stepped through but never showed: the frame
// before it reached the screen late and took its display slot (a live session's display clock).
inline constexpr const char* kSkippedFrameKind = "skipped";

// One row per trial/shot/click/match/rating/phase change. The columns every game shares are
// typed; everything game-specific (difficulty, target speed, aim time, cursor, ratings ...)
// is in detailJson, whose keys each game documents in docs/session-format.md.
struct EventRecord {
    std::int64_t frame = 0;
    std::string type;  // "shot", "timeout", "phase", "level", "click", "match", "rating" ...
    std::string phase;
    int trial = -1;  // trial (shooter) or match (click) index; -1: not part of one
    std::string condition;
    double eventTime = 0;  // seconds on the display clock
    std::string worldOutcome, displayedOutcome;  // "hit" | "miss" | "timeout" | "green" | "red" | ""
    std::string detailJson;  // a JSON object text ("" = none), keys sorted (nlohmann dump)
};

}  // namespace warplab::session
