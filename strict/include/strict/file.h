// The one way warplab reads a file a user hands it (a protocol, a study plan and its protocol
// copies, a population, an input script): a regular file only, of bounded size, and every
// refusal one sentence that starts with what the file is and its path. A FIFO would block the
// reader for ever and /dev/zero would fill memory, so neither is opened for reading at all.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace warplab::strict {

// A refusal: one sentence naming the file and where in it.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// What is being read, for every message: "protocol 'p.json': test.timeout_s must be ...".
struct Source {
    // Throws the reader's own error type (protocol::ProtocolError, plan::PlanError, ...) with the
    // sentence, so that callers keep catching what they caught; nullptr: strict::Error.
    using Raise = void (*)(const std::string& sentence);

    std::string kind;  // "protocol", "study plan", "population file", "input script"
    std::string path;  // as the user gave it
    std::size_t maxBytes = 0;  // the most such a file may be: no file can make reading slow
    Raise raise = nullptr;

    // "KIND 'PATH': WHERE REASON", or "KIND 'PATH': REASON" when where is empty.
    [[noreturn]] void fail(const std::string& where, const std::string& reason) const;
    // "KIND 'PATH' line N: REASON", for a file read line by line.
    [[noreturn]] void failAtLine(std::size_t line, const std::string& reason) const;
};

// The text of the regular file at `path`, or why there is none: "no such file", "is a
// directory, not a file", "is a FIFO (a named pipe), not a regular file", "is 2000000 bytes,
// more than a protocol may be (1048576)" (`kind` names what the file is). A message may put
// the problem after a path of its own (a plan names the copy's field, then the problem).
struct FileText {
    std::string text;
    std::string problem;  // "" when text is the whole file
};
FileText readRegularFile(const std::string& path, std::size_t maxBytes, const std::string& kind);

// The whole file as text, or source.fail("", problem).
std::string readFile(const Source& source);

}  // namespace warplab::strict
