// What every study protocol file shares, whichever game it is for: the error type, reading the
// file, and the top-level "game" field that picks the game's own parser (shooter_protocol.h,
// click_protocol.h). docs/protocol.md describes the
// files.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace warplab::protocol {

// Camera limits that every protocol's display section and `warplab render` share, so that a
// view the one accepts is never refused by the other (degrees, both ends allowed).
inline constexpr double kMinVerticalFovDeg = 1;  // narrower is a telescope, not a study
inline constexpr double kMaxVerticalFovDeg = 179;  // the projection degenerates at 180
// Straight up or down (90) turns the world-up view basis over; the game itself clamps to ~86.
inline constexpr double kMaxCameraPitchDeg = 89;

// The protocols' fields that pick one of a few spellings, parsed once into an enum. Each
// value's JSON spelling is written once, in EnumNames below, which parsing, the messages that
// list the allowed values and toJson all read.
// Which outcome scores, both games alike (DESIGN.md "Scoring"); both are always logged.
enum class Scoring { Displayed, World };
// When a click counts (docs/protocol.md, "Click timing"): at the display frame where the button
// goes down, or only at frames where the condition reads input.
enum class ClickTiming { Display, InputReads };
// A live session on a display whose refresh is known to differ from the protocol's: refuse to
// start, or warn and pace frames by timer.
enum class RefreshMismatch { Refuse, Warn };
// Where a live session draws its photodiode marker (docs/live-sessions.md, "Measuring
// click-to-photon latency with a photodiode"), or none.
enum class PhotonMarker { Off, TopLeft, TopRight, BottomLeft, BottomRight };

template <class E>
struct EnumName {
    E value;
    const char* name;
};
template <class E>
struct EnumNames;
template <>
struct EnumNames<Scoring> {
    static constexpr EnumName<Scoring> list[] = {{Scoring::Displayed, "displayed"}, {Scoring::World, "world"}};
};
template <>
struct EnumNames<ClickTiming> {
    static constexpr EnumName<ClickTiming> list[] = {{ClickTiming::Display, "display"},
                                                     {ClickTiming::InputReads, "input_reads"}};
};
template <>
struct EnumNames<RefreshMismatch> {
    static constexpr EnumName<RefreshMismatch> list[] = {{RefreshMismatch::Refuse, "refuse"},
                                                         {RefreshMismatch::Warn, "warn"}};
};
template <>
struct EnumNames<PhotonMarker> {
    static constexpr EnumName<PhotonMarker> list[] = {{PhotonMarker::Off, "off"},
                                                      {PhotonMarker::TopLeft, "top_left"},
                                                      {PhotonMarker::TopRight, "top_right"},
                                                      {PhotonMarker::BottomLeft, "bottom_left"},
                                                      {PhotonMarker::BottomRight, "bottom_right"}};
};

// The JSON spelling of `value`.
template <class E>
const char* nameOf(E value) {
    for (const auto& entry : EnumNames<E>::list)
        if (entry.value == value) return entry.name;
    return "?";  // not reached for a value of the enum
}
// The value spelt `name`, exactly; nullopt for a name that is none of them.
template <class E>
std::optional<E> valueNamed(const std::string& name) {
    for (const auto& entry : EnumNames<E>::list)
        if (name == entry.name) return entry.value;
    return std::nullopt;
}

// How a session's frames are rendered (the protocol's display.guard_band,
// display.supersampling and display.photon_marker, both games alike). They change what a
// participant sees, never the game's state: the outcomes a session logs replay the same
// whatever they say.
struct RenderSettings {
    // Warp conditions render their sources this fraction of the displayed width and height beyond
    // each side, so what a turn brings into view is really there (renderer::GuardBand).
    double guardBand = 0.1;
    // Samples per pixel side for every conventional frame's colour (1 = none, 2 = 2x2 ...).
    int supersampling = 1;
    // A live session's square for a photodiode: black, white on the first frame shown that
    // depicts a left-button press (game::ShownFrame::inputFrame).
    PhotonMarker photonMarker = PhotonMarker::Off;
    // A live session whose display frames were late or skipped (its display clock) more often
    // than this share is flagged missed_frames, so that an analysis can leave it out.
    double maxLateShare = 0.01;
};
// Their ranges are scene/limits.h's, which the renderer and the command line share.

// A bad protocol file: one sentence naming the file and the JSON path of the culprit.
class ProtocolError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// What a protocol file may be: bounded, so that no file can make reading or parsing slow. A
// real protocol is a few kilobytes.
inline constexpr std::size_t kMaxProtocolBytes = 1 << 20;

// The whole file as text (strict/file.h). A missing file, a folder, a FIFO, a device, a file
// over kMaxProtocolBytes or an unreadable file is a ProtocolError naming the path.
std::string readProtocolFile(const std::string& path);

// The value of the top-level "game" field, which says which parser reads the rest ("shooter",
// "click"). A ProtocolError naming sourceName when the text is not JSON (with line and column),
// not an object, or has no string "game". Nothing else in the file is checked.
std::string protocolGame(const std::string& jsonText, const std::string& sourceName);

// Whether the file has a top-level field beyond those every protocol has (format_version, name,
// description, game, conditions): one that only some game's protocol knows. False for text that
// is not a JSON object.
bool hasGameFields(const std::string& jsonText);

// `jsonText` (a protocol object) with its `section`.`key` set to `list`, every other field as
// the text has it, written with two-space indent and a trailing newline. A section the text
// leaves out is added with the list alone: its other fields keep their defaults, as they did.
// For a game's Study::withConditionOrder.
std::string withList(const std::string& jsonText, const char* section, const char* key,
                     const std::vector<std::string>& list);

}  // namespace warplab::protocol
