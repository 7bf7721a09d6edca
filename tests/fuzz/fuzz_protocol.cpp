// libFuzzer target: arbitrary bytes as a study protocol file (docs/fuzzing.md).
//
// game::parseStudy either returns a study or throws protocol::ProtocolError, one sentence
// naming the file and the field (game/registry.h). Anything else is a bug: another exception,
// a crash, a sanitizer report, a leak, a hang, a gigabyte of memory.
//
// A protocol that parses must also survive the trip every session makes: the session stores
// the study's canonical copy (Study::protocolJson) and replay, export and `replay --render`
// parse that copy again. So the copy must parse, to a study with the same canonical copy.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>

#include "game/registry.h"
#include "games/games.h"
#include "protocol/study_protocol.h"

namespace {

using warplab::game::Study;

[[noreturn]] void bug(const char* what, const std::string& detail) {
    std::fprintf(stderr, "fuzz_protocol: %s\n%s\n", what, detail.c_str());
    std::abort();
}

// nullptr when the text is rejected the documented way.
std::unique_ptr<Study> parse(const std::string& text, const std::string& name) {
    try {
        return warplab::game::parseStudy(text, name);
    } catch (const warplab::protocol::ProtocolError&) {
        return nullptr;
    } catch (const std::exception& e) {
        bug("parseStudy threw something other than protocol::ProtocolError:", e.what());
    }
}

}  // namespace

// The built-in games, known to the loader as the app makes them known.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
    warplab::games::registerGames();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const std::unique_ptr<Study> study = parse(text, "fuzz.json");
    if (!study) return 0;

    const std::string canonical = study->protocolJson();
    std::unique_ptr<Study> again;
    try {
        again = warplab::game::parseStudy(canonical, "fuzz-canonical.json");
    } catch (const std::exception& e) {
        bug("a protocol that parses has a canonical copy that does not:",
            std::string(e.what()) + "\n--- canonical copy ---\n" + canonical);
    }
    if (again->protocolJson() != canonical)
        bug("the canonical copy of a protocol parses to a different canonical copy:",
            "--- first ---\n" + canonical + "\n--- second ---\n" + again->protocolJson());
    return 0;
}
